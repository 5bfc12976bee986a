/* The leg controller (config.h) on the FMU runtime. output = 0: F = F_ff + kp (L_ref - L) + kd
 * (L_dot_ref - L_dot), evaluated whenever an input changed; a step only checks the inputs.
 * output = 1: the current cascade (cascade.h); a step integrates each leg's speed error. */
#include <math.h>
#include <string.h>

#include "bindings.h"
#include "cascade.h"
#include "controller.h"
#include "logging.h"
#include "model_interface.h"
#include "model_without_saved_state.h"

static const double kDefaultKp = 1e6, kDefaultKd = 1e4;

void model_start_values(fmu_values *v) {
    fmu_start_values(v);
    v->real[VR_kp] = kDefaultKp;
    v->real[VR_kd] = kDefaultKd;
    for (int k = 0; k < LEGS; ++k) v->real[VR_gear_ratio_1 + k] = 1.0; /* the platform's default */
}

void model_reset(fmu_instance *inst) { (void)inst; }

void model_free(fmu_instance *inst) { (void)inst; }

fmu_status model_start(fmu_instance *inst) {
    memset(inst->v.model.speed_integral, 0, sizeof inst->v.model.speed_integral);
    return FMU_OK;
}

int controller_current_mode(const fmu_values *v) { return v->integer[VR_output] == 1; }

/* The value references of the parameters that must be finite and >= 0 in every mode, and of
 * those that must be > 0 on every leg in current mode. */
static const unsigned kNonNegative[] = {VR_kp, VR_kd, VR_position_gain, VR_speed_gain,
                                        VR_speed_integral_time};
static const unsigned kDrive[] = {VR_screw_lead_1, VR_gear_ratio_1, VR_torque_constant_1};
static const unsigned kLimits[] = {VR_current_max_1, VR_motor_speed_max_1};

/* Why the parameters in v cannot run, with the parameter's name in *vr, or NULL. */
static const char *refused_parameter(const fmu_values *v, unsigned *vr) {
    if (v->integer[VR_output] != 0 && v->integer[VR_output] != 1) {
        *vr = VR_output;
        return "output is 0 (force) or 1 (current)";
    }
    for (size_t i = 0; i < sizeof kNonNegative / sizeof *kNonNegative; ++i)
        if (!(isfinite(v->real[ *vr = kNonNegative[i]]) && v->real[*vr] >= 0.0))
            return "a gain must be finite and >= 0";
    for (int k = 0; k < LEGS; ++k)
        for (size_t i = 0; i < sizeof kLimits / sizeof *kLimits; ++i)
            if (!(isfinite(v->real[ *vr = kLimits[i] + k]) && v->real[*vr] >= 0.0))
                return "a drive limit must be finite and >= 0 (0: none)";
    if (!controller_current_mode(v)) return NULL;
    if (!(v->real[ *vr = VR_speed_gain] > 0))
        return "output = 1 (current) needs a speed gain > 0 (docs/drives.md: tuning the cascade)";
    for (int k = 0; k < LEGS; ++k)
        for (size_t i = 0; i < sizeof kDrive / sizeof *kDrive; ++i)
            if (!(isfinite(v->real[ *vr = kDrive[i] + k]) && v->real[*vr] > 0.0))
                return "output = 1 (current) needs a drive on every leg: screw_lead, gear_ratio "
                       "and torque_constant finite and > 0, as the platform's";
    for (int k = 0; k < LEGS; ++k) /* else every command of the leg is NaN, blamed on inputs */
        if (!isfinite(cascade_motor_per_leg(v->real[ *vr = VR_screw_lead_1 + k],
                                            v->real[VR_gear_ratio_1 + k])))
            return "output = 1 (current): 2 pi gear_ratio / screw_lead overflows a double; give "
                   "the lead in metres, as the platform's";
    return NULL;
}

fmu_status model_apply_parameters(fmu_instance *inst) {
    unsigned vr = 0;
    const char *why = refused_parameter(&inst->v, &vr);
    if (!why) return FMU_OK;
    const double value = vr == VR_output ? inst->v.integer[vr] : inst->v.real[vr];
    fmu_log(inst, FMU_ERROR, LOG_ERROR, "invalid parameter %s = %g: %s",
            fmu_variable_by_vr(vr)->name, value, why);
    return FMU_ERROR;
}

void controller_drive(const fmu_values *v, int k, cascade_drive *d, cascade_gains *g) {
    d->motor_per_leg =
        cascade_motor_per_leg(v->real[VR_screw_lead_1 + k], v->real[VR_gear_ratio_1 + k]);
    d->torque_constant = v->real[VR_torque_constant_1 + k];
    d->current_max = v->real[VR_current_max_1 + k];
    d->motor_speed_max = v->real[VR_motor_speed_max_1 + k];
    g->position = v->real[VR_position_gain];
    g->speed = v->real[VR_speed_gain];
    g->integral_time = v->real[VR_speed_integral_time];
}

void controller_leg_inputs(const fmu_values *v, int k, double in[CASCADE_INPUTS]) {
    for (int b = 0; b < CASCADE_INPUTS; ++b) in[b] = v->real[VR_L_ref_1 + 6 * b + k];
}

/* Leg k's command at the current inputs and state; its cascade terms in *r (current mode). */
static double command(const fmu_values *v, int k, cascade_result *r) {
    if (!controller_current_mode(v))
        return v->real[VR_F_ff_1 + k] +
               v->real[VR_kp] * (v->real[VR_L_ref_1 + k] - v->real[VR_L_1 + k]) +
               v->real[VR_kd] * (v->real[VR_L_dot_ref_1 + k] - v->real[VR_L_dot_1 + k]);
    cascade_drive d;
    cascade_gains g;
    double in[CASCADE_INPUTS];
    controller_drive(v, k, &d, &g);
    controller_leg_inputs(v, k, in);
    *r = cascade_leg(&d, &g, in, v->model.speed_integral[k]);
    return r->current;
}

/* The outputs at the current inputs and state; each leg's cascade terms in r (may be NULL). */
static fmu_status evaluate(fmu_instance *inst, cascade_result r[LEGS]) {
    fmu_values *v = &inst->v;
    for (unsigned vr = VR_L_ref_1; vr <= VR_L_dot_6; ++vr)
        if (!isfinite(v->real[vr])) {
            fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                    "t = %.17g: input %s = %g is not finite; F "
                    "keeps its last valid value",
                    v->time, fmu_variable_by_vr(vr)->name, v->real[vr]);
            v->integer[VR_status] = 3;
            return v->model.solve_status = FMU_DISCARD;
        }
    double out[LEGS];
    cascade_result unused[LEGS];
    if (!r) r = unused;
    for (int k = 0; k < LEGS; ++k) {
        out[k] = command(v, k, &r[k]);
        if (!isfinite(out[k])) {
            fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                    "t = %.17g: F[%d] overflows (inputs too "
                    "large for the gains); F keeps its last valid value",
                    v->time, k + 1);
            v->integer[VR_status] = 3;
            return v->model.solve_status = FMU_DISCARD;
        }
    }
    memcpy(&v->real[VR_F_1], out, sizeof out);
    v->integer[VR_status] = 0;
    v->outputs_current = 1;
    return v->model.solve_status = FMU_OK;
}

fmu_status model_refresh_outputs(fmu_instance *inst) {
    if (inst->v.outputs_current) return inst->v.model.solve_status;
    const fmu_status s = evaluate(inst, NULL);
    inst->v.outputs_current = 1;
    return s;
}

fmu_status model_do_step(fmu_instance *inst, double t, double h) {
    (void)t;
    fmu_values *v = &inst->v;
    if (!controller_current_mode(v)) return model_refresh_outputs(inst); /* no state */
    cascade_result r[LEGS];
    const fmu_status s = evaluate(inst, r); /* the inputs held over the step */
    if (s != FMU_OK) return s;
    double before[LEGS];
    memcpy(before, v->model.speed_integral, sizeof before);
    cascade_gains g;
    cascade_drive unused;
    controller_drive(v, 0, &unused, &g);
    for (int k = 0; k < LEGS; ++k)
        v->model.speed_integral[k] = cascade_integrate(&r[k], &g, before[k], h);
    if (evaluate(inst, NULL) == FMU_OK) return FMU_OK;      /* the outputs at t + h */
    memcpy(v->model.speed_integral, before, sizeof before); /* refused: the state stays at t */
    v->outputs_current = 1;
    return FMU_DISCARD;
}

const char *model_check_state(fmu_instance *inst, const fmu_values *v, const unsigned char *in,
                              size_t size, char *why, size_t why_size) {
    (void)inst;
    (void)in;
    (void)why;
    (void)why_size;
    if (size != 0) return "the controller has no saved resources";
    for (int k = 0; k < LEGS; ++k)
        if (!isfinite(v->real[VR_F_1 + k])) return "an output is not finite";
    for (int k = 0; k < LEGS; ++k)
        if (!isfinite(v->model.speed_integral[k])) return "a speed integral is not finite";
    if (v->integer[VR_status] != 0 && v->integer[VR_status] != 3) return "status is not 0 or 3";
    if (v->model.solve_status < FMU_OK || v->model.solve_status > FMU_ERROR)
        return "a flag is out of range";
    unsigned vr;
    if (refused_parameter(v, &vr)) return "a parameter is refused (a gain or a drive)";
    return NULL;
}
