/* The instance life cycle, shared by every model (the step's checks and time bookkeeping are
 * do_step.c's). */
#include "instance.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "call_table.h"
#include "logging.h"
#include "model_interface.h"

/* Start values of the variables and the model, and the runtime's own. */
static void start_values(fmu_values *v) {
    memset(v, 0, sizeof *v);
    model_start_values(v);
    v->mode = MODE_INSTANTIATED;
}

fmu_instance *fmu_instantiate(const char *name, fmu_version version, fmu_log_fn log_fn,
                              const void *callbacks, void *environment, int logging_on) {
    fmu_instance *inst = (fmu_instance *)calloc(1, sizeof *inst);
    if (!inst) return NULL;
    const char *n = name ? name : "";
    inst->name = (char *)malloc(strlen(n) + 1);
    if (!inst->name) {
        free(inst);
        return NULL;
    }
    strcpy(inst->name, n);
    inst->version = version;
    inst->log_fn = log_fn;
    inst->callbacks = callbacks;
    inst->environment = environment;
    fmu_logging_init(inst, logging_on);
    start_values(&inst->v);
    return inst;
}

void fmu_free(fmu_instance *inst) {
    if (!inst) return;
    model_free(inst);
    free(inst->name);
    free(inst);
}

/* The mode leaves step mode: a model's usual route goes to 0 (do_step.h: fmu_usual_call). */
static void leave_step_mode(fmu_values *v, int mode) {
    v->mode = mode;
#if FMU_MODEL_USUAL_STEP
    FMU_USUAL_ROUTE(v) = 0;
#endif
}

fmu_status fmu_fail(fmu_instance *inst) {
    leave_step_mode(&inst->v, MODE_ERROR);
    return FMU_ERROR;
}

fmu_status fmu_set_debug_logging(fmu_instance *inst, int on, size_t n, const char *const cats[]) {
    if (fmu_check_call(inst, CALL_SET_DEBUG_LOGGING, "SetDebugLogging") != FMU_OK) return FMU_ERROR;
    return fmu_logging_set(inst, on, n, cats);
}

int fmu_after_initialization(const fmu_values *v) {
    return (v->mode & (MODES_RUNNING | MODE_TERMINATED)) != 0;
}

fmu_status fmu_apply_initial_parameters(fmu_instance *inst) {
    if (model_apply_parameters(inst) != FMU_OK) return FMU_ERROR;
    return model_start(inst);
}

fmu_status fmu_setup_experiment(fmu_instance *inst, double start_time) {
    if (fmu_check_call(inst, CALL_SETUP_EXPERIMENT, "SetupExperiment") != FMU_OK) return FMU_ERROR;
    if (!isfinite(start_time)) { /* a NaN time would reach FMU states and outputs */
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "SetupExperiment: startTime = %g must be finite",
                start_time);
        return FMU_ERROR;
    }
    fmu_values_set_time(&inst->v, start_time);
    return FMU_OK;
}

fmu_status fmu_enter_initialization(fmu_instance *inst, int has_start, double start_time) {
    if (fmu_check_call(inst, CALL_ENTER_INITIALIZATION, "EnterInitializationMode") != FMU_OK)
        return FMU_ERROR;
    if (!has_start) start_time = inst->v.time;
    if (!isfinite(start_time)) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "startTime = %g must be finite", start_time);
        return FMU_ERROR;
    }
    fmu_values_set_time(&inst->v, start_time);
    inst->v.last_successful_time = start_time;
    inst->v.outputs_current = 0;
    inst->v.mode = MODE_INITIALIZATION;
    return FMU_OK;
}

fmu_status fmu_exit_initialization(fmu_instance *inst) {
    if (fmu_check_call(inst, CALL_EXIT_INITIALIZATION, "ExitInitializationMode") != FMU_OK)
        return FMU_ERROR;
    if (fmu_apply_initial_parameters(inst) != FMU_OK) return fmu_fail(inst);
    inst->v.outputs_current = 0;
    fmu_status s = model_refresh_outputs(inst);
    if (s == FMU_ERROR) return fmu_fail(inst);
    if (s == FMU_DISCARD) s = FMU_WARNING; /* the status output tells the master it is bad */
    inst->v.mode = MODE_AFTER_INITIALIZATION;
    fmu_log(inst, FMU_OK, LOG_EVENTS, "initialised at t = %.17g", inst->v.time);
    return s;
}

fmu_status fmu_terminate(fmu_instance *inst) {
    if (fmu_check_call(inst, CALL_TERMINATE, "Terminate") != FMU_OK) return FMU_ERROR;
    leave_step_mode(&inst->v, MODE_TERMINATED);
    return FMU_OK;
}

fmu_status fmu_reset(fmu_instance *inst) {
    if (fmu_check_call(inst, CALL_RESET, "Reset") != FMU_OK) return FMU_ERROR;
    start_values(&inst->v);
    model_reset(inst);
    fmu_log(inst, FMU_OK, LOG_EVENTS, "reset to the start values");
    return FMU_OK;
}

fmu_status fmu_get_step_status(fmu_instance *inst, int *status) {
    if (fmu_check_call(inst, CALL_GET_STATUS, "GetStatus") != FMU_OK || !status) return FMU_ERROR;
    *status = inst->v.last_step_status;
    return FMU_OK;
}

fmu_status fmu_get_last_successful_time(fmu_instance *inst, double *time) {
    if (fmu_check_call(inst, CALL_GET_STATUS, "GetRealStatus") != FMU_OK || !time) return FMU_ERROR;
    *time = inst->v.last_successful_time;
    return FMU_OK;
}
