/* FMI 2.0 Model Exchange layer: each function translates its arguments onto one runtime call
 * (runtime/model_exchange.h), which checks the call order and, in a co-simulation unit, says
 * that the unit does not support it. */
#include "fmi2Functions.h"
#include "model_exchange.h"

#define INST ((fmu_instance *)c)
/* The runtime's statuses are numbered as fmi2Status. */
#define CALL(expression) return (fmi2Status)(expression)

fmi2Status fmi2EnterEventMode(fmi2Component c) { CALL(fmu_enter_event_mode(INST)); }

fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo *info) {
    const fmu_status s = fmu_new_discrete_states(INST);
    if ((s == FMU_OK || s == FMU_WARNING) && info) { /* Warning: outputs valid */
        info->newDiscreteStatesNeeded = fmi2False;
        info->terminateSimulation = fmi2False;
        info->nominalsOfContinuousStatesChanged = fmi2False;
        info->valuesOfContinuousStatesChanged = fmi2False;
        info->nextEventTimeDefined = fmi2False;
        info->nextEventTime = 0.0;
    }
    CALL(s);
}

fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c) {
    CALL(fmu_enter_continuous_time_mode(INST));
}

fmi2Status fmi2CompletedIntegratorStep(fmi2Component c,
                                       fmi2Boolean noSetFMUStatePriorToCurrentPoint,
                                       fmi2Boolean *enterEventMode,
                                       fmi2Boolean *terminateSimulation) {
    (void)noSetFMUStatePriorToCurrentPoint;
    int event = 0, terminate = 0;
    const fmu_status s = fmu_completed_integrator_step(INST, &event, &terminate);
    if (enterEventMode) *enterEventMode = event ? fmi2True : fmi2False;
    if (terminateSimulation) *terminateSimulation = terminate ? fmi2True : fmi2False;
    CALL(s);
}

fmi2Status fmi2SetTime(fmi2Component c, fmi2Real time) { CALL(fmu_set_time(INST, time)); }

fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real x[], size_t nx) {
    CALL(fmu_set_continuous_states(INST, x, nx));
}

fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real derivatives[], size_t nx) {
    CALL(fmu_get_derivatives(INST, derivatives, nx));
}

fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real eventIndicators[], size_t ni) {
    CALL(fmu_get_event_indicators(INST, eventIndicators, ni));
}

fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real x[], size_t nx) {
    CALL(fmu_get_continuous_states(INST, x, nx));
}

fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real x_nominal[], size_t nx) {
    CALL(fmu_get_nominals(INST, x_nominal, nx));
}
