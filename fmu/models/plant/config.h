/*
 * The plant model's identity and sizes (StewartPlant.fmu: forward dynamics, the actuator forces
 * in, the platform's motion out), read by the runtime (fmu/runtime) when it is compiled for this
 * model, and the model's own parts of an instance: plain values that an FMU state copies, and the
 * plant (stewart_plant.h) whose state travels through model_save / model_load.
 */
#ifndef STEWART_FMU_CONFIG_H
#define STEWART_FMU_CONFIG_H

#include <stdint.h>

#include "stewart/stewart.h"
#include "stewart/stewart_plant.h"
/* The library's parameter and plant option tables: variables.def expands them (the inverse
 * FMU's names and value references for the geometry and masses). */
#include "stewart/stewart_table.h"

#define FMU_MODEL_IDENTIFIER "StewartPlant"
/* What its variables bind to (runtime/bindings.h): the parameters to stewart_params, the start
 * state and the Real options to plant_settings, the options to the plant's option table. */
#define FMU_PARAMS_STRUCT stewart_params
#define FMU_SETTINGS_STRUCT plant_settings
#define FMU_OPTION_TABLE STEWART_PLANT_OPTION_TABLE
#define FMU_OPTION_TABLE_STRUCT stewart_plant_options
#define FMU_GUID "{b7e2c4a1-3f58-4d9e-8a61-2c0f7d93e5b2}"
/* Every value reference is below this bound (checked at compile time in variables.c). */
#define FMU_NVR 786

#define FMU_MODEL_DESCRIPTION_TEXT                                                               \
    "Stewart platform forward dynamics (the plant): the six actuator forces in, the platform's " \
    "motion, leg lengths and rates and the base wrench out"
#define FMU_DEFAULT_EXPERIMENT "startTime=\"0\" stopTime=\"1\" stepSize=\"0.001\""
/* FMI 2 canInterpolateInputs: order-1 derivatives of F make the forces linear over the step. */
#define FMU_CAN_INTERPOLATE_INPUTS 1

/* The motion (pose, rates, lengths, length rates) is the plant's state: no input reaches it
 * within a step, so a loop through it is not algebraic (the model description says so). */
#define FMU_OUTPUT_WITHOUT_FEEDTHROUGH(vr) ((vr) >= VR_x && (vr) <= VR_L_dot_6)

/* Integrator counters summed over accepted steps (part of the state: a rollback restores them). */
typedef struct plant_totals {
    int64_t steps, rhs_evaluations, nonlinear_iterations, error_test_failures, jacobian_evaluations;
} plant_totals;

/* The model's plain values: part of every FMU state, copied and serialised as bytes. */
typedef struct model_values {
    double force_rate[STEWART_LEGS]; /* FMI 2 order-1 derivatives of F, for the next step */
    int input_derivatives;           /* fmi2SetRealInputDerivatives called since the last step */
    int solve_status;                /* fmu_status of the outputs' last refresh */
    int legs_outside;                /* bit k: leg k+1 was outside its stroke at the last step */
    int limit_warnings;              /* STEWART_WARN_JOINT_LIMIT, _INTERFERENCE at the last step */
    plant_totals totals;
} model_values;

/* The model's settings beyond the platform's parameters: integrator options and start state. */
typedef struct plant_settings {
    stewart_plant_options options;
    double pose0[6], rate0[6];
} plant_settings;

/* The model's resources: built at the end of initialisation; the plant's state travels through
 * model_save / model_load, never as plain bytes. */
typedef struct model_resources {
    stewart_model *model; /* built from `params` */
    stewart_plant *plant; /* on `model`, with `options` */
    stewart_params params;
    stewart_plant_options options;
    /* on `model`, with `checker_options`: where deserialised states with the instance's
     * parameters are loaded to be checked (model_state.c), kept so that no check builds a model */
    stewart_plant *checker;
    stewart_plant_options checker_options;
    char message[2 * STEWART_MESSAGE_SIZE];
} model_resources;

#endif
