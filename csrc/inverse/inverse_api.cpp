// The inverse direction's C API: the solver object's life cycle, and the per-pose solve
// dispatched on the fidelity level.
#include <cmath>
#include <cstring>
#include <new>

#include "drives/drive_outputs.hpp"
#include "model.hpp"
#include "util/create.hpp"
#include "util/message.hpp"

using stewart::clear_message;
using stewart::set_message;

extern "C" stewart_inverse *stewart_inverse_create(const stewart_model *m,
                                                   const stewart_inverse_options *o, char *msg,
                                                   size_t size) {
    stewart_inverse *d =
        stewart::new_object_for<stewart_inverse>(m, o, stewart_inverse_options_check,
                                                 "inverse solver", msg, size);
    if (!d) return nullptr;
    d->full.reset(new (std::nothrow) mbs_data(m->full.get(), mbs::SolverOptions()));
    if (!d->full || !d->full->state.ok()) {
        set_message(msg, size, STEWART_ERR_MEMORY,
                    "out of memory creating the inverse solver's full-level state");
        delete d;
        return nullptr;
    }
    stewart_inverse_reset(d);
    clear_message(msg, size);
    return d;
}

extern "C" void stewart_inverse_free(stewart_inverse *d) { delete d; }

extern "C" stewart_status stewart_inverse_copy(stewart_inverse *dst, const stewart_inverse *src) {
    const stewart_status checked = stewart::copy_arguments_ok(dst, src, "inverse solvers");
    if (checked != STEWART_OK) return checked;
    std::memcpy(dst->message, src->message, sizeof dst->message);
    mbs::copy_state(dst->full->state, src->full->state);
    return STEWART_OK;
}

extern "C" size_t stewart_inverse_state_size(const stewart_inverse *d) {
    return d && d->full ? mbs::saved_state_size(d->full->state) : 0;
}

extern "C" stewart_status stewart_inverse_save(const stewart_inverse *d, void *buffer,
                                               size_t size) {
    if (!d || !d->full) return STEWART_ERR_ARGUMENT;
    if (!buffer || size < stewart_inverse_state_size(d))
        return set_message(d->message, sizeof d->message, STEWART_ERR_ARGUMENT,
                           "state not saved: a buffer of %zu bytes%s, the state needs %zu", size,
                           buffer ? "" : " (NULL)", stewart_inverse_state_size(d));
    mbs::save_state(d->full->state, static_cast<unsigned char *>(buffer));
    return STEWART_OK;
}

extern "C" stewart_status stewart_inverse_load(stewart_inverse *d, const void *buffer,
                                               size_t size) {
    if (!d || !d->full) return STEWART_ERR_ARGUMENT;
    if (!buffer)
        return set_message(d->message, sizeof d->message, STEWART_ERR_ARGUMENT, "buffer is NULL");
    char why[MBS_MESSAGE_SIZE];
    if (!mbs::load_state(d->full->state, static_cast<const unsigned char *>(buffer), size, why,
                         sizeof why))
        return set_message(d->message, sizeof d->message, STEWART_ERR_ARGUMENT,
                           "state not loaded (the inverse solver is unchanged): %s", why);
    d->message[0] = '\0';
    return STEWART_OK;
}

extern "C" void stewart_inverse_reset(stewart_inverse *d) {
    if (!d) return;
    d->message[0] = '\0';
    if (d->full) mbs::reset(d->full->state);
}

extern "C" const char *stewart_inverse_message(const stewart_inverse *d) {
    return d ? d->message : "inverse is NULL";
}

extern "C" const stewart_model *stewart_inverse_model(const stewart_inverse *d) {
    return d ? d->model : nullptr;
}

extern "C" const stewart_inverse_options *stewart_inverse_options_of(const stewart_inverse *d) {
    return d ? &d->options : nullptr;
}

namespace {

// Finite inputs can still overflow (|z| = 1e154 squares to inf): the last guard before output.
const char *first_non_finite(const stewart_inverse_output &o) {
    static const char *const names[4] = {"length", "length_rate", "length_accel", "force"};
    const double *groups[4] = {o.lengths.length, o.lengths.length_rate, o.lengths.length_accel,
                               o.force};
    for (int g = 0; g < 4; ++g)
        for (int k = 0; k < STEWART_LEGS; ++k)
            if (!std::isfinite(groups[g][k])) return names[g];
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(o.base_force[i]) || !std::isfinite(o.base_torque[i]))
            return "base wrench";
    if (!std::isfinite(o.condition)) return "condition";
    return nullptr;
}

// Sets out.stroke_legs (one bit per leg outside the stroke) and out.warnings.
void stroke_and_condition_warnings(const stewart_params &p, const stewart_inverse_options &o,
                                   stewart_inverse_output &out) {
    out.stroke_legs = 0;
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (out.lengths.length[k] < p.stroke_min[k] || out.lengths.length[k] > p.stroke_max[k])
            out.stroke_legs |= 1 << k;
    out.warnings = out.stroke_legs ? STEWART_WARN_STROKE : 0;
    if (out.condition > o.warn_condition) out.warnings |= STEWART_WARN_NEAR_SINGULAR;
}

}  // namespace

extern "C" stewart_status stewart_inverse_solve(stewart_inverse *d,
                                                const stewart_inverse_input *input,
                                                stewart_inverse_output *output) {
    if (!d || !input || !output) {
        if (d) set_message(d->message, sizeof d->message, STEWART_ERR_ARGUMENT, "NULL argument");
        return STEWART_ERR_ARGUMENT;
    }
    const stewart_model *m = d->model;
    const stewart_inverse_options *o = &d->options;
    const stewart_pose *pose = &input->pose;
    char *msg = d->message;
    const size_t size = sizeof d->message;
    stewart_status s;
    if ((s = stewart::check_pose(*pose, msg, size)) != STEWART_OK) return s;
    // The pose given is the tool's in the user frame: the platform's in the base frame moves so.
    const stewart::Motion motion = m->frames.identity
                                       ? stewart::motion_of_pose(*pose)
                                       : stewart::platform_motion_of_pose(m->frames, *pose);
    if (!m->frames.identity && !stewart::motion_finite(motion))
        return stewart::input_out_of_range(*pose, 0, 2, "platform's motion (tool and user frames)",
                                           msg, size);
    stewart::LegKinematics legs;
    if ((s = stewart::leg_kinematics(m->geometry, motion, legs, msg, size)) != STEWART_OK) return s;

    stewart_inverse_output out{};
    for (int k = 0; k < STEWART_LEGS; ++k) {
        out.lengths.length[k] = legs.length[k];
        out.lengths.length_rate[k] = legs.rate[k];
        out.lengths.length_accel[k] = legs.accel[k];
    }
    switch (o->fidelity) {
        case STEWART_KINEMATIC: break;
        case STEWART_MASSLESS:
            s = stewart::massless_forces(m->geometry, m->platform, m->gravity, motion, legs,
                                         o->singular_condition, out, msg, size);
            break;
        case STEWART_FULL: {
            // Rates and accelerations too large to solve with are the inputs' fault (the closed
            // levels find them in their outputs).
            if (legs.length.allFinite() && !(legs.rate.allFinite() && legs.accel.allFinite())) {
                s = stewart::input_out_of_range(*pose, 1, 2, "leg length rates or accelerations",
                                                msg, size);
                break;
            }
            stewart::LegJacobian jacobian;
            stewart::leg_jacobian(m->geometry, legs, jacobian);
            out.condition = jacobian.condition;
            if ((s = stewart::check_condition(out.condition, o->singular_condition, msg, size)) !=
                STEWART_OK)
                break;
            s = stewart::full_solve(m->full_layout, d->full->state, *o, motion, legs, out, msg,
                                    size);
            if (s == STEWART_ERR_ARGUMENT)  // the core's rates, accelerations or multipliers
                s = stewart::input_out_of_range(*pose, 1, 2, "full model's rates or forces", msg,
                                                size);
            break;
        }
    }
    if (s != STEWART_OK) return s;
    if (const char *name = first_non_finite(out)) {
        // The outputs of the positions, the rates, or of rates and accelerations.
        const int last_row = !std::strcmp(name, "length")        ? 0
                             : !std::strcmp(name, "length_rate") ? 1
                                                                 : 2;
        return stewart::input_out_of_range(*pose, last_row > 0 ? 1 : 0, last_row, name, msg, size);
    }
    stroke_and_condition_warnings(m->params, *o, out);  // on the Cardan-to-Cardan lengths
    if (m->length_offsets)                              // the sensors read length - offset
        for (int k = 0; k < STEWART_LEGS; ++k) out.lengths.length[k] -= m->params.length_offset[k];
    if (m->drives) {  // on the readings: the motor's encoder turns with the sensor's length
        stewart::fill_drive_outputs(m->drive, m->params, out);
        if (!stewart::drive_outputs_finite(out))
            return stewart::input_out_of_range(*pose, 0, 2, "motor torque, current or voltage", msg,
                                               size);
    }
    stewart::base_wrench_to_given_frame(m->frames, out.base_force, out.base_torque);
    *output = out;
    msg[0] = '\0';
    return STEWART_OK;
}
