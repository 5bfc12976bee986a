// The cueing unit's leg motion limiter (leg_limiter.hpp).
#include "cueing/leg_limiter.hpp"

#include <cmath>
#include <limits>

#include "kinematics/motion.hpp"

namespace stewart {
namespace cueing {

namespace {

// How fast the output is pulled back to the cue after it left it [1/s]: errors decay by e in
// 50 ms.
constexpr double kTrackingFrequency = 20.0;
// The share of the acceleration limit of the stop that every output must be able to make (its
// stop pose within the pose limits), and of the brake it makes when it has to: the rest is left
// to the legs' acceleration that the motion itself makes (the centripetal terms), and the brake,
// firmer, stops short of the stop checked.
constexpr double kStopShare = 0.5, kBrakeShare = 0.6;
// Bisections of the tracking acceleration's factor: to 1/64 of it.
constexpr int kBisections = 6;
// The limits enforced are this much (relative) inside the given ones, so that the legs' rates
// computed another way (the inverse solver through the tool and user frames) are within too.
constexpr double kRoundingMargin = 1e-7;

// One end state of a step: excursion from home, its rate and acceleration.
struct EndState {
    double q[6], q_dot[6], q_ddot[6];
};

// The legs' lengths, rates and accelerations at home + x moving at x_dot, x_ddot; false when a
// leg has no length (no direction: nothing vouches for it).
bool legs_at(const LegLimiter &l, const double x[6], const double x_dot[6], const double x_ddot[6],
             LegKinematics &legs) {
    double q[6];
    for (int i = 0; i < 6; ++i) q[i] = l.limiter->home[i] + x[i];
    char unused[2];
    return leg_kinematics(*l.geometry, motion_of_pose<double>(q, x_dot, x_ddot), legs, unused,
                          sizeof unused) == STEWART_OK;
}

bool accels_within(const LegLimiter &l, const LegKinematics &legs) {
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (!(std::fabs(legs.accel[k]) <= l.accel_max[k])) return false;
    return true;
}

bool speeds_within(const LegLimiter &l, const LegKinematics &legs) {
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (!(std::fabs(legs.rate[k]) <= l.speed_max[k])) return false;
    return true;
}

// The time to stop every leg from its rate on `share` of its acceleration limit [s].
double stop_time(const LegLimiter &l, const LegKinematics &legs, double share) {
    double T = 0.0;
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (std::isfinite(l.accel_max[k]))
            T = std::fmax(T, std::fabs(legs.rate[k]) / (share * l.accel_max[k]));
    return T;
}

// The end state passes: legs within their speed and acceleration limits, the pose within the
// pose limits (unless known to be), and, if `stop`, the pose where a stop at constant
// deceleration along the rate would end within them too (a stop of at least one step dt: the
// acceleration changes at the samples only), and the pose of the brake's first step (the pose
// limits need not be convex between the pose and its stop).
bool passes(const LegLimiter &l, const EndState &s, double dt, bool pose_known_within,
            bool stop = true) {
    LegKinematics legs;
    if (!legs_at(l, s.q, s.q_dot, s.q_ddot, legs) || !speeds_within(l, legs) ||
        !accels_within(l, legs))
        return false;
    if (!pose_known_within && !within(*l.limiter, s.q, 1.0)) return false;
    if (!stop) return true;
    const double T = std::fmax(stop_time(l, legs, kStopShare), dt);
    if (!(T > 0.0)) return true;
    double stopped[6];
    for (int i = 0; i < 6; ++i) stopped[i] = s.q[i] + 0.5 * T * s.q_dot[i];
    if (!within(*l.limiter, stopped, 1.0)) return false;
    const double brake = std::fmax(stop_time(l, legs, kBrakeShare), dt);
    double braked[6];
    for (int i = 0; i < 6; ++i) braked[i] = s.q[i] + dt * s.q_dot[i] * (1.0 - 0.5 * dt / brake);
    return within(*l.limiter, braked, 1.0);
}

// The cubic from the last output (x0, v0) to the cue's (x1, v1) over dt has leg accelerations
// within the limits at both ends.
bool cubic_within(const LegLimiter &l, const LegState &last, const EndState &cue, double dt) {
    double start_accel[6], end_accel[6];
    for (int i = 0; i < 6; ++i) {
        const double dx = cue.q[i] - last.q[i];
        start_accel[i] = (6.0 * dx - dt * (4.0 * last.q_dot[i] + 2.0 * cue.q_dot[i])) / (dt * dt);
        end_accel[i] = (-6.0 * dx + dt * (2.0 * last.q_dot[i] + 4.0 * cue.q_dot[i])) / (dt * dt);
    }
    LegKinematics legs;
    return legs_at(l, last.q, last.q_dot, start_accel, legs) && accels_within(l, legs) &&
           legs_at(l, cue.q, cue.q_dot, end_accel, legs) && accels_within(l, legs);
}

// The output may take the cue itself.
bool follows_exactly(const LegLimiter &l, const LegState &last, const EndState &cue, double dt) {
    if (dt > 0.0) {
        if (!cubic_within(l, last, cue, dt)) return false;
    } else {
        for (int i = 0; i < 6; ++i)  // no time passes: only the acceleration may change
            if (cue.q[i] != last.q[i] || cue.q_dot[i] != last.q_dot[i]) return false;
    }
    return passes(l, cue, dt, true);  // the pose limiter checked the cue's pose
}

// The end of a step of dt at constant acceleration a from the last output.
EndState constant_accel(const LegState &last, const double a[6], double dt) {
    EndState s;
    for (int i = 0; i < 6; ++i) {
        s.q[i] = last.q[i] + dt * last.q_dot[i] + 0.5 * dt * dt * a[i];
        s.q_dot[i] = last.q_dot[i] + dt * a[i];
        s.q_ddot[i] = a[i];
    }
    return s;
}

EndState scaled_step(const LegState &last, const double a[6], double factor, double dt) {
    double scaled[6];
    for (int i = 0; i < 6; ++i) scaled[i] = factor * a[i];
    return constant_accel(last, scaled, dt);
}

// The largest factor in [0, 1] that keeps every leg's rate and acceleration within its limits
// with the legs' motion taken linear in the factor between `none` (factor 0, known within) and
// `full` (factor 1).
double linear_factor(const LegLimiter &l, const LegKinematics &none, const LegKinematics &full) {
    double factor = 1.0;
    const auto bound = [&factor](double f0, double f1, double limit) {
        const double df = f1 - f0;
        if (df > 0.0 && f0 + df > limit) factor = std::fmin(factor, (limit - f0) / df);
        if (df < 0.0 && f0 + df < -limit) factor = std::fmin(factor, (limit + f0) / -df);
    };
    for (int k = 0; k < STEWART_LEGS; ++k) {
        bound(none.rate[k], full.rate[k], l.speed_max[k]);
        bound(none.accel[k], full.accel[k], l.accel_max[k]);
    }
    return std::fmax(factor, 0.0);
}

// The tracking acceleration's step, scaled by the largest factor found to pass (with the stop
// pose checked if `stop`): the linear estimate, else bisections below it. false when even factor
// 0 (coasting) does not pass.
bool tracking_step(const LegLimiter &l, const LegState &last, const double track[6], double dt,
                   bool stop, EndState &s) {
    s = scaled_step(last, track, 1.0, dt);
    if (passes(l, s, dt, false, stop)) return true;
    const EndState coast = scaled_step(last, track, 0.0, dt);
    if (!passes(l, coast, dt, false, stop)) return false;
    LegKinematics none, full;
    double hi = 0.0;
    if (legs_at(l, coast.q, coast.q_dot, coast.q_ddot, none) &&
        legs_at(l, s.q, s.q_dot, s.q_ddot, full))
        hi = linear_factor(l, none, full);
    s = scaled_step(last, track, hi, dt);
    if (hi > 0.0 && passes(l, s, dt, false, stop)) return true;
    double lo = 0.0;
    for (int n = 0; n < kBisections; ++n) {
        const double mid = 0.5 * (lo + hi);
        if (passes(l, scaled_step(last, track, mid, dt), dt, false, stop)) lo = mid;
        else hi = mid;
    }
    s = scaled_step(last, track, lo, dt);
    return true;
}

// The step that ends where the last one did, at rest: the cubic from (x0, v0) back to (x0, 0),
// whose end acceleration is 2 v0 / dt. Its pose is the last output's, within the pose limits.
EndState hold(const LegState &last, double dt) {
    EndState s;
    for (int i = 0; i < 6; ++i) {
        s.q[i] = last.q[i];
        s.q_dot[i] = 0.0;
        s.q_ddot[i] = dt > 0.0 ? 2.0 * last.q_dot[i] / dt : 0.0;
    }
    return s;
}

// The output's own step when it cannot follow the cue: the tracking acceleration (toward the cue,
// its errors decaying at kTrackingFrequency) scaled, else a brake along the rate, else the
// tracking step without the stop's check, else a hold (within the pose limits, its legs perhaps
// not); false only when the hold's pose, home + the stored excursion, rounds beyond a pose
// limit.
bool own_step(const LegLimiter &l, const LegState &last, const EndState &cue, double dt,
              EndState &s) {
    // The acceleration that brings the end of the step onto e' + w e = 0 (e the error to the
    // cue): the error then decays as exp(-w t), by (2 - w dt) / (2 + w dt) a step at any dt, and
    // a cue the output is on is followed as it is (its own acceleration over the step). No time
    // passing, only the acceleration can change: the cue's, pulled as a PD.
    const double w = kTrackingFrequency;
    double track[6];
    for (int i = 0; i < 6; ++i) {
        const double ex = last.q[i] - cue.q[i], ev = last.q_dot[i] - cue.q_dot[i];
        track[i] = dt > 0.0 ? -(ev + w * (ex + dt * last.q_dot[i])) / (dt * (1.0 + 0.5 * w * dt))
                            : cue.q_ddot[i] - 2.0 * w * ev - w * w * ex;
    }
    if (tracking_step(l, last, track, dt, true, s)) return true;
    // Coasting does not pass: brake along the rate, within one step if the limits allow. The
    // last output's stop (on kStopShare) was within the pose limits; this one is shorter, on the
    // same line.
    LegKinematics legs;
    const double none[6] = {0, 0, 0, 0, 0, 0};
    const double T = legs_at(l, last.q, last.q_dot, none, legs)
                         ? std::fmax(stop_time(l, legs, kBrakeShare), dt)
                         : dt;
    if (T > 0.0) {
        double brake[6];
        for (int i = 0; i < 6; ++i) brake[i] = -last.q_dot[i] / T;
        s = constant_accel(last, brake, dt);
        if (passes(l, s, dt, false, true) || passes(l, s, dt, false, false)) return true;
    }
    // The brake leaves the pose limits (they need not be convex between the pose and its stop):
    // the tracking step without the stop's check, toward the cue (within them).
    if (tracking_step(l, last, track, dt, false, s)) return true;
    s = hold(last, dt);
    return within(*l.limiter, s.q, 1.0);
}

}  // namespace

LegLimiter leg_limiter(const Limiter &limiter, const PlatformGeometry &geometry,
                       const stewart_params &p) {
    LegLimiter l;
    l.limiter = &limiter;
    l.geometry = &geometry;
    l.active = false;
    const double none = std::numeric_limits<double>::infinity();
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const double inside = 1.0 - kRoundingMargin;
        l.speed_max[k] = p.leg_speed_max[k] > 0.0 ? inside * p.leg_speed_max[k] : none;
        l.accel_max[k] = p.leg_accel_max[k] > 0.0 ? inside * p.leg_accel_max[k] : none;
        l.active = l.active || p.leg_speed_max[k] > 0.0 || p.leg_accel_max[k] > 0.0;
    }
    return l;
}

bool leg_limited_step(const LegLimiter &l, const stewart_pose &desired, double dt, LegState &state,
                      stewart_pose &platform) {
    EndState cue;
    for (int i = 0; i < 6; ++i) {
        cue.q[i] = desired.q[i] - l.limiter->home[i];
        cue.q_dot[i] = desired.q_dot[i];
        cue.q_ddot[i] = desired.q_ddot[i];
    }
    EndState own;
    const bool exact =
        !l.active || follows_exactly(l, state, cue, dt) || !own_step(l, state, cue, dt, own);
    for (int i = 0; i < 6; ++i) {
        platform.q[i] = exact ? desired.q[i] : l.limiter->home[i] + own.q[i];
        platform.q_dot[i] = exact ? desired.q_dot[i] : own.q_dot[i];
        platform.q_ddot[i] = exact ? desired.q_ddot[i] : own.q_ddot[i];
        state.q[i] = exact ? cue.q[i] : own.q[i];
        state.q_dot[i] = exact ? cue.q_dot[i] : own.q_dot[i];
    }
    return !exact;
}

}  // namespace cueing
}  // namespace stewart
