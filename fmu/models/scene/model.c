/* The scene player (config.h): each pose component mean + amplitude sin(omega t + phase) and its
 * derivatives at the instance's time; a step moves the outputs to t + h. */
#include <math.h>
#include <string.h>

#include "logging.h"
#include "model_interface.h"
#include "model_without_resources.h"

void model_start_values(fmu_values *v) {
#define FMU_OUTPUT(vr, id, name, unit, field, desc) v->real[vr] = 0.0;
#define FMU_OPTION_REAL(vr, id, name, field, unit, desc) v->real[vr] = 0.0;
#include "variables.def"
    v->real[VR_z_mean] = 0.5; /* at rest at home */
    memset(&v->model, 0, sizeof v->model);
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

/* The outputs at time t. */
static void evaluate(fmu_values *v, double t) {
    for (int i = 0; i < 6; ++i) {
        const double *p = &v->real[VR_x_mean + 4 * i]; /* mean, amplitude, omega, phase */
        const double a = p[1], w = p[2], angle = w * t + p[3];
        v->real[VR_x + i] = p[0] + a * sin(angle);
        v->real[VR_x_dot + i] = a * w * cos(angle);
        v->real[VR_x_ddot + i] = -a * w * w * sin(angle);
    }
}

fmu_status model_refresh_outputs(fmu_instance *inst) {
    evaluate(&inst->v, inst->v.time);
    inst->v.outputs_current = 1;
    return FMU_OK;
}

fmu_status model_do_step(fmu_instance *inst, double t, double h) {
    evaluate(&inst->v, t + h);
    inst->v.outputs_current = 1;
    return FMU_OK;
}

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
