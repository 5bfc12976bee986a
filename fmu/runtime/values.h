/* Value binding: get and set through the model's variable table, by value reference. */
#ifndef STEWART_FMU_VALUES_H
#define STEWART_FMU_VALUES_H

#include <stddef.h>
#include <stdint.h>

#include "instance.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Outputs asked for (in initialisation, step, event or continuous-time mode): unless current,
 * initialisation applies the parameters first, then the model makes them those of the current
 * inputs (and states). Discard and Warning are reported by the status outputs (OK here); Error
 * puts the instance in Error. */
fmu_status fmu_refresh_outputs(fmu_instance *inst);
/* Reals (inputs, outputs, parameters, time) by value reference; outputs are refreshed first. */
fmu_status fmu_get_real(fmu_instance *inst, const unsigned vr[], size_t n, double value[]);
/* Integers by value reference; outputs are refreshed first. */
fmu_status fmu_get_integer(fmu_instance *inst, const unsigned vr[], size_t n, int32_t value[]);
/* Inputs in any mode before Terminate, parameters until the end of initialisation. */
fmu_status fmu_set_real(fmu_instance *inst, const unsigned vr[], size_t n, const double value[]);
/* As fmu_set_real, for Integer variables. */
fmu_status fmu_set_integer(fmu_instance *inst, const unsigned vr[], size_t n,
                           const int32_t value[]);
/* Strings by value reference: String parameters of a model with FMU_STRING_PARAMETERS (the
 * pointers stay valid until the value is set again); Error for any other value reference. */
fmu_status fmu_get_string(fmu_instance *inst, const unsigned vr[], size_t n, const char *value[]);
/* As fmu_set_real for parameters; a value of FMU_STRING_SIZE bytes or more is refused. */
fmu_status fmu_set_string(fmu_instance *inst, const unsigned vr[], size_t n,
                          const char *const value[]);
/* FMI 2 input derivatives, handed to the model after the call-order and argument checks. */
fmu_status fmu_set_input_derivatives(fmu_instance *inst, const unsigned vr[], size_t n,
                                     const int order[], const double value[]);

#ifdef __cplusplus
}
#endif

#endif
