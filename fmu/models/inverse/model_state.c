/*
 * The inverse model's part of an FMU state: its plain values are checked when deserialised, and
 * the solver's data block travels as the bytes of stewart_inverse_save; loading them is the
 * library's decision (stewart_inverse_load), and a block it refuses is refused with a message.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "logging.h"
#include "model.h"

size_t model_state_size(const fmu_instance *inst) {
    return inst->res.inverse ? stewart_inverse_state_size(inst->res.inverse) : 0;
}

fmu_status model_save(const fmu_instance *inst, unsigned char *out, size_t size) {
    if (!inst->res.inverse) return size == 0 ? FMU_OK : FMU_ERROR;
    return stewart_inverse_save(inst->res.inverse, out, size) == STEWART_OK ? FMU_OK : FMU_ERROR;
}

/* The library's reason for refusing a data block, or a generic one. */
static const char *refusal(const stewart_inverse *d) {
    const char *m = stewart_inverse_message(d);
    return m && *m ? m : "not a saved state of this model (stewart_inverse_load refused it)";
}

fmu_status model_load(fmu_instance *inst, const unsigned char *in, size_t size) {
    model_resources *r = &inst->res;
    const int after_init = fmu_after_initialization(&inst->v);
    if (!r->inverse) return FMU_OK;
    stewart_params p;
    inverse_params_from_values(&inst->v, &p);
    /* Before the end of initialisation the bytes are a warm start of whatever model the instance
     * had then: used only if they belong to the model built now. */
    if (size == 0 || (!after_init && memcmp(&p, &r->params, sizeof p) != 0)) {
        stewart_inverse_reset(r->inverse);
        return FMU_OK;
    }
    if (stewart_inverse_load(r->inverse, in, size) != STEWART_OK) {
        if (!after_init) {
            stewart_inverse_reset(r->inverse);
            return FMU_OK;
        }
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "SetFMUState: the state's solver data is refused: %s",
                refusal(r->inverse));
        return FMU_ERROR;
    }
    return FMU_OK;
}

/* The solver data block of a state after initialisation, checked by loading it into a data block
 * of a model built from the state's parameters (the instance's own model if they match). */
static const char *check_solver_data(fmu_instance *inst, const fmu_values *v,
                                     const unsigned char *in, size_t size, char *why,
                                     size_t why_size) {
    stewart_params p;
    inverse_params_from_values(v, &p);
    stewart_model *own = NULL;
    const stewart_model *model = inst->res.model;
    if (!model || memcmp(&p, &inst->res.params, sizeof p) != 0)
        model = own = stewart_model_create(&p, NULL, 0);
    stewart_inverse_options o;
    inverse_options_from_values(v, &o);
    stewart_inverse *d = model ? stewart_inverse_create(model, &o, NULL, 0) : NULL;
    const char *result = NULL;
    if (!d) {
        result = "out of memory checking the solver data";
    } else if (stewart_inverse_load(d, in, size) != STEWART_OK) {
        snprintf(why, why_size, "the solver data is refused: %s", refusal(d));
        result = why;
    }
    stewart_inverse_free(d);
    stewart_model_free(own);
    return result;
}

const char *model_check_state(fmu_instance *inst, const fmu_values *v, const unsigned char *in,
                              size_t size, char *why, size_t why_size) {
    const model_values *m = &v->model;
    if (m->n_history < 0 || m->n_history > 2) return "finite-difference history is not 0..2 poses";
    if ((m->input_derivatives & ~1) || (m->advance_discarded & ~1) || m->solve_status < FMU_OK ||
        m->solve_status > FMU_ERROR)
        return "a flag is out of range";
    if (m->newer & ~1) return "finite-difference history's newer point is not 0 or 1";
    /* (points are committed by accepted steps: the hold step relies on it, usual_step.c
     * step_end) */
    if (m->n_history > 0 && !v->has_stepped) return "finite-difference history without a step";
    if (m->n_history > 0) {
        const fd_point *newer = &m->history[m->newer];
        if (!(newer->t < v->time) || (m->n_history == 2 && !(newer->interval > 0)))
            return "finite-difference history is not before the current time and ordered";
        for (int i = 0; i < 6; ++i)
            if (!isfinite(newer->pose.q[i])) return "finite-difference history is not finite";
    }
#define FMU_OUTPUT(vr, id, name, unit, field, desc) \
    if (!isfinite(v->real[vr])) return "output " name " is not finite";
#include "variables.def"
    if (v->integer[VR_status] < 0 || v->integer[VR_status] > 3) return "status is not 0..3";
    if (v->integer[VR_newton_iterations] < 0) return "newton_iterations is negative";
    static const char *const kRoute = "the usual step's route does not match the values";
    if (!fmu_after_initialization(v)) return inverse_usual_route_valid(v) ? NULL : kRoute;
    /* parameters and options: exactly what initialisation accepted (model_apply_parameters) */
    if (v->integer[VR_derivatives] != 0 && v->integer[VR_derivatives] != 1)
        return "option derivatives is out of range";
    stewart_inverse_options o;
    inverse_options_from_values(v, &o);
    if (stewart_inverse_options_check(&o, NULL, 0) != STEWART_OK)
        return "an option is out of range";
    stewart_params p;
    inverse_params_from_values(v, &p);
    if (stewart_params_check(&p, NULL, 0) != STEWART_OK) return "a parameter is invalid";
    if (!inverse_usual_route_valid(v)) return kRoute; /* (after the values it is made of) */
    return size ? check_solver_data(inst, v, in, size, why, why_size) : NULL;
}
