/* The integrator model (config.h): the model interface of fmu/runtime/model_interface.h. */
#include <math.h>
#include <string.h>

#include "bindings.h"
#include "logging.h"
#include "model_interface.h"
#include "model_without_resources.h"

void model_start_values(fmu_values *v) {
    fmu_start_values(v);
    v->real[VR_gain] = 1.0;
}

fmu_status model_apply_parameters(fmu_instance *inst) {
    fmu_values *v = &inst->v;
    if (!isfinite(v->real[VR_gain]) || !isfinite(v->real[VR_y0])) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "invalid parameter: gain = %g, y0 = %g must be finite",
                v->real[VR_gain], v->real[VR_y0]);
        return FMU_ERROR;
    }
    if (v->mode == MODE_INITIALIZATION) v->model.y = v->real[VR_y0];
    return FMU_OK;
}

fmu_status model_refresh_outputs(fmu_instance *inst) {
    fmu_values *v = &inst->v;
    v->real[VR_y] = v->model.y;
    v->integer[VR_steps] = v->model.steps;
    v->outputs_current = 1;
    return FMU_OK;
}

fmu_status model_do_step(fmu_instance *inst, double t, double h) {
    fmu_values *v = &inst->v;
    if (!isfinite(v->real[VR_u])) {
        fmu_log(inst, FMU_DISCARD, LOG_DISCARD, "t = %g: input u = %g is not finite", t,
                v->real[VR_u]);
        return FMU_DISCARD;
    }
    v->model.y += v->real[VR_gain] * v->real[VR_u] * h;
    ++v->model.steps;
    return model_refresh_outputs(inst);
}

const char *model_check_state(fmu_instance *inst, const fmu_values *v, const unsigned char *in,
                              size_t size, char *why, size_t why_size) {
    (void)inst;
    (void)in;
    (void)why;
    (void)why_size;
    if (size != 0) return "the integrator has no saved resources";
    if (!isfinite(v->model.y) || v->model.steps < 0) return "the state y or the step count is bad";
    return NULL;
}
