#include "forward/continuation.hpp"

#include <algorithm>
#include <cmath>

#include "kinematics/motion.hpp"
#include "util/message.hpp"

namespace stewart {

namespace {
constexpr int kMaxSteps = 4000;  // path-tracker trials, then refused
}  // namespace

double largest_arm(const PlatformGeometry &g) {
    double arm = 0;
    for (int k = 0; k < STEWART_LEGS; ++k)
        arm = std::max(arm, g.platform_points.col(k).norm() / g.characteristic_length);
    return arm;
}

ProvenStep proven_step(const PlatformGeometry &g, double inverse_norm1, double shortest, double arm,
                       double tolerance) {
    // Pose increments u = (dp, r_t phi), phi the rotation vector of R R0^T. beta = |J^-1|_1
    // and gamma = how fast a row of J turns per unit of |u| (its axis n by |d(leg)| / L, its
    // moment arm by the arm and n): the Kantorovich form with these estimates, which leave out
    // the norms' dimension factors (up to 6) and the chart's curvature.
    const double r_t = g.characteristic_length;
    const double beta = inverse_norm1;
    const double half = 0.5 * shortest;  // the legs keep half their length in the ball
    const double ball = std::min(half / (1 + arm), 0.5 * r_t);
    const double dn = (1 + arm) / half;
    const double gamma = dn + arm / r_t + arm * dn;
    ProvenStep step;
    if (!(beta > 0) || !std::isfinite(beta)) return step;
    // h = beta^2 gamma |F| <= 1/2: one pose within r0 <= 2 beta |F| (kept inside the ball), the
    // only one within (1 + sqrt(1 - 2h)) / (beta gamma) >= 1 / (beta gamma).
    step.radius = std::min(1.0 / (beta * gamma), ball);
    step.max_change = std::min(0.5 / (beta * beta * gamma), step.radius / (2 * beta)) - tolerance;
    if (step.max_change < 0) step.max_change = 0;
    return step;
}

double pose_distance(const PlatformGeometry &g, const double a[6], const double b[6]) {
    // The angle from |R_a - R_b|_F = 2 sqrt2 sin(angle / 2): exact to rounding for small angles
    // (acos of the trace loses half the digits there).
    const double chord =
        (rotation_from_rpy(a[3], a[4], a[5]) - rotation_from_rpy(b[3], b[4], b[5])).norm();
    double d = g.characteristic_length * 2.0 * std::asin(std::min(1.0, chord / std::sqrt(8.0)));
    for (int i = 0; i < 3; ++i) d = std::max(d, std::fabs(a[i] - b[i]));
    return d;
}

bool continue_lengths(const PlatformGeometry &g, ForwardNewton &newton, const double start[6],
                      const double start_lengths[6], const double target[6], double tolerance,
                      double q[6], int &steps, char *msg, size_t size) {
    // A path tracker: a step is taken when Newton from the last pose reaches the next lengths in
    // a few iterations, the determinant keeps its sign and the pose moves less than a tenth of the
    // platform radius; else the step is halved. The steps double again after a success.
    constexpr double kLongest = 1.0 / 8, kShortest = 1.0 / 65536;
    constexpr int kFewIterations = 4;
    std::copy(start, start + 6, q);
    LegsAt legs;
    evaluate_legs(g, q, start_lengths, legs);
    LegFactors factors;
    double norm1;
    if (!factor_legs(g, legs, factors, norm1)) {
        set_message(msg, size, STEWART_ERR_SINGULAR,
                    "the path of lengths starts at a singular pose");
        return false;
    }
    const int sign = determinant_sign(factors);
    double t = 0, dt = kLongest;
    steps = 0;
    while (t < 1 && steps < kMaxSteps) {
        const double t_next = std::min(1.0, t + dt);
        double next[6], trial[6];
        for (int k = 0; k < STEWART_LEGS; ++k)
            next[k] = t_next >= 1 ? target[k]
                                  : start_lengths[k] + t_next * (target[k] - start_lengths[k]);
        std::copy(q, q + 6, trial);
        NewtonStats stats;
        bool taken = newton.solve(g, next, tolerance, kFewIterations, nullptr, 0, trial, stats, msg,
                                  size) == STEWART_OK &&
                     pose_distance(g, trial, q) < 0.1 * g.characteristic_length;
        if (taken) {
            const LegsAt &at = newton.last();
            taken = factor_legs(g, at, factors, norm1) && determinant_sign(factors) == sign;
        }
        ++steps;
        if (taken) {
            std::copy(trial, trial + 6, q);
            t = t_next;
            dt = std::min(kLongest, 2 * dt);
        } else if ((dt *= 0.5) < kShortest) {
            break;
        }
    }
    if (t >= 1) return true;
    set_message(msg, size, STEWART_ERR_SINGULAR,
                "the straight path of lengths from home meets a singular pose (or passes so near "
                "one that steps of 1/65536 of the way do not pass it), %.3g of the way",
                t);
    return false;
}

}  // namespace stewart
