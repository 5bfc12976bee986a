/* The leg controller (config.h) on the FMU runtime: F = F_ff + kp (L_ref - L) + kd (L_dot_ref -
 * L_dot), evaluated whenever an input changed; a step only checks the inputs. */
#include <math.h>
#include <string.h>

#include "bindings.h"
#include "logging.h"
#include "model_interface.h"
#include "model_without_resources.h"

enum { LEGS = 6 };
static const double kDefaultKp = 1e6, kDefaultKd = 1e4;

void model_start_values(fmu_values *v) {
    fmu_start_values(v);
    v->real[VR_kp] = kDefaultKp;
    v->real[VR_kd] = kDefaultKd;
}

fmu_status model_apply_parameters(fmu_instance *inst) {
    const fmu_values *v = &inst->v;
    const unsigned gains[2] = {VR_kp, VR_kd};
    for (int i = 0; i < 2; ++i)
        if (!(isfinite(v->real[gains[i]]) && v->real[gains[i]] >= 0.0)) {
            fmu_log(inst, FMU_ERROR, LOG_ERROR, "invalid parameter %s = %g: a gain must be finite "
                    "and >= 0", fmu_variable_by_vr(gains[i])->name, v->real[gains[i]]);
            return FMU_ERROR;
        }
    return FMU_OK;
}

fmu_status model_refresh_outputs(fmu_instance *inst) {
    fmu_values *v = &inst->v;
    if (v->outputs_current) return v->model.solve_status;
    v->outputs_current = 1;
    for (unsigned vr = VR_L_ref_1; vr <= VR_L_dot_6; ++vr)
        if (!isfinite(v->real[vr])) {
            fmu_log(inst, FMU_DISCARD, LOG_DISCARD, "t = %.17g: input %s = %g is not finite; F "
                    "keeps its last valid value", v->time, fmu_variable_by_vr(vr)->name,
                    v->real[vr]);
            v->integer[VR_status] = 3;
            return v->model.solve_status = FMU_DISCARD;
        }
    double force[LEGS];
    for (int k = 0; k < LEGS; ++k) {
        force[k] = v->real[VR_F_ff_1 + k] + v->real[VR_kp] * (v->real[VR_L_ref_1 + k] - v->real[VR_L_1 + k]) +
                   v->real[VR_kd] * (v->real[VR_L_dot_ref_1 + k] - v->real[VR_L_dot_1 + k]);
        if (!isfinite(force[k])) {
            fmu_log(inst, FMU_DISCARD, LOG_DISCARD, "t = %.17g: F[%d] overflows (inputs too "
                    "large for the gains); F keeps its last valid value", v->time, k + 1);
            v->integer[VR_status] = 3;
            return v->model.solve_status = FMU_DISCARD;
        }
    }
    memcpy(&v->real[VR_F_1], force, sizeof force);
    v->integer[VR_status] = 0;
    return v->model.solve_status = FMU_OK;
}

fmu_status model_do_step(fmu_instance *inst, double t, double h) {
    (void)t; (void)h;
    return model_refresh_outputs(inst); /* no state: the outputs stay those of the inputs */
}

const char *model_check_state(fmu_instance *inst, const fmu_values *v, const unsigned char *in,
                              size_t size, char *why, size_t why_size) {
    (void)inst; (void)in; (void)why; (void)why_size;
    if (size != 0) return "the controller has no saved resources";
    for (int k = 0; k < LEGS; ++k)
        if (!isfinite(v->real[VR_F_1 + k])) return "an output is not finite";
    if (v->integer[VR_status] != 0 && v->integer[VR_status] != 3) return "status is not 0 or 3";
    if (v->model.solve_status < FMU_OK || v->model.solve_status > FMU_ERROR)
        return "a flag is out of range";
    if (!(isfinite(v->real[VR_kp]) && v->real[VR_kp] >= 0 && isfinite(v->real[VR_kd]) &&
          v->real[VR_kd] >= 0))
        return "a gain is not finite and >= 0";
    return NULL;
}
