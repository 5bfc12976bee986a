// The cueing unit's final limiter: the excursion from home scaled by s in [0, 1] so that every
// output pose is within every limit of the machine (stewart_limits_check), s moving smoothly at
// most `rate` per second while that suffices, cut at once when it does not.
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
    double lookahead;        // [s]
};

// The platform pose home + s e in the caller's frames (tool in user frame); false when it cannot
// be formed (the tool's pitch at 90 deg with derivatives asked for).
bool caller_pose(const Limiter &l, const stewart_pose &platform, int derivatives,
                 stewart_pose &caller);

// True if home + s e is within every limit.
bool within(const Limiter &l, const double e[6], double s);

// The scale of this sample from the last one's: the largest within the limits now and at the
// excursion extrapolated lookahead seconds ahead, approached at most rate * dt, and never above
// the largest scale within the limits now (found by bisection; 0, home, always is).
double limited_scale(const Limiter &l, const Excursion &e, double last, double dt);

}  // namespace cueing
}  // namespace stewart
