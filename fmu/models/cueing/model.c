/*
 * The cueing model on the FMU runtime: the vehicle's specific force and angular velocity, held
 * over each communication step, go to stewart_cueing_step; its pose, rates, accelerations and
 * flags fill the output variables. The start's outputs are a step of no time at the start inputs.
 * A refused step (a non-finite input) is Discard naming the input, the state left as it was.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bindings.h"
#include "logging.h"
#include "model_interface.h"

/* ---------------------------------------------------------------- values <-> library */

void model_start_values(fmu_values *v) {
    stewart_params p;
    stewart_params_default(&p);
    stewart_cueing_options o;
    stewart_cueing_options_default(&o);
    fmu_start_values(v);
    fmu_params_to_values(v, &p);
    fmu_table_options_to_values(v, &o);
    v->integer[VR_status] = 3; /* nothing stepped yet */
}

static void params_from_values(const fmu_values *v, stewart_params *p, stewart_cueing_options *o) {
    stewart_params_default(p);
    fmu_params_from_values(v, p);
    stewart_cueing_options_default(o);
    fmu_table_options_from_values(v, o);
}

/* Why the values' parameters and options cannot build a cueing unit (names the variable), or
 * NULL; the library's checks. */
static const char *check_settings(const fmu_values *v, char *why, size_t size) {
    stewart_params p;
    stewart_cueing_options o;
    params_from_values(v, &p, &o);
    char message[STEWART_MESSAGE_SIZE];
    if (stewart_cueing_options_check(&o, message, sizeof message) != STEWART_OK ||
        stewart_params_check(&p, message, sizeof message) != STEWART_OK) {
        snprintf(why, size, "%s", message);
        return why;
    }
    return NULL;
}

/* ---------------------------------------------------------------- parameters */

/* Builds the model and cueing unit for the values' parameters (reusing what did not change). */
static fmu_status build_cueing(fmu_instance *inst, const stewart_params *p,
                               const stewart_cueing_options *o) {
    model_resources *r = &inst->res;
    const int new_model = !r->model || memcmp(p, &r->params, sizeof *p) != 0;
    if (!new_model && r->cueing && fmu_same_table_options(o, &r->options)) return FMU_OK;
    stewart_model *m =
        new_model ? stewart_model_create(p, r->message, sizeof r->message) : r->model;
    stewart_cueing *c = m ? stewart_cueing_create(m, o, r->message, sizeof r->message) : NULL;
    if (!c) {
        if (new_model) stewart_model_free(m);
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "invalid parameter: %s", r->message);
        return FMU_ERROR;
    }
    stewart_cueing_free(r->cueing);
    if (new_model) {
        stewart_model_free(r->model);
        r->model = m;
        r->params = *p;
    }
    r->cueing = c;
    r->options = *o;
    fmu_log(inst, FMU_OK, LOG_EVENTS, "cueing unit built (algorithm %d)", o->algorithm);
    return FMU_OK;
}

fmu_status model_apply_parameters(fmu_instance *inst) {
    model_resources *r = &inst->res;
    if (check_settings(&inst->v, r->message, sizeof r->message)) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "invalid parameter: %s", r->message);
        return FMU_ERROR;
    }
    stewart_params p;
    stewart_cueing_options o;
    params_from_values(&inst->v, &p, &o);
    return build_cueing(inst, &p, &o);
}

/* ---------------------------------------------------------------- steps */

/* The cue after holding the inputs over dt: outputs written on success; Discard (state and
 * outputs unchanged, status 3) naming the cause when the unit refuses the inputs. */
static fmu_status cue(fmu_instance *inst, double dt) {
    fmu_values *v = &inst->v;
    stewart_cueing_input in;
    in.dt = dt;
    for (int i = 0; i < 3; ++i) {
        in.specific_force[i] = v->real[VR_specific_force_1 + i];
        in.angular_velocity[i] = v->real[VR_angular_velocity_1 + i];
    }
    stewart_cueing_output out;
    if (stewart_cueing_step(inst->res.cueing, &in, &out) != STEWART_OK) {
        fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                "t = %.17g: step refused: %s; the state stays at t, outputs keep their last "
                "valid values",
                v->time, stewart_cueing_message(inst->res.cueing));
        v->integer[VR_status] = 3;
        v->model.solve_status = FMU_DISCARD;
        v->outputs_current = 1;
        return FMU_DISCARD;
    }
#define FMU_OUTPUT(vr, id, name, unit, field, desc) v->real[vr] = out.field;
#include "variables.def"
    v->integer[VR_limited] = out.limited;
    v->integer[VR_cut] = out.cut;
    v->integer[VR_tilt_limited] = out.tilt_limited;
    v->integer[VR_leg_limits] = out.leg_limits;
    v->integer[VR_status] = 0;
    v->model.solve_status = FMU_OK;
    v->model.stepped = 1;
    v->outputs_current = 1;
    return FMU_OK;
}

/* Initialisation: at rest, and the start's outputs at the start inputs. */
fmu_status model_start(fmu_instance *inst) {
    stewart_cueing_reset(inst->res.cueing);
    inst->v.model.stepped = 0;
    inst->v.model.solve_status = FMU_OK;
    inst->v.outputs_current = 0;
    return FMU_OK;
}

void model_reset(fmu_instance *inst) { (void)inst; /* the unit is reset at initialisation */ }

void model_free(fmu_instance *inst) {
    stewart_cueing_free(inst->res.cueing);
    stewart_model_free(inst->res.model);
    inst->res.cueing = NULL;
    inst->res.model = NULL;
}

/* The outputs change at steps only (no feedthrough); before the first step they are the start's:
 * a step of no time at the inputs set so far. */
fmu_status model_refresh_outputs(fmu_instance *inst) {
    if (inst->v.outputs_current || inst->v.model.stepped) {
        inst->v.outputs_current = 1;
        return inst->v.model.solve_status;
    }
    if (!inst->res.cueing) return FMU_OK; /* before the end of initialisation: start values */
    return cue(inst, 0.0);
}

fmu_status model_do_step(fmu_instance *inst, double t, double h) {
    (void)t;
    if (!inst->v.model.stepped) {
        const fmu_status start = cue(inst, 0.0); /* the start's outputs, if never read */
        if (start != FMU_OK) return start;
    }
    return cue(inst, h);
}

fmu_status model_set_input_derivatives(fmu_instance *inst, const unsigned vr[], size_t n,
                                       const int order[], const double value[]) {
    (void)vr;
    (void)order;
    (void)value;
    if (n == 0) return FMU_OK;
    fmu_log(inst, FMU_ERROR, LOG_ERROR,
            "SetRealInputDerivatives: StewartCueing takes no input derivatives");
    return FMU_ERROR;
}

/* ---------------------------------------------------------------- FMU state */

size_t model_state_size(const fmu_instance *inst) {
    return inst->res.cueing ? stewart_cueing_state_size(inst->res.cueing) : 0;
}

fmu_status model_save(const fmu_instance *inst, unsigned char *out, size_t size) {
    if (!inst->res.cueing) return size == 0 ? FMU_OK : FMU_ERROR;
    return stewart_cueing_save(inst->res.cueing, out, size) == STEWART_OK ? FMU_OK : FMU_ERROR;
}

fmu_status model_load(fmu_instance *inst, const unsigned char *in, size_t size) {
    if (!fmu_after_initialization(&inst->v)) return FMU_OK; /* reset at initialisation */
    if (stewart_cueing_load(inst->res.cueing, in, size) != STEWART_OK) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "SetFMUState: the state's cueing data is refused: %s",
                stewart_cueing_message(inst->res.cueing));
        return FMU_ERROR;
    }
    return FMU_OK;
}

const char *model_check_state(fmu_instance *inst, const fmu_values *v, const unsigned char *in,
                              size_t size, char *why, size_t why_size) {
    (void)inst;
    const model_values *m = &v->model;
    if ((m->stepped & ~1) || m->solve_status < FMU_OK || m->solve_status > FMU_ERROR)
        return "a flag is out of range";
#define FMU_OUTPUT(vr, id, name, unit, field, desc) \
    if (!isfinite(v->real[vr])) return "output " name " is not finite";
#include "variables.def"
    if (v->integer[VR_status] != 0 && v->integer[VR_status] != 3) return "status is not 0 or 3";
    if (!fmu_after_initialization(v)) return NULL; /* cueing data, if any, is not used */
    if (check_settings(v, why, why_size)) return why;
    /* The bytes are checked by the library when loaded (their options must be the state's). */
    if (size == 0) return "no cueing data after initialisation";
    (void)in;
    return NULL;
}
