/* Model Exchange calls on the shared instance (model_exchange.h): call order, argument checks,
 * the states as the instance's Real variables, derivatives through model_refresh_outputs. */
#include "model_exchange.h"

#include <math.h>

#include "call_table.h"
#include "logging.h"
#include "model_interface.h"
#include "values.h"

#ifndef FMU_ME_ACCEPTED_STATE
#define FMU_ME_ACCEPTED_STATE 0
#endif

#ifndef FMU_N_STATES
#define FMU_N_STATES 0
#define FMU_STATE_VR(i) 0u
#define FMU_DERIVATIVE_VR(i) 0u
#endif

size_t fmu_state_count(void) { return FMU_N_STATES; }

/* FMU_OK if a Model Exchange unit may make `call` now; a co-simulation unit never may. */
static fmu_status check_me_call(fmu_instance *inst, fmu_call call, const char *function) {
    if (!FMU_MODEL_EXCHANGE) {
        if (inst)
            fmu_log(inst, FMU_ERROR, LOG_ERROR,
                    "%s is not supported by this FMU (co-simulation only)", function);
        return FMU_ERROR;
    }
    return fmu_check_call(inst, call, function);
}

/* FMU_OK if `array` holds the unit's states (n of them, not NULL unless n is 0). */
static fmu_status check_array(fmu_instance *inst, const char *function, const void *array,
                              size_t n) {
    if (n != FMU_N_STATES) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "%s: the array has %zu elements, the unit has %d "
                "continuous states",
                function, n, FMU_N_STATES);
        return FMU_ERROR;
    }
    if (n > 0 && !array) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "%s: the array is NULL", function);
        return FMU_ERROR;
    }
    return FMU_OK;
}

fmu_status fmu_enter_event_mode(fmu_instance *inst) {
    if (check_me_call(inst, CALL_ENTER_EVENT_MODE, "EnterEventMode") != FMU_OK) return FMU_ERROR;
    inst->v.mode = MODE_EVENT;
    return FMU_OK;
}

/* What the model reports at an accepted state (OK if it reports nothing). */
static fmu_status accepted_state(fmu_instance *inst) {
#if FMU_ME_ACCEPTED_STATE
    return model_accepted_state(inst);
#else
    (void)inst;
    return FMU_OK;
#endif
}

fmu_status fmu_new_discrete_states(fmu_instance *inst) {
    if (check_me_call(inst, CALL_NEW_DISCRETE_STATES, "NewDiscreteStates") != FMU_OK)
        return FMU_ERROR;
    /* the event update's state is an accepted state: the same Warning as CompletedIntegratorStep
     * (after initialisation it is the first the master sees) */
    return accepted_state(inst);
}

fmu_status fmu_enter_continuous_time_mode(fmu_instance *inst) {
    if (check_me_call(inst, CALL_ENTER_CONTINUOUS_TIME_MODE, "EnterContinuousTimeMode") != FMU_OK)
        return FMU_ERROR;
    inst->v.mode = MODE_CONTINUOUS_TIME;
    return FMU_OK;
}

fmu_status fmu_completed_integrator_step(fmu_instance *inst, int *enter_event_mode,
                                         int *terminate_simulation) {
    if (check_me_call(inst, CALL_COMPLETED_INTEGRATOR_STEP, "CompletedIntegratorStep") != FMU_OK)
        return FMU_ERROR;
    if (enter_event_mode) *enter_event_mode = 0;
    if (terminate_simulation) *terminate_simulation = 0;
    return accepted_state(inst);
}

fmu_status fmu_set_time(fmu_instance *inst, double time) {
    if (check_me_call(inst, CALL_SET_TIME, "SetTime") != FMU_OK) return FMU_ERROR;
    if (!isfinite(time)) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "SetTime: time = %g must be finite", time);
        return FMU_ERROR;
    }
    if (time != inst->v.time) inst->v.outputs_current = 0;
    inst->v.time = time;
    inst->v.real[fmu_time_vr] = time;
    inst->v.last_successful_time = time;
    return FMU_OK;
}

fmu_status fmu_set_continuous_states(fmu_instance *inst, const double x[], size_t n) {
    if (check_me_call(inst, CALL_SET_CONTINUOUS_STATES, "SetContinuousStates") != FMU_OK ||
        check_array(inst, "SetContinuousStates", x, n) != FMU_OK)
        return FMU_ERROR;
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(x[i])) {
            fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                    "SetContinuousStates: state %s = %g is not "
                    "finite; the states are not changed",
                    fmu_variable_by_vr(FMU_STATE_VR(i))->name, x[i]);
            return FMU_DISCARD;
        }
    for (size_t i = 0; i < n; ++i) inst->v.real[FMU_STATE_VR(i)] = x[i];
    if (n > 0) inst->v.outputs_current = 0;
    return FMU_OK;
}

fmu_status fmu_get_continuous_states(fmu_instance *inst, double x[], size_t n) {
    if (check_me_call(inst, CALL_GET_CONTINUOUS_STATES, "GetContinuousStates") != FMU_OK ||
        check_array(inst, "GetContinuousStates", x, n) != FMU_OK)
        return FMU_ERROR;
    /* in initialisation the states are those the parameters give: apply them first */
    if (inst->v.mode == MODE_INITIALIZATION && fmu_refresh_outputs(inst) != FMU_OK)
        return FMU_ERROR;
    for (size_t i = 0; i < n; ++i) x[i] = inst->v.real[FMU_STATE_VR(i)];
    return FMU_OK;
}

fmu_status fmu_get_derivatives(fmu_instance *inst, double dx[], size_t n) {
    if (check_me_call(inst, CALL_GET_CONTINUOUS_STATES, "GetDerivatives") != FMU_OK ||
        check_array(inst, "GetDerivatives", dx, n) != FMU_OK)
        return FMU_ERROR;
    fmu_status s = FMU_OK;
    if (inst->v.mode & (MODE_INITIALIZATION | MODES_RUNNING)) {
        if (inst->v.mode == MODE_INITIALIZATION && !inst->v.outputs_current &&
            fmu_apply_initial_parameters(inst) != FMU_OK)
            return fmu_fail(inst);
        s = model_refresh_outputs(inst); /* the stored status if already current */
        if (s == FMU_ERROR) return fmu_fail(inst);
        if (s == FMU_DISCARD) return s; /* the model named the value; dx untouched */
    }
    for (size_t i = 0; i < n; ++i) dx[i] = inst->v.real[FMU_DERIVATIVE_VR(i)];
    return s;
}

fmu_status fmu_get_nominals(fmu_instance *inst, double nominal[], size_t n) {
    if (check_me_call(inst, CALL_GET_CONTINUOUS_STATES, "GetNominalsOfContinuousStates") !=
            FMU_OK ||
        check_array(inst, "GetNominalsOfContinuousStates", nominal, n) != FMU_OK)
        return FMU_ERROR;
    for (size_t i = 0; i < n; ++i) nominal[i] = 1.0;
    return FMU_OK;
}

fmu_status fmu_get_event_indicators(fmu_instance *inst, double z[], size_t n) {
    (void)z;
    if (check_me_call(inst, CALL_GET_CONTINUOUS_STATES, "GetEventIndicators") != FMU_OK)
        return FMU_ERROR;
    if (n == 0) return FMU_OK;
    fmu_log(inst, FMU_ERROR, LOG_ERROR, "GetEventIndicators: %zu asked for, the unit has none", n);
    return FMU_ERROR;
}
