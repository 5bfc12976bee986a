// The C API: model and data lifetime, and the per-pose solve dispatched on the fidelity level.
#include <cmath>
#include <cstring>
#include <new>

#include "model.hpp"
#include "util/message.hpp"

using stewart::clear_message;
using stewart::set_message;

extern "C" stewart_model *stewart_model_create(const stewart_params *params, char *msg,
                                               size_t size) {
    if (stewart_params_check(params, msg, size) != STEWART_OK) return nullptr;
    stewart_model *m = new (std::nothrow) stewart_model;
    if (!m) {
        set_message(msg, size, STEWART_ERR_MEMORY, "out of memory creating the model");
        return nullptr;
    }
    m->params = *params;
    m->geometry = stewart::platform_geometry(*params);
    m->platform = stewart::lumped_platform(*params);
    m->gravity = Eigen::Vector3d(params->gravity);
    m->full = stewart::build_full_platform(*params, stewart::FullDrive::ActuatorLengths,
                                           m->full_layout, msg, size);
    if (!m->full) {
        delete m;
        return nullptr;
    }
    clear_message(msg, size);
    return m;
}

extern "C" void stewart_model_free(stewart_model *m) { delete m; }

extern "C" const stewart_params *stewart_model_params(const stewart_model *m) {
    return m ? &m->params : nullptr;
}

extern "C" stewart_data *stewart_data_create(const stewart_model *m) {
    if (!m) return nullptr;
    stewart_data *d = new (std::nothrow) stewart_data;
    if (!d) return nullptr;
    d->model = m;
    d->full.reset(new (std::nothrow) mbs_data(m->full.get(), mbs::SolverOptions()));
    if (!d->full || !d->full->state.ok()) {
        delete d;
        return nullptr;
    }
    stewart_data_reset(d);
    return d;
}

extern "C" void stewart_data_free(stewart_data *d) { delete d; }

extern "C" stewart_status stewart_data_copy(stewart_data *dst, const stewart_data *src) {
    if (!dst || !src) return STEWART_ERR_ARGUMENT;
    if (dst->model != src->model)
        return set_message(dst->message, sizeof dst->message, STEWART_ERR_ARGUMENT,
                           "the data blocks were made for different models");
    std::memcpy(dst->message, src->message, sizeof dst->message);
    mbs::copy_state(dst->full->state, src->full->state);
    return STEWART_OK;
}

extern "C" size_t stewart_data_state_size(const stewart_data *d) {
    return d && d->full ? mbs::saved_state_size(d->full->state) : 0;
}

extern "C" stewart_status stewart_data_save(const stewart_data *d, void *buffer, size_t size) {
    if (!d || !d->full || !buffer || size < stewart_data_state_size(d)) return STEWART_ERR_ARGUMENT;
    mbs::save_state(d->full->state, static_cast<unsigned char *>(buffer));
    return STEWART_OK;
}

extern "C" stewart_status stewart_data_load(stewart_data *d, const void *buffer, size_t size) {
    if (!d || !d->full) return STEWART_ERR_ARGUMENT;
    if (!buffer) return set_message(d->message, sizeof d->message, STEWART_ERR_ARGUMENT, "buffer is NULL");
    char why[MBS_MESSAGE_SIZE];
    if (!mbs::load_state(d->full->state, static_cast<const unsigned char *>(buffer), size, why,
                         sizeof why))
        return set_message(d->message, sizeof d->message, STEWART_ERR_ARGUMENT,
                           "state not loaded (the data block is unchanged): %s", why);
    d->message[0] = '\0';
    return STEWART_OK;
}

extern "C" void stewart_data_reset(stewart_data *d) {
    if (!d) return;
    d->message[0] = '\0';
    if (d->full) mbs::reset(d->full->state);
    d->forward.reset();
}

extern "C" const char *stewart_data_message(const stewart_data *d) {
    return d ? d->message : "data is NULL";
}

extern "C" const char *stewart_status_name(stewart_status s) {
    switch (s) {
        case STEWART_OK: return "ok";
        case STEWART_ERR_ARGUMENT: return "invalid argument";
        case STEWART_ERR_PARAMETER: return "invalid parameter";
        case STEWART_ERR_SINGULAR: return "singular";
        case STEWART_ERR_UNREACHABLE: return "unreachable pose";
        case STEWART_ERR_NOT_CONVERGED: return "not converged";
        case STEWART_ERR_UNSUPPORTED: return "unsupported";
        case STEWART_ERR_MEMORY: return "out of memory";
        case STEWART_ERR_OTHER_BRANCH: return "other assembly mode";
    }
    return "unknown status";
}

namespace {

// Finite inputs can still overflow (|z| = 1e154 squares to inf): the last guard before output.
const char *first_non_finite(const stewart_output &o) {
    static const char *const names[4] = {"length", "length_rate", "length_accel", "force"};
    const double *groups[4] = {o.length, o.length_rate, o.length_accel, o.force};
    for (int g = 0; g < 4; ++g)
        for (int k = 0; k < STEWART_LEGS; ++k)
            if (!std::isfinite(groups[g][k])) return names[g];
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(o.base_force[i]) || !std::isfinite(o.base_torque[i])) return "base wrench";
    if (!std::isfinite(o.condition)) return "condition";
    return nullptr;
}

// Sets out.stroke_legs (one bit per leg outside the stroke) and out.warnings.
void stroke_and_condition_warnings(const stewart_params &p, const stewart_options &o,
                                   stewart_output &out) {
    out.stroke_legs = 0;
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (out.length[k] < p.stroke_min || out.length[k] > p.stroke_max) out.stroke_legs |= 1 << k;
    out.warnings = out.stroke_legs ? STEWART_WARN_STROKE : 0;
    if (out.condition > o.warn_condition) out.warnings |= STEWART_WARN_NEAR_SINGULAR;
}

}  // namespace

extern "C" stewart_status stewart_solve(const stewart_model *m, stewart_data *d,
                                        const stewart_options *o, const stewart_pose *pose,
                                        stewart_output *output) {
    if (!m || !d || !o || !pose || !output) {
        if (d) set_message(d->message, sizeof d->message, STEWART_ERR_ARGUMENT, "NULL argument");
        return STEWART_ERR_ARGUMENT;
    }
    char *msg = d->message;
    const size_t size = sizeof d->message;
    if (d->model != m)
        return set_message(msg, size, STEWART_ERR_ARGUMENT,
                           "this data block was made for another model: make one for this model "
                           "with stewart_data_create");
    stewart_status s = stewart_options_check(o, msg, size);
    if (s != STEWART_OK) return s;
    if ((s = stewart::check_pose(*pose, msg, size)) != STEWART_OK) return s;

    const stewart::RigidMotion motion = stewart::rigid_motion(*pose);
    stewart::LegKinematics legs;
    if ((s = stewart::leg_kinematics(m->geometry, motion, legs, msg, size)) != STEWART_OK) return s;

    stewart_output out{};
    for (int k = 0; k < STEWART_LEGS; ++k) {
        out.length[k] = legs.length[k];
        out.length_rate[k] = legs.rate[k];
        out.length_accel[k] = legs.accel[k];
    }
    switch (o->fidelity) {
        case STEWART_KINEMATIC:
            break;
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
            if ((s = stewart::check_condition(out.condition, o->singular_condition, msg,
                                              size)) != STEWART_OK)
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
        const int last_row = !std::strcmp(name, "length") ? 0 : !std::strcmp(name, "length_rate") ? 1 : 2;
        return stewart::input_out_of_range(*pose, last_row > 0 ? 1 : 0, last_row, name, msg, size);
    }
    stroke_and_condition_warnings(m->params, *o, out);
    *output = out;
    msg[0] = '\0';
    return STEWART_OK;
}
