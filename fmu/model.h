/*
 * The one model behind both FMI layers: the instance struct, its state machine, get/set through
 * the variable table, the step semantics and FMU state. fmi2_functions.c and fmi3_functions.c are
 * thin translations onto these functions. No global mutable state: everything lives in the
 * instance. Nothing here allocates after initialisation except FMU state snapshots.
 */
#ifndef STEWART_FMU_MODEL_H
#define STEWART_FMU_MODEL_H

#include <stdint.h>

#include "stewart/stewart.h"
#include "variables.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Same numbering as fmi2Status and fmi3Status. */
typedef enum { FMU_OK = 0, FMU_WARNING = 1, FMU_DISCARD = 2, FMU_ERROR = 3, FMU_FATAL = 4 } fmu_status;

/* Mode of an instance (bit flags, so a call can list the modes it is allowed in). */
typedef enum {
    MODE_INSTANTIATED = 1 << 0,
    MODE_INITIALIZATION = 1 << 1,
    MODE_STEP = 1 << 2,
    MODE_TERMINATED = 1 << 3,
    MODE_ERROR = 1 << 4
} fmu_mode;

/* The calls whose allowed modes are checked, in one table (model.c: kAllowed). */
typedef enum {
    CALL_SET_DEBUG_LOGGING, CALL_SETUP_EXPERIMENT, CALL_ENTER_INITIALIZATION,
    CALL_EXIT_INITIALIZATION, CALL_DO_STEP, CALL_TERMINATE, CALL_RESET, CALL_GET,
    CALL_SET, CALL_SET_INPUT_DERIVATIVES, CALL_GET_STATUS, CALL_GET_FMU_STATE,
    CALL_SET_FMU_STATE, CALL_SERIALIZE, CALL_COUNT
} fmu_call;

typedef enum { FMU_VERSION_2 = 2, FMU_VERSION_3 = 3 } fmu_version;

/* Everything an FMU state holds besides the solver data block: plain data, memcpy-able. */
typedef struct fmu_values {
    double real[FMU_NVR];      /* Real variables by value reference */
    int32_t integer[FMU_NVR];  /* Integer variables by value reference */
    double time;               /* communication point the current inputs belong to */
    int n_history;             /* poses committed at earlier communication points (0..2) */
    double history_t[2];       /* [0] older, [1] newer */
    double history_q[2][6];
    int input_derivatives;     /* fmi2SetRealInputDerivatives called since the last step */
    int solved;                /* outputs belong to the current inputs and time */
    fmu_status solve_status;   /* what that solve returned (OK, Warning, Discard) */
    double last_successful_time;
    int mode;                  /* fmu_mode */
} fmu_values;

typedef struct fmu_instance fmu_instance;
/* Hands a message to the master's logger (the per-version layer knows how). */
typedef void (*fmu_log_fn)(const fmu_instance *inst, fmu_status status, const char *category,
                           const char *message);

struct fmu_instance {
    fmu_values v;
    stewart_model *model;      /* built from the parameters when initialisation ends */
    stewart_data *data;
    stewart_params model_params;  /* the parameters `model` was built from */
    unsigned long model_generation; /* counts the models built: tells FMU states which fits */
    stewart_options options;
    fmu_version version;
    char *name;
    fmu_log_fn log_fn;
    const void *callbacks;     /* fmi2CallbackFunctions* (FMI 2) or the log callback (FMI 3) */
    void *environment;
    int logging_on;
    int category_on[FMU_N_LOG_CATEGORIES];
    char message[2 * STEWART_MESSAGE_SIZE];
};

fmu_instance *fmu_instantiate(const char *name, fmu_version version, fmu_log_fn log_fn,
                              const void *callbacks, void *environment, int logging_on);
void fmu_free(fmu_instance *inst);

/* The central state-machine check: FMU_OK, or FMU_ERROR with a message naming the call. */
fmu_status fmu_check_call(fmu_instance *inst, fmu_call call, const char *function);
/* Logs under `category` if logging is on and that category is enabled. printf-style. */
void fmu_log(const fmu_instance *inst, fmu_status status, int category, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

fmu_status fmu_set_debug_logging(fmu_instance *inst, int on, size_t n, const char *const cats[]);
fmu_status fmu_enter_initialization(fmu_instance *inst, double start_time);
fmu_status fmu_exit_initialization(fmu_instance *inst);
fmu_status fmu_do_step(fmu_instance *inst, double t, double h);
fmu_status fmu_terminate(fmu_instance *inst);
fmu_status fmu_reset(fmu_instance *inst);

fmu_status fmu_get_real(fmu_instance *inst, const unsigned vr[], size_t n, double value[]);
fmu_status fmu_get_integer(fmu_instance *inst, const unsigned vr[], size_t n, int32_t value[]);
fmu_status fmu_set_real(fmu_instance *inst, const unsigned vr[], size_t n, const double value[]);
fmu_status fmu_set_integer(fmu_instance *inst, const unsigned vr[], size_t n,
                           const int32_t value[]);
/* FMI 2 input derivatives: order 1 or 2 of a pose input (or order 1 of a *_dot input). */
fmu_status fmu_set_input_derivatives(fmu_instance *inst, const unsigned vr[], size_t n,
                                     const int order[], const double value[]);

/* FMU state: a snapshot of fmu_values and a copy of the solver data block. */
typedef struct fmu_snapshot fmu_snapshot;
fmu_status fmu_get_state(fmu_instance *inst, fmu_snapshot **state);
fmu_status fmu_set_state(fmu_instance *inst, const fmu_snapshot *state);
fmu_status fmu_free_state(fmu_instance *inst, fmu_snapshot **state);
/* Bytes of a serialised snapshot (its values, and the solver data block when it has one). */
size_t fmu_serialized_size(const fmu_snapshot *state);
fmu_status fmu_serialize_state(fmu_instance *inst, const fmu_snapshot *state, unsigned char *out,
                               size_t size);
fmu_status fmu_deserialize_state(fmu_instance *inst, const unsigned char *in, size_t size,
                                 fmu_snapshot **state);

#ifdef __cplusplus
}
#endif

#endif
