// The plant's C API (stewart_plant.h): state in roll-pitch-yaw outside, quaternion and twist
// inside; input checks; stroke warnings; statistics.
#include <cfloat>
#include <cmath>
#include <cstring>

#include "limits/limit_check.hpp"
#include "model.hpp"
#include "plant/plant_integrator.hpp"
#include "plant/plant_object.hpp"
#include "plant/plant_reactions.hpp"
#include "stewart/stewart_plant.h"
#include "stewart/stewart_table.h"
#include "util/create.hpp"
#include "util/message.hpp"

using stewart::clear_message;
using stewart::set_message;
namespace plant = stewart::plant;

namespace {

// time, the states, angles, forces, warnings, step hint (the windings' currents among the states
// only where they are states: kSavedDoubles without them)
constexpr int kSavedDoubles = 1 + plant::kStates + 3 + STEWART_LEGS + 1 + 1;
constexpr int kMaxSavedDoubles = kSavedDoubles + (plant::kMaxStates - plant::kStates);
using plant::kMinCosPitch;
// The plant's range (docs/forward-dynamics.md section 4): speeds far beyond any platform's, below
// which a 1 ms step stays within the default max_internal_steps; continuous roll and yaw within
// +-1e12 rad, where 2 pi still has digits to spare.
constexpr double kMaxSpeed = 1e3;       // [m/s] of the platform origin, [rad/s] of omega
constexpr double kMaxTurnAngle = 1e12;  // [rad]
// The smallest first internal step a step may start with: below it SUNDIALS' products of step
// sizes underflow (a saved hint of 4.9e-324 s left ARKODE unable to step).
constexpr double kMinStepSize = 1e-100;  // [s]
// The plant's clock: within +-1e10 s (317 years) a step of 1e-5 s still advances time by
// itself to 1 part in 5.
constexpr double kMaxTime = 1e10;  // [s]
using stewart::kPoseNames;

}  // namespace

// struct stewart_plant: plant/plant_object.hpp (the derivative call shares it).

namespace stewart {
namespace plant {

// The plant's equations read the model through this copy (plant_equations.hpp), made here where
// the model's layout is known (model.hpp is for the API files).
DynamicsModel dynamics_model(const stewart_model &model, int fidelity) {
    DynamicsModel d;
    const stewart_params &p = model.params;
    const FullLayout &l = model.full_layout;
    d.legs.base_points = model.geometry.base_points;
    d.legs.platform_points = model.geometry.platform_points;
    d.legs.base_arm = l.base_arm;
    d.legs.platform_arm = l.platform_arm;
    d.legs.cylinder_com = p.cylinder_com;
    d.legs.piston_com = p.piston_com;
    d.legs.min_length = model.geometry.min_length;
    d.legs.min_cardan_sin = 1e-9;
    d.with_legs = fidelity == STEWART_FULL;
    d.platform_mass = model.platform.mass;
    d.platform_com = model.platform.com;
    d.platform_inertia = model.platform.inertia;
    d.platform_inertia_inverse = model.platform.inertia.inverse();
    d.cylinder_mass = p.cylinder_mass;
    d.piston_mass = p.piston_mass;
    d.cylinder_inertia = Vec3(p.cylinder_inertia);
    d.piston_inertia = Vec3(p.piston_inertia);
    d.gravity = model.gravity;
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < STEWART_LEGS; ++k) {
            d.platform_point_rows[i][k] = d.legs.platform_points(i, k);
            d.base_point_rows[i][k] = d.legs.base_points(i, k);
        }
    return d;
}

}  // namespace plant
}  // namespace stewart

namespace {

// The warnings a plant sets.
constexpr int kPlantWarnings =
    STEWART_WARN_STROKE | STEWART_WARN_JOINT_LIMIT | STEWART_WARN_INTERFERENCE;

// omega = E(pitch, yaw) * (roll, pitch, yaw)_dot (kinematics/motion.hpp).
plant::Mat3 rate_matrix(double pitch, double yaw) {
    return stewart::angle_rate_matrix(std::cos(pitch), std::sin(pitch), std::cos(yaw),
                                      std::sin(yaw));
}

// Lengths, their rates, the stroke check: bit k of the result set when leg k+1 is outside.
int leg_outputs(const stewart_plant &p, const stewart::Motion &m, double length[6],
                double rate[6]) {
    const stewart_params &par = p.model->params;
    int stroke_legs = 0;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const plant::Vec3 arm = m.rotation * p.dynamics.legs.platform_points.col(k);
        const plant::Vec3 d = m.position + arm - p.dynamics.legs.base_points.col(k);
        length[k] = d.norm();
        rate[k] = d.dot(m.velocity + m.omega.cross(arm)) / length[k];
        if (length[k] < par.stroke_min[k] || length[k] > par.stroke_max[k]) stroke_legs |= 1 << k;
    }
    return stroke_legs;
}

// Every leg's vector p + R b_k - a_k at the platform's motion m (Eigen's arithmetic).
void leg_vectors(const stewart_plant &p, const stewart::Motion &m, double d[STEWART_LEGS][3]) {
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const plant::Vec3 &a = p.dynamics.legs.base_points.col(k),
                          &b = p.dynamics.legs.platform_points.col(k);
        const plant::Vec3 v = m.position + m.rotation * b - a;
        for (int i = 0; i < 3; ++i) d[k][i] = v[i];
    }
}

// STEWART_WARN_JOINT_LIMIT and STEWART_WARN_INTERFERENCE as they hold at the platform's pose
// (its state's position and rotation: the roll-pitch-yaw pose's verdicts to rounding distance
// from a limit, without the angles' sines and cosines). clearance: the plant's, kept from step
// to step (the same verdicts, without the check near a pose far from every limit), or nullptr.
int limit_warnings(const stewart_plant &p, const stewart::Motion &m,
                   stewart::LimitClearance *clearance = nullptr) {
    const int failed =
        clearance ? stewart::platform_limit_failures(p.limits, m.position, m.rotation, *clearance)
                  : stewart::platform_limit_failures(p.limits, m.position, m.rotation);
    const int joints =
        1 << (STEWART_LIMIT_BASE_JOINT - 1) | 1 << (STEWART_LIMIT_PLATFORM_JOINT - 1);
    return (failed & joints ? STEWART_WARN_JOINT_LIMIT : 0) |
           (failed & 1 << (STEWART_LIMIT_INTERFERENCE - 1) ? STEWART_WARN_INTERFERENCE : 0);
}

// The 13 bodies' motion (accelerations included) under the given forces (NULL: the last step's);
// STEWART_ERR_ARGUMENT for a force that is not finite, STEWART_ERR_SINGULAR at a singular pose.
// known: the equations already evaluated at this state and these forces (or nullptr: then
// evaluated into e; e is left as it was otherwise). platform: the platform's motion, if wanted.
// state_motion: motion_of_state(p.y) if the caller has it (or nullptr).
stewart_status all_bodies(const stewart_plant &p, const double *force, plant::Evaluation &e,
                          stewart::Motion bodies[STEWART_PLANT_BODIES],
                          const plant::Evaluation *known = nullptr,
                          stewart::Motion *platform = nullptr,
                          const stewart::Motion *state_motion = nullptr) {
    if (!force) force = p.force;
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (!std::isfinite(force[k])) return STEWART_ERR_ARGUMENT;
    stewart::Motion m = state_motion ? *state_motion : plant::motion_of_state(p.y);
    if (!known) {
        e.winding_current = p.y + plant::kStates;
        if (!plant::twist_rate(p.dynamics, m, force, e)) return STEWART_ERR_SINGULAR;
        known = &e;
    }
    m.acceleration = known->twist_rate.head<3>();
    m.alpha = known->twist_rate.tail<3>();
    if (bodies) plant::body_motions(p.dynamics, m, *known, bodies);  // nullptr: not wanted
    if (platform) *platform = m;
    return STEWART_OK;
}

// 0 if the n values are all finite, else NaN: the sum of v * 0 (NaN for an infinite or NaN v),
// one pass without a branch per value.
inline double zero_if_finite(const double *values, int n) {
    double sum = 0;
    for (int i = 0; i < n; ++i) sum += values[i] * 0.0;
    return sum;
}

stewart_status check_finite(const double *values, const char *name, char *msg, size_t size) {
    if (zero_if_finite(values, STEWART_LEGS) == 0) return STEWART_OK;
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (!std::isfinite(values[k]))
            return set_message(msg, size, STEWART_ERR_ARGUMENT, "%s[%d] = %g must be finite", name,
                               k + 1, values[k]);
    return STEWART_OK;
}

// Why a state (time and angles aside) is outside the plant's range, or STEWART_OK: the speeds
// and the continuous roll and yaw; `what` says whose state it is.
stewart_status check_range(const double y[plant::kStates], const double angles[3], const char *what,
                           char *msg, size_t size) {
    const plant::Vec3 velocity(y[7], y[8], y[9]), omega(y[10], y[11], y[12]);
    if (!(velocity.norm() <= kMaxSpeed))
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "%s: the speed |v| = %g m/s is beyond the plant's range (%g m/s)", what,
                           velocity.norm(), kMaxSpeed);
    if (!(omega.norm() <= kMaxSpeed))
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "%s: the angular speed |omega| = %g rad/s is beyond the plant's range "
                           "(%g rad/s)",
                           what, omega.norm(), kMaxSpeed);
    for (int i : {0, 2})
        if (!(std::fabs(angles[i]) <= kMaxTurnAngle))
            return set_message(msg, size, STEWART_ERR_ARGUMENT,
                               "%s: %s = %g rad is beyond +-%g rad", what, kPoseNames[3 + i],
                               angles[i], kMaxTurnAngle);
    return STEWART_OK;
}

// Whether saved roll, pitch, yaw are the angles of the saved quaternion (roll and yaw on any
// branch): to a few roundings of the angle.
bool angles_match(const double y[plant::kStates], const double saved[3]) {
    double principal[3];
    const double zero[3] = {0, 0, 0};
    stewart::angles_of_rotation(plant::motion_of_state(y).rotation, zero, principal);
    for (int i = 0; i < 3; ++i) {
        const double off =
            i == 1 ? saved[i] - principal[i] : std::remainder(saved[i] - principal[i], 2 * M_PI);
        if (!(std::fabs(off) <= 1e-9 + 8 * DBL_EPSILON * std::fabs(saved[i]))) return false;
    }
    return true;
}

// A plant's state without its integrator and counters: what a rollback puts back.
struct PlantState {
    double time;
    double y[plant::kMaxStates];
    double angles[3];
    double force[STEWART_LEGS];
    int warnings;
    double step_hint;
};

// The fields a rollback keeps, from one holder (a plant or a PlantState) to the other.
template <class To, class From>
void copy_rollback_fields(To &to, const From &from) {
    to.time = from.time;
    std::memcpy(to.y, from.y, sizeof to.y);
    std::memcpy(to.angles, from.angles, sizeof to.angles);
    std::memcpy(to.force, from.force, sizeof to.force);
    to.warnings = from.warnings;
    to.step_hint = from.step_hint;
}

PlantState state_of(const stewart_plant &p) {
    PlantState s;
    copy_rollback_fields(s, p);
    return s;
}

// Sets time, the platform's pose (angles within (-pi/2, pi/2) of pitch) and its rates, checked
// (stewart_plant_set_state's statuses and messages).
stewart_status start_at(stewart_plant &p, double time, const double pose[6], const double rate[6]);

// The pose and rates the outputs show at state y (motion m) with continuous angles (those of
// m's rotation): the tool's in the user frame (the platform's when the frames are identity).
// False at the tool's pitch +-90 deg.
bool shown_pose(const stewart_plant &p, const double y[plant::kStates], const stewart::Motion &m,
                const double angles[3], stewart_pose &pose) {
    double angle_rates[3];  // from the rotation: no sines and cosines of the angles
    stewart::angle_rates_of_rotation(m.rotation, m.omega, angle_rates);
    stewart_pose platform{};
    for (int i = 0; i < 3; ++i) {
        platform.q[i] = y[i];
        platform.q[3 + i] = angles[i];
        platform.q_dot[i] = y[7 + i];
        platform.q_dot[3 + i] = angle_rates[i];
    }
    if (p.model->frames.identity) {
        pose = platform;
        return true;
    }
    return stewart::tool_pose(p.model->frames, platform, 1, pose, kMinCosPitch);
}

void restore_state(stewart_plant &p, const PlantState &s) {
    p.step_end_valid = false;
    copy_rollback_fields(p, s);
}

}  // namespace

extern "C" void stewart_plant_options_default(stewart_plant_options *o) {
    if (!o) return;
    // the option table's defaults (stewart_table.h), where the FMU's and the Python API's are read
#define PLANT_OPTION_DEFAULT(id, name, type, unit, min, min_closed, max, max_closed, value, text) \
    o->name = value;
    STEWART_PLANT_OPTION_TABLE(PLANT_OPTION_DEFAULT)
#undef PLANT_OPTION_DEFAULT
}

// stewart_plant_options_check: table/options.cpp, from the option table.

extern "C" stewart_plant *stewart_plant_create(const stewart_model *model,
                                               const stewart_plant_options *options, char *msg,
                                               size_t size) {
    stewart_plant *p =
        stewart::new_object_for<stewart_plant>(model, options, stewart_plant_options_check, "plant",
                                               msg, size);
    if (!p) return nullptr;
    p->limits = stewart::limit_constants(model->params, model->geometry, HUGE_VAL);
    p->dynamics = plant::dynamics_model(*model, options->fidelity);
    if (plant::drive_model(model->params, *options, p->dynamics.drives, msg, size) != STEWART_OK) {
        delete p;
        return nullptr;
    }
    if (!p->integrator.init(&p->dynamics, *options, msg, size)) {
        delete p;
        return nullptr;
    }
    const double home[6] = {0, 0, model->params.home_height, 0, 0, 0}, rest[6] = {0};
    if (start_at(*p, 0.0, home, rest) != STEWART_OK) {
        set_message(msg, size, STEWART_ERR_PARAMETER, "home pose: %s", p->message);
        delete p;
        return nullptr;
    }
    // SUNDIALS allocates some workspaces at the first step: take one here, on a copy, so that
    // no step of the caller allocates.
    plant::ForceProfile rest_forces;
    rest_forces.h = 1e-6;
    double y[plant::kMaxStates], hint = 0;
    for (int i = 0; i < plant::kMaxStates; ++i) y[i] = p->y[i];
    char why[STEWART_MESSAGE_SIZE];
    if (p->integrator.advance(y, rest_forces, hint, why, sizeof why) != STEWART_OK) {
        set_message(msg, size, STEWART_ERR_PARAMETER,
                    "a first step at rest at the home pose fails with these parameters and "
                    "options (gravity = (%g, %g, %g) m/s2, relative_tolerance = %g, "
                    "absolute_tolerance = %g): %s",
                    model->params.gravity[0], model->params.gravity[1], model->params.gravity[2],
                    options->relative_tolerance, options->absolute_tolerance, why);
        delete p;
        return nullptr;
    }
    clear_message(msg, size);
    return p;
}

extern "C" void stewart_plant_free(stewart_plant *p) { delete p; }

extern "C" void stewart_plant_reset(stewart_plant *p) {
    if (!p) return;
    const double home[6] = {0, 0, p->model->params.home_height, 0, 0, 0}, rest[6] = {0};
    start_at(*p, 0.0, home, rest);  // accepted when the plant was made
    p->stats = stewart_plant_statistics{};
    p->message[0] = '\0';
}

extern "C" stewart_status stewart_plant_copy(stewart_plant *dst, const stewart_plant *src) {
    const stewart_status checked = stewart::copy_arguments_ok(dst, src, "plants");
    if (checked != STEWART_OK) return checked;
    restore_state(*dst, state_of(*src));
    std::memcpy(dst->message, src->message, sizeof dst->message);
    return STEWART_OK;
}

extern "C" stewart_status stewart_plant_set_state(stewart_plant *p, double time,
                                                  const double pose[6], const double rate[6]) {
    const stewart_status checked = stewart::call_arguments_ok(p, pose, rate, "pose or rates");
    if (checked != STEWART_OK) return checked;
    char *msg = p->message;
    const size_t size = sizeof p->message;
    if (!(std::fabs(time) <= kMaxTime))
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "time = %g s must be finite and within +-%g s", time, kMaxTime);
    for (int i = 0; i < 6; ++i) {
        if (!std::isfinite(pose[i]))
            return set_message(msg, size, STEWART_ERR_ARGUMENT, "%s0 = %g must be finite",
                               kPoseNames[i], pose[i]);
        if (!std::isfinite(rate[i]))
            return set_message(msg, size, STEWART_ERR_ARGUMENT, "%s_dot0 = %g must be finite",
                               kPoseNames[i], rate[i]);
    }
    if (!(std::fabs(std::cos(pose[4])) > kMinCosPitch))
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "pitch0 = %g is at +-90 degrees, where roll and yaw are undefined",
                           pose[4]);
    // Beyond +-90 degrees the same rotation is (roll + pi, +-pi - pitch, yaw + pi), the triple
    // the outputs would show: refused rather than silently renamed.
    if (!(std::fabs(pose[4]) < M_PI / 2))
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "pitch0 = %g rad must be within (-pi/2, pi/2)", pose[4]);
    const stewart::Frames &frames = p->model->frames;
    if (frames.identity) return start_at(*p, time, pose, rate);
    // The pose given is the tool's in the user frame; the plant integrates the platform's.
    double platform_q[6], platform_rate[6];
    if (!stewart::platform_pose(frames, pose, rate, platform_q, platform_rate, kMinCosPitch))
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "this tool pose puts the platform's pitch at +-90 degrees (tool_frame, "
                           "user_frame), where its roll and yaw are undefined");
    for (int i = 0; i < 6; ++i)
        if (!std::isfinite(platform_q[i]) || !std::isfinite(platform_rate[i]))
            return set_message(msg, size, STEWART_ERR_ARGUMENT,
                               "%s0 = %g, %s_dot0 = %g are out of range: the platform's pose or "
                               "rates they give (tool and user frames) overflow",
                               kPoseNames[i], pose[i], kPoseNames[i], rate[i]);
    return start_at(*p, time, platform_q, platform_rate);
}

namespace {

stewart_status start_at(stewart_plant &plant, double time, const double pose[6],
                        const double rate[6]) {
    stewart_plant *p = &plant;
    char *msg = p->message;
    const size_t size = sizeof p->message;
    const plant::Mat3 R = stewart::rotation_from_rpy(pose[3], pose[4], pose[5]);
    const plant::Vec3 omega =
        rate_matrix(pose[4], pose[5]) * plant::Vec3(rate[3], rate[4], rate[5]);
    // Finite angle rates near DBL_MAX can overflow the angular velocity (found by the fuzz
    // target: such a state could be set, but not saved and loaded back).
    if (!omega.allFinite())
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "roll_dot0, pitch_dot0, yaw_dot0 = %g, %g, %g rad/s overflow the "
                           "angular velocity",
                           rate[3], rate[4], rate[5]);
    double y[plant::kMaxStates] = {0};  // the windings start without current
    const Eigen::Quaterniond q(R);
    const double yq[7] = {pose[0], pose[1], pose[2], q.w(), q.x(), q.y(), q.z()};
    for (int i = 0; i < 7; ++i) y[i] = yq[i];
    for (int i = 0; i < 3; ++i) y[7 + i] = rate[i], y[10 + i] = omega[i];
    stewart_status range;
    if ((range = check_range(y, pose + 3, "start state", msg, size)) != STEWART_OK) return range;
    // The pose must give every leg a direction (and, full level, unlocked Cardans).
    plant::Evaluation e;
    const double zero[STEWART_LEGS] = {0};
    e.winding_current = y + plant::kStates;
    if (!plant::twist_rate(p->dynamics, plant::motion_of_state(y), zero, e))
        return set_message(msg, size,
                           e.fault == plant::LegFault::ZeroLength ? STEWART_ERR_UNREACHABLE
                                                                  : STEWART_ERR_SINGULAR,
                           "the start pose is singular: leg %d %s", e.fault_leg + 1,
                           e.fault == plant::LegFault::ZeroLength ? "has zero length"
                                                                  : "lies along a Cardan arm");
    p->time = time;
    p->step_end_valid = false;
    for (int i = 0; i < plant::kMaxStates; ++i) p->y[i] = y[i];
    for (int i = 0; i < 3; ++i) p->angles[i] = pose[3 + i];
    for (int k = 0; k < STEWART_LEGS; ++k) p->force[k] = 0;
    p->step_hint = 0;
    double length[6], length_rate[6];
    msg[0] = '\0';
    const stewart::Motion m = plant::motion_of_state(y);
    p->warnings =
        (leg_outputs(*p, m, length, length_rate) ? STEWART_WARN_STROKE : 0) | limit_warnings(*p, m);
    return STEWART_OK;
}

}  // namespace

namespace {
// The legs' lengths (Cardan to Cardan), rates and stroke bits (leg_outputs) at a state.
struct LegOutputs {
    double length[STEWART_LEGS], rate[STEWART_LEGS];
    int stroke_legs;
};

// stewart_plant_output_get with what the step already knows (defined below it).
stewart_status output_of(const stewart_plant *p, const double *force,
                         const plant::Evaluation *known, int limit_bits, const LegOutputs *legs,
                         stewart_plant_output *out, const stewart::Motion *state_motion = nullptr);

// STEWART_OK, or STEWART_ERR_ARGUMENT saying what of a step's input is refused: the choice of
// derivatives, a step h that does not advance time or takes it out of range, a force or force
// rate that is not finite.
stewart_status check_step_input(const stewart_plant &p, const stewart_plant_input &input, char *msg,
                                size_t size) {
    if (input.derivatives != 0 && input.derivatives != 1)
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "derivatives is %d: it must be 0 (forces linear over the step) or 1 "
                           "(cubic Hermite with the force rates)",
                           input.derivatives);
    const double h = input.h;
    if (!(h > 0 && std::isfinite(h)))
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "communication step h = %g s must be > 0 and finite", h);
    if (!(h >= kMinStepSize && p.time + h > p.time))
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "communication step h = %g s does not advance time t = %.17g s (h must "
                           "be >= %g s and above the resolution of t)",
                           h, p.time, kMinStepSize);
    if (!(std::fabs(p.time + h) <= kMaxTime))
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "communication step h = %g s takes time beyond %g s", h, kMaxTime);
    stewart_status s;
    if ((s = check_finite(input.force_start, "F (start of step)", msg, size)) != STEWART_OK ||
        (s = check_finite(input.force_end, "F (end of step)", msg, size)) != STEWART_OK)
        return s;
    if (input.derivatives &&
        ((s = check_finite(input.force_rate_start, "dF/dt (start of step)", msg, size)) !=
             STEWART_OK ||
         (s = check_finite(input.force_rate_end, "dF/dt (end of step)", msg, size)) != STEWART_OK))
        return s;
    return STEWART_OK;
}

// The forces over the step the input gives: linear between its end values, or cubic Hermite
// with its force rates.
plant::ForceProfile force_profile(const stewart_plant_input &input) {
    const double *r0 = input.derivatives ? input.force_rate_start : nullptr;
    const double *r1 = input.derivatives ? input.force_rate_end : nullptr;
    plant::ForceProfile profile;
    profile.h = input.h;
    profile.hermite = r0 != nullptr;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        profile.start[k] = input.force_start[k];
        profile.end[k] = input.force_end[k];
        profile.start_rate[k] = r0 ? r0[k] : 0;
        profile.end_rate[k] = r1 ? r1[k] : 0;
    }
    return profile;
}

// The last step's counters, and added to the totals.
void record_statistics(const stewart_plant_statistics &last, stewart_plant_statistics &st) {
    st.steps = last.steps;
    st.rhs_evaluations = last.rhs_evaluations;
    st.nonlinear_iterations = last.nonlinear_iterations;
    st.error_test_failures = last.error_test_failures;
    st.jacobian_evaluations = last.jacobian_evaluations;
    st.last_order = last.last_order;
    st.last_step_size = last.last_step_size;
    st.total_steps += last.steps;
    st.total_rhs_evaluations += last.rhs_evaluations;
    st.total_nonlinear_iterations += last.nonlinear_iterations;
    st.total_error_test_failures += last.error_test_failures;
    st.total_jacobian_evaluations += last.jacobian_evaluations;
}

// A leg that passes through zero length between two evaluations flips its direction: refused
// (STEWART_ERR_UNREACHABLE) if any leg points against itself from the step's start to its end
// m. The legs at the step's start are the last step's end legs when it left them; end_legs gets
// the legs at m.
stewart_status check_legs_kept_direction(const stewart_plant &p, const stewart::Motion &m,
                                         double end_legs[STEWART_LEGS][3], char *msg, size_t size) {
    double start_legs[STEWART_LEGS][3];
    if (p.step_end_valid) std::memcpy(start_legs, p.leg_vectors, sizeof start_legs);
    else leg_vectors(p, plant::motion_of_state(p.y), start_legs);
    leg_vectors(p, m, end_legs);
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const plant::Vec3 d0(start_legs[k][0], start_legs[k][1], start_legs[k][2]),
            d1(end_legs[k][0], end_legs[k][1], end_legs[k][2]);
        if (!(d0.dot(d1) > 0))
            return set_message(msg, size, STEWART_ERR_UNREACHABLE,
                               "the motion takes leg %d through zero length within the step",
                               k + 1);
    }
    return STEWART_OK;
}

// The roll, pitch, yaw of the step's end state y: principal (which the next step's start needs
// too) and continued from the last step's (angles); refused at pitch +-90 degrees or a state out
// of range. angles_of_rotation(m.rotation, p.angles) in two parts: the principal angles (its
// formulas on the same rotation entries, motion_of_state's), then the turns of roll and yaw
// nearest the last step's, as it adds them.
stewart_status end_angles(const stewart_plant &p, const double *y, double principal[3],
                          double angles[3], char *msg, size_t size) {
    plant::principal_angles(y, principal);
    for (int i = 0; i < 3; ++i) angles[i] = principal[i];
    stewart::nearest_turns(p.angles, angles);
    if (!(std::fabs(std::cos(angles[1])) > kMinCosPitch))
        return set_message(msg, size, STEWART_ERR_SINGULAR,
                           "the motion reaches pitch = %g rad (+-90 degrees), where roll and yaw "
                           "are undefined",
                           angles[1]);
    return check_range(y, angles, "the forces are out of range: after the step", msg, size);
}

// The legs' lengths, rates and stroke bits at the step's end m (refused if one overflows), and
// the step's warnings.
stewart_status end_legs_and_warnings(stewart_plant &p, const stewart::Motion &m, LegOutputs &legs,
                                     int &limit_bits, int &warnings, char *msg, size_t size) {
    limit_bits = limit_warnings(p, m, &p.limit_clearance);
    legs.stroke_legs = leg_outputs(p, m, legs.length, legs.rate);
    warnings = (legs.stroke_legs ? STEWART_WARN_STROKE : 0) | limit_bits;
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (!std::isfinite(legs.length[k]) || !std::isfinite(legs.rate[k]))
            return set_message(msg, size, STEWART_ERR_ARGUMENT,
                               "the forces are out of range: leg %d's length or rate overflows "
                               "after the step",
                               k + 1);
    return STEWART_OK;
}

// The plant at the step's end: its state, angles, forces, time, the next step's first internal
// step, the warnings, and what the next step's start takes over (its legs and principal angles).
void take_step_end(stewart_plant &p, const double *y, const double angles[3],
                   const double principal[3], const double end_legs[STEWART_LEGS][3],
                   const stewart_plant_input &input, double step_hint, int warnings) {
    for (int i = 0; i < plant::kMaxStates; ++i) p.y[i] = y[i];
    for (int i = 0; i < 3; ++i) p.angles[i] = angles[i];
    for (int k = 0; k < STEWART_LEGS; ++k) p.force[k] = input.force_end[k];
    p.time += input.h;
    p.step_hint = step_hint >= kMinStepSize ? step_hint : 0;  // a hint a load takes back
    p.warnings = warnings;
    std::memcpy(p.leg_vectors, end_legs, sizeof p.leg_vectors);
    std::memcpy(p.principal_angles, principal, sizeof p.principal_angles);
    p.step_end_valid = true;
}
}  // namespace

extern "C" stewart_status stewart_plant_step(stewart_plant *p, const stewart_plant_input *input,
                                             stewart_plant_output *output) {
    stewart_status s = stewart::call_arguments_ok(p, input, output, "argument");
    if (s != STEWART_OK) return s;
    char *msg = p->message;
    const size_t size = sizeof p->message;
    if ((s = check_step_input(*p, *input, msg, size)) != STEWART_OK) return s;
    const plant::ForceProfile profile = force_profile(*input);
    double y[plant::kMaxStates];
    for (int i = 0; i < plant::kMaxStates; ++i) y[i] = p->y[i];
    double step_hint = p->step_hint;
    s = p->integrator.advance(y, profile, step_hint, msg, size,
                              p->step_end_valid ? p->principal_angles : nullptr);
    record_statistics(p->integrator.statistics(), p->stats);
    if (s != STEWART_OK) return s;

    const stewart::Motion m = plant::motion_of_state(y);
    double end_legs[STEWART_LEGS][3], principal[3], angles[3];
    if ((s = check_legs_kept_direction(*p, m, end_legs, msg, size)) != STEWART_OK ||
        (s = end_angles(*p, y, principal, angles, msg, size)) != STEWART_OK)
        return s;
    stewart_pose shown;
    if (!p->model->frames.identity && !shown_pose(*p, y, m, angles, shown))
        return set_message(msg, size, STEWART_ERR_SINGULAR,
                           "the motion reaches the tool frame's pitch +-90 degrees in the user "
                           "frame, where its roll and yaw are undefined");
    LegOutputs legs;
    int limit_bits, warnings;
    if ((s = end_legs_and_warnings(*p, m, legs, limit_bits, warnings, msg, size)) != STEWART_OK)
        return s;
    const PlantState before_step = state_of(*p);  // the outputs may overflow: then back to it
    take_step_end(*p, y, angles, principal, end_legs, *input, step_hint, warnings);
    // the outputs from the integrator's own evaluation at the end of the step when it made one
    // (the state before the quaternion's normalisation: the same equations to rounding), and the
    // legs and warnings just found at this state
    if (output_of(p, input->force_end, p->integrator.end_evaluation(), limit_bits, &legs, output,
                  &m) != STEWART_OK) {
        restore_state(*p, before_step);
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "the forces are out of range: the outputs overflow after the step");
    }
    msg[0] = '\0';
    return STEWART_OK;
}

// The legs' forces and drive outputs of o at the evaluation e of the inputs.
void plant_drive_outputs(const stewart_plant &p, const double *input, const plant::Evaluation &e,
                         stewart_plant_output &o) {
    const plant::DriveModel &dm = p.dynamics.drives;
    if (dm.input == STEWART_PLANT_INPUT_FORCE) {
        std::memcpy(o.force, input, sizeof o.force);
        return;
    }
    const stewart_params &par = p.model->params;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const stewart::LegDrive &d = dm.legs[k];
        const double i = e.drive.current[k], omega = d.motor_per_leg * e.drive.length_rate[k];
        o.force[k] = e.drive.leg_force[k];
        o.current[k] = i;
        o.motor_speed[k] = omega;
        o.motor_torque[k] = d.torque_constant * i;
        o.voltage[k] = dm.input == STEWART_PLANT_INPUT_VOLTAGE
                           ? input[k]
                           : d.resistance * i + d.torque_constant * omega;
        o.electrical_power[k] = o.voltage[k] * i;
        const int bit = 1 << k;
        if (par.current_max[k] > 0 && std::fabs(i) > par.current_max[k]) o.current_max_legs |= bit;
        if (par.voltage_max[k] > 0 && std::fabs(o.voltage[k]) > par.voltage_max[k])
            o.voltage_max_legs |= bit;
        if (par.motor_speed_max[k] > 0 && std::fabs(omega) > par.motor_speed_max[k])
            o.motor_speed_max_legs |= bit;
    }
}

namespace {

// stewart_plant_output_get's body. known: the equations' evaluation at the state and forces (the
// step's last, or nullptr); limit_bits: the joint-limit and interference warnings of the state
// (the step's, or -1: found here); legs: leg_outputs at the state (the step's, or nullptr);
// state_motion: motion_of_state(p->y) (the step's, or nullptr).
stewart_status output_of(const stewart_plant *p, const double *force,
                         const plant::Evaluation *known, int limit_bits, const LegOutputs *legs,
                         stewart_plant_output *out, const stewart::Motion *state_motion) {
    plant::Evaluation e;
    stewart::Motion m;
    const stewart_status s = all_bodies(*p, force, e, nullptr, known, &m, state_motion);
    if (s != STEWART_OK) return s;
    // the base wrench without the bodies' motions where it can (axisymmetric legs)
    plant::Vec3 f, t;
    plant::base_wrench(p->dynamics, m, known ? *known : e, f, t);

    stewart_plant_output o{};
    o.time = p->time;
    if (!shown_pose(*p, p->y, m, p->angles, o.pose)) return STEWART_ERR_SINGULAR;
    for (int i = 0; i < 3; ++i) {
        o.base_force[i] = f[i];
        o.base_torque[i] = t[i];
    }
    stewart::base_wrench_to_given_frame(p->model->frames, o.base_force, o.base_torque);
    if (legs) {
        o.stroke_legs = legs->stroke_legs;
        for (int k = 0; k < STEWART_LEGS; ++k) {
            o.lengths.length[k] = legs->length[k];
            o.lengths.length_rate[k] = legs->rate[k];
        }
    } else {
        o.stroke_legs = leg_outputs(*p, m, o.lengths.length, o.lengths.length_rate);
    }
    if (limit_bits < 0) limit_bits = limit_warnings(*p, m);
    o.warnings = (o.stroke_legs ? STEWART_WARN_STROKE : 0) | limit_bits;
    if (p->model->length_offsets)  // the sensors read Cardan-to-Cardan length - offset
        for (int k = 0; k < STEWART_LEGS; ++k)
            o.lengths.length[k] -= p->model->params.length_offset[k];
    plant_drive_outputs(*p, force ? force : p->force, known ? *known : e, o);
    // Finite forces can still overflow the base wrench (|F| near 1e308): no output then.
    if (!(zero_if_finite(o.pose.q, 6) + zero_if_finite(o.pose.q_dot, 6) +
              zero_if_finite(o.lengths.length, STEWART_LEGS) +
              zero_if_finite(o.lengths.length_rate, STEWART_LEGS) +
              zero_if_finite(o.base_force, 3) + zero_if_finite(o.base_torque, 3) +
              zero_if_finite(o.force, STEWART_LEGS) + zero_if_finite(o.electrical_power, 6) ==
          0))
        return STEWART_ERR_ARGUMENT;
    *out = o;
    return STEWART_OK;
}

}  // namespace

extern "C" stewart_status stewart_plant_output_get(const stewart_plant *p, const double *force,
                                                   stewart_plant_output *out) {
    if (!p || !out) return STEWART_ERR_ARGUMENT;
    return output_of(p, force, nullptr, -1, nullptr, out);
}

extern "C" stewart_status stewart_plant_reactions_get(const stewart_plant *p, const double *force,
                                                      stewart_plant_reactions *reactions) {
    if (!p || !reactions) return STEWART_ERR_ARGUMENT;
    plant::Evaluation e;
    stewart::Motion bodies[STEWART_PLANT_BODIES];
    const stewart_status s = all_bodies(*p, force, e, bodies);
    if (s != STEWART_OK) return s;
    if (!force) force = p->force;
    // the legs' axial forces: the input, or what the drives made of it
    if (p->dynamics.drives.input != STEWART_PLANT_INPUT_FORCE) force = e.drive.leg_force;
    stewart_plant_reactions r;
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (!plant::leg_reactions(p->dynamics, k, e.legs[k], bodies, force[k], r))
            return STEWART_ERR_SINGULAR;
    const double *values = &r.base_cardan_force[0][0];
    for (size_t i = 0; i < sizeof r / sizeof(double); ++i)
        if (!std::isfinite(values[i])) return STEWART_ERR_ARGUMENT;
    *reactions = r;
    return STEWART_OK;
}

extern "C" stewart_status stewart_plant_bodies(const stewart_plant *p,
                                               stewart_plant_body bodies[STEWART_PLANT_BODIES]) {
    if (!p || !bodies) return STEWART_ERR_ARGUMENT;
    plant::Evaluation e;
    stewart::Motion motion[STEWART_PLANT_BODIES];
    const stewart_status s = all_bodies(*p, nullptr, e, motion);
    if (s != STEWART_OK) return s;
    const int count = p->dynamics.with_legs ? STEWART_PLANT_BODIES : 1;
    stewart_plant_body out[STEWART_PLANT_BODIES] = {};
    for (int b = 0; b < count; ++b)
        for (int i = 0; i < 3; ++i) {
            out[b].position[i] = motion[b].position[i];
            out[b].velocity[i] = motion[b].velocity[i];
            out[b].omega[i] = motion[b].omega[i];
            for (int j = 0; j < 3; ++j) out[b].rotation[3 * i + j] = motion[b].rotation(i, j);
        }
    // A finite state can still overflow a leg body's rates (platform rates near 1e308, as the
    // fuzz target found): no bodies then, as output_get and reactions_get do.
    const double *values = out[0].position;
    constexpr size_t kDoubles = sizeof(stewart_plant_body) * STEWART_PLANT_BODIES / sizeof(double);
    for (size_t i = 0; i < kDoubles; ++i)
        if (!std::isfinite(values[i])) return STEWART_ERR_ARGUMENT;
    std::memcpy(bodies, out, sizeof out);
    return STEWART_OK;
}

extern "C" double stewart_plant_time(const stewart_plant *p) { return p ? p->time : NAN; }

extern "C" void stewart_plant_statistics_get(const stewart_plant *p,
                                             stewart_plant_statistics *stats) {
    if (p && stats) *stats = p->stats;
}

extern "C" const char *stewart_plant_message(const stewart_plant *p) {
    return p ? p->message : "plant is NULL";
}

namespace {

// The saved state: a header (magic, version, size in bytes) then kSavedDoubles doubles.
constexpr unsigned kStateMagic = 0x53545044u;  // "STPD"
constexpr unsigned kStateVersion = 1;
constexpr size_t kStateHeader = 3 * sizeof(unsigned);

// The doubles and bytes of p's saved state.
int saved_doubles(const stewart_plant &p) {
    return kSavedDoubles + (plant::state_count(p.dynamics) - plant::kStates);
}
size_t state_bytes(const stewart_plant &p) {
    return kStateHeader + saved_doubles(p) * sizeof(double);
}

void save_doubles(const stewart_plant &p, double *out) {
    *out++ = p.time;
    for (int i = 0; i < plant::state_count(p.dynamics); ++i) *out++ = p.y[i];
    for (double v : p.angles) *out++ = v;
    for (double v : p.force) *out++ = v;
    *out++ = p.warnings;
    *out++ = p.step_hint;
}

}  // namespace

extern "C" size_t stewart_plant_state_size(const stewart_plant *p) {
    return p ? state_bytes(*p) : 0;
}

extern "C" stewart_status stewart_plant_save(const stewart_plant *p, void *buffer, size_t size) {
    if (!p) return STEWART_ERR_ARGUMENT;
    const size_t bytes = state_bytes(*p);
    if (!buffer || size < bytes)
        return set_message(p->message, sizeof p->message, STEWART_ERR_ARGUMENT,
                           "state not saved: a buffer of %zu bytes%s, the state needs %zu", size,
                           buffer ? "" : " (NULL)", bytes);
    const unsigned header[3] = {kStateMagic, kStateVersion, static_cast<unsigned>(bytes)};
    double state[kMaxSavedDoubles];
    save_doubles(*p, state);
    unsigned char *out = static_cast<unsigned char *>(buffer);
    std::memcpy(out, header, sizeof header);
    std::memcpy(out + kStateHeader, state, saved_doubles(*p) * sizeof(double));
    return STEWART_OK;
}

extern "C" stewart_status stewart_plant_load(stewart_plant *p, const void *buffer, size_t size) {
    if (!p) return STEWART_ERR_ARGUMENT;
    if (!buffer)
        return set_message(p->message, sizeof p->message, STEWART_ERR_ARGUMENT, "buffer is NULL");
    const size_t bytes = state_bytes(*p);
    const int states = plant::state_count(p->dynamics), kSaved = saved_doubles(*p);
    unsigned header[3] = {0, 0, 0};
    if (size >= kStateHeader) std::memcpy(header, buffer, sizeof header);
    if (size != bytes || header[0] != kStateMagic || header[1] != kStateVersion ||
        header[2] != bytes)
        return set_message(p->message, sizeof p->message, STEWART_ERR_ARGUMENT,
                           "not a saved plant state of this version (%zu bytes, magic %#x, "
                           "version %u; expected %zu bytes, %#x, %u)",
                           size, header[0], header[1], bytes, kStateMagic, kStateVersion);
    double state[kMaxSavedDoubles];
    std::memcpy(state, static_cast<const unsigned char *>(buffer) + kStateHeader,
                kSaved * sizeof(double));
    const size_t count = kSaved;
    for (size_t i = 0; i < count; ++i)
        if (!std::isfinite(state[i]))
            return set_message(p->message, sizeof p->message, STEWART_ERR_ARGUMENT,
                               "saved plant state: value %zu is not finite", i);
    // What a step could have left: a unit quaternion, pitch off +-90 degrees, a defined pose.
    const double *y = state + 1, *angles = y + states;
    const double warnings = state[kSaved - 2], hint = state[kSaved - 1];
    const double q_norm = std::sqrt(y[3] * y[3] + y[4] * y[4] + y[5] * y[5] + y[6] * y[6]);
    plant::Evaluation e;
    const double zero[STEWART_LEGS] = {0};
    if (!(std::fabs(q_norm - 1) < 1e-9) || !(std::fabs(std::cos(angles[1])) > kMinCosPitch) ||
        !(warnings >= 0 && warnings <= kPlantWarnings &&
          (static_cast<int>(warnings) & ~kPlantWarnings) == 0 &&
          warnings == std::floor(warnings)) ||
        !(hint == 0 || hint >= kMinStepSize) ||
        !(e.winding_current = y + plant::kStates,
          plant::twist_rate(p->dynamics, plant::motion_of_state(y), zero, e)))
        return set_message(p->message, sizeof p->message, STEWART_ERR_ARGUMENT,
                           "saved plant state is not one a step leaves (quaternion norm %g, pitch "
                           "%g rad, warnings %g, step hint %g s (0 or >= %g s), or a singular "
                           "pose)",
                           q_norm, angles[1], warnings, hint, kMinStepSize);
    if (!(std::fabs(state[0]) <= kMaxTime))
        return set_message(p->message, sizeof p->message, STEWART_ERR_ARGUMENT,
                           "saved plant state: time = %g s is beyond +-%g s", state[0], kMaxTime);
    if (!angles_match(y, angles))
        return set_message(p->message, sizeof p->message, STEWART_ERR_ARGUMENT,
                           "saved plant state is not one a step leaves: roll, pitch, yaw = %g, %g, "
                           "%g rad are not the angles of its quaternion",
                           angles[0], angles[1], angles[2]);
    if (check_range(y, angles, "saved plant state", p->message, sizeof p->message) != STEWART_OK)
        return STEWART_ERR_ARGUMENT;
    const double *in = state;
    p->step_end_valid = false;
    p->time = *in++;
    for (int i = 0; i < states; ++i) p->y[i] = *in++;
    for (double &v : p->angles) v = *in++;
    for (double &v : p->force) v = *in++;
    p->warnings = static_cast<int>(*in++);
    p->step_hint = *in++;
    p->message[0] = '\0';
    return STEWART_OK;
}
