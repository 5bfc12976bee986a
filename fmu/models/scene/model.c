/* The scene player (config.h): each pose component mean + amplitude sin(omega t + phase) and its
 * derivatives at the instance's time; a step moves the outputs to t + h. */
#include <math.h>
#include <string.h>

#include "bindings.h"
#include "logging.h"
#include "model_interface.h"
#include "model_without_resources.h"

void model_start_values(fmu_values *v) {
    fmu_start_values(v);
    v->real[VR_z_mean] = 0.5; /* at rest at home */
}

fmu_status model_apply_parameters(fmu_instance *inst) {
#define FMU_OPTION_REAL(vr, id, name, field, unit, desc)                                    \
    if (!isfinite(inst->v.real[vr])) {                                                      \
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "invalid parameter " name " = %g: must be finite", \
                inst->v.real[vr]);                                                          \
        return FMU_ERROR;                                                                   \
    }
#include "variables.def"
    return FMU_OK;
}

/* The outputs at time t, written only if all are finite: else Discard naming the component (finite
 * parameters can still overflow, e.g. omega = 1e308), the last values kept. */
static fmu_status evaluate(fmu_instance *inst, double t) {
    fmu_values *v = &inst->v;
    double out[3][6];
    for (int i = 0; i < 6; ++i) {
        const double *p = &v->real[VR_x_mean + 4 * i]; /* mean, amplitude, omega, phase */
        const double a = p[1], w = p[2], angle = w * t + p[3];
        out[0][i] = p[0] + a * sin(angle);
        out[1][i] = a * w * cos(angle);
        out[2][i] = -a * w * w * sin(angle);
        for (int d = 0; d < 3; ++d)
            if (!isfinite(out[d][i])) {
                fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                        "t = %.17g: %s of the scene is not finite (mean %g, amplitude %g, omega "
                        "%g, phase %g); outputs keep their last values",
                        t, fmu_variable_by_vr(VR_x + 6 * d + i)->name, p[0], p[1], p[2], p[3]);
                return FMU_DISCARD;
            }
    }
    for (int i = 0; i < 6; ++i) {
        v->real[VR_x + i] = out[0][i];
        v->real[VR_x_dot + i] = out[1][i];
        v->real[VR_x_ddot + i] = out[2][i];
    }
    v->outputs_current = 1;
    return FMU_OK;
}

fmu_status model_refresh_outputs(fmu_instance *inst) { return evaluate(inst, inst->v.time); }

fmu_status model_do_step(fmu_instance *inst, double t, double h) { return evaluate(inst, t + h); }

const char *model_check_state(fmu_instance *inst, const fmu_values *v, const unsigned char *in,
                              size_t size, char *why, size_t why_size) {
    (void)inst; (void)in; (void)why; (void)why_size;
    if (size != 0) return "the scene player has no saved resources";
#define FMU_OUTPUT(vr, id, name, unit, field, desc) \
    if (!isfinite(v->real[vr])) return "output " name " is not finite";
#define FMU_OPTION_REAL(vr, id, name, field, unit, desc) \
    if (!isfinite(v->real[vr])) return "parameter " name " is not finite";
#include "variables.def"
    return NULL;
}
