/* FMI 3.0 Model Exchange layer: each function translates its arguments onto one runtime call
 * (runtime/model_exchange.h), which checks the call order and, in a co-simulation unit, says
 * that the unit does not support it. */
#include "fmi3Functions.h"
#include "model_exchange.h"

#define INST ((fmu_instance *)instance)
/* The runtime's statuses are numbered as fmi3Status. */
#define CALL(expression) return (fmi3Status)(expression)

fmi3Status fmi3EnterEventMode(fmi3Instance instance) { CALL(fmu_enter_event_mode(INST)); }

fmi3Status fmi3UpdateDiscreteStates(fmi3Instance instance, fmi3Boolean *discreteStatesNeedUpdate,
                                    fmi3Boolean *terminateSimulation,
                                    fmi3Boolean *nominalsOfContinuousStatesChanged,
                                    fmi3Boolean *valuesOfContinuousStatesChanged,
                                    fmi3Boolean *nextEventTimeDefined, fmi3Float64 *nextEventTime) {
    const fmu_status s = fmu_new_discrete_states(INST);
    if (s == FMU_OK || s == FMU_WARNING) { /* Warning: outputs valid */
        fmi3Boolean *flags[5] = {discreteStatesNeedUpdate, terminateSimulation,
                                 nominalsOfContinuousStatesChanged, valuesOfContinuousStatesChanged,
                                 nextEventTimeDefined};
        for (int i = 0; i < 5; ++i)
            if (flags[i]) *flags[i] = fmi3False;
        if (nextEventTime) *nextEventTime = 0.0;
    }
    CALL(s);
}

fmi3Status fmi3EnterContinuousTimeMode(fmi3Instance instance) {
    CALL(fmu_enter_continuous_time_mode(INST));
}

fmi3Status fmi3CompletedIntegratorStep(fmi3Instance instance,
                                       fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi3Boolean *enterEventMode,
                                       fmi3Boolean *terminateSimulation) {
    (void)noSetFMUStatePriorToCurrentPoint;
    int event = 0, terminate = 0;
    const fmu_status s = fmu_completed_integrator_step(INST, &event, &terminate);
    if (enterEventMode) *enterEventMode = event ? fmi3True : fmi3False;
    if (terminateSimulation) *terminateSimulation = terminate ? fmi3True : fmi3False;
    CALL(s);
}

fmi3Status fmi3SetTime(fmi3Instance instance, fmi3Float64 time) { CALL(fmu_set_time(INST, time)); }

fmi3Status fmi3SetContinuousStates(fmi3Instance instance, const fmi3Float64 x[], size_t n) {
    CALL(fmu_set_continuous_states(INST, x, n));
}

fmi3Status fmi3GetContinuousStateDerivatives(fmi3Instance instance, fmi3Float64 d[], size_t n) {
    CALL(fmu_get_derivatives(INST, d, n));
}

fmi3Status fmi3GetEventIndicators(fmi3Instance instance, fmi3Float64 e[], size_t n) {
    CALL(fmu_get_event_indicators(INST, e, n));
}

fmi3Status fmi3GetContinuousStates(fmi3Instance instance, fmi3Float64 x[], size_t n) {
    CALL(fmu_get_continuous_states(INST, x, n));
}

fmi3Status fmi3GetNominalsOfContinuousStates(fmi3Instance instance, fmi3Float64 x[], size_t n) {
    CALL(fmu_get_nominals(INST, x, n));
}

fmi3Status fmi3GetNumberOfEventIndicators(fmi3Instance instance, size_t *n) {
    if (!instance || !n) return fmi3Error;
    *n = 0;
    return fmi3OK;
}

fmi3Status fmi3GetNumberOfContinuousStates(fmi3Instance instance, size_t *n) {
    if (!instance || !n) return fmi3Error;
    *n = fmu_state_count();
    return fmi3OK;
}
