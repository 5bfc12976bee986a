/*
 * The cueing model's identity and sizes (StewartCueing.fmu: motion cueing, the vehicle's specific
 * force and angular velocity in, the platform's pose with its rates and accelerations out, within
 * every limit of the machine), read by the runtime (fmu/runtime) when it is compiled for this
 * model, and the model's own parts of an instance: plain values that an FMU state copies, and the
 * cueing object (stewart_cueing.h) whose state travels through model_save / model_load.
 */
#ifndef STEWART_FMU_CONFIG_H
#define STEWART_FMU_CONFIG_H

#include "stewart/stewart.h"
#include "stewart/stewart_cueing.h"
/* The library's parameter and cueing option tables: variables.def expands them. */
#include "stewart/stewart_table.h"

#define FMU_MODEL_IDENTIFIER "StewartCueing"
/* What its variables bind to (runtime/bindings.h): the parameters to stewart_params, the options
 * to the cueing option table. */
#define FMU_PARAMS_STRUCT stewart_params
#define FMU_OPTION_TABLE STEWART_CUEING_OPTION_TABLE
#define FMU_OPTION_TABLE_STRUCT stewart_cueing_options
#define FMU_GUID "{3c8f1d52-6a4e-4b07-9e2d-7f51a0c9b6e4}"
/* Every value reference is below this bound (checked at compile time in variables.c). */
#define FMU_NVR 826

#define FMU_MODEL_DESCRIPTION_TEXT                                                               \
    "Stewart platform motion cueing (classical washout with tilt coordination and a limiter "    \
    "on the machine's exact limits): the vehicle's specific force and angular velocity in, the " \
    "platform's pose, pose rates and accelerations out"
#define FMU_DEFAULT_EXPERIMENT "startTime=\"0\" stopTime=\"10\" stepSize=\"0.001\""
#define FMU_CAN_INTERPOLATE_INPUTS 0
/* The outputs are the cue at the end of the last step, the inputs held over it: an input set
 * after a step reaches them at the next step only. */
#define FMU_OUTPUT_WITHOUT_FEEDTHROUGH(vr) 1

/* The model's plain values: part of every FMU state, copied and serialised as bytes. */
typedef struct model_values {
    int solve_status; /* fmu_status of the outputs' last refresh */
    int stepped;      /* 1 once the outputs are a step's (or the start's) */
} model_values;

/* The model's resources: built at the end of initialisation; the cueing object's state travels
 * through model_save / model_load, never as plain bytes. */
typedef struct model_resources {
    stewart_model *model;   /* built from `params` */
    stewart_cueing *cueing; /* on `model`, with `options` */
    stewart_params params;
    stewart_cueing_options options;
    char message[2 * STEWART_MESSAGE_SIZE];
} model_resources;

#endif
