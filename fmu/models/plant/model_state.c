/*
 * The plant model's part of an FMU state: its plain values are checked when deserialised, and
 * the plant's state (stewart_plant_save: time, pose, twist, last forces) travels as bytes;
 * loading them is the library's decision (stewart_plant_load), and a refusal is an Error with
 * its reason.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "logging.h"
#include "model.h"

size_t model_state_size(const fmu_instance *inst) {
    return inst->res.plant ? stewart_plant_state_size(inst->res.plant) : 0;
}

fmu_status model_save(const fmu_instance *inst, unsigned char *out, size_t size) {
    if (!inst->res.plant) return size == 0 ? FMU_OK : FMU_ERROR;
    if (size != stewart_plant_state_size(inst->res.plant) ||
        stewart_plant_save(inst->res.plant, out, size) != STEWART_OK)
        return FMU_ERROR;
    return FMU_OK;
}

/* Loads saved plant bytes into a plant (the library checks them). */
static stewart_status load_bytes(stewart_plant *plant, const unsigned char *in, size_t size) {
    return stewart_plant_load(plant, in, size);
}

fmu_status model_load(fmu_instance *inst, const unsigned char *in, size_t size) {
    /* before the end of initialisation the plant is set afresh there: nothing to load */
    if (!fmu_after_initialization(&inst->v)) return FMU_OK;
    /* the runtime has built a plant for the state's parameters */
    if (load_bytes(inst->res.plant, in, size) != STEWART_OK) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "SetFMUState: the state's plant data is refused: %s",
                *stewart_plant_message(inst->res.plant) ? stewart_plant_message(inst->res.plant)
                                                        : "wrong size");
        return FMU_ERROR;
    }
    return FMU_OK;
}

/* Why the saved values do not belong to the plant's loaded state, or NULL: the plant's time is
 * the unit's (to the rounding of a clock), and outputs the plant computed (status 0 or 1) are
 * the motion of that state with the stroke bits and status it gives. */
static const char *mismatch(const fmu_values *v, const stewart_plant *plant,
                            const stewart_params *p, char *why, size_t why_size) {
    const double t = plant_time(plant);
    if (!(fabs(t - v->time) <= clock_rounding(fmax(fabs(t), fabs(v->time))))) {
        snprintf(why, why_size, "the plant's time %.17g is not the unit's time %.17g", t, v->time);
        return why;
    }
    const int32_t status = v->integer[VR_status];
    const int solve = v->model.solve_status;
    if ((status == 3) != (solve == FMU_DISCARD) || (status == 1) != (solve == FMU_WARNING))
        return "status does not match the last refresh's result";
    if (status == 3) return NULL; /* outputs are older than the state: nothing to compare */
    const double zero[STEWART_LEGS] = {0};
    stewart_plant_output out;
    if (stewart_plant_output_get(plant, zero, &out) != STEWART_OK)
        return "the plant's outputs overflow at the state's pose";
    const double *motion[4] = {out.pose.q, out.pose.q_dot, out.lengths.length,
                               out.lengths.length_rate};
    for (int vr = VR_x; vr <= VR_L_dot_6; ++vr) { /* four groups of six, in that order */
        const int group = (vr - VR_x) / 6, index = (vr - VR_x) % 6;
        if (memcmp(&v->real[vr], &motion[group][index], sizeof(double)) != 0) {
            snprintf(why, why_size, "output %s = %.17g is not the plant's %.17g",
                     fmu_variable_by_vr((unsigned)vr)->name, v->real[vr], motion[group][index]);
            return why;
        }
    }
    int outside = 0;
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (out.lengths.length[k] < p->stroke_min[k] || out.lengths.length[k] > p->stroke_max[k])
            outside |= 1 << k;
    if (outside != v->model.legs_outside || (status == 1) != (outside != 0))
        return "the stroke flags or status do not match the leg lengths";
    if (v->model.limit_warnings !=
        (out.warnings & (STEWART_WARN_JOINT_LIMIT | STEWART_WARN_INTERFERENCE)))
        return "the joint-limit and interference flags do not match the pose";
    return NULL;
}

void plant_free_checker(model_resources *r) {
    stewart_plant_free(r->checker);
    r->checker = NULL;
}

/* The instance's checking plant for options o (built on the instance's model on first use or when
 * the options change), or NULL with the reason in message. */
static stewart_plant *kept_checker(model_resources *r, const stewart_plant_options *o,
                                   char *message, size_t size) {
    if (r->checker && !memcmp(o, &r->checker_options, sizeof *o)) return r->checker;
    stewart_plant *plant = stewart_plant_create(r->model, o, message, size);
    if (!plant) return NULL;
    plant_free_checker(r);
    r->checker = plant;
    memcpy(&r->checker_options, o, sizeof *o); /* bytes, padding included, for the memcmp */
    return plant;
}

/* The plant bytes of a state after initialisation, checked by loading them into a plant on a
 * model of the state's parameters, and against the values they travel with. The instance's own
 * model when the parameters are its own (bitwise: a rollback's), else a temporary one: building a
 * model is most of a check's cost. The load and the comparisons are the same either way. */
static const char *check_plant_data(fmu_instance *inst, const fmu_values *v,
                                    const unsigned char *in, size_t size, char *why,
                                    size_t why_size) {
    stewart_params p;
    plant_settings s;
    plant_params_from_values(v, &p);
    plant_settings_from_values(v, &s);
    char message[STEWART_MESSAGE_SIZE] = "";
    model_resources *r = &inst->res;
    stewart_model *own_model = NULL;
    stewart_plant *own_plant = NULL, *plant = NULL;
    if (r->model && !memcmp(&p, &r->params, sizeof p)) {
        plant = kept_checker(r, &s.options, message, sizeof message);
    } else {
        own_model = stewart_model_create(&p, message, sizeof message);
        plant = own_plant =
            own_model ? stewart_plant_create(own_model, &s.options, message, sizeof message) : NULL;
    }
    const char *result = NULL;
    if (!plant) {
        snprintf(why, why_size, "the state's parameters and options make no plant: %s", message);
        result = why;
    } else if (load_bytes(plant, in, size) != STEWART_OK) {
        snprintf(why, why_size, "the plant data is refused: %s",
                 *stewart_plant_message(plant) ? stewart_plant_message(plant) : "wrong size");
        result = why;
    } else {
        result = mismatch(v, plant, &p, why, why_size);
    }
    stewart_plant_free(own_plant);
    stewart_model_free(own_model);
    return result;
}

const char *model_check_state(fmu_instance *inst, const fmu_values *v, const unsigned char *in,
                              size_t size, char *why, size_t why_size) {
    const model_values *m = &v->model;
    if ((m->input_derivatives & ~1) || m->solve_status < FMU_OK || m->solve_status > FMU_ERROR ||
        (m->legs_outside & ~63) ||
        (m->limit_warnings & ~(STEWART_WARN_JOINT_LIMIT | STEWART_WARN_INTERFERENCE)))
        return "a flag is out of range";
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (!isfinite(m->force_rate[k])) return "an input derivative is not finite";
    if (m->totals.steps < 0 || m->totals.rhs_evaluations < 0 ||
        m->totals.nonlinear_iterations < 0 || m->totals.error_test_failures < 0 ||
        m->totals.jacobian_evaluations < 0)
        return "an integrator total is negative";
#define FMU_OUTPUT(vr, id, name, unit, field, desc) \
    if (!isfinite(v->real[vr])) return "output " name " is not finite";
#include "variables.def"
    if (v->integer[VR_status] < 0 || v->integer[VR_status] > 3) return "status is not 0..3";
    for (int vr = VR_steps; vr <= VR_last_order; ++vr)
        if (v->integer[vr] < 0) return "an integrator statistic is negative";
    if (!fmu_after_initialization(v))
        return NULL; /* plant data, if any, is not used (model_load) */
    if (plant_check_settings(v, why, why_size)) return why;
    if (size == 0) return "no plant data after initialisation";
    return check_plant_data(inst, v, in, size, why, why_size);
}
