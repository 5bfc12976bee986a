/*
 * The inverse-dynamics model on the FMU runtime (StewartPlatform): the pose inputs (and their
 * derivatives, given or by finite differences) go to stewart_inverse_solve, whose output fills the
 * output variables. This file: the values to the library (parameters, options) and the resources
 * built from them, and FMI 2 input derivatives. The solve is solve.c's, the step rules
 * step_rules.c's and usual_step.c's (model.h lists the files).
 */
#include <math.h>
#include <string.h>

#include "bindings.h"
#include "logging.h"
#include "model.h"

void model_start_values(fmu_values *v) {
    stewart_params p;
    stewart_inverse_options o;
    stewart_params_default(&p);
    stewart_inverse_options_default(&o);
    fmu_start_values(v);
    fmu_params_to_values(v, &p);
    fmu_table_options_to_values(v, &o);
    v->integer[VR_fidelity] = STEWART_FULL; /* the FMU's default; the library's is massless */
    v->integer[VR_status] = 3;              /* nothing solved yet */
}

void inverse_params_from_values(const fmu_values *v, stewart_params *p) {
    stewart_params_default(p);
    fmu_params_from_values(v, p);
}

void inverse_options_from_values(const fmu_values *v, stewart_inverse_options *o) {
    stewart_inverse_options_default(o);
    fmu_table_options_from_values(v, o);
}

/* ---------------------------------------------------------------- parameters */

/* The unit's own options (not the library's): Error naming one out of range. */
static fmu_status check_unit_options(fmu_instance *inst) {
    const fmu_values *v = &inst->v;
    if (v->integer[VR_limit_outputs] < 0 || v->integer[VR_limit_outputs] > 2) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "invalid parameter limit_outputs = %d: it must be 0 (none), 1 (the limit check) "
                "or 2 (and the axis ranges)",
                (int)v->integer[VR_limit_outputs]);
        return FMU_ERROR;
    }
    if (v->integer[VR_derivatives] != 0 && v->integer[VR_derivatives] != 1) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "invalid parameter derivatives = %d: it must be 0 (finite differences) or 1 "
                "(the *_dot and *_ddot inputs)",
                (int)v->integer[VR_derivatives]);
        return FMU_ERROR;
    }
    return FMU_OK;
}

/* The model is rebuilt from p (new_model), and the inverse solver for it with options o; a solver
 * rebuilt for the same model keeps its warm start. */
static fmu_status build_solver(fmu_instance *inst, const stewart_params *p,
                               const stewart_inverse_options *o, int new_model) {
    model_resources *r = &inst->res;
    stewart_model *m =
        new_model ? stewart_model_create(p, r->message, sizeof r->message) : r->model;
    if (!m) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "invalid parameter: %s", r->message);
        return FMU_ERROR;
    }
    stewart_inverse *d = stewart_inverse_create(m, o, r->message, sizeof r->message);
    if (!d) {
        if (new_model) stewart_model_free(m);
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "creating the inverse solver: %s", r->message);
        return FMU_ERROR;
    }
    if (!new_model) stewart_inverse_copy(d, r->inverse); /* the warm start goes on */
    stewart_inverse_free(r->inverse);
    r->inverse = d;
    if (new_model) {
        stewart_linearize_free(r->linearize); /* made for the old model */
        r->linearize = NULL;
        stewart_model_free(r->model);
        r->model = m;
        r->params = *p;
        fmu_log(inst, FMU_OK, LOG_EVENTS,
                "model built from the parameters (fidelity %d, "
                "derivatives %d)",
                (int)inst->v.integer[VR_fidelity], (int)inst->v.integer[VR_derivatives]);
    }
    return FMU_OK;
}

/* The limit check for the model and the condition limit of o (cheap to make: no workspace). */
static fmu_status build_limits(fmu_instance *inst, const stewart_inverse_options *o) {
    model_resources *r = &inst->res;
    stewart_limits_options lo;
    stewart_limits_options_default(&lo);
    lo.warn_condition = o->warn_condition;
    stewart_limits *l = stewart_limits_create(r->model, &lo, r->message, sizeof r->message);
    if (!l) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "creating the limit check: %s", r->message);
        return FMU_ERROR;
    }
    stewart_limits_free(r->limits);
    r->limits = l;
    return FMU_OK;
}

fmu_status model_apply_parameters(fmu_instance *inst) {
    fmu_values *v = &inst->v;
    model_resources *r = &inst->res;
    if (check_unit_options(inst) != FMU_OK) return FMU_ERROR;
    stewart_inverse_options o;
    inverse_options_from_values(v, &o);
    if (stewart_inverse_options_check(&o, r->message, sizeof r->message) != STEWART_OK) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "invalid parameter: %s", r->message);
        return FMU_ERROR;
    }
    stewart_params p;
    inverse_params_from_values(v, &p);
    const int new_model = !r->model || memcmp(&p, &r->params, sizeof p) != 0;
    if ((new_model || !r->inverse ||
         !fmu_same_table_options(&o, stewart_inverse_options_of(r->inverse))) &&
        build_solver(inst, &p, &o, new_model) != FMU_OK)
        return FMU_ERROR;
    if ((new_model || !r->limits || r->options.warn_condition != o.warn_condition) &&
        build_limits(inst, &o) != FMU_OK)
        return FMU_ERROR;
    r->options = o;
    inverse_settle_usual_route(v);
    return FMU_OK;
}

/* The inverse solver starts from what model_apply_parameters built: nothing more to set. */
fmu_status model_start(fmu_instance *inst) {
    (void)inst;
    return FMU_OK;
}

void model_reset(fmu_instance *inst) {
    if (inst->res.inverse) stewart_inverse_reset(inst->res.inverse);
}

void model_free(fmu_instance *inst) {
    stewart_linearize_free(inst->res.linearize);
    inst->res.linearize = NULL;
    stewart_limits_free(inst->res.limits);
    stewart_inverse_free(inst->res.inverse);
    stewart_model_free(inst->res.model);
    inst->res.limits = NULL;
    inst->res.inverse = NULL;
    inst->res.model = NULL;
}

/* ---------------------------------------------------------------- input derivatives */

fmu_status model_set_input_derivatives(fmu_instance *inst, const unsigned vr[], size_t n,
                                       const int order[], const double value[]) {
    fmu_values *v = &inst->v;
    for (size_t i = 0; i < n; ++i) {
        const int pose = vr[i] <= VR_yaw, rate = vr[i] >= VR_x_dot && vr[i] <= VR_yaw_dot;
        if (!((pose && (order[i] == 1 || order[i] == 2)) || (rate && order[i] == 1))) {
            fmu_log(inst, FMU_ERROR, LOG_ERROR,
                    "SetRealInputDerivatives: derivative of order %d of value reference %u is "
                    "not supported (orders 1 and 2 of the pose inputs, order 1 of *_dot)",
                    order[i], vr[i]);
            return FMU_ERROR;
        }
    }
    /* With derivatives = 0 the *_dot and *_ddot slots hold only what this call and the others
     * before the same step give: an order the master does not give is zero for the step, never
     * a value left from an earlier step. */
    if (n > 0 && !v->model.input_derivatives && v->integer[VR_derivatives] == 0)
        for (unsigned vr_slot = VR_x_dot; vr_slot <= VR_yaw_ddot; ++vr_slot) v->real[vr_slot] = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const unsigned base = vr[i] <= VR_yaw ? vr[i] : vr[i] - VR_x_dot;
        v->real[(order[i] == 1 && vr[i] <= VR_yaw ? VR_x_dot : VR_x_ddot) + base] = value[i];
        if (!isfinite(value[i])) v->inputs_unchecked = 1; /* the step looks at the inputs */
    }
    if (n > 0) v->model.input_derivatives = 1;
    inverse_settle_usual_route(v);
    return FMU_OK;
}
