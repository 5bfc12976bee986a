/*
 * The model-interface functions (model_interface.h) of a model that has no resources, no saved
 * state beyond its plain values and takes no input derivatives: model_reset, model_free,
 * model_start (nothing to set), model_set_input_derivatives (Error for any), model_state_size
 * (0), model_save and model_load (of 0 bytes). Include it in exactly one .c file of such a model
 * (it defines them), after model_interface.h and logging.h.
 */
#ifndef STEWART_FMU_MODEL_WITHOUT_RESOURCES_H
#define STEWART_FMU_MODEL_WITHOUT_RESOURCES_H

#include "model_without_saved_state.h"

void model_reset(fmu_instance *inst) { (void)inst; }

void model_free(fmu_instance *inst) { (void)inst; }

fmu_status model_start(fmu_instance *inst) {
    (void)inst;
    return FMU_OK;
}

#endif
