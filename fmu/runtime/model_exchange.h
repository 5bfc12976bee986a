/*
 * Model Exchange: the master integrates the unit's continuous states itself. A model's config.h
 * makes a Model Exchange unit with FMU_MODEL_EXCHANGE 1 and names its states and their
 * derivatives by value reference: FMU_N_STATES, FMU_STATE_VR(i), FMU_DERIVATIVE_VR(i). The
 * states are Real variables of the instance (so FMU states, get and set carry them as they are);
 * the derivatives are outputs that model_refresh_outputs computes. No event indicators, no time
 * events: event mode only passes through. In a co-simulation unit every call here is an Error
 * saying so. The FMI 2 and FMI 3 layers (fmi2_me_functions.c, fmi3_me_functions.c) translate
 * onto these functions.
 */
#ifndef STEWART_FMU_MODEL_EXCHANGE_H
#define STEWART_FMU_MODEL_EXCHANGE_H

#include <stddef.h>

#include "instance.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The number of continuous states (0 for a co-simulation unit). */
size_t fmu_state_count(void);
/* EnterEventMode (from continuous-time mode). */
fmu_status fmu_enter_event_mode(fmu_instance *inst);
/* NewDiscreteStates / UpdateDiscreteStates: nothing discrete changes; no next time event. OK,
 * or Warning (the model's, at an accepted state: outputs valid, the event info to be filled). */
fmu_status fmu_new_discrete_states(fmu_instance *inst);
/* EnterContinuousTimeMode (from event mode). */
fmu_status fmu_enter_continuous_time_mode(fmu_instance *inst);
/* CompletedIntegratorStep: never asks for an event or to terminate (both set to 0). */
fmu_status fmu_completed_integrator_step(fmu_instance *inst, int *enter_event_mode,
                                         int *terminate_simulation);
/* SetTime: the time the next derivatives belong to (Error naming it unless finite). */
fmu_status fmu_set_time(fmu_instance *inst, double time);
/* SetContinuousStates: n must be fmu_state_count(); a non-finite state is Discard naming it
 * (nothing changes). */
fmu_status fmu_set_continuous_states(fmu_instance *inst, const double x[], size_t n);
/* GetContinuousStates (in initialisation: those the parameters give). */
fmu_status fmu_get_continuous_states(fmu_instance *inst, double x[], size_t n);
/* GetDerivatives: the model's right-hand side at the current time, states and inputs; Discard
 * (the model names the value) where the state is outside the model's domain. */
fmu_status fmu_get_derivatives(fmu_instance *inst, double dx[], size_t n);
/* GetNominalsOfContinuousStates: 1 for every state. */
fmu_status fmu_get_nominals(fmu_instance *inst, double nominal[], size_t n);
/* GetEventIndicators: the unit has none (n must be 0). */
fmu_status fmu_get_event_indicators(fmu_instance *inst, double z[], size_t n);

#ifdef __cplusplus
}
#endif

#endif
