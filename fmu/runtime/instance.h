/*
 * One FMU instance, shared by every model: its plain values (what an FMU state copies), the
 * model's resources, the logger, and the life cycle (instantiate, set-up, initialisation, step,
 * terminate, reset, free). The FMI 2 and FMI 3 layers translate calls onto these functions and
 * never touch the fields; the model (models/<name>/model.c) reads and writes the values.
 * No global mutable state: everything lives in the instance.
 */
#ifndef STEWART_FMU_INSTANCE_H
#define STEWART_FMU_INSTANCE_H

#include <stddef.h>
#include <stdint.h>
#include <string.h> /* memcpy: fmu_outputs_current_or_inputs_unchecked */

#include "config.h"
#include "variables.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Same numbering as fmi2Status and fmi3Status. */
typedef enum {
    FMU_OK = 0,
    FMU_WARNING = 1,
    FMU_DISCARD = 2,
    FMU_ERROR = 3,
    FMU_FATAL = 4
} fmu_status;

/* Mode of an instance (bit flags, so a call can list the modes it is allowed in). */
typedef enum {
    MODE_INSTANTIATED = 1 << 0,
    MODE_INITIALIZATION = 1 << 1,
    MODE_STEP = 1 << 2,
    MODE_TERMINATED = 1 << 3,
    MODE_ERROR = 1 << 4,
    MODE_EVENT = 1 << 5,          /* Model Exchange (runtime/model_exchange.h) */
    MODE_CONTINUOUS_TIME = 1 << 6 /* Model Exchange */
} fmu_mode;

/* A model's config.h defines FMU_MODEL_EXCHANGE 1 to make a Model Exchange unit (and only that):
 * initialisation ends in event mode, and runtime/model_exchange.c serves its states. */
#ifndef FMU_MODEL_EXCHANGE
#define FMU_MODEL_EXCHANGE 0
#endif
/* A model's config.h defines FMU_MODEL_USUAL_STEP 1 when it takes the usual doStep itself
 * (model_usual_steps, model_interface.h). */
#ifndef FMU_MODEL_USUAL_STEP
#define FMU_MODEL_USUAL_STEP 0
#endif
/* Where an instance goes at the end of initialisation, and the modes after it. */
#define MODE_AFTER_INITIALIZATION (FMU_MODEL_EXCHANGE ? MODE_EVENT : MODE_STEP)
#define MODES_RUNNING (MODE_STEP | MODE_EVENT | MODE_CONTINUOUS_TIME)

typedef enum { FMU_VERSION_2 = 2, FMU_VERSION_3 = 3 } fmu_version;

/* Marks a function out of line where the compiler allows: a path the usual step does not take,
 * so that the step's own path stays short (doStep within 5 % of the library call it wraps). */
#if defined(__GNUC__)
#define FMU_RARE_PATH __attribute__((noinline, cold))
#else
#define FMU_RARE_PATH
#endif

/* Everything an FMU state holds besides the model's saved resources: plain data, memcpy-able.
 * Serialised as is; the last two members stay last_successful_time and mode (tests corrupt
 * them by offset). */
typedef struct fmu_values {
    double real[FMU_NVR];     /* Real variables by value reference */
    int32_t integer[FMU_NVR]; /* Integer variables by value reference */
    model_values model;       /* the model's own plain values (config.h) */
    double time;              /* communication point the current inputs belong to */
    double last_step_point;   /* communication point of the last accepted step */
    int has_stepped;          /* a step has been accepted since initialisation */
    int outputs_current;      /* the outputs belong to the current inputs and time (1) */
    int inputs_unchecked;     /* 0: every input is finite (the step need not look); set when a
                                  value that is not finite is set or restored, cleared by the
                                  model's scan of its inputs */
    int last_step_status;     /* what the last doStep returned (fmi2GetStatus) */
    double last_successful_time;
    int mode; /* fmu_mode */
} fmu_values;

/* A step's end (t + h) and t, side by side as the unit's time and last step point are. */
typedef struct fmu_step_span {
    double end, t;
} fmu_step_span;

typedef struct fmu_instance fmu_instance;
/* Hands a message to the master's logger (the per-version layer knows how): the callbacks and
 * environment given at instantiation, the instance name. */
typedef void (*fmu_log_fn)(const void *callbacks, void *environment, const char *instance_name,
                           fmu_status status, const char *category, const char *message);

struct fmu_instance {
    fmu_values v;
    model_resources res; /* the model's resources (config.h), freed by model_free */
    fmu_version version;
    char *name;
    fmu_log_fn log_fn;
    const void *callbacks; /* fmi2CallbackFunctions* (FMI 2) or the log callback (FMI 3) */
    void *environment;
    int logging_on;
    int category_on[FMU_N_LOG_CATEGORIES];
    /* FMI 3's lastSuccessfulTime of the doStep under way (do_step.h; NULL for FMI 2): a step not
     * taken writes the unit's last successful time through it. Set by every fmi3DoStep before
     * its step and read only inside a doStep, so never stale when read; not part of a state. */
    double *last_successful_time_out;
    /* A usual step's end and t across its library call, where a model keeps them (in memory
     * rather than callee-saved registers: no frame to save them in); not part of a state. */
    fmu_step_span step;
};

/* A new instance at its start values, or NULL (out of memory). */
fmu_instance *fmu_instantiate(const char *name, fmu_version version, fmu_log_fn log_fn,
                              const void *callbacks, void *environment, int logging_on);
/* Frees the instance and the model's resources (NULL is ignored). */
void fmu_free(fmu_instance *inst);

/* SetDebugLogging: enables (on) or disables the n named categories, or all of them if n is 0. */
fmu_status fmu_set_debug_logging(fmu_instance *inst, int on, size_t n, const char *const cats[]);
/* FMI 2 fmi2SetupExperiment: records the start time (checked at initialisation). */
fmu_status fmu_setup_experiment(fmu_instance *inst, double start_time);
/* Enters initialisation at start_time, or at the set-up's start time if has_start is 0. */
fmu_status fmu_enter_initialization(fmu_instance *inst, int has_start, double start_time);
/* Applies the parameters and solves for the initial inputs (Discard there becomes Warning). */
fmu_status fmu_exit_initialization(fmu_instance *inst);
/* doStep's entry: fmu_do_step and fmu_do_step_reporting (do_step.h); the rest of a step
 * (do_step.c): */
/* The model's step rules (model_do_step) over [t, t + h], which the call checks accepted, and
 * the time bookkeeping around them. */
fmu_status fmu_run_step(fmu_instance *inst, double t, double h);
/* The step rules in full for a call that passed do_step.h's fmu_usual_call, which leaves the
 * mode to here where the model takes the usual step itself (the inputs not set since the last
 * step or not all finite, or the model's route 0, which it is outside step mode): in step mode
 * fmu_run_step, else the call refused with its message. */
fmu_status fmu_run_step_in_step_mode(fmu_instance *inst, double t, double h);
/* The bookkeeping of a step from t that the model did not take (Discard: time stays at t; Error:
 * time and outputs_current go back to time_before and outputs_current_before, and the instance
 * enters the Error mode); FMI 3: the last successful time through last_successful_time_out.
 * Returns s. */
fmu_status fmu_step_not_taken(fmu_instance *inst, double t, fmu_status s, double time_before,
                              int outputs_current_before);

/* The unit's time, and the time variable that shows it. */
static inline void fmu_values_set_time(fmu_values *v, double t) {
    v->time = t;
    v->real[fmu_time_vr] = t;
}

/* The bookkeeping of an accepted step (s OK or Warning) from t to t + h: time moves on. Inline:
 * it is on the usual step's path, which a call would lengthen. Returns s. */
static inline fmu_status fmu_step_accepted(fmu_values *v, double t, double h, fmu_status s) {
    const double end = t + h;
    v->time = end;
    v->real[FMU_TIME_VR] = end;
    v->last_step_point = t;
    v->has_stepped = 1;
    v->last_successful_time = end;
    v->last_step_status = s;
    return s;
}

/* fmu_step_accepted from the step's end and t as a model kept them across its library call
 * (fmu_instance.step): side by side, as the unit's time and last step point, so that they move
 * as one pair; the same values. stepped_before: the model knows a step was accepted before
 * (has_stepped is 1 already, and stays). */
static inline fmu_status fmu_step_accepted_kept(fmu_values *v, const fmu_step_span *kept,
                                                fmu_status s, int stepped_before) {
    _Static_assert(offsetof(fmu_values, last_step_point) ==
                       offsetof(fmu_values, time) + sizeof(double),
                   "the unit's time and last step point no longer lie side by side");
    const double end = kept->end;
    v->time = end;
    v->last_step_point = kept->t;
    v->real[FMU_TIME_VR] = end;
    if (!stepped_before) v->has_stepped = 1;
    v->last_successful_time = end;
    v->last_step_status = s;
    return s;
}

/* outputs_current or inputs_unchecked set (a usual step needs both clear): the two flags, side
 * by side, read as one. */
static inline int fmu_outputs_current_or_inputs_unchecked(const fmu_values *v) {
    _Static_assert(offsetof(fmu_values, inputs_unchecked) ==
                           offsetof(fmu_values, outputs_current) + sizeof(int) &&
                       sizeof(int) == sizeof(uint32_t),
                   "outputs_current and inputs_unchecked no longer lie side by side");
    uint64_t both;
    memcpy(&both, (const unsigned char *)v + offsetof(fmu_values, outputs_current), sizeof both);
    return both != 0;
}
fmu_status fmu_terminate(fmu_instance *inst);
/* Back to the start values (the model keeps its built resources for reuse). */
fmu_status fmu_reset(fmu_instance *inst);
/* fmi2GetStatus(fmi2DoStepStatus): what the last doStep returned. */
fmu_status fmu_get_step_status(fmu_instance *inst, int *status);
/* fmi2GetRealStatus(fmi2LastSuccessfulTime). */
fmu_status fmu_get_last_successful_time(fmu_instance *inst, double *time);
/* Whether values are those of a unit past its initialisation (step mode or terminated): its
 * resources are built for its parameters. */
int fmu_after_initialization(const fmu_values *v);
/* Initialisation mode, when the outputs are first needed and at its end: the model's parameters
 * applied (model_apply_parameters), then its start state set (model_start). */
fmu_status fmu_apply_initial_parameters(fmu_instance *inst);
/* Puts the instance into the Error mode and returns FMU_ERROR (the model calls it too). */
fmu_status fmu_fail(fmu_instance *inst);

#ifdef __cplusplus
}
#endif

#endif
