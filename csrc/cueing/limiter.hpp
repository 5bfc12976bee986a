// The cueing unit's final limiter: the excursion from home scaled by s in [0, 1] so that every
// output pose is within every limit of the machine (stewart_limits_check). s moves smoothly (its
// rate at most `rate`, its acceleration at most `accel`) toward the largest scale within the
// limits now and `lookahead` seconds ahead, and is cut at once, to a scale within the limits found
// by bisection, when that does not suffice. Over a step s is the cubic through its values and
// rates at both ends, so the pose's rates and accelerations are exact and s' is continuous.
#pragma once

#include "cueing/classical.hpp"
#include "kinematics/frames.hpp"
#include "stewart/stewart_limits.h"

namespace stewart {
namespace cueing {

struct Limiter {
    stewart_limits *limits;  // the machine's exact limits (owned by the cueing object)
    const Frames *frames;    // the caller's pose from the platform's
    double home[6];          // the platform's home pose, solvers' base frame
    double rate;             // largest smooth rate of s [1/s]
    double accel;            // largest smooth acceleration of s [1/s2]
    double lookahead;        // [s]
};

// The scale s, its rate and its acceleration at the end of a step.
struct Scale {
    double value, rate, accel;
    bool cut;  // the smooth motion did not suffice: s was cut to a scale within the limits
};

// The platform pose in the caller's frames (tool in user frame); false when it cannot be formed
// (the tool's pitch at 90 deg with derivatives asked for).
bool caller_pose(const Limiter &l, const stewart_pose &platform, int derivatives,
                 stewart_pose &caller);

// True if home + s e is within every limit.
bool within(const Limiter &l, const double e[6], double s);

// The scale at the end of a step of dt from (last, last_rate), for the excursion e.
Scale limited_scale(const Limiter &l, const Excursion &e, double last, double last_rate, double dt);

}  // namespace cueing
}  // namespace stewart
