/*
 * The model-interface functions (model_interface.h) of a model that has no resources, no saved
 * state beyond its plain values and takes no input derivatives: model_reset, model_free,
 * model_start (nothing to set), model_set_input_derivatives (Error for any), model_state_size
 * (0), model_save and model_load (of 0 bytes). Include it in exactly one .c file of such a model
 * (it defines them), after model_interface.h and logging.h.
 */
#ifndef STEWART_FMU_MODEL_WITHOUT_RESOURCES_H
#define STEWART_FMU_MODEL_WITHOUT_RESOURCES_H

void model_reset(fmu_instance *inst) { (void)inst; }

void model_free(fmu_instance *inst) { (void)inst; }

fmu_status model_start(fmu_instance *inst) {
    (void)inst;
    return FMU_OK;
}

fmu_status model_set_input_derivatives(fmu_instance *inst, const unsigned vr[], size_t n,
                                       const int order[], const double value[]) {
    (void)vr; (void)order; (void)value;
    if (n == 0) return FMU_OK;
    fmu_log(inst, FMU_ERROR, LOG_ERROR, "SetRealInputDerivatives: " FMU_MODEL_IDENTIFIER
            " takes no input derivatives");
    return FMU_ERROR;
}

size_t model_state_size(const fmu_instance *inst) {
    (void)inst;
    return 0;
}

fmu_status model_save(const fmu_instance *inst, unsigned char *out, size_t size) {
    (void)inst; (void)out;
    return size == 0 ? FMU_OK : FMU_ERROR;
}

fmu_status model_load(fmu_instance *inst, const unsigned char *in, size_t size) {
    (void)inst; (void)in;
    return size == 0 ? FMU_OK : FMU_ERROR;
}

#endif
