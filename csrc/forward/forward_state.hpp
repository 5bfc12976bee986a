// Forward kinematics' part of a data block: the Newton solver (allocated with the block) and the
// tracking history (the last pose, its rates, the pose before it).
#pragma once

#include <memory>

#include "forward/branch.hpp"
#include "forward/newton.hpp"

namespace stewart {

struct ForwardState {
    ForwardState() : newton(new (std::nothrow) ForwardNewton) {}
    std::unique_ptr<ForwardNewton> newton;  // null or !ok(): forward solves fail as out of memory
    bool has_pose = false;                  // a last pose to track from
    bool has_rates = false, has_accels = false;
    double time = 0;
    double q[6] = {0}, q_dot[6] = {0}, q_ddot[6] = {0};
    bool has_previous = false;  // the pose before the last (a secant predictor without rates)
    double previous_time = 0;
    double previous_q[6] = {0};
    Matrix36 points;       // the last pose's platform points, world (the jump check)
    // Of the model, worked out at the first solve: the sign of the leg Jacobian's determinant
    // at home (0: not yet known) and the bounds on pairs of lengths.
    int working_sign = 0;
    LengthPairBounds pair_bounds = {};
    // Forgets the history.
    void reset() { has_pose = has_rates = has_accels = has_previous = false; }
};

}  // namespace stewart
