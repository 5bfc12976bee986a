/*
 * The plant model on the FMU runtime: the six forces go to stewart_plant_step over each
 * communication step (held, or linear with their FMI 2 input derivatives); the plant's outputs and
 * statistics fill the output variables. A refused step is Discard with the plant's reason, the
 * state left at the last good point.
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bindings.h"
#include "logging.h"
#include "model.h"

/* What the output variables are bound to (variables.def's `field`). */
typedef struct plant_outputs {
    stewart_plant_output out;
    stewart_plant_statistics stats;
} plant_outputs;

/* ---------------------------------------------------------------- values <-> library */

static void default_settings(plant_settings *s, const stewart_params *p) {
    stewart_plant_options_default(&s->options);
    for (int i = 0; i < 6; ++i) s->pose0[i] = s->rate0[i] = 0.0;
    s->pose0[2] = p->home_height;
}

void model_start_values(fmu_values *v) {
    stewart_params p;
    stewart_params_default(&p);
    plant_settings s;
    default_settings(&s, &p);
    fmu_start_values(v);
    fmu_params_to_values(v, &p);
    fmu_settings_to_values(v, &s);
    fmu_table_options_to_values(v, &s.options);
    v->integer[VR_status] = 3; /* nothing integrated yet */
}

void plant_params_from_values(const fmu_values *v, stewart_params *p) {
    stewart_params_default(p);
    fmu_params_from_values(v, p);
}

void plant_settings_from_values(const fmu_values *v, plant_settings *s) {
    memset(s, 0, sizeof *s);
    stewart_plant_options_default(&s->options);
    fmu_settings_from_values(v, s);
    fmu_table_options_from_values(v, &s->options);
}

const char *plant_check_settings(const fmu_values *v, char *why, size_t size) {
    plant_settings s;
    plant_settings_from_values(v, &s);
    if (s.options.fidelity != STEWART_MASSLESS && s.options.fidelity != STEWART_FULL) {
        snprintf(why, size, "fidelity = %d must be 1 (massless) or 2 (full)",
                 (int)s.options.fidelity);
        return why;
    }
    char message[STEWART_MESSAGE_SIZE];
    if (stewart_plant_options_check(&s.options, message, sizeof message) != STEWART_OK) {
        snprintf(why, size, "%s", message);
        return why;
    }
#define FMU_OPTION_REAL(vr, id, name, field, unit, desc)               \
    if (!isfinite(v->real[vr])) {                                      \
        snprintf(why, size, name " = %g must be finite", v->real[vr]); \
        return why;                                                    \
    }
#include "variables.def"
    stewart_params p;
    plant_params_from_values(v, &p);
    if (stewart_params_check(&p, message, sizeof message) != STEWART_OK) {
        snprintf(why, size, "%s", message);
        return why;
    }
    return NULL;
}

/* Saturating conversion of a counter to an Int32 output. */
static int32_t counter(int64_t n) { return n > INT32_MAX ? INT32_MAX : (int32_t)n; }

/* The output variables from the plant's outputs and statistics. */
static void outputs_to_values(fmu_values *v, const plant_outputs *o) {
#define FMU_OUTPUT(vr, id, name, unit, field, desc) v->real[vr] = o->field;
#include "variables.def"
    const plant_totals *t = &v->model.totals;
    v->integer[VR_steps] = counter(o->stats.steps);
    v->integer[VR_rhs_evaluations] = counter(o->stats.rhs_evaluations);
    v->integer[VR_nonlinear_iterations] = counter(o->stats.nonlinear_iterations);
    v->integer[VR_error_test_failures] = counter(o->stats.error_test_failures);
    v->integer[VR_jacobian_evaluations] = counter(o->stats.jacobian_evaluations);
    v->integer[VR_total_steps] = counter(t->steps);
    v->integer[VR_total_rhs_evaluations] = counter(t->rhs_evaluations);
    v->integer[VR_total_nonlinear_iterations] = counter(t->nonlinear_iterations);
    v->integer[VR_total_error_test_failures] = counter(t->error_test_failures);
    v->integer[VR_total_jacobian_evaluations] = counter(t->jacobian_evaluations);
    v->integer[VR_last_order] = o->stats.last_order;
    v->integer[VR_current_max_legs] = o->out.current_max_legs;
    v->integer[VR_voltage_max_legs] = o->out.voltage_max_legs;
    v->integer[VR_motor_speed_max_legs] = o->out.motor_speed_max_legs;
}

/* ---------------------------------------------------------------- parameters */

/* Builds the model and plant for the values' parameters (reusing what did not change). */
static fmu_status build_plant(fmu_instance *inst, const stewart_params *p,
                              const stewart_plant_options *o) {
    model_resources *r = &inst->res;
    const int new_model = !r->model || memcmp(p, &r->params, sizeof *p) != 0;
    if (!new_model && r->plant && !memcmp(o, &r->options, sizeof *o)) return FMU_OK;
    stewart_model *m =
        new_model ? stewart_model_create(p, r->message, sizeof r->message) : r->model;
    stewart_plant *plant = m ? stewart_plant_create(m, o, r->message, sizeof r->message) : NULL;
    if (!plant) {
        if (new_model) stewart_model_free(m);
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "invalid parameter: %s", r->message);
        return FMU_ERROR;
    }
    stewart_plant_free(r->plant);
    if (new_model) {
        plant_free_checker(r);
        stewart_model_free(r->model);
        r->model = m;
        r->params = *p;
    }
    r->plant = plant;
    r->options = *o;
    fmu_log(inst, FMU_OK, LOG_EVENTS, "plant built (fidelity %d, method %d)", o->fidelity,
            o->method);
    return FMU_OK;
}

fmu_status model_apply_parameters(fmu_instance *inst) {
    fmu_values *v = &inst->v;
    model_resources *r = &inst->res;
    if (plant_check_settings(v, r->message, sizeof r->message)) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "invalid parameter: %s", r->message);
        return FMU_ERROR;
    }
    stewart_params p;
    plant_settings s;
    plant_params_from_values(v, &p);
    plant_settings_from_values(v, &s);
    return build_plant(inst, &p, &s.options);
}

/* Initialisation: the start state x0..yaw_dot0 and a fresh start's bookkeeping. */
fmu_status model_start(fmu_instance *inst) {
    fmu_values *v = &inst->v;
    model_resources *r = &inst->res;
    plant_settings s;
    plant_settings_from_values(v, &s);
    if (stewart_plant_set_state(r->plant, v->time, s.pose0, s.rate0) != STEWART_OK) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "invalid parameter: start state x0..yaw0 = (%g, %g, %g, %g, %g, %g), "
                "x_dot0..yaw_dot0 = (%g, %g, %g, %g, %g, %g): %s",
                s.pose0[0], s.pose0[1], s.pose0[2], s.pose0[3], s.pose0[4], s.pose0[5], s.rate0[0],
                s.rate0[1], s.rate0[2], s.rate0[3], s.rate0[4], s.rate0[5],
                stewart_plant_message(r->plant));
        return FMU_ERROR;
    }
    /* A fresh start's bookkeeping; input derivatives the master set before the end of
     * initialisation (FMI 2 allows it) are kept for the first step. */
    memset(&v->model.totals, 0, sizeof v->model.totals);
    v->model.legs_outside = 0;
    v->model.limit_warnings = 0;
    v->model.solve_status = 0;
    v->outputs_current = 0;
    return FMU_OK;
}

void model_reset(fmu_instance *inst) { (void)inst; /* the plant is set afresh at initialisation */ }

void model_free(fmu_instance *inst) {
    plant_free_checker(&inst->res);
    stewart_plant_free(inst->res.plant);
    stewart_model_free(inst->res.model);
    inst->res.plant = NULL;
    inst->res.model = NULL;
}

/* ---------------------------------------------------------------- outputs */

/* Forgets the FMI 2 input derivatives: a refused set is not kept for a retry that sets the forces
 * again. */
static void clear_input_derivatives(model_values *m) {
    m->input_derivatives = 0;
    memset(m->force_rate, 0, sizeof m->force_rate);
}

/* The first input (force, or with FMI 2 derivatives its rate) that is not finite: logs it and
 * returns 1 (a bad derivative clears them all). */
static int bad_force(fmu_instance *inst, double t) {
    fmu_values *v = &inst->v;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const double f = v->real[VR_F_1 + k], rate = v->model.force_rate[k];
        const char *name = fmu_variable_by_vr(VR_F_1 + k)->name;
        if (!isfinite(f)) {
            fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                    "t = %.17g: input %s = %g is not finite; the state stays at t, outputs keep "
                    "their last valid values",
                    t, name, f);
            return 1;
        }
        if (v->model.input_derivatives && !isfinite(rate)) {
            fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                    "t = %.17g: input derivative d%s/dt = %g is not finite; the state stays at "
                    "t, outputs keep their last valid values; the input derivatives are cleared "
                    "(forces held unless set again)",
                    t, name, rate);
            clear_input_derivatives(&v->model);
            return 1;
        }
    }
    return 0;
}

/* Not integrated or not evaluated: status 3, outputs keep their last valid values; it stands
 * until the master sets an input or steps again. */
static fmu_status refused(fmu_values *v) {
    v->integer[VR_status] = 3;
    v->outputs_current = 1;
    v->model.solve_status = FMU_DISCARD;
    return FMU_DISCARD;
}

/* Logs the legs that have just left their stroke; Warning while any leg is outside. */
static fmu_status stroke_status(fmu_instance *inst, const stewart_plant_output *out) {
    const stewart_params *p = &inst->res.params;
    int outside = 0;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        if (!(out->stroke_legs & (1 << k))) continue;
        outside |= 1 << k;
        if (!(inst->v.model.legs_outside & (1 << k)))
            fmu_log(inst, FMU_WARNING, LOG_WARNING,
                    "t = %.17g: L[%d] = %.9g m left the stroke [%g, %g] m (end stops are not "
                    "modelled)",
                    inst->v.time, k + 1, out->lengths.length[k], p->stroke_min[k],
                    p->stroke_max[k]);
    }
    inst->v.model.legs_outside = outside;
    return outside ? FMU_WARNING : FMU_OK;
}

/* Logs a joint beyond its angle limit or two legs interfering when it starts (the plant's
 * warning bits); Warning while either lasts. */
static fmu_status limit_status(fmu_instance *inst, const stewart_plant_output *out) {
    static const struct {
        int bit;
        const char *what;
    } kinds[] = {{STEWART_WARN_JOINT_LIMIT, "a joint is beyond its angle limit "
                                            "(base_joint_limit, platform_joint_limit)"},
                 {STEWART_WARN_INTERFERENCE, "two legs are closer than leg_diameter"}};
    const int now = out->warnings & (STEWART_WARN_JOINT_LIMIT | STEWART_WARN_INTERFERENCE);
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; ++i)
        if ((now & kinds[i].bit) && !(inst->v.model.limit_warnings & kinds[i].bit))
            fmu_log(inst, FMU_WARNING, LOG_WARNING, "t = %.17g: %s (contacts are not modelled)",
                    inst->v.time, kinds[i].what);
    inst->v.model.limit_warnings = now;
    return now ? FMU_WARNING : FMU_OK;
}

/* Outputs of the plant's current state under the current forces (the base wrench needs them);
 * after a step, the step's own outputs (under the same forces). */
static fmu_status evaluate(fmu_instance *inst, const stewart_plant_output *after_step) {
    fmu_values *v = &inst->v;
    model_resources *r = &inst->res;
    if (bad_force(inst, v->time)) return refused(v);
    plant_outputs o;
    if (after_step) {
        o.out = *after_step;
    } else if (stewart_plant_output_get(r->plant, &v->real[VR_F_1], &o.out) != STEWART_OK) {
        fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                "t = %.17g: the outputs overflow at this state under these forces; outputs keep "
                "their last valid values",
                v->time);
        return refused(v);
    }
    stewart_plant_statistics_get(r->plant, &o.stats);
    if (!after_step) { /* keep the statistics of the last step the outputs show */
        o.stats.steps = v->integer[VR_steps];
        o.stats.rhs_evaluations = v->integer[VR_rhs_evaluations];
        o.stats.nonlinear_iterations = v->integer[VR_nonlinear_iterations];
        o.stats.error_test_failures = v->integer[VR_error_test_failures];
        o.stats.jacobian_evaluations = v->integer[VR_jacobian_evaluations];
        o.stats.last_order = v->integer[VR_last_order];
        o.stats.last_step_size = v->real[VR_last_step_size];
    }
    outputs_to_values(v, &o);
    fmu_status s = stroke_status(inst, &o.out);
    v->integer[VR_status] = s == FMU_WARNING ? 1 : 0;
    if (limit_status(inst, &o.out) == FMU_WARNING) s = FMU_WARNING;
    v->outputs_current = 1;
    v->model.solve_status = s;
    return s;
}

fmu_status model_refresh_outputs(fmu_instance *inst) {
    if (inst->v.outputs_current) return inst->v.model.solve_status;
    return evaluate(inst, NULL);
}

/* ---------------------------------------------------------------- the step */

static void add_totals(plant_totals *t, const stewart_plant_statistics *s) {
    t->steps += s->steps;
    t->rhs_evaluations += s->rhs_evaluations;
    t->nonlinear_iterations += s->nonlinear_iterations;
    t->error_test_failures += s->error_test_failures;
    t->jacobian_evaluations += s->jacobian_evaluations;
}

double plant_time(const stewart_plant *plant) { return stewart_plant_time(plant); }

double clock_rounding(double t) { return 16.0 * DBL_EPSILON * fabs(t); }

/* The plant integrates continuously: a step must start where the last one ended, to the rounding
 * of the master's clock (the runtime lets a stateless unit start later). Error: a gap cannot be
 * integrated without its forces. *end gets the plant's time. */
static fmu_status check_continuous(fmu_instance *inst, double t, double *end) {
    *end = plant_time(inst->res.plant);
    if (fabs(t - *end) <= clock_rounding(fmax(fabs(t), fabs(*end)))) return FMU_OK;
    fmu_log(inst, FMU_ERROR, LOG_ERROR,
            "DoStep: currentCommunicationPoint = %.17g is not the plant's time %.17g (the end of "
            "its last step; they differ by %.3g s, more than the rounding of a clock): the plant "
            "cannot skip time; restore an FMU state or reset",
            t, *end, t - *end);
    return FMU_ERROR;
}

fmu_status model_do_step(fmu_instance *inst, double t, double h) {
    fmu_values *v = &inst->v;
    model_values *m = &v->model;
    model_resources *r = &inst->res;
    double end;
    if (check_continuous(inst, t, &end) != FMU_OK) return FMU_ERROR;
    if (bad_force(inst, t)) return refused(v);
    double f0[STEWART_LEGS], f1[STEWART_LEGS];
    for (int k = 0; k < STEWART_LEGS; ++k) {
        f0[k] = v->real[VR_F_1 + k];
        f1[k] = m->input_derivatives ? f0[k] + h * m->force_rate[k] : f0[k];
        if (!isfinite(f1[k])) {
            fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                    "t = %.17g: F[%d] extrapolated to t + h = %.17g overflows (F = %g, dF/dt = "
                    "%g); the state stays at t; the input derivatives are cleared (forces held "
                    "unless set again)",
                    t, k + 1, t + h, f0[k], m->force_rate[k]);
            clear_input_derivatives(m);
            return refused(v);
        }
    }
    /* The master's clock is the truth: the plant steps from its own time to the master's t + h,
     * so the rounding of the two clocks never adds up over a run. */
    stewart_plant_input in = {0};
    in.h = (t + h) - end;
    memcpy(in.force_start, f0, sizeof f0);
    memcpy(in.force_end, f1, sizeof f1);
    stewart_plant_output at_end;
    const stewart_status s = stewart_plant_step(r->plant, &in, &at_end);
    if (s != STEWART_OK) {
        fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                "t = %.17g, h = %g: step refused (%s): %s; the state stays at t, outputs keep "
                "their last valid values",
                t, h, stewart_status_name(s), stewart_plant_message(r->plant));
        return refused(v);
    }
    /* accepted: the forces read their values at t + h; derivatives served this step only */
    memcpy(&v->real[VR_F_1], f1, sizeof f1);
    clear_input_derivatives(m);
    stewart_plant_statistics stats;
    stewart_plant_statistics_get(r->plant, &stats);
    add_totals(&m->totals, &stats);
    v->time = t + h; /* the outputs belong to t + h (the runtime sets it again) */
    const fmu_status out = evaluate(inst, &at_end);
    v->time = t;
    /* an accepted step whose end cannot be evaluated is still accepted: status 3 says so */
    return out == FMU_DISCARD ? FMU_WARNING : out;
}

fmu_status model_set_input_derivatives(fmu_instance *inst, const unsigned vr[], size_t n,
                                       const int order[], const double value[]) {
    fmu_values *v = &inst->v;
    for (size_t i = 0; i < n; ++i)
        if (vr[i] > VR_F_6 || order[i] != 1) {
            fmu_log(inst, FMU_ERROR, LOG_ERROR,
                    "SetRealInputDerivatives: derivative of order %d of value reference %u is not "
                    "supported (order 1 of F[1..6])",
                    order[i], vr[i]);
            return FMU_ERROR;
        }
    if (n > 0 && !v->model.input_derivatives)
        memset(v->model.force_rate, 0, sizeof v->model.force_rate); /* not given: zero */
    for (size_t i = 0; i < n; ++i) v->model.force_rate[vr[i] - VR_F_1] = value[i];
    if (n > 0) v->model.input_derivatives = 1;
    return FMU_OK;
}
