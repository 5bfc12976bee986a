// The cueing unit's leg motion limiter: after the pose limiter (limiter.hpp), it keeps every leg's
// speed and acceleration within leg_speed_max and leg_accel_max at every output sample, the
// legs' rates and accelerations exact (leg_kinematics on the output pose and its derivatives).
//
// An end state passes when its legs are within both limits, its pose within every pose limit,
// and so are the pose where a stop along its rate would end (braking on half the acceleration
// limit, at least one step long) and the pose of that brake's first step: the output never
// commits to a motion it cannot stop before a stroke end. The output follows the pose limiter's
// pose exactly while that passes and the cubic from the last output to it has leg accelerations
// within the limit at both ends (a jump of the cue's rate fails this). Otherwise it moves on its
// own: a constant pose acceleration over the step, the tracking acceleration (toward the cue)
// scaled by the largest factor in [0, 1] found to pass; if none does, a brake along the pose
// rate, the tracking step without the stop's checks, a hold at the last pose. The pose limits
// come first: when no motion passes them and the legs' limits, the legs' are broken (and
// reported by the caller's check).
#pragma once

#include "cueing/limiter.hpp"
#include "kinematics/closed_form.hpp"
#include "stewart/stewart.h"

namespace stewart {
namespace cueing {

struct LegLimiter {
    const Limiter *limiter;            // the pose limits and the home pose
    const PlatformGeometry *geometry;  // the solvers' joints
    double speed_max[STEWART_LEGS];    // [m/s], +inf where none is given
    double accel_max[STEWART_LEGS];    // [m/s2], +inf where none is given
    bool active;                       // some speed or acceleration limit is given
};

// The output's motion at the last sample: the excursion of the platform pose from home and its
// rate, solvers' base frame.
struct LegState {
    double q[6], q_dot[6];
};

// The limiter for params (its leg_speed_max and leg_accel_max; 0 is none).
LegLimiter leg_limiter(const Limiter &limiter, const PlatformGeometry &geometry,
                       const stewart_params &params);

// One step of dt toward the pose limiter's platform pose `desired` (solvers' frame, with its
// rates and accelerations): the output platform pose, true when it left `desired`.
bool leg_limited_step(const LegLimiter &l, const stewart_pose &desired, double dt, LegState &state,
                      stewart_pose &platform);

}  // namespace cueing
}  // namespace stewart
