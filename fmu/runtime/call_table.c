/* The call-order table (FMI 2 §2.1.3 / §4.2.4, FMI 3 §3.2): which mode allows which call. */
#include "call_table.h"

#include "logging.h"

#define ANY_MODE \
    (MODE_INSTANTIATED | MODE_INITIALIZATION | MODES_RUNNING | MODE_TERMINATED | MODE_ERROR)
static const int kAllowed[CALL_COUNT] = {
    [CALL_SET_DEBUG_LOGGING] = ANY_MODE,
    [CALL_SETUP_EXPERIMENT] = MODE_INSTANTIATED,
    [CALL_ENTER_INITIALIZATION] = MODE_INSTANTIATED,
    [CALL_EXIT_INITIALIZATION] = MODE_INITIALIZATION,
    [CALL_DO_STEP] = MODE_STEP,
    [CALL_TERMINATE] = MODES_RUNNING,
    [CALL_RESET] = ANY_MODE,
    [CALL_GET] = MODE_INITIALIZATION | MODES_RUNNING | MODE_TERMINATED | MODE_ERROR,
    [CALL_SET] = MODE_INSTANTIATED | MODE_INITIALIZATION | MODES_RUNNING,
    [CALL_SET_INPUT_DERIVATIVES] = MODE_INSTANTIATED | MODE_INITIALIZATION | MODE_STEP,
    [CALL_GET_STATUS] = MODE_STEP | MODE_TERMINATED | MODE_ERROR,
    /* no state is taken in Error (its values may be anything), but restoring one is a way out
     * of Error (FMI 2 §2.1.3, FMI 3 §3.2.1) */
    [CALL_GET_FMU_STATE] =
        MODE_INSTANTIATED | MODE_INITIALIZATION | MODES_RUNNING | MODE_TERMINATED,
    [CALL_SET_FMU_STATE] = ANY_MODE,
    [CALL_FREE_FMU_STATE] = ANY_MODE,
    [CALL_SERIALIZE] = ANY_MODE,
    /* Model Exchange: FMI 2 §3.2.3, FMI 3 §3.2 */
    [CALL_ENTER_EVENT_MODE] = MODE_EVENT | MODE_CONTINUOUS_TIME,
    [CALL_NEW_DISCRETE_STATES] = MODE_EVENT,
    [CALL_ENTER_CONTINUOUS_TIME_MODE] = MODE_EVENT,
    [CALL_COMPLETED_INTEGRATOR_STEP] = MODE_CONTINUOUS_TIME,
    [CALL_SET_TIME] = MODE_EVENT | MODE_CONTINUOUS_TIME,
    [CALL_SET_CONTINUOUS_STATES] = MODE_CONTINUOUS_TIME,
    /* states, derivatives, nominals, event indicators */
    [CALL_GET_CONTINUOUS_STATES] =
        MODE_INITIALIZATION | MODE_EVENT | MODE_CONTINUOUS_TIME | MODE_TERMINATED | MODE_ERROR,
    /* as the outputs: once initialisation has begun (FMI 2 §4.2.4, FMI 3 §4.2.2) */
    [CALL_GET_DIRECTIONAL_DERIVATIVE] = MODE_INITIALIZATION | MODES_RUNNING | MODE_TERMINATED,
};

const char *fmu_mode_name(int mode) {
    switch (mode) {
        case MODE_INSTANTIATED: return "instantiated";
        case MODE_INITIALIZATION: return "initialization mode";
        case MODE_STEP: return "step mode";
        case MODE_TERMINATED: return "terminated";
        case MODE_ERROR: return "error";
        case MODE_EVENT: return "event mode";
        case MODE_CONTINUOUS_TIME: return "continuous-time mode";
    }
    return "?";
}

fmu_status fmu_check_call(fmu_instance *inst, fmu_call call, const char *function) {
    if (!inst) return FMU_ERROR;
    if (kAllowed[call] & inst->v.mode) return FMU_OK;
    fmu_log(inst, FMU_ERROR, LOG_ERROR, "%s is not allowed in %s", function,
            fmu_mode_name(inst->v.mode));
    return FMU_ERROR;
}
