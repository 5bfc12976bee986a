// The cueing unit's final limiter (limiter.hpp).
#include "cueing/limiter.hpp"

#include <algorithm>
#include <cmath>

namespace stewart {
namespace cueing {

namespace {

// How finely the scale within the limits is found: the scale used (now) to 1e-6 of the
// excursion, the goals ahead (only aims of the smooth motion) to 1e-3.
constexpr double kScaleTolerance = 1e-6, kGoalTolerance = 1e-3;

// The largest scale in [0, high] found within the limits by bisection, starting from 0 (home)
// as the known good end: the result is always a checked pose or home. hint, a scale near the
// answer (the last sample's), narrows the first bracket to 1/64 when it is right.
double largest_within(const Limiter &l, const double e[6], double high, double hint,
                      double tolerance) {
    if (within(l, e, high)) return high;
    double lo = 0.0, hi = high;
    if (hint > 0.0 && hint < high) {
        if (within(l, e, hint)) {
            lo = hint;
            const double up = std::min(high, hint + 1.0 / 64.0);
            if (within(l, e, up)) lo = up;
            else hi = up;
        } else {
            hi = hint;
        }
    }
    while (hi - lo > tolerance) {
        const double mid = 0.5 * (lo + hi);
        if (within(l, e, mid)) lo = mid;
        else hi = mid;
    }
    return lo;
}

// The acceleration at the end of the step of the cubic with value and rate (s0, v0) at its start
// and (s1, v1) at its end.
double cubic_end_accel(double s0, double v0, double s1, double v1, double dt) {
    return (6.0 * (s0 - s1) + dt * (2.0 * v0 + 4.0 * v1)) / (dt * dt);
}

// One step of a bounded-rate, bounded-acceleration motion of s toward goal: the rate that
// still stops at the goal under the acceleration bound, reached as far as the bound allows.
Scale smooth_step(const Limiter &l, double s0, double v0, double goal, double dt) {
    const double d = goal - s0;
    const double v_goal =
        std::copysign(std::min(l.rate, std::sqrt(2.0 * l.accel * std::fabs(d))), d);
    const double a = std::clamp((v_goal - v0) / dt, -l.accel, l.accel);
    Scale s{s0 + v0 * dt + 0.5 * a * dt * dt, v0 + a * dt, a, false};
    if (s.value > 1.0 || s.value < 0.0) {  // at an end of [0, 1]: stop there
        s.value = std::clamp(s.value, 0.0, 1.0);
        s.rate = 0.0;
        s.accel = cubic_end_accel(s0, v0, s.value, s.rate, dt);
    }
    return s;
}

}  // namespace

bool caller_pose(const Limiter &l, const stewart_pose &platform, int derivatives,
                 stewart_pose &caller) {
    if (l.frames->identity) {
        caller = platform;
        return true;
    }
    return tool_pose(*l.frames, platform, derivatives, caller);
}

bool within(const Limiter &l, const double e[6], double s) {
    stewart_pose platform{};
    for (int i = 0; i < 6; ++i) platform.q[i] = l.home[i] + s * e[i];
    stewart_pose caller;
    if (!caller_pose(l, platform, 0, caller)) return false;
    stewart_limits_input in{};  // the pose alone: no derivatives, no forces
    for (int i = 0; i < 6; ++i) in.q[i] = caller.q[i];
    stewart_limits_output out;
    return stewart_limits_check(l.limits, &in, &out) == STEWART_OK &&
           out.first == STEWART_LIMIT_NONE;
}

Scale limited_scale(const Limiter &l, const Excursion &e, double last, double last_rate,
                    double dt) {
    const double now = largest_within(l, e.q, 1.0, last, kScaleTolerance);
    double goal = now;
    for (const double T : {0.5 * l.lookahead, l.lookahead}) {  // the excursion extrapolated
        if (!(T > 0.0)) break;
        double ahead[6];
        for (int i = 0; i < 6; ++i) ahead[i] = e.q[i] + T * e.q_dot[i] + 0.5 * T * T * e.q_ddot[i];
        goal = std::min(goal, largest_within(l, ahead, 1.0, last, kGoalTolerance));
    }
    Scale s =
        dt > 0.0 ? smooth_step(l, last, last_rate, goal, dt) : Scale{last, last_rate, 0.0, false};
    // The final pose is always a checked one: `now` was, any other scale is checked (the poses
    // within the limits along the excursion need not be an interval).
    if (s.value == now || within(l, e.q, s.value)) return s;
    s.value = largest_within(l, e.q, s.value, 0.0, kScaleTolerance);
    // Leave a cut moving down at the largest smooth rate: the scale within the limits is
    // usually still falling, and a scale at rest would be cut again at the next sample.
    s.rate = dt > 0.0 && s.value > 0.0 ? -l.rate : 0.0;
    s.accel = dt > 0.0 ? cubic_end_accel(last, last_rate, s.value, s.rate, dt) : 0.0;
    s.cut = true;
    return s;
}

}  // namespace cueing
}  // namespace stewart
