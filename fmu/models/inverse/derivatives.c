/* The inverse model's directional derivatives (model_interface.h): the library's Jacobian of the
 * inverse side (stewart_linearize_inverse) at the pose the outputs are solved at, composed with
 * how that pose follows from the inputs: directly (rates as inputs), or through the finite
 * differences of the pose over the last communication points (rate inputs unused). */
#include <string.h>

#include "logging.h"
#include "model.h"
#include "model_interface.h"
#include "variables.h"

/* Row of the library's Jacobian (stewart_linearize_inverse_output.jacobian) for output vr, or -1
 * if the output has none (the condition number and the residual are not differentiable). */
static int jacobian_row(unsigned vr) {
    if (vr >= VR_L_1 && vr <= VR_L_6) return (int)(vr - VR_L_1);
    if (vr >= VR_L_dot_1 && vr <= VR_L_dot_6) return 6 + (int)(vr - VR_L_dot_1);
    if (vr >= VR_L_ddot_1 && vr <= VR_L_ddot_6) return 12 + (int)(vr - VR_L_ddot_1);
    if (vr >= VR_F_1 && vr <= VR_F_6) return 18 + (int)(vr - VR_F_1);
    if (vr >= VR_base_force_1 && vr <= VR_base_force_3) return 24 + (int)(vr - VR_base_force_1);
    if (vr >= VR_base_torque_1 && vr <= VR_base_torque_3) return 27 + (int)(vr - VR_base_torque_1);
    return -1;
}

/* d(q_dot, q_ddot)/dq of the finite differences the model uses without rate inputs (model.c:
 * current_pose): the chord through the last pose, or the quadratic through the last two. */
static void difference_weights(const model_values *m, double time, double *rate, double *accel) {
    const fd_point *newer = &m->history[m->newer];
    *rate = *accel = 0;
    if (m->n_history == 1) {
        *rate = 1 / (time - newer->t);
    } else if (m->n_history == 2) {
        const double h1 = newer->interval, h2 = time - newer->t;
        *rate = 1 / h2 + 1 / (h1 + h2);
        *accel = 2 / (h2 * (h1 + h2));
    }
}

fmu_status model_directional_derivative(fmu_instance *inst, const unsigned unknown[],
                                        size_t n_unknown, const unsigned known[], size_t n_known,
                                        const double seed[], double sensitivity[],
                                        const char *function) {
    fmu_values *v = &inst->v;
    model_resources *r = &inst->res;
    for (size_t i = 0; i < n_unknown; ++i)
        if (jacobian_row(unknown[i]) < 0) {
            fmu_log(inst, FMU_ERROR, LOG_ERROR,
                    "%s: output %s has no derivative (a condition number or a residual is not "
                    "differentiable); ask for lengths, rates, accelerations, forces or the base "
                    "wrench", function, fmu_variable_by_vr(unknown[i])->name);
            return FMU_ERROR;
        }
    /* The forces' model: massless legs below fidelity 2 (fidelity 0 has no forces at all). */
    const int fidelity = r->options.fidelity == STEWART_FULL ? STEWART_FULL : STEWART_MASSLESS;
    if (r->linearize && stewart_linearize_options_of(r->linearize)->fidelity != fidelity) {
        stewart_linearize_free(r->linearize);
        r->linearize = NULL;
    }
    if (!r->linearize) {
        stewart_linearize_options o;
        stewart_linearize_options_default(&o);
        o.fidelity = fidelity;
        r->linearize = stewart_linearize_create(r->model, &o, r->message, sizeof r->message);
        if (!r->linearize) {
            fmu_log(inst, FMU_ERROR, LOG_ERROR, "%s: %s", function, r->message);
            return FMU_ERROR;
        }
    }
    stewart_pose pose;
    inverse_current_pose(v, v->time, &pose);
    stewart_linearize_inverse_output out;
    const stewart_status s = stewart_linearize_inverse(r->linearize, &pose, &out);
    if (s != STEWART_OK) {
        fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                "t = %.17g: %s: no derivatives at this pose: %s", v->time, function,
                stewart_linearize_message(r->linearize));
        return FMU_DISCARD;
    }
    const int from_inputs = inverse_uses_rate_inputs(v);
    double rate_weight = 0, accel_weight = 0;
    if (!from_inputs) difference_weights(&v->model, v->time, &rate_weight, &accel_weight);
    for (size_t i = 0; i < n_unknown; ++i) {
        const int row = jacobian_row(unknown[i]);
        const double *d = out.jacobian[row];
        /* fidelity 0 gives no forces and no base wrench: they are constant zero */
        const int constant = r->options.fidelity == 0 && row >= 18;
        double sum = 0;
        for (size_t j = 0; j < n_known && !constant; ++j) {
            const unsigned c = known[j] - VR_x; /* the inputs are q, q_dot, q_ddot in order */
            if (from_inputs)
                sum += d[c] * seed[j];
            else if (c < 6)
                sum += (d[c] + rate_weight * d[6 + c] + accel_weight * d[12 + c]) * seed[j];
        }
        sensitivity[i] = sum;
    }
    return FMU_OK;
}
