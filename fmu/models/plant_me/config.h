/*
 * The Model Exchange plant's identity and sizes (StewartPlantME.fmu: the plant's equations of
 * motion for a master that integrates them itself; fmu/models/plant is the co-simulation unit
 * that integrates them inside), read by the runtime (fmu/runtime) when it is compiled for this
 * model, and the model's own parts of an instance.
 */
#ifndef STEWART_FMU_CONFIG_H
#define STEWART_FMU_CONFIG_H

#include "stewart/stewart.h"
#include "stewart/stewart_limits.h"
#include "stewart/stewart_linearize.h"
#include "stewart/stewart_plant.h"
/* The library's parameter table: variables.def expands it (the plant's names and value
 * references for the geometry and masses). */
#include "stewart/stewart_table.h"

#define FMU_MODEL_IDENTIFIER "StewartPlantME"
/* What its variables bind to (runtime/bindings.h): the parameters to stewart_params, the start
 * state to plant_me_start (below). */
#define FMU_PARAMS_STRUCT stewart_params
#define FMU_SETTINGS_STRUCT plant_me_start
#define FMU_GUID "{1082c231-0cb7-4444-8668-eaa9aa9d2c96}"
/* Every value reference is below this bound (checked at compile time in variables.c): the
 * plant's. */
#define FMU_NVR 786

#define FMU_MODEL_DESCRIPTION_TEXT                                                               \
    "Stewart platform forward dynamics as Model Exchange: the six actuator forces in; the pose " \
    "and its rates are the continuous states, their derivatives the pose rates and "             \
    "accelerations; leg lengths and rates and the base wrench out"
#define FMU_DEFAULT_EXPERIMENT "startTime=\"0\" stopTime=\"1\" tolerance=\"1e-10\""
#define FMU_CAN_INTERPOLATE_INPUTS 0

/* Model Exchange (runtime/model_exchange.h): the states are x .. yaw, x_dot .. yaw_dot (value
 * references 100..111); their derivatives x_dot .. yaw_dot and x_ddot .. yaw_ddot. */
#define FMU_MODEL_EXCHANGE 1
#define FMU_N_STATES 12
#define FMU_STATE_VR(i) ((unsigned)(VR_x + (i)))
#define FMU_DERIVATIVE_VR(i) ((unsigned)((i) < 6 ? VR_x_dot + (i) : VR_x_ddot + (i) - 6))
/* The motion (pose, rates, lengths, length rates) depends on the states alone. */
#define FMU_OUTPUT_WITHOUT_FEEDTHROUGH(vr) ((vr) >= VR_x && (vr) <= VR_L_dot_6)

/* At CompletedIntegratorStep (model_accepted_state): a leg outside its stroke, a joint beyond its
 * angle limit, two legs interfering, logged when each starts and Warning while any lasts, as
 * the co-simulation plant's steps (not at GetDerivatives: it is called at trial states). */
#define FMU_ME_ACCEPTED_STATE 1

/* Directional derivatives of the state derivatives and outputs with respect to the states and
 * the forces (derivatives.c). */
#define FMU_PROVIDES_DIRECTIONAL_DERIVATIVE 1
/* The model structure (gen_model_description.c): which states and inputs each output and state
 * derivative depends on, over every value of the parameters. A state (and x' = x_dot) on itself,
 * the lengths on the pose, their rates on the pose and its rates; the accelerations, the base
 * wrench and status (which also tells a refused force) on every state and force. */
#define FMU_ME_DEPENDS_ON(unknown, known)                                                \
    ((unknown) >= VR_x && (unknown) <= VR_yaw_dot ? (known) == (unknown)                 \
     : (unknown) >= VR_L_1 && (unknown) <= VR_L_6 ? (known) >= VR_x && (known) <= VR_yaw \
     : (unknown) >= VR_L_dot_1 && (unknown) <= VR_L_dot_6                                \
         ? (known) >= VR_x && (known) <= VR_yaw_dot                                      \
         : 1)

/* The model's plain values: part of every FMU state, copied and serialised as bytes. */
/* The start state's parameters (variables.def's FMU_OPTION_REAL fields). */
typedef struct plant_me_start {
    double pose0[6], rate0[6];
    double smoothing_speed; /* the plant option of the drives' friction [m/s] */
} plant_me_start;

typedef struct model_values {
    int solve_status;   /* fmu_status of the outputs' last refresh */
    int stroke_legs;    /* bit k: leg k+1 outside its stroke at the last refresh */
    int legs_outside;   /* the same at the last accepted state (reported) */
    int limit_warnings; /* STEWART_WARN_JOINT_LIMIT, _INTERFERENCE at the last accepted state */
} model_values;

/* The plant linearised at `point` (states x .. yaw_dot, forces; derivatives.c), and the base
 * wrench's rows by (states, forces) if has_wrench: kept while the point stays. */
typedef struct plant_me_derivatives {
    int valid, has_wrench;
    double point[STEWART_LINEARIZE_STATES + STEWART_LINEARIZE_INPUTS];
    stewart_linearize_output plant;
    stewart_linearize_driven_output driven; /* with current or voltage input: plant's source */
    double wrench[6][STEWART_LINEARIZE_STATES + STEWART_LINEARIZE_INPUTS];
} plant_me_derivatives;

/* The model's resources: built at the end of initialisation from the parameters. The plant
 * object only evaluates the equations (stewart_plant_derivatives); its own state is unused. */
typedef struct model_resources {
    stewart_model *model;         /* built from `params` */
    stewart_plant *plant;         /* on `model`, with `fidelity` */
    stewart_linearize *linearize; /* the same: the directional derivatives (derivatives.c) */
    stewart_limits *limits;       /* on `model`: joint limits and interference at accepted states */
    plant_me_derivatives derivatives; /* of `linearize`; cleared when it is rebuilt */
    stewart_params params;
    int fidelity;
    int input;              /* stewart_plant_options.input of `plant` */
    double smoothing_speed; /* stewart_plant_options.smoothing_speed of `plant` */
    char message[2 * STEWART_MESSAGE_SIZE];
} model_resources;

#endif
