// The linearisation's C API (stewart_linearize.h): input checks, plant_jacobian.* laid out as
// A, B, C, D, and the inverse side's Jacobian (plant_derivatives.*' dual evaluations and the
// implicit function theorem on the plant's equations).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <new>

#include <Eigen/LU>

#include "linearize/driven_jacobian.hpp"
#include "linearize/plant_jacobian.hpp"
#include "model.hpp"
#include "stewart/stewart_linearize.h"
#include "util/create.hpp"
#include "util/message.hpp"

using stewart::clear_message;
using stewart::Dual;
using stewart::set_message;
namespace plant = stewart::plant;
namespace lin = stewart::lin;

struct stewart_linearize {
    const stewart_model *model = nullptr;
    stewart_linearize_options options{};
    plant::DynamicsModel dynamics;
    char message[STEWART_MESSAGE_SIZE] = "";
};

namespace {

constexpr uint32_t kMagic = 0x4c494e31u;  // "LIN1"
constexpr uint32_t kVersion = 1;
// Below it the forces do not hold the pose: the map from forces to pose accelerations is
// singular (reciprocal condition number, 1-norm).
constexpr double kMinForceMapConditionInverse = 1e-13;

struct SavedState {
    uint32_t magic, version;
    int32_t fidelity;
};

// STEWART_ERR_ARGUMENT naming the first of n values that is not finite (name[index] = value).
stewart_status check_finite(const double *values, int n, const char *name, int first_index,
                            char *msg, size_t size) {
    for (int i = 0; i < n; ++i)
        if (!std::isfinite(values[i]))
            return set_message(msg, size, STEWART_ERR_ARGUMENT, "%s[%d] = %g must be finite", name,
                               first_index + i, values[i]);
    return STEWART_OK;
}

// STEWART_ERR_ARGUMENT if one of the doubles in the bytes [values, values + bytes) is not finite:
// inputs beyond the plant's range overflow its equations.
stewart_status check_overflow(const double *values, size_t bytes, char *msg, size_t size) {
    for (size_t i = 0; i < bytes / sizeof(double); ++i)
        if (!std::isfinite(values[i]))
            return set_message(msg, size, STEWART_ERR_ARGUMENT,
                               "the linearisation overflows at this operating point (its value "
                               "%zu is %g): the inputs are beyond the plant's range",
                               i, values[i]);
    return STEWART_OK;
}

// The message and status of a failed evaluation.
stewart_status failure(const lin::Failure &why, double pitch, char *msg, size_t size) {
    if (why.unsettled_leg >= 0)
        return set_message(msg, size, STEWART_ERR_SINGULAR,
                           "leg %d's power flow turns here (the plant's screw force flips with "
                           "its own efficiency): the driven plant has no derivative at this "
                           "point; linearise a little away from it",
                           why.unsettled_leg + 1);
    if (why.pitch)
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "pitch = %g rad is at +-90 degrees, where roll and yaw rates are "
                           "undefined",
                           pitch);
    if (why.fault == plant::LegFault::ZeroLength)
        return set_message(msg, size, STEWART_ERR_UNREACHABLE,
                           "leg %d has zero length at this pose", why.leg + 1);
    return set_message(msg, size, STEWART_ERR_SINGULAR, "the %s Cardan of leg %d is locked",
                       why.fault == plant::LegFault::LockedBaseCardan ? "base" : "platform",
                       why.leg + 1);
}

int stroke_legs_of(const stewart_params &p, const double length[STEWART_LEGS]) {
    int legs = 0;
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (length[k] < p.stroke_min[k] || length[k] > p.stroke_max[k]) legs |= 1 << k;
    return legs;
}

// The sensors read the Cardan-to-Cardan length less length_offset (a constant: no derivative).
void subtract_offsets(const stewart_model &model, double length[STEWART_LEGS]) {
    if (model.length_offsets)
        for (int k = 0; k < STEWART_LEGS; ++k) length[k] -= model.params.length_offset[k];
}

// The pose checks both calls share: pose finite (rows 0 to last_row), pitch off +-90 degrees.
stewart_status check_pose_rows(const stewart_pose &pose, int last_row, char *msg, size_t size) {
    const double *rows[3] = {pose.q, pose.q_dot, pose.q_ddot};
    const char *names[3] = {"q", "q_dot", "q_ddot"};
    for (int r = 0; r <= last_row; ++r) {
        const stewart_status s = check_finite(rows[r], 6, names[r], 0, msg, size);
        if (s != STEWART_OK) return s;
    }
    if (!(std::fabs(std::cos(pose.q[4])) > lin::kMinCosPitch))
        return failure(lin::Failure{plant::LegFault::None, -1, true}, pose.q[4], msg, size);
    return STEWART_OK;
}

// The base wrench at pose and its Jacobian rows (force, then torque) by (q, q_dot, q_ddot).
bool base_wrench(const stewart_linearize &l, const stewart_pose &pose, double force[3],
                 double torque[3], double rows[6][STEWART_LINEARIZE_INVERSE_COLUMNS],
                 lin::Failure &why) {
    Dual f[3], t[3];
    if (!lin::pose_base_wrench(l.dynamics, l.model->frames, pose.q, pose.q_dot, pose.q_ddot, f, t,
                               why))
        return false;
    for (int i = 0; i < 3; ++i) {
        force[i] = f[i].value();
        torque[i] = t[i].value();
        for (int j = 0; j < STEWART_LINEARIZE_INVERSE_COLUMNS; ++j) {
            rows[i][j] = f[i].derivatives()[j];
            rows[3 + i][j] = t[i].derivatives()[j];
        }
    }
    return true;
}

}  // namespace

// stewart_linearize_options_default and _check: table/options.cpp, from the option table.

extern "C" stewart_linearize *stewart_linearize_create(const stewart_model *model,
                                                       const stewart_linearize_options *options,
                                                       char *msg, size_t size) {
    stewart_linearize *l =
        stewart::new_object_for<stewart_linearize>(model, options, stewart_linearize_options_check,
                                                   "linearisation", msg, size);
    if (!l) return nullptr;
    l->dynamics = plant::dynamics_model(*model, options->fidelity);
    clear_message(msg, size);
    return l;
}

extern "C" const stewart_linearize_options *stewart_linearize_options_of(
    const stewart_linearize *l) {
    return l ? &l->options : nullptr;
}

extern "C" void stewart_linearize_free(stewart_linearize *l) { delete l; }

extern "C" void stewart_linearize_reset(stewart_linearize *l) {
    if (l) l->message[0] = '\0';
}

extern "C" stewart_status stewart_linearize_copy(stewart_linearize *dst,
                                                 const stewart_linearize *src) {
    const stewart_status checked = stewart::copy_arguments_ok(dst, src, "linearisations");
    if (checked != STEWART_OK) return checked;
    dst->options = src->options;
    dst->dynamics = src->dynamics;
    std::memcpy(dst->message, src->message, sizeof dst->message);
    return STEWART_OK;
}

extern "C" size_t stewart_linearize_state_size(const stewart_linearize *l) {
    return l ? sizeof(SavedState) : 0;
}

extern "C" stewart_status stewart_linearize_save(const stewart_linearize *l, void *buffer,
                                                 size_t size) {
    if (!l) return STEWART_ERR_ARGUMENT;
    if (!buffer || size < sizeof(SavedState)) return STEWART_ERR_ARGUMENT;
    const SavedState s{kMagic, kVersion, l->options.fidelity};
    std::memcpy(buffer, &s, sizeof s);
    return STEWART_OK;
}

extern "C" stewart_status stewart_linearize_load(stewart_linearize *l, const void *buffer,
                                                 size_t size) {
    if (!l) return STEWART_ERR_ARGUMENT;
    char *msg = l->message;
    if (!buffer || size != sizeof(SavedState))
        return set_message(msg, sizeof l->message, STEWART_ERR_ARGUMENT,
                           "state: %zu bytes, a linearisation's state has %zu", buffer ? size : 0,
                           sizeof(SavedState));
    SavedState s;
    std::memcpy(&s, buffer, sizeof s);
    if (s.magic != kMagic || s.version != kVersion)
        return set_message(msg, sizeof l->message, STEWART_ERR_ARGUMENT,
                           "state: not a linearisation's state of this version (magic %#x, "
                           "version %u)",
                           s.magic, s.version);
    stewart_linearize_options o{s.fidelity};
    char why[STEWART_MESSAGE_SIZE];
    if (stewart_linearize_options_check(&o, why, sizeof why) != STEWART_OK)
        return set_message(msg, sizeof l->message, STEWART_ERR_ARGUMENT, "state: %s", why);
    l->options = o;
    l->dynamics = plant::dynamics_model(*l->model, o.fidelity);
    return clear_message(msg, sizeof l->message);
}

extern "C" const char *stewart_linearize_message(const stewart_linearize *l) {
    return l ? l->message : "linearisation is NULL";
}

extern "C" stewart_status stewart_linearize_plant(stewart_linearize *l,
                                                  const stewart_linearize_input *in,
                                                  stewart_linearize_output *out) {
    stewart_status s = stewart::call_arguments_ok(l, in, out, "input or output");
    if (s != STEWART_OK) return s;
    char *msg = l->message;
    const size_t size = sizeof l->message;
    if ((s = check_pose_rows(in->pose, 1, msg, size)) != STEWART_OK) return s;
    if ((s = check_finite(in->force, STEWART_LEGS, "force", 1, msg, size)) != STEWART_OK) return s;
    lin::PlantJacobian p;
    lin::Failure why;
    if (!lin::plant_jacobian(l->dynamics, l->model->frames, in->pose.q, in->pose.q_dot, in->force,
                             p, why))
        return failure(why, in->pose.q[4], msg, size);

    stewart_linearize_output o;
    std::memset(&o, 0, sizeof o);
    for (int i = 0; i < 6; ++i) {
        o.state_rate[i] = in->pose.q_dot[i];
        o.state_rate[6 + i] = p.q_ddot[i];
        o.A[i][6 + i] = 1;  // d q_dot / d q_dot
        std::memcpy(o.A[6 + i], p.q_ddot_wrt_state[i], sizeof o.A[6 + i]);
        std::memcpy(o.B[6 + i], p.q_ddot_wrt_force[i], sizeof o.B[6 + i]);
        // y = (q, q_dot, L, L_dot).
        o.output[i] = in->pose.q[i];
        o.output[6 + i] = in->pose.q_dot[i];
        o.C[i][i] = 1;
        o.C[6 + i][6 + i] = 1;
    }
    for (int k = 0; k < STEWART_LEGS; ++k) {
        o.output[12 + k] = p.length[k];
        o.output[18 + k] = p.length_rate[k];
        std::memcpy(o.C[12 + k], p.length_wrt_state[k], sizeof o.C[12 + k]);
        std::memcpy(o.C[18 + k], p.length_rate_wrt_state[k], sizeof o.C[18 + k]);
    }  // D = 0: the lengths and their rates do not depend on the forces
    o.stroke_legs = stroke_legs_of(l->model->params, p.length);
    o.warnings = o.stroke_legs ? STEWART_WARN_STROKE : 0;
    subtract_offsets(*l->model, o.output + 12);
    static_assert(offsetof(stewart_linearize_output, D) + sizeof o.D ==
                      offsetof(stewart_linearize_output, state_rate) + sizeof o.state_rate +
                          sizeof o.output + sizeof o.A + sizeof o.B + sizeof o.C + sizeof o.D,
                  "the checked values are contiguous");
    if ((s = check_overflow(&o.state_rate[0],
                            sizeof o.state_rate + sizeof o.output + sizeof o.A + sizeof o.B +
                                sizeof o.C + sizeof o.D,
                            msg, size)) != STEWART_OK)
        return s;
    *out = o;
    return clear_message(msg, size);
}

namespace {

// The checks every call on a pose starts with: a linearisation, a pose and an output, the pose's
// rows (to its accelerations) finite.
stewart_status check_pose_call(stewart_linearize *l, const stewart_pose *pose, const void *out) {
    const stewart_status s = stewart::call_arguments_ok(l, pose, out, "pose or output");
    if (s != STEWART_OK) return s;
    return check_pose_rows(*pose, 2, l->message, sizeof l->message);
}

// The legs' lengths, rates and accelerations at the pose, and their rows of the Jacobian.
bool length_rows(const stewart_linearize &l, const stewart_pose &pose,
                 stewart_linearize_inverse_output &o, lin::Failure &why) {
    Dual L[STEWART_LEGS], L_dot[STEWART_LEGS], L_ddot[STEWART_LEGS];
    const stewart::Frames &frames = l.model->frames;
    if (!lin::leg_lengths(l.dynamics.legs, frames, pose.q, pose.q_dot, pose.q_ddot, L, L_dot,
                          L_ddot, why))
        return false;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        o.lengths.length[k] = L[k].value();
        o.lengths.length_rate[k] = L_dot[k].value();
        o.lengths.length_accel[k] = L_ddot[k].value();
        const Dual *rows[3] = {&L[k], &L_dot[k], &L_ddot[k]};
        for (int r = 0; r < 3; ++r)
            for (int j = 0; j < STEWART_LINEARIZE_INVERSE_COLUMNS; ++j)
                o.jacobian[6 * r + k][j] = rows[r]->derivatives()[j];
    }
    return true;
}

// The legs' forces that give the pose's accelerations, and their rows of the Jacobian. The
// plant's q_ddot = a(q, q_dot) + G(q) F (affine in F): F = G^-1 (q_ddot - a), and by the implicit
// function theorem dF/dz = -G^-1 d q_ddot/dz at that F (z = q, q_dot), G^-1 for q_ddot. a and G in
// plain numbers at no force; the derivatives once, at the forces found.
stewart_status force_rows(const stewart_linearize &l, const stewart_pose &pose,
                          stewart_linearize_inverse_output &o, char *msg, size_t size) {
    const stewart::Frames &frames = l.model->frames;
    lin::Failure why;
    const double no_force[STEWART_LEGS] = {0};
    lin::PlantRate rate;
    if (!lin::plant_rate(l.dynamics, frames, pose.q, pose.q_dot, no_force, rate, why))
        return failure(why, pose.q[4], msg, size);
    Eigen::Matrix<double, 6, 6> G;
    Eigen::Matrix<double, 6, 1> missing;
    for (int i = 0; i < 6; ++i) {
        for (int k = 0; k < STEWART_LEGS; ++k) G(i, k) = rate.q_ddot_wrt_force[i][k];
        missing[i] = pose.q_ddot[i] - rate.q_ddot[i];
    }
    const Eigen::PartialPivLU<Eigen::Matrix<double, 6, 6>> lu(G);
    const double rcond = lu.rcond();
    if (!std::isfinite(rcond))  // G not finite: the legs' directions give no force map at all
        return set_message(msg, size, STEWART_ERR_SINGULAR,
                           "the legs cannot hold this pose: it is a singular pose (the legs' "
                           "directions do not span the platform's six motions, e.g. every leg "
                           "in one plane); linearise about a pose within the limits "
                           "(Platform.check gives home's condition number)");
    if (!(rcond > kMinForceMapConditionInverse))
        return set_message(msg, size, STEWART_ERR_SINGULAR,
                           "the legs cannot hold this pose: the map from forces to pose "
                           "accelerations is singular (reciprocal condition %g), a singular "
                           "pose; linearise about a pose within the limits",
                           rcond);
    const Eigen::Matrix<double, 6, 1> force = lu.solve(missing);
    double force_values[STEWART_LEGS];
    for (int k = 0; k < STEWART_LEGS; ++k) force_values[k] = force[k];
    lin::plant_rate_add_force(rate, force_values);
    lin::PlantJacobian at_force;
    if (!lin::plant_jacobian(l.dynamics, frames, pose.q, pose.q_dot, force_values, rate, at_force,
                             why))
        return failure(why, pose.q[4], msg, size);
    const Eigen::Map<const Eigen::Matrix<double, 6, 12, Eigen::RowMajor>> accel_wrt_state(
        &at_force.q_ddot_wrt_state[0][0]);
    const Eigen::Matrix<double, 6, 12> force_wrt_state = -lu.solve(accel_wrt_state);
    const Eigen::Matrix<double, 6, 6> force_wrt_accel = lu.inverse();
    for (int k = 0; k < STEWART_LEGS; ++k) {
        o.force[k] = force[k];
        for (int j = 0; j < 12; ++j) o.jacobian[18 + k][j] = force_wrt_state(k, j);
        for (int j = 0; j < 6; ++j) o.jacobian[18 + k][12 + j] = force_wrt_accel(k, j);
    }
    return STEWART_OK;
}

// A call at one pose: its arguments checked, then rows fills a zeroed output (STEWART_OK or the
// status with msg naming the cause), which is given to the caller only when complete.
template <class Output, class Rows>
stewart_status pose_call(stewart_linearize *l, const stewart_pose *pose, Output *out, Rows rows) {
    stewart_status s = check_pose_call(l, pose, out);
    if (s != STEWART_OK) return s;
    Output o;
    std::memset(&o, 0, sizeof o);
    if ((s = rows(*l, *pose, o, l->message, sizeof l->message)) != STEWART_OK) return s;
    *out = o;
    return clear_message(l->message, sizeof l->message);
}

stewart_status inverse_rows(const stewart_linearize &l, const stewart_pose &pose,
                            stewart_linearize_inverse_output &o, char *msg, size_t size) {
    stewart_status s;
    lin::Failure why;
    if (!length_rows(l, pose, o, why)) return failure(why, pose.q[4], msg, size);
    if ((s = force_rows(l, pose, o, msg, size)) != STEWART_OK) return s;
    if (!base_wrench(l, pose, o.base_force, o.base_torque, o.jacobian + 24, why))
        return failure(why, pose.q[4], msg, size);
    static_assert(offsetof(stewart_linearize_inverse_output, jacobian) ==
                      offsetof(stewart_linearize_inverse_output, lengths) +
                          sizeof(stewart_lengths) + 12 * sizeof(double),
                  "the checked values are contiguous");
    if ((s = check_overflow(&o.lengths.length[0],
                            sizeof o.lengths + sizeof o.force + 6 * sizeof(double) +
                                sizeof o.jacobian,
                            msg, size)) != STEWART_OK)
        return s;
    o.stroke_legs = stroke_legs_of(l.model->params, o.lengths.length);
    o.warnings = o.stroke_legs ? STEWART_WARN_STROKE : 0;
    subtract_offsets(*l.model, o.lengths.length);
    return STEWART_OK;
}

stewart_status wrench_rows(const stewart_linearize &l, const stewart_pose &pose,
                           stewart_linearize_wrench_output &o, char *msg, size_t size) {
    lin::Failure why;
    if (!base_wrench(l, pose, o.base_force, o.base_torque, o.jacobian, why))
        return failure(why, pose.q[4], msg, size);
    static_assert(sizeof o == (6 + 6 * STEWART_LINEARIZE_INVERSE_COLUMNS) * sizeof(double),
                  "the checked values are contiguous");
    return check_overflow(o.base_force, sizeof o, msg, size);
}

}  // namespace

extern "C" stewart_status stewart_linearize_inverse(stewart_linearize *l, const stewart_pose *pose,
                                                    stewart_linearize_inverse_output *out) {
    return pose_call(l, pose, out, inverse_rows);
}

extern "C" stewart_status stewart_linearize_base_wrench(stewart_linearize *l,
                                                        const stewart_pose *pose,
                                                        stewart_linearize_wrench_output *out) {
    return pose_call(l, pose, out, wrench_rows);
}

namespace {

// The driven plant's linearisation laid out as the output (y as stewart_linearize_plant's).
void driven_output(const stewart_linearize &l, const stewart_linearize_driven_input &in,
                   const lin::DrivenJacobian &p, stewart_linearize_driven_output &o) {
    std::memset(&o, 0, sizeof o);
    o.states = p.states;
    std::memcpy(o.state_rate, p.state_rate, sizeof o.state_rate);
    std::memcpy(o.A, p.A, sizeof o.A);
    std::memcpy(o.B, p.B, sizeof o.B);
    for (int i = 0; i < 6; ++i) {
        o.output[i] = in.pose.q[i];
        o.output[6 + i] = in.pose.q_dot[i];
        o.C[i][i] = 1;
        o.C[6 + i][6 + i] = 1;
    }
    for (int k = 0; k < STEWART_LEGS; ++k) {
        o.output[12 + k] = p.length[k];
        o.output[18 + k] = p.length_rate[k];
        std::memcpy(o.C[12 + k], p.length_wrt_state[k], sizeof p.length_wrt_state[k]);
        std::memcpy(o.C[18 + k], p.length_rate_wrt_state[k], sizeof p.length_rate_wrt_state[k]);
    }
    std::memcpy(o.leg_force, p.leg_force, sizeof o.leg_force);
    o.stroke_legs = stroke_legs_of(l.model->params, p.length);
    o.not_smooth_legs = p.not_smooth_legs;
    o.warnings = (o.stroke_legs ? STEWART_WARN_STROKE : 0) |
                 (o.not_smooth_legs ? STEWART_WARN_NOT_SMOOTH : 0);
    subtract_offsets(*l.model, o.output + 12);
}

}  // namespace

extern "C" stewart_status stewart_linearize_driven(stewart_linearize *l,
                                                   const stewart_plant_options *plant_options,
                                                   const stewart_linearize_driven_input *in,
                                                   stewart_linearize_driven_output *out) {
    if (!l) return STEWART_ERR_ARGUMENT;
    char *msg = l->message;
    const size_t size = sizeof l->message;
    if (!plant_options || !in || !out)
        return set_message(msg, size, STEWART_ERR_ARGUMENT, "NULL options, input or output");
    if (plant_options->input != STEWART_PLANT_INPUT_CURRENT &&
        plant_options->input != STEWART_PLANT_INPUT_VOLTAGE)
        return set_message(msg, size, STEWART_ERR_PARAMETER,
                           "input = %d: the driven linearisation takes current (%d) or voltage "
                           "(%d) input; stewart_linearize_plant linearises force input",
                           plant_options->input, STEWART_PLANT_INPUT_CURRENT,
                           STEWART_PLANT_INPUT_VOLTAGE);
    if (!(plant_options->smoothing_speed > 0))
        return set_message(msg, size, STEWART_ERR_PARAMETER, "smoothing_speed = %g must be > 0",
                           plant_options->smoothing_speed);
    plant::DynamicsModel driven = l->dynamics;
    stewart_status s =
        plant::drive_model(l->model->params, *plant_options, driven.drives, msg, size);
    if (s != STEWART_OK) return s;
    if ((s = check_pose_rows(in->pose, 1, msg, size)) != STEWART_OK) return s;
    if ((s = check_finite(in->input, STEWART_LEGS, "input", 1, msg, size)) != STEWART_OK) return s;
    if (driven.drives.inductive &&
        (s = check_finite(in->current, STEWART_LEGS, "current", 1, msg, size)) != STEWART_OK)
        return s;
    static const double no_current[STEWART_LEGS] = {0, 0, 0, 0, 0, 0};
    lin::DrivenJacobian p;
    lin::Failure why;
    if (!lin::driven_jacobian(l->dynamics, driven, l->model->frames, in->pose.q, in->pose.q_dot,
                              in->input, driven.drives.inductive ? in->current : no_current, p,
                              why))
        return failure(why, in->pose.q[4], msg, size);
    stewart_linearize_driven_output o;
    driven_output(*l, *in, p, o);
    static_assert(offsetof(stewart_linearize_driven_output, leg_force) + sizeof o.leg_force ==
                      offsetof(stewart_linearize_driven_output, state_rate) + sizeof o.state_rate +
                          sizeof o.output + sizeof o.A + sizeof o.B + sizeof o.C + sizeof o.D +
                          sizeof o.leg_force,
                  "the checked values are contiguous");
    if ((s = check_overflow(&o.state_rate[0],
                            sizeof o.state_rate + sizeof o.output + sizeof o.A + sizeof o.B +
                                sizeof o.C + sizeof o.D + sizeof o.leg_force,
                            msg, size)) != STEWART_OK)
        return s;
    *out = o;
    return clear_message(msg, size);
}
