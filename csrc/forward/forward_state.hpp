// Forward kinematics' state: the Newton solver (allocated with the solver object) and the tracking
// history (the last pose, its rates, the pose before it, the leg Jacobian factored there).
#pragma once

#include <memory>

#include "forward/branch.hpp"
#include "forward/continuation.hpp"
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
    LegVectors points = {};  // the last pose's platform points, world (the jump check)
    // The leg Jacobian factored at the last pose (its last Newton iterate): the next tracking
    // solve's first Newton step (a chord step) needs no Jacobian or factoring of its own.
    bool has_chord = false;
    LegFactors chord = {};
    // The last pose's Cardan-to-Cardan lengths and the proven step there (tolerance 0): a
    // tracked pose within it is the one the lengths' change leads to.
    double lengths[6] = {0};
    ProvenStep step;
    // Forgets the history.
    void reset() { has_pose = has_rates = has_accels = has_previous = has_chord = false; }
};

// The history as bytes: its size, and save/load (load checks every field; false + message).
size_t forward_history_size();
void forward_history_save(const ForwardState &f, unsigned char *buffer);
bool forward_history_load(ForwardState &f, const unsigned char *buffer, size_t size, char *msg,
                          size_t msg_size);

}  // namespace stewart
