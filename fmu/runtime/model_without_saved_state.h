/*
 * The model-interface functions (model_interface.h) of a model whose FMU state is its plain values
 * alone and that takes no input derivatives: model_set_input_derivatives (Error for any),
 * model_state_size (0), model_save and model_load (of 0 bytes). Include it in exactly one .c file
 * of such a model (it defines them), after model_interface.h and logging.h; a model with no
 * resources at all includes model_without_resources.h instead.
 */
#ifndef STEWART_FMU_MODEL_WITHOUT_SAVED_STATE_H
#define STEWART_FMU_MODEL_WITHOUT_SAVED_STATE_H

fmu_status model_set_input_derivatives(fmu_instance *inst, const unsigned vr[], size_t n,
                                       const int order[], const double value[]) {
    (void)vr;
    (void)order;
    (void)value;
    if (n == 0) return FMU_OK;
    fmu_log(inst, FMU_ERROR, LOG_ERROR,
            "SetRealInputDerivatives: " FMU_MODEL_IDENTIFIER " takes no input derivatives");
    return FMU_ERROR;
}

size_t model_state_size(const fmu_instance *inst) {
    (void)inst;
    return 0;
}

fmu_status model_save(const fmu_instance *inst, unsigned char *out, size_t size) {
    (void)inst;
    (void)out;
    return size == 0 ? FMU_OK : FMU_ERROR;
}

fmu_status model_load(fmu_instance *inst, const unsigned char *in, size_t size) {
    (void)inst;
    (void)in;
    return size == 0 ? FMU_OK : FMU_ERROR;
}

#endif
