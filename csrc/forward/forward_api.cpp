// The forward-kinematics C API: input checks, the starts (guess, tracking predictor, last pose,
// home), the Newton solve, the checks of the pose found, and its rates and accelerations through
// the leg Jacobian.
#include "forward/forward_state.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "forward/branch.hpp"
#include "forward/forward_object.hpp"
#include "forward/leg_pairs.hpp"
#include "forward/newton.hpp"
#include "kinematics/frames.hpp"
#include "kinematics/motion.hpp"
#include "model.hpp"
#include "stewart/stewart_forward.h"
#include "util/create.hpp"
#include "util/message.hpp"

using stewart::set_message;

namespace {

constexpr double kPi = 3.14159265358979323846;

// STEWART_ERR_ARGUMENT naming e.g. "L_dot3" unless all six values are finite (and, for lengths,
// positive).
stewart_status check_values(const double *v, const char *name, bool positive, char *msg,
                            size_t size) {
    // The common case in one test: lengths inside (0, 1e150) (false for NaN); v * 0 is 0 for a
    // finite v, NaN otherwise.
    using stewart::load_pair;
    if (positive) {
        stewart::PairBits outside = {0, 0};
        for (int k = 0; k < STEWART_LEGS; k += 2)
            outside |= ~((load_pair(v + k) > 0) & (load_pair(v + k) < 1e150));
        if (!stewart::any(outside)) return STEWART_OK;
    } else {
        stewart::Pair zero = {0, 0};
        for (int k = 0; k < STEWART_LEGS; k += 2) zero += load_pair(v + k) * 0.0;
        if (zero[0] + zero[1] == 0) return STEWART_OK;
    }
    for (int k = 0; k < STEWART_LEGS; ++k) {
        if (!std::isfinite(v[k]))
            return set_message(msg, size, STEWART_ERR_ARGUMENT, "%s%d is %g: it must be finite",
                               name, k + 1, v[k]);
        // Squares of lengths above 1e150 overflow; no platform is that large.
        if (positive && !(v[k] > 0 && v[k] < 1e150))
            return set_message(msg, size, STEWART_ERR_ARGUMENT,
                               "%s%d = %g m: an actuator length must be > 0 and < 1e150 m", name,
                               k + 1, v[k]);
    }
    return STEWART_OK;
}

// The leg accelerations at pose q moving at rates q_dot with zero pose accelerations
// (kinematics/closed_form leg_kinematics of motion_of_pose, the same formulas), from the cosines
// and sines of q's angles, known already; STEWART_ERR_UNREACHABLE if a leg has no length.
stewart_status velocity_leg_accelerations(const stewart::PlatformGeometry &g, const double q[6],
                                          const double q_dot[6], double cr, double sr,
                                          const stewart::PitchYawTrig &t, double accel[6],
                                          char *msg, size_t size) {
    const Eigen::Matrix3d R =
        stewart::rotation_from_trig(cr, sr, t.cos_pitch, t.sin_pitch, t.cos_yaw, t.sin_yaw);
    const Eigen::Vector3d rate(q_dot[3], q_dot[4], q_dot[5]);
    const Eigen::Vector3d omega =
        stewart::angle_rate_matrix(t.cos_pitch, t.sin_pitch, t.cos_yaw, t.sin_yaw) * rate;
    const Eigen::Vector3d alpha =
        stewart::angle_rate_matrix_dot(t.cos_pitch, t.sin_pitch, t.cos_yaw, t.sin_yaw, rate[1],
                                       rate[2]) *
        rate;
    // Written out, two legs at a time (forward/leg_pairs.hpp: each lane the scalar arithmetic).
    const double w0 = omega[0], w1 = omega[1], w2 = omega[2];
    const double e0 = alpha[0], e1 = alpha[1], e2 = alpha[2];
    const double *platform = g.platform_points.data(), *base = g.base_points.data();
    using stewart::Pair;
    using stewart::point_pair;
    for (int k = 0; k < STEWART_LEGS; k += 2) {
        const Pair b0 = point_pair(platform, 0, k), b1 = point_pair(platform, 1, k),
                   b2 = point_pair(platform, 2, k);
        const Pair r0 = R(0, 0) * b0 + R(0, 1) * b1 + R(0, 2) * b2;
        const Pair r1 = R(1, 0) * b0 + R(1, 1) * b1 + R(1, 2) * b2;
        const Pair r2 = R(2, 0) * b0 + R(2, 1) * b1 + R(2, 2) * b2;
        const Pair d0 = q[0] + r0 - point_pair(base, 0, k), d1 = q[1] + r1 - point_pair(base, 1, k),
                   d2 = q[2] + r2 - point_pair(base, 2, k);
        const Pair L = stewart::sqrt_pair(d0 * d0 + d1 * d1 + d2 * d2);
        if (stewart::any(~(L > g.min_length)))  // (NaN too)
            for (int lane = 0; lane < 2; ++lane)
                if (!(L[lane] > g.min_length))
                    return stewart::check_leg_length(k + lane, L[lane], g.min_length, msg, size);
        const Pair inv_L = 1.0 / L;
        const Pair n0 = d0 * inv_L, n1 = d1 * inv_L, n2 = d2 * inv_L;
        const Pair wr0 = w1 * r2 - w2 * r1, wr1 = w2 * r0 - w0 * r2, wr2 = w0 * r1 - w1 * r0;
        const Pair v0 = q_dot[0] + wr0, v1 = q_dot[1] + wr1, v2 = q_dot[2] + wr2;
        const Pair a0 = (e1 * r2 - e2 * r1) + (w1 * wr2 - w2 * wr1),
                   a1 = (e2 * r0 - e0 * r2) + (w2 * wr0 - w0 * wr2),
                   a2 = (e0 * r1 - e1 * r0) + (w0 * wr1 - w1 * wr0);
        const Pair L_dot = n0 * v0 + n1 * v1 + n2 * v2;
        stewart::store_pair(accel + k, (v0 * v0 + v1 * v1 + v2 * v2 - L_dot * L_dot) * inv_L +
                                           (n0 * a0 + n1 * a1 + n2 * a2));
    }
    return STEWART_OK;
}

// STEWART_ERR_ARGUMENT naming the first value of a pose found (`what`) that overflowed.
stewart_status check_found(const stewart_pose &pose, const char *what, char *msg, size_t size) {
    const double *groups[3] = {pose.q, pose.q_dot, pose.q_ddot};
    stewart::Pair zero = {0, 0};  // (v * 0 is 0 for a finite v, NaN otherwise)
    for (const double *v : groups)
        for (int i = 0; i < 6; i += 2) zero += stewart::load_pair(v + i) * 0.0;
    if (zero[0] + zero[1] == 0) return STEWART_OK;
    for (const double *v : groups)
        for (int i = 0; i < 6; ++i)
            if (!std::isfinite(v[i]))
                return set_message(msg, size, STEWART_ERR_ARGUMENT,
                                   "the %s found overflows (%s is %g): the inputs are out of "
                                   "range",
                                   what, stewart::kPoseNames[i], v[i]);
    return STEWART_OK;
}

// The Cardan-to-Cardan lengths of the sensors' readings: reading + length_offset, each finite,
// > 0 and < 1e150 m (else STEWART_ERR_ARGUMENT naming the leg).
stewart_status cardan_lengths(const stewart_model &m, const double reading[6], double length[6],
                              char *msg, size_t size) {
    const stewart_params &p = m.params;
    if (!m.length_offsets) {
        std::memcpy(length, reading, STEWART_LEGS * sizeof(double));
        return check_values(reading, "L", true, msg, size);
    }
    stewart_status s = check_values(reading, "L", false, msg, size);
    if (s != STEWART_OK) return s;
    for (int k = 0; k < STEWART_LEGS; ++k) length[k] = reading[k] + p.length_offset[k];
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (!(length[k] > 0 && length[k] < 1e150))
            return set_message(msg, size, STEWART_ERR_ARGUMENT,
                               "L%d + length_offset[%d] = %g + %g m: a Cardan-to-Cardan length "
                               "must be > 0 and < 1e150 m",
                               k + 1, k + 1, reading[k], p.length_offset[k]);
    return STEWART_OK;
}

// The output as the caller sees it: out with its pose the tool's in the user frame (rates and
// accelerations to `derivatives`). STEWART_ERR_SINGULAR at the tool's pitch +-90 deg with
// rates, STEWART_ERR_ARGUMENT if the pose overflows; shown untouched then.
stewart_status shown_pose(const stewart_model &m, const stewart_forward_output &out,
                          int derivatives, stewart_forward_output &shown, char *msg, size_t size) {
    if (m.frames.identity) {
        shown = out;
        return STEWART_OK;
    }
    stewart_forward_output tool = out;
    if (!stewart::tool_pose(m.frames, out.pose, derivatives, tool.pose)) {
        stewart::tool_pose(m.frames, out.pose, 0, tool.pose);
        return set_message(msg, size, STEWART_ERR_SINGULAR,
                           "the tool frame's pitch in the user frame = %g rad is at +-90 deg: its "
                           "roll and yaw rates are not defined there",
                           tool.pose.q[4]);
    }
    const stewart_status s = check_found(tool.pose, "tool's pose", msg, size);
    if (s != STEWART_OK) return s;
    shown = tool;
    return STEWART_OK;
}

// The first reason in the STEWART_BRANCH_* bits, as a sentence.
const char *branch_reason(int branch) {
    if (branch & STEWART_BRANCH_BELOW_BASE)
        return "a leg leaves its base Cardan downward (the platform mirrored below the base)";
    if (branch & STEWART_BRANCH_PLATFORM_CARDAN)
        return "a leg reaches its platform Cardan from above the platform";
    if (branch & STEWART_BRANCH_FLIPPED) return "the platform faces down";
    if (branch & STEWART_BRANCH_UNPROVEN)
        return "these lengths have more than one pose on the working mode's side of every check, "
               "and this one is neither a proven step from the last pose nor the pose reached from "
               "home along the straight path of lengths: track the machine from a proven pose "
               "(samples close enough for each step to be proven), or reset to take the pose "
               "reached from home";
    if (branch & STEWART_BRANCH_SINGULARITY)
        return "the leg Jacobian's determinant has the other sign than at home (a singular pose "
               "lies in between)";
    return "a platform point jumped farther than the stroke since the last pose";
}

// A STEWART_START_* for messages.
const char *start_name(int start) {
    static const char *const names[4] = {"home pose", "guess", "tracking predictor", "last pose"};
    return names[start];
}

}  // namespace

namespace {

// A converged start: the pose and what the checks and the outputs need there.
struct Found {
    double q[6];
    int start = 0;
    int branch = 0;
    double jump = 0;
    stewart::LegFactors factors;                     // the leg Jacobian at q, factored
    double condition = 0;                            // its 1-norm condition number
    double angles[3], cos_angles[3], sin_angles[3];  // of the Newton iterate (before the wrap)
    stewart::LegVectors points;                      // the platform points, world
    stewart::Vector6 residual;
    stewart::ProvenStep step;  // at q (tolerance 0)
};

// The start pose of attempt `start`.
void start_pose(const stewart_model &m, const stewart::ForwardState &f, int start, double time,
                const double *guess, double q[6]) {
    switch (start) {
        case STEWART_START_GUESS: std::memcpy(q, guess, 6 * sizeof(double)); return;
        case STEWART_START_PREDICTOR: {  // (two coordinates at a time, each the scalar formula)
            using stewart::load_pair;
            const double dt = time - f.time, half_dt2 = 0.5 * dt * dt;
            for (int i = 0; i < 6; i += 2) {
                const stewart::Pair last = load_pair(f.q + i);
                const stewart::Pair rate =
                    f.has_rates ? load_pair(f.q_dot + i)
                                : (last - load_pair(f.previous_q + i)) / (f.time - f.previous_time);
                const stewart::Pair accel =
                    f.has_accels ? half_dt2 * load_pair(f.q_ddot + i) : stewart::Pair{0.0, 0.0};
                stewart::store_pair(q + i, last + dt * rate + accel);
            }
            return;
        }
        case STEWART_START_LAST: std::memcpy(q, f.q, 6 * sizeof(double)); return;
        default:
            for (int i = 0; i < 6; ++i) q[i] = 0;
            q[2] = m.params.home_height;
    }
}

// The legs, Jacobian and checks at the Newton solution (the legs at its last iterate):
// STEWART_ERR_SINGULAR if the pose is singular for the inverse side's threshold or the lengths
// do not determine it, else OK with the branch bits set.
stewart_status examine(const stewart_model &m, const stewart::ForwardState &f,
                       const stewart_forward_options &o, const stewart::LegsAt &at, bool tracking,
                       Found &x, char *msg, size_t size) {
    const stewart::PlatformGeometry &g = m.geometry;
    x.residual = at.residual;
    for (int i = 0; i < 3; ++i) x.angles[i] = at.q[3 + i];
    x.cos_angles[0] = at.cos_roll, x.cos_angles[1] = at.cos_pitch, x.cos_angles[2] = at.cos_yaw;
    x.sin_angles[0] = at.sin_roll, x.sin_angles[1] = at.sin_pitch, x.sin_angles[2] = at.sin_yaw;
    // cond_1(J) = |J|_1 |J^-1|_1 from the one factoring that also serves the step, the rates and
    // the next solve's chord.
    double norm1;
    const double inverse = stewart::factor_legs(g, at, x.factors, norm1)
                               ? stewart::inverse_norm1(x.factors)
                               : HUGE_VAL;
    x.condition = norm1 * inverse;
    x.step = stewart::proven_step(g, inverse, at.length.minCoeff(), m.forward.arm, 0.0);
    const double condition = x.condition;
    stewart_status s = stewart::check_condition(condition, o.singular_condition, msg, size);
    if (s != STEWART_OK) return s;
    // Kantorovich: Newton's answer is the unique pose near it only if h = beta^2 gamma |F| <=
    // 1/2 (beta = |J^-1|, gamma the Lipschitz constant of J, about 1/platform radius, |F| up to
    // the tolerance). Above that, lengths known to the tolerance do not fix the pose: at the
    // thesis' yaw = 90 deg Newton stops 5.7e-7 rad short, at a condition of only 4e6.
    const double h = condition * condition * o.tolerance / g.characteristic_length;
    if (h > 0.5)
        return set_message(msg, size, STEWART_ERR_SINGULAR,
                           "these lengths are at (or next to) a singular pose: leg Jacobian "
                           "condition number %g, so lengths known to the tolerance %g m do not "
                           "determine the pose (condition^2 tolerance / platform_radius = %g > "
                           "0.5)",
                           condition, o.tolerance, h);
    // The platform points, two legs at a time; the jump as the largest squared distance (the sum
    // in Eigen's order), then one square root (monotonic and correctly rounded): bit for bit
    // Eigen's colwise().norm().maxCoeff().
    using stewart::load_pair;
    using stewart::Pair;
    double farthest = 0;
    for (int k = 0; k < STEWART_LEGS; k += 2) {  // legs k and k + 1
        Pair d[3];
        for (int i = 0; i < 3; ++i) {
            const Pair point = load_pair(at.arm[i] + k) + at.q[i];
            stewart::store_pair(x.points.c[i] + k, point);
            d[i] = point - load_pair(f.points.c[i] + k);
        }
        const Pair squared = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        farthest = std::max(farthest, std::max(squared[0], squared[1]));
    }
    x.branch =
        stewart::assembly_branch(g, m.forward.sides, at.rotation, x.points,
                                 stewart::determinant_sign(x.factors), m.forward.working_sign);
    if (tracking) {
        x.jump = std::sqrt(farthest);
        if (x.jump > m.forward.shortest_stroke_range) x.branch |= STEWART_BRANCH_JUMP;
    }
    return STEWART_OK;
}

// sin and cos of `angle` from those of a nearby angle0: within 1e-9 rad the first-order terms
// leave an error below 5e-19, far under rounding (so within an ulp or two of libm's); libm
// farther away (an angle wrapped by turns).
void sincos_near(double angle, double angle0, double sin0, double cos0, double *sin_out,
                 double *cos_out) {
    const double d = angle - angle0;
    if (std::fabs(d) <= 1e-9) {
        *sin_out = sin0 + d * cos0;
        *cos_out = cos0 - d * sin0;
    } else {
        ::sincos(angle, sin_out, cos_out);
    }
}

// Rates and accelerations of the pose out (x's, corrected) through x's leg Jacobian; false
// (message) at pitch = +-90 deg or if anything overflows.
stewart_status derivatives(const stewart_model &m, const Found &x, const double *rates,
                           const double *accels, stewart_forward_output &out, char *msg,
                           size_t size) {
    const double *q = out.pose.q;
    if (rates) {  // (accelerations only with rates)
        // The corrected pose is within rounding of the iterate whose trig is known.
        stewart::PitchYawTrig at;
        sincos_near(q[4], x.angles[1], x.sin_angles[1], x.cos_angles[1], &at.sin_pitch,
                    &at.cos_pitch);
        sincos_near(q[5], x.angles[2], x.sin_angles[2], x.cos_angles[2], &at.sin_yaw, &at.cos_yaw);
        if (!stewart::pose_rates_from(x.factors, at, rates, out.pose.q_dot))
            return set_message(msg, size, STEWART_ERR_SINGULAR,
                               "pitch = %g rad is at +-90 deg: the roll and yaw rates are not "
                               "defined there",
                               q[4]);
        if (accels) {
            // L_ddot = J (a, c alpha_E) + the part of the leg accelerations from the velocities
            // alone: the leg accelerations at zero pose accelerations.
            double sin_roll, cos_roll, moving[6];
            sincos_near(q[3], x.angles[0], x.sin_angles[0], x.cos_angles[0], &sin_roll, &cos_roll);
            const stewart_status s =
                velocity_leg_accelerations(m.geometry, q, out.pose.q_dot, cos_roll, sin_roll, at,
                                           moving, msg, size);
            if (s != STEWART_OK) return s;
            double rhs[6];
            for (int k = 0; k < 6; ++k) rhs[k] = accels[k] - moving[k];
            stewart::pose_rates_from(x.factors, at, rhs, out.pose.q_ddot);
        }
    }
    return check_found(out.pose, "pose", msg, size);
}

// The accepted pose becomes the solver's last pose.
void remember(stewart::ForwardState &f, const Found &x, const stewart_forward_output &out,
              const double lengths[6], double time, bool from_guess, bool rates, bool accels) {
    f.has_previous = f.has_pose && !from_guess;  // a guess starts a new history
    f.previous_time = f.time;
    std::memcpy(f.previous_q, f.q, sizeof f.q);
    f.has_pose = true;
    f.time = time;
    f.has_rates = rates;
    f.has_accels = accels;
    std::memcpy(f.q, out.pose.q, sizeof f.q);
    std::memcpy(f.q_dot, out.pose.q_dot, sizeof f.q_dot);
    std::memcpy(f.q_ddot, out.pose.q_ddot, sizeof f.q_ddot);
    f.points = x.points;
    f.has_chord = true;
    f.chord = x.factors;
    std::memcpy(f.lengths, lengths, sizeof f.lengths);
    f.step = x.step;
}


// Whether the pose x (on the working mode's side of every check) is the one the lengths lead to:
// a proven step from the last pose (tracking) or from home (no history), else the pose reached
// from home along the straight path of lengths in proven steps. From home with another answer,
// that pose is taken (into walked, walked.start = -1: the caller's marker); from the last pose or
// a guess, x is refused (STEWART_BRANCH_UNPROVEN). STEWART_ERR_SINGULAR (message) when the path
// from home meets a singular pose and nothing else proves x.
stewart_status prove(const stewart_model &m, stewart::ForwardState &f,
                     const stewart_forward_options &o, const double lengths[6], bool tracking,
                     Found &x, Found &walked, char *msg, size_t size) {
    const stewart::PlatformGeometry &g = m.geometry;
    const double home[6] = {0, 0, m.params.home_height, 0, 0, 0};
    const bool from_home = x.start == STEWART_START_HOME;
    if (tracking || from_home) {
        const double *from_lengths = tracking ? f.lengths : m.forward.home_lengths;
        const stewart::ProvenStep &step = tracking ? f.step : m.forward.home_step;
        double change = 0;
        for (int k = 0; k < STEWART_LEGS; ++k)
            change = std::max(change, std::fabs(lengths[k] - from_lengths[k]));
        // The rotation angle between two Euler triples is at most the sum of the three angles'
        // changes (each elementary turn moves the rotation by its own angle): a bound on
        // pose_distance without trigonometry.
        const double *from = tracking ? f.q : home;
        double moved = 0;
        for (int i = 0; i < 3; ++i) moved = std::max(moved, std::fabs(x.q[i] - from[i]));
        const double turned =
            std::fabs(x.q[3] - from[3]) + std::fabs(x.q[4] - from[4]) + std::fabs(x.q[5] - from[5]);
        if (change + o.tolerance <= step.max_change &&
            std::max(moved, g.characteristic_length * turned) < step.radius)
            return STEWART_OK;
    }
    // Same pose: within the radius where the lengths have one pose, or a millionth of the
    // platform radius (both ends solved to the tolerance; near a singular pose that radius is
    // smaller than their rounding).
    const double same = std::max(x.step.radius, 1e-6 * g.characteristic_length);
    double reached[6];
    int steps = 0;
    char why[STEWART_MESSAGE_SIZE];
    // From the last pose along the straight path of lengths (tracking), then from home.
    if (tracking &&
        stewart::continue_lengths(g, *f.newton, f.q, f.lengths, lengths, o.tolerance, reached,
                                  steps, why, sizeof why) &&
        stewart::pose_distance(g, reached, x.q) <= same)
        return STEWART_OK;
    if (!stewart::continue_lengths(g, *f.newton, home, m.forward.home_lengths, lengths, o.tolerance,
                                   reached, steps, why, sizeof why))
        return set_message(msg, size, STEWART_ERR_SINGULAR,
                           "the pose found cannot be proven to be the one these lengths lead to: "
                           "%s; track the machine from a proven pose (samples close enough), or "
                           "give a guess",
                           why);
    if (stewart::pose_distance(g, reached, x.q) <= same) return STEWART_OK;
    if (!from_home) {
        x.branch |= STEWART_BRANCH_UNPROVEN;
        return STEWART_OK;
    }
    walked = x;
    std::memcpy(walked.q, reached, sizeof reached);
    stewart_status s = examine(m, f, o, f.newton->last(), false, walked, msg, size);
    if (s != STEWART_OK) return s;
    walked.start = -1;
    return STEWART_OK;
}
}  // namespace


namespace stewart {

stewart_status forward_constants(const PlatformGeometry &g, const stewart_params &p,
                                 ForwardConstants &f, char *msg, size_t size) {
    f.shortest_stroke_range = p.stroke_max[0] - p.stroke_min[0];
    for (int k = 1; k < STEWART_LEGS; ++k)
        f.shortest_stroke_range =
            std::min(f.shortest_stroke_range, p.stroke_max[k] - p.stroke_min[k]);
    f.sides = branch_sides(g, p.home_height);
    stewart_pose home{};
    home.q[2] = p.home_height;
    LegKinematics legs;
    stewart_status s = leg_kinematics(g, motion_of_pose(home), legs, msg, size);
    if (s != STEWART_OK) return s;
    LegJacobian J;
    leg_jacobian(g, legs, J);
    f.working_sign = jacobian_sign(J.transposed);
    if (f.working_sign == 0)
        return set_message(msg, size, STEWART_ERR_SINGULAR,
                           "the leg Jacobian is singular at the home pose: the working assembly "
                           "mode is not defined");
    f.pair_bounds = length_pair_bounds(g);
    f.arm = largest_arm(g);
    const double q_home[6] = {0, 0, p.home_height, 0, 0, 0};
    LegsAt at;
    evaluate_legs(g, q_home, q_home, at);  // (target unused: the lengths are read)
    for (int k = 0; k < STEWART_LEGS; ++k) f.home_lengths[k] = at.length[k];
    LegFactors factors;
    double norm1;
    if (factor_legs(g, at, factors, norm1))
        f.home_step = proven_step(g, inverse_norm1(factors), at.length.minCoeff(), f.arm, 0.0);
    return STEWART_OK;
}

// The saved history: a header (magic, version, size) then the fields in a fixed order.
namespace {

constexpr unsigned kHistoryMagic = 0x53544657u;  // "STFW"
constexpr unsigned kHistoryVersion = 3;          // 2: the chord's factors; 3: lengths, proven step
// times, q, q_dot, q_ddot, previous_q, points; the chord's LU, pitch and yaw trig, scale
constexpr size_t kHistoryDoubles = 2 + 6 * 4 + 18 + 36 + 4 + 1 + 6 + 2;
constexpr size_t kHistoryFlags = 5 + 6;  // has_pose .. has_chord; the chord's pivots
constexpr size_t kHistoryHeader = 3 * sizeof(unsigned);

}  // namespace

size_t forward_history_size() {
    return kHistoryHeader + kHistoryFlags + kHistoryDoubles * sizeof(double);
}

void forward_history_save(const ForwardState &f, unsigned char *buffer) {
    const unsigned header[3] = {kHistoryMagic, kHistoryVersion,
                                static_cast<unsigned>(forward_history_size())};
    std::memcpy(buffer, header, sizeof header);
    unsigned char *flags = buffer + kHistoryHeader;
    flags[0] = f.has_pose, flags[1] = f.has_rates, flags[2] = f.has_accels,
    flags[3] = f.has_previous, flags[4] = f.has_chord;
    for (int k = 0; k < 6; ++k) flags[5 + k] = static_cast<unsigned char>(f.chord.pivot[k]);
    double v[kHistoryDoubles];
    double *p = v;
    *p++ = f.time;
    *p++ = f.previous_time;
    for (const double *a : {f.q, f.q_dot, f.q_ddot, f.previous_q})
        for (int i = 0; i < 6; ++i) *p++ = a[i];
    for (int k = 0; k < STEWART_LEGS; ++k)  // (leg after leg)
        for (int i = 0; i < 3; ++i) *p++ = f.points.c[i][k];
    for (int i = 0; i < 36; ++i) *p++ = f.chord.lu[i];
    *p++ = f.chord.trig.cos_pitch, *p++ = f.chord.trig.sin_pitch;
    *p++ = f.chord.trig.cos_yaw, *p++ = f.chord.trig.sin_yaw;
    *p++ = f.chord.scale;
    for (int k = 0; k < 6; ++k) *p++ = f.lengths[k];
    *p++ = f.step.max_change, *p++ = f.step.radius;
    std::memcpy(flags + kHistoryFlags, v, sizeof v);
}

bool forward_history_load(ForwardState &f, const unsigned char *buffer, size_t size, char *msg,
                          size_t msg_size) {
    unsigned header[3];
    if (size < kHistoryHeader) {
        set_message(msg, msg_size, STEWART_ERR_ARGUMENT,
                    "%zu bytes: a saved forward history has %zu", size, forward_history_size());
        return false;
    }
    std::memcpy(header, buffer, sizeof header);
    if (header[0] != kHistoryMagic || header[1] != kHistoryVersion ||
        header[2] != forward_history_size() || size < forward_history_size()) {
        set_message(msg, msg_size, STEWART_ERR_ARGUMENT,
                    "not a forward history of this version (magic %#x, version %u, %u of %zu "
                    "bytes; expected %#x, %u, %zu)",
                    header[0], header[1], header[2], size, kHistoryMagic, kHistoryVersion,
                    forward_history_size());
        return false;
    }
    const unsigned char *flags = buffer + kHistoryHeader;
    for (size_t i = 0; i < 5; ++i)
        if (flags[i] > 1) {
            set_message(msg, msg_size, STEWART_ERR_ARGUMENT,
                        "forward history flag %zu is %d: it must be 0 or 1", i, flags[i]);
            return false;
        }
    double v[kHistoryDoubles];
    std::memcpy(v, flags + kHistoryFlags, sizeof v);
    for (size_t i = 0; i < kHistoryDoubles; ++i)
        if (!std::isfinite(v[i])) {
            set_message(msg, msg_size, STEWART_ERR_ARGUMENT,
                        "forward history value %zu is %g: it must be finite", i, v[i]);
            return false;
        }
    LegFactors chord = {};
    for (int k = 0; k < 6; ++k) chord.pivot[k] = flags[5 + k];
    const double *p = v + 2 + 6 * 4 + 18;
    for (int i = 0; i < 36; ++i) chord.lu[i] = *p++;
    chord.trig.cos_pitch = *p++, chord.trig.sin_pitch = *p++;
    chord.trig.cos_yaw = *p++, chord.trig.sin_yaw = *p++;
    chord.scale = *p++;
    double lengths[6];
    for (int k = 0; k < 6; ++k) lengths[k] = *p++;
    ProvenStep step;
    step.max_change = *p++, step.radius = *p++;
    if (flags[4] && !factors_usable(chord)) {
        set_message(msg, msg_size, STEWART_ERR_ARGUMENT,
                    "the forward history's leg Jacobian factors are not usable (a pivot out of "
                    "range, a zero on U's diagonal or a scale <= 0)");
        return false;
    }
    f.has_pose = flags[0], f.has_rates = flags[1], f.has_accels = flags[2],
    f.has_previous = flags[3], f.has_chord = flags[4];
    f.chord = chord;
    std::memcpy(f.lengths, lengths, sizeof lengths);
    f.step = step;
    p = v;
    f.time = *p++;
    f.previous_time = *p++;
    for (double *a : {f.q, f.q_dot, f.q_ddot, f.previous_q})
        for (int i = 0; i < 6; ++i) a[i] = *p++;
    for (int k = 0; k < STEWART_LEGS; ++k)
        for (int i = 0; i < 3; ++i) f.points.c[i][k] = *p++;
    return true;
}

}  // namespace stewart

extern "C" stewart_forward *stewart_forward_create(const stewart_model *m,
                                                   const stewart_forward_options *o, char *msg,
                                                   size_t size) {
    if (!stewart::create_arguments_ok(m, o, stewart_forward_options_check, msg, size))
        return nullptr;
    if (m->forward.working_sign == 0) {  // the model's constants say why
        stewart::ForwardConstants again;
        stewart::forward_constants(m->geometry, m->params, again, msg, size);
        return nullptr;
    }
    stewart_forward *d = new (std::nothrow) stewart_forward;
    if (!d || !d->state.newton || !d->state.newton->ok()) {
        set_message(msg, size, STEWART_ERR_MEMORY, "out of memory creating the forward solver");
        delete d;
        return nullptr;
    }
    d->model = m;
    d->options = *o;
    d->message[0] = '\0';
    return d;
}

extern "C" void stewart_forward_free(stewart_forward *d) { delete d; }

extern "C" void stewart_forward_reset(stewart_forward *d) {
    if (!d) return;
    d->message[0] = '\0';
    d->state.reset();
}

extern "C" stewart_status stewart_forward_copy(stewart_forward *dst, const stewart_forward *src) {
    const stewart_status checked = stewart::copy_arguments_ok(dst, src, "forward solvers");
    if (checked != STEWART_OK) return checked;
    std::memcpy(dst->message, src->message, sizeof dst->message);
    // The history; the Newton solver's workspace is rebuilt by every solve.
    stewart::ForwardState &d = dst->state;
    const stewart::ForwardState &s = src->state;
    d.has_pose = s.has_pose, d.has_rates = s.has_rates, d.has_accels = s.has_accels;
    d.has_previous = s.has_previous;
    d.time = s.time, d.previous_time = s.previous_time;
    std::memcpy(d.q, s.q, sizeof d.q);
    std::memcpy(d.q_dot, s.q_dot, sizeof d.q_dot);
    std::memcpy(d.q_ddot, s.q_ddot, sizeof d.q_ddot);
    std::memcpy(d.previous_q, s.previous_q, sizeof d.previous_q);
    d.points = s.points;
    d.has_chord = s.has_chord;
    d.chord = s.chord;
    std::memcpy(d.lengths, s.lengths, sizeof d.lengths);
    d.step = s.step;
    return STEWART_OK;
}

extern "C" size_t stewart_forward_state_size(const stewart_forward *d) {
    return d ? stewart::forward_history_size() : 0;
}

extern "C" stewart_status stewart_forward_save(const stewart_forward *d, void *buffer,
                                               size_t size) {
    if (!d) return STEWART_ERR_ARGUMENT;
    if (!buffer || size < stewart::forward_history_size())
        return set_message(d->message, sizeof d->message, STEWART_ERR_ARGUMENT,
                           "state not saved: a buffer of %zu bytes%s, the state needs %zu", size,
                           buffer ? "" : " (NULL)", stewart::forward_history_size());
    stewart::forward_history_save(d->state, static_cast<unsigned char *>(buffer));
    return STEWART_OK;
}

extern "C" stewart_status stewart_forward_load(stewart_forward *d, const void *buffer,
                                               size_t size) {
    if (!d) return STEWART_ERR_ARGUMENT;
    if (!buffer)
        return set_message(d->message, sizeof d->message, STEWART_ERR_ARGUMENT, "buffer is NULL");
    char why[STEWART_MESSAGE_SIZE];
    // Every field is checked before any is written: a refused history leaves the solver as it was.
    if (!stewart::forward_history_load(d->state, static_cast<const unsigned char *>(buffer), size,
                                       why, sizeof why))
        return set_message(d->message, sizeof d->message, STEWART_ERR_ARGUMENT,
                           "state not loaded (the forward solver is unchanged): %s", why);
    d->message[0] = '\0';
    return STEWART_OK;
}

extern "C" const char *stewart_forward_message(const stewart_forward *d) {
    return d ? d->message : "forward is NULL";
}

extern "C" const stewart_model *stewart_forward_model(const stewart_forward *d) {
    return d ? d->model : nullptr;
}

extern "C" const stewart_forward_options *stewart_forward_options_of(const stewart_forward *d) {
    return d ? &d->options : nullptr;
}

namespace {

// One forward call's input, checked: the time, the Cardan-to-Cardan lengths, the rates and
// accelerations given (or null) and the guess of the platform's pose (or null).
struct CheckedInput {
    double time;
    double lengths[STEWART_LEGS];
    const double *rates, *accels, *guess;
    double platform_guess[6];  // the guess in the platform's frames, where the frames move it
};

// The input of stewart_forward_solve, every value finite and the lengths reachable; else the
// message of the first that is not.
stewart_status check_input(const stewart_model &m, const stewart_forward_input &input,
                           CheckedInput &in, char *msg, size_t size) {
    if (input.derivatives < 0 || input.derivatives > 2)
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "derivatives is %d: it must be 0 (lengths), 1 (and rates) or 2 (and "
                           "accelerations)",
                           input.derivatives);
    in.time = input.time;
    in.rates = input.derivatives >= 1 ? input.lengths.length_rate : nullptr;
    in.accels = input.derivatives >= 2 ? input.lengths.length_accel : nullptr;
    in.guess = input.use_guess ? input.guess : nullptr;
    stewart_status s;
    if (!std::isfinite(in.time))
        return set_message(msg, size, STEWART_ERR_ARGUMENT, "time is %g: it must be finite",
                           in.time);
    // The lengths given are the sensors' readings; the Cardan-to-Cardan ones add the offsets.
    if ((s = cardan_lengths(m, input.lengths.length, in.lengths, msg, size)) != STEWART_OK)
        return s;
    if (in.rates && (s = check_values(in.rates, "L_dot", false, msg, size)) != STEWART_OK) return s;
    if (in.accels && (s = check_values(in.accels, "L_ddot", false, msg, size)) != STEWART_OK)
        return s;
    if (in.guess)
        for (int i = 0; i < 6; ++i)
            if (!std::isfinite(in.guess[i]))
                return set_message(msg, size, STEWART_ERR_ARGUMENT,
                                   "guess %s is %g: it must be finite", stewart::kPoseNames[i],
                                   in.guess[i]);
    if (in.guess && !m.frames.identity) {  // the guess is the tool's pose in the user frame
        stewart::platform_pose(m.frames, in.guess, nullptr, in.platform_guess, nullptr);
        for (int i = 0; i < 6; ++i)
            if (!std::isfinite(in.platform_guess[i]))
                return set_message(msg, size, STEWART_ERR_ARGUMENT,
                                   "guess %s = %g is out of range: the platform's pose it gives "
                                   "(tool and user frames) overflows",
                                   stewart::kPoseNames[i], in.guess[i]);
        in.guess = in.platform_guess;
    }
    return stewart::check_length_pairs(m.forward.pair_bounds, in.lengths, msg, size);
}

// The starts, in order, into starts (returns how many): the guess alone; or, tracking, the
// predictor then the last pose; or home.
int choose_starts(const stewart::ForwardState &f, const CheckedInput &in, int starts[2]) {
    int n = 0;
    if (in.guess) {
        starts[n++] = STEWART_START_GUESS;
    } else if (f.has_pose) {
        if (in.time > f.time && (f.has_rates || (f.has_previous && f.time > f.previous_time)))
            starts[n++] = STEWART_START_PREDICTOR;
        starts[n++] = STEWART_START_LAST;
    } else {
        starts[n++] = STEWART_START_HOME;
    }
    return n;
}

// How far start_q is from the last pose, where the chord step's Jacobian was factored: the
// largest coordinate's move, positions in units of the characteristic length. (Two coordinates
// at a time; the maximum is exact in any order; a NaN is ignored.)
double chord_drift(const stewart_model &m, const stewart::ForwardState &f,
                   const double start_q[6]) {
    const double c = m.geometry.characteristic_length;
    const stewart::Pair per[3] = {{c, c}, {c, 1.0}, {1.0, 1.0}};
    double drift = 0;
    for (int i = 0; i < 6; i += 2) {
        using stewart::load_pair;
        const stewart::Pair moved =
            stewart::abs_pair(load_pair(start_q + i) - load_pair(f.q + i)) / per[i / 2];
        drift = std::max(std::max(drift, moved[0]), moved[1]);
    }
    return drift;
}

// The poses Newton found from the starts: the first on the working mode is chosen, else the
// first converged (chosen -1 then).
struct Attempts {
    Found found[2];
    int n_found = 0, chosen = -1, iterations = 0;
    stewart_status last_error = STEWART_OK;  // its message is the last attempt's
};

// Newton from each start in turn until a pose on the working mode is found.
void solve_from_starts(const stewart_model &m, stewart::ForwardState &f,
                       const stewart_forward_options &o, const CheckedInput &in,
                       const int starts[2], int n_starts, Attempts &a, char *msg, size_t size) {
    const bool tracking = !in.guess && f.has_pose;
    for (int k = 0; k < n_starts && a.chosen < 0; ++k) {
        Found &x = a.found[a.n_found];
        double start_q[6];
        start_pose(m, f, starts[k], in.time, in.guess, start_q);
        std::memcpy(x.q, start_q, sizeof start_q);
        stewart::NewtonStats stats;
        // Tracking, the first step takes the Jacobian factored at the last pose.
        const stewart::LegFactors *chord =
            starts[k] == STEWART_START_PREDICTOR && f.has_chord ? &f.chord : nullptr;
        const double drift = chord ? chord_drift(m, f, start_q) : 0;
        stewart_status &error = a.last_error;
        error = f.newton->solve(m.geometry, in.lengths, o.tolerance, o.max_iterations, chord, drift,
                                x.q, stats, msg, size);
        a.iterations += stats.iterations;
        if (error == STEWART_OK) error = examine(m, f, o, f.newton->last(), tracking, x, msg, size);
        else if (std::isfinite(stats.residual) &&  // Newton creeping toward a singular pose
                 examine(m, f, o, f.newton->last(), tracking, x, msg, size) == STEWART_ERR_SINGULAR)
            error = STEWART_ERR_SINGULAR;
        if (error != STEWART_OK) continue;
        // Angles within half a turn of the start's: the same rotation, the continuous angles.
        // (Inside half a turn the remainder is the difference itself, exactly: no libm call.)
        for (int i = 3; i < 6; ++i) {
            const double turned = x.q[i] - start_q[i];
            x.q[i] =
                start_q[i] + (std::fabs(turned) < kPi ? turned : std::remainder(turned, 2 * kPi));
        }
        x.start = starts[k];
        if (x.branch == 0) a.chosen = a.n_found;
        ++a.n_found;
    }
}

// The legs whose length is outside their stroke, a bit each. (Two legs at a time; then which.)
int legs_beyond_stroke(const stewart_params &p, const double lengths[STEWART_LEGS]) {
    stewart::PairBits beyond = {0, 0};
    for (int k = 0; k < STEWART_LEGS; k += 2)
        beyond |= (stewart::load_pair(lengths + k) < stewart::load_pair(p.stroke_min + k)) |
                  (stewart::load_pair(lengths + k) > stewart::load_pair(p.stroke_max + k));
    int legs = 0;
    for (int k = 0; stewart::any(beyond) && k < STEWART_LEGS; ++k)
        if (lengths[k] < p.stroke_min[k] || lengths[k] > p.stroke_max[k]) legs |= 1 << k;
    return legs;
}

// The pose found at x as the answer: one more Newton correction with the exact Jacobian the
// rates need anyway (the pose then sits at rounding level even when KINSOL stopped just under the
// tolerance), its rates and accelerations, statistics and warnings, shown in the caller's frames
// in result; refused if it is on another assembly mode, else remembered for tracking.
stewart_status answer(const stewart_model &m, stewart::ForwardState &f,
                      const stewart_forward_options &o, const CheckedInput &in, Found &x,
                      int iterations, stewart_forward_output &result, char *msg, size_t size) {
    stewart_forward_output out{};
    double step[6];
    std::memcpy(out.pose.q, x.q, sizeof x.q);
    if (stewart::pose_rates_from(x.factors, x.factors.trig, x.residual.data(), step))
        for (int i = 0; i < 6; ++i) out.pose.q[i] -= step[i];
    stewart_status s;
    if ((s = derivatives(m, x, in.rates, in.accels, out, msg, size)) != STEWART_OK) return s;
    out.iterations = iterations;
    out.residual = x.residual.cwiseAbs().maxCoeff();
    out.condition = x.condition;
    out.branch = x.branch;
    out.jump = x.jump;
    out.start = x.start;
    out.stroke_legs = legs_beyond_stroke(m.params, in.lengths);
    if (out.stroke_legs) out.warnings |= STEWART_WARN_STROKE;
    if (out.condition > o.warn_condition) out.warnings |= STEWART_WARN_NEAR_SINGULAR;
    const int derivatives_given = in.accels ? 2 : in.rates ? 1 : 0;
    if ((s = shown_pose(m, out, derivatives_given, result, msg, size)) != STEWART_OK) return s;
    if (x.branch != 0) {
        result.warnings |= STEWART_WARN_OTHER_BRANCH;
        return set_message(msg, size, STEWART_ERR_OTHER_BRANCH,
                           "the pose found from the %s is on another assembly mode: %s (z = %g "
                           "m); not taken as the answer",
                           start_name(x.start), branch_reason(x.branch), x.q[2]);
    }
    remember(f, x, out, in.lengths, in.time, in.guess != nullptr, in.rates != nullptr,
             in.accels != nullptr);
    msg[0] = '\0';
    return STEWART_OK;
}

}  // namespace

extern "C" stewart_status stewart_forward_solve(stewart_forward *d,
                                                const stewart_forward_input *input,
                                                stewart_forward_output *result) {
    if (!d || !input || !result) {
        if (d) set_message(d->message, sizeof d->message, STEWART_ERR_ARGUMENT, "NULL argument");
        return STEWART_ERR_ARGUMENT;
    }
    const stewart_model &m = *d->model;
    char *msg = d->message;
    const size_t size = sizeof d->message;
    CheckedInput in;
    stewart_status s;
    if ((s = check_input(m, *input, in, msg, size)) != STEWART_OK) return s;
    int starts[2];
    const int n_starts = choose_starts(d->state, in, starts);
    Attempts a;
    solve_from_starts(m, d->state, d->options, in, starts, n_starts, a, msg, size);
    if (a.n_found == 0) return a.last_error;  // the message is the last attempt's
    if (a.chosen < 0) a.chosen = 0;
    Found &found = a.found[a.chosen], walked;
    if (found.branch == 0) {  // on the working mode's side of every check: is it the lengths' pose?
        const bool tracking = !in.guess && d->state.has_pose;
        s = prove(m, d->state, d->options, in.lengths, tracking, found, walked, msg, size);
        if (s != STEWART_OK) return s;
    }
    Found &x = found.branch == 0 && walked.start == -1 ? walked : found;
    if (x.start == -1) x.start = STEWART_START_LAST;  // reached from home in proven steps
    return answer(m, d->state, d->options, in, x, a.iterations, *result, msg, size);
}
