/*
 * The Model Exchange plant on the FMU runtime: the states (x .. yaw_dot) and forces the master set
 * go to stewart_plant_derivatives; its pose rates and accelerations are the derivatives, its
 * lengths, rates and base wrench the other outputs. A state where the equations are undefined
 * (pitch at +-90 degrees, a zero-length leg, a locked Cardan) or a non-finite force is Discard at
 * the derivative call, naming the value. The master integrates; no step here. At an accepted state
 * (CompletedIntegratorStep) the stroke, joint-limit and interference warnings, as the
 * co-simulation plant's steps give them.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "bindings.h"
#include "logging.h"
#include "model_interface.h"

void model_start_values(fmu_values *v) {
    stewart_params p;
    stewart_params_default(&p);
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    plant_me_start s = {{0, 0, p.home_height, 0, 0, 0}, {0}, o.smoothing_speed};
    fmu_start_values(v);
    fmu_params_to_values(v, &p);
    fmu_settings_to_values(v, &s);
    v->integer[VR_status] = 3; /* nothing evaluated yet */
}

static void params_from_values(const fmu_values *v, stewart_params *p) {
    stewart_params_default(p);
    fmu_params_from_values(v, p);
}

/* ---------------------------------------------------------------- parameters */

fmu_status model_apply_parameters(fmu_instance *inst) {
    fmu_values *v = &inst->v;
    model_resources *r = &inst->res;
    const int fidelity = v->integer[VR_fidelity];
    if (fidelity != STEWART_MASSLESS && fidelity != STEWART_FULL) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "invalid parameter: fidelity = %d must be 1 (massless) or 2 (full)", fidelity);
        return FMU_ERROR;
    }
    const int input = v->integer[VR_input];
    plant_me_start settings;
    fmu_settings_from_values(v, &settings);
    stewart_params p;
    params_from_values(v, &p);
    const int new_model = !r->model || memcmp(&p, &r->params, sizeof p) != 0;
    if (!new_model && r->plant && fidelity == r->fidelity && input == r->input &&
        settings.smoothing_speed == r->smoothing_speed)
        return FMU_OK;
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    o.fidelity = fidelity;
    o.input = input;
    o.smoothing_speed = settings.smoothing_speed;
    stewart_model *m =
        new_model ? stewart_model_create(&p, r->message, sizeof r->message) : r->model;
    stewart_plant *plant = m ? stewart_plant_create(m, &o, r->message, sizeof r->message) : NULL;
    stewart_linearize_options lo;
    stewart_linearize_options_default(&lo);
    lo.fidelity = fidelity;
    stewart_linearize *linearize =
        plant ? stewart_linearize_create(m, &lo, r->message, sizeof r->message) : NULL;
    stewart_limits_options limit_options;
    stewart_limits_options_default(&limit_options);
    stewart_limits *limits =
        linearize ? stewart_limits_create(m, &limit_options, r->message, sizeof r->message) : NULL;
    if (!limits) {
        stewart_linearize_free(linearize);
        stewart_plant_free(plant);
        if (new_model) stewart_model_free(m);
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "invalid parameter: %s", r->message);
        return FMU_ERROR;
    }
    stewart_plant_free(r->plant);
    stewart_linearize_free(r->linearize);
    stewart_limits_free(r->limits);
    if (new_model) {
        stewart_model_free(r->model);
        r->model = m;
        r->params = p;
    }
    r->plant = plant;
    r->linearize = linearize;
    r->limits = limits;
    r->derivatives.valid = 0;
    r->fidelity = fidelity;
    r->input = input;
    r->smoothing_speed = settings.smoothing_speed;
    fmu_log(inst, FMU_OK, LOG_EVENTS, "plant built (fidelity %d)", fidelity);
    return FMU_OK;
}

/* Initialisation: the states from the start parameters, checked as the co-simulation plant
 * checks them (stewart_plant_set_state: finite, pitch off +-90 degrees, every leg defined). */
fmu_status model_start(fmu_instance *inst) {
    fmu_values *v = &inst->v;
    plant_me_start s;
    fmu_settings_from_values(v, &s);
    if (stewart_plant_set_state(inst->res.plant, 0.0, s.pose0, s.rate0) != STEWART_OK) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "invalid parameter: start state x0..yaw0 = (%g, %g, %g, %g, %g, %g), "
                "x_dot0..yaw_dot0 = (%g, %g, %g, %g, %g, %g): %s",
                s.pose0[0], s.pose0[1], s.pose0[2], s.pose0[3], s.pose0[4], s.pose0[5], s.rate0[0],
                s.rate0[1], s.rate0[2], s.rate0[3], s.rate0[4], s.rate0[5],
                stewart_plant_message(inst->res.plant));
        return FMU_ERROR;
    }
    for (int i = 0; i < 6; ++i) {
        v->real[VR_x + i] = s.pose0[i];
        v->real[VR_x_dot + i] = s.rate0[i];
    }
    v->outputs_current = 0;
    return FMU_OK;
}

void model_reset(fmu_instance *inst) { (void)inst; /* the states are set at initialisation */ }

void model_free(fmu_instance *inst) {
    stewart_plant_free(inst->res.plant);
    stewart_linearize_free(inst->res.linearize);
    stewart_limits_free(inst->res.limits);
    stewart_model_free(inst->res.model);
    inst->res.plant = NULL;
    inst->res.linearize = NULL;
    inst->res.limits = NULL;
    inst->res.model = NULL;
}

/* ---------------------------------------------------------------- the right-hand side */

fmu_status model_refresh_outputs(fmu_instance *inst) {
    fmu_values *v = &inst->v;
    if (v->outputs_current) return v->model.solve_status;
    stewart_plant_derivative_input in;
    in.time = v->time;
    for (int i = 0; i < 6; ++i) {
        in.pose.q[i] = v->real[VR_x + i];
        in.pose.q_dot[i] = v->real[VR_x_dot + i];
        in.pose.q_ddot[i] = 0.0;
        in.force[i] = v->real[VR_F_1 + i];
    }
    stewart_plant_output out;
    const stewart_status s = stewart_plant_derivatives(inst->res.plant, &in, &out);
    v->outputs_current = 1;
    if (s != STEWART_OK) {
        fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                "t = %.17g: no derivatives at this state (%s): %s; outputs keep their last valid "
                "values",
                v->time, stewart_status_name(s), stewart_plant_message(inst->res.plant));
        v->integer[VR_status] = 3;
        v->model.solve_status = FMU_DISCARD;
        return FMU_DISCARD;
    }
#define FMU_OUTPUT(vr, id, name, unit, field, desc) v->real[vr] = out.field;
#include "variables.def"
    v->integer[VR_status] = out.stroke_legs ? 1 : 0;
    v->integer[VR_current_max_legs] = out.current_max_legs;
    v->integer[VR_voltage_max_legs] = out.voltage_max_legs;
    v->integer[VR_motor_speed_max_legs] = out.motor_speed_max_legs;
    v->model.stroke_legs = out.stroke_legs;
    v->model.solve_status = FMU_OK;
    return FMU_OK;
}

/* The legs that have just left their stroke, logged; bit k of the result for each leg outside. */
static int report_stroke(fmu_instance *inst) {
    const fmu_values *v = &inst->v;
    const stewart_params *p = &inst->res.params;
    const int outside = v->model.stroke_legs;
    for (int k = 0; k < STEWART_LEGS; ++k)
        if ((outside & (1 << k)) && !(v->model.legs_outside & (1 << k)))
            fmu_log(inst, FMU_WARNING, LOG_WARNING,
                    "t = %.17g: L[%d] = %.9g m left the stroke [%g, %g] m (end stops are not "
                    "modelled)",
                    v->time, k + 1, v->real[VR_L_1 + k], p->stroke_min[k], p->stroke_max[k]);
    return outside;
}

/* A joint beyond its angle limit or two legs interfering at the state's pose (the tool's in the
 * user frame: the limits object transforms it), logged when it starts; the STEWART_WARN_ bits. */
static int report_limits(fmu_instance *inst) {
    static const struct {
        int bit;
        const char *what;
    } kinds[] = {{STEWART_WARN_JOINT_LIMIT, "a joint is beyond its angle limit "
                                            "(base_joint_limit, platform_joint_limit)"},
                 {STEWART_WARN_INTERFERENCE, "two legs are closer than leg_diameter"}};
    const fmu_values *v = &inst->v;
    stewart_limits_input in;
    memset(&in, 0, sizeof in);
    for (int i = 0; i < 6; ++i) in.q[i] = v->real[VR_x + i];
    stewart_limits_output o;
    if (stewart_limits_check(inst->res.limits, &in, &o) != STEWART_OK) return 0; /* finite here */
    const int joints =
        1 << (STEWART_LIMIT_BASE_JOINT - 1) | 1 << (STEWART_LIMIT_PLATFORM_JOINT - 1);
    const int now =
        (o.failed & joints ? STEWART_WARN_JOINT_LIMIT : 0) |
        (o.failed & 1 << (STEWART_LIMIT_INTERFERENCE - 1) ? STEWART_WARN_INTERFERENCE : 0);
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; ++i)
        if ((now & kinds[i].bit) && !(v->model.limit_warnings & kinds[i].bit))
            fmu_log(inst, FMU_WARNING, LOG_WARNING, "t = %.17g: %s (contacts are not modelled)",
                    v->time, kinds[i].what);
    return now;
}

fmu_status model_accepted_state(fmu_instance *inst) {
    fmu_values *v = &inst->v;
    /* A state without derivatives was Discard at GetDerivatives already: nothing to add. */
    if (model_refresh_outputs(inst) != FMU_OK) return FMU_OK;
    v->model.legs_outside = report_stroke(inst);
    v->model.limit_warnings = report_limits(inst);
    return v->model.legs_outside || v->model.limit_warnings ? FMU_WARNING : FMU_OK;
}

fmu_status model_do_step(fmu_instance *inst, double t, double h) {
    (void)t;
    (void)h;
    fmu_log(inst, FMU_ERROR, LOG_ERROR, "DoStep: " FMU_MODEL_IDENTIFIER " is Model Exchange only");
    return FMU_ERROR;
}

/* ---------------------------------------------------------------- FMU state */

/* The instance's values are the whole state (the plant object holds none of it); no input
 * derivatives (Model Exchange has none). */
#include "model_without_saved_state.h"

const char *model_check_state(fmu_instance *inst, const fmu_values *v, const unsigned char *in,
                              size_t size, char *why, size_t why_size) {
    (void)inst;
    (void)in;
    if (size != 0) return "the state has model data, this model has none";
    const int solve = v->model.solve_status;
    if (solve != FMU_OK && solve != FMU_DISCARD) return "a flag is out of range";
#define FMU_OUTPUT(vr, id, name, unit, field, desc) \
    if (!isfinite(v->real[vr])) return "output " name " is not finite";
#include "variables.def"
    const model_values *m = &v->model;
    if ((m->stroke_legs | m->legs_outside) & ~0x3f ||
        m->limit_warnings & ~(STEWART_WARN_JOINT_LIMIT | STEWART_WARN_INTERFERENCE))
        return "a flag is out of range";
    const int32_t status = v->integer[VR_status];
    if (status < 0 || status > 3 || status == 2) return "status is not 0, 1 or 3";
    if (v->integer[VR_fidelity] != STEWART_MASSLESS && v->integer[VR_fidelity] != STEWART_FULL) {
        snprintf(why, why_size, "fidelity = %d must be 1 or 2", (int)v->integer[VR_fidelity]);
        return why;
    }
    return NULL;
}
