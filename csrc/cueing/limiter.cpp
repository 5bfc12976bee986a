// The cueing unit's final limiter (limiter.hpp).
#include "cueing/limiter.hpp"

#include <algorithm>
#include <cmath>

namespace stewart {
namespace cueing {

namespace {

// Bisection steps: the scale to 2^-30 of the excursion (1e-9), about 30 limit checks.
constexpr int kBisections = 30;

// The largest scale in [0, high] found within the limits by bisection, starting from 0 (home)
// as the known good end: the result is always a checked pose or home.
double largest_within(const Limiter &l, const double e[6], double high) {
    if (within(l, e, high)) return high;
    double lo = 0.0, hi = high;
    for (int k = 0; k < kBisections; ++k) {
        const double mid = 0.5 * (lo + hi);
        if (within(l, e, mid)) lo = mid;
        else hi = mid;
    }
    return lo;
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
    stewart_limits_input in;
    for (int i = 0; i < 6; ++i) in.q[i] = caller.q[i];
    stewart_limits_output out;
    return stewart_limits_check(l.limits, &in, &out) == STEWART_OK &&
           out.first == STEWART_LIMIT_NONE;
}

double limited_scale(const Limiter &l, const Excursion &e, double last, double dt) {
    double ahead[6];
    const double T = l.lookahead;
    for (int i = 0; i < 6; ++i) ahead[i] = e.q[i] + T * e.q_dot[i] + 0.5 * T * T * e.q_ddot[i];
    const double now = largest_within(l, e.q, 1.0);
    const double goal = T > 0.0 ? std::min(now, largest_within(l, ahead, 1.0)) : now;
    const double reach = l.rate * dt;
    const double smooth = std::clamp(last + std::clamp(goal - last, -reach, reach), 0.0, 1.0);
    // The final pose is always a checked one: `now` was, a smaller scale is checked again (the
    // poses within the limits along the excursion need not be an interval).
    return smooth == now ? now : largest_within(l, e.q, smooth);
}

}  // namespace cueing
}  // namespace stewart
