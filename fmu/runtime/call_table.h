/* The call-order table: one mask of allowed modes per call, checked before every call runs. */
#ifndef STEWART_FMU_CALL_TABLE_H
#define STEWART_FMU_CALL_TABLE_H

#include "instance.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The calls whose allowed modes are checked (call_table.c: kAllowed). */
typedef enum {
    CALL_SET_DEBUG_LOGGING,
    CALL_SETUP_EXPERIMENT,
    CALL_ENTER_INITIALIZATION,
    CALL_EXIT_INITIALIZATION,
    CALL_DO_STEP,
    CALL_TERMINATE,
    CALL_RESET,
    CALL_GET,
    CALL_SET,
    CALL_SET_INPUT_DERIVATIVES,
    CALL_GET_STATUS,
    CALL_GET_FMU_STATE,
    CALL_SET_FMU_STATE,
    CALL_FREE_FMU_STATE,
    CALL_SERIALIZE,
    CALL_GET_DIRECTIONAL_DERIVATIVE,
    /* Model Exchange (runtime/model_exchange.c) */
    CALL_ENTER_EVENT_MODE,
    CALL_NEW_DISCRETE_STATES,
    CALL_ENTER_CONTINUOUS_TIME_MODE,
    CALL_COMPLETED_INTEGRATOR_STEP,
    CALL_SET_TIME,
    CALL_SET_CONTINUOUS_STATES,
    CALL_GET_CONTINUOUS_STATES,
    CALL_COUNT
} fmu_call;

/* FMU_OK if `call` is allowed in the instance's mode; else FMU_ERROR with a message naming the
 * function (a NULL instance is an Error, without message: there is no logger). */
fmu_status fmu_check_call(fmu_instance *inst, fmu_call call, const char *function);
/* "step mode", "error", ... for messages. */
const char *fmu_mode_name(int mode);

#ifdef __cplusplus
}
#endif

#endif
