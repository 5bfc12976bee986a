/*
 * The inverse-dynamics model's identity and sizes, read by the runtime (fmu/runtime) when it is
 * compiled for this model: identifier, GUID, the bound on value references, the texts of the
 * model description, and the model's own parts of an instance (plain values that an FMU state
 * copies bit for bit, and the solver resources that it saves through model_save).
 */
#ifndef STEWART_FMU_CONFIG_H
#define STEWART_FMU_CONFIG_H

#include "stewart/stewart.h"
#include "stewart/stewart_linearize.h"
#include "stewart/stewart_limits.h"
/* The library's parameter and option tables: variables.def expands them (no parameter is
 * listed twice). */
#include "stewart/stewart_table.h"

#define FMU_MODEL_IDENTIFIER "StewartPlatform"
/* What its variables bind to (runtime/bindings.h): the parameters to stewart_params, the options
 * to the library's option table. */
#define FMU_PARAMS_STRUCT stewart_params
#define FMU_OPTION_TABLE STEWART_OPTION_TABLE
#define FMU_OPTION_TABLE_STRUCT stewart_inverse_options
#define FMU_GUID "{5d0f6a3e-9b1c-4c2e-a7f4-3e8b2c7d1a04}"
/* Every value reference is below this bound (checked at compile time in variables.c). */
#define FMU_NVR 1058

#define FMU_MODEL_DESCRIPTION_TEXT                                                        \
    "Stewart platform inverse kinematics and inverse dynamics: actuator lengths, rates, " \
    "accelerations and forces for a prescribed platform pose"
#define FMU_DEFAULT_EXPERIMENT "startTime=\"0\" stopTime=\"12\" stepSize=\"0.1\""
/* FMI 2 canInterpolateInputs: the model takes input derivatives (model_set_input_derivatives). */
#define FMU_CAN_INTERPOLATE_INPUTS 1
/* The usual doStep goes straight from the FMI call to the route's step (usual_step.c:
 * model_usual_steps), by the route model_values.usual_route. */
#define FMU_MODEL_USUAL_STEP 1
#define FMU_USUAL_ROUTE(v) ((v)->model.usual_route)

/* Directional derivatives of the outputs with respect to the inputs (derivatives.c). */
#define FMU_PROVIDES_DIRECTIONAL_DERIVATIVE 1
/* The model structure: which inputs each output depends on (over every value of the parameters
 * derivatives and fidelity). Lengths on the pose, their rates on the pose and its rates (the
 * rates are inputs, or finite differences of the pose), the condition number, the Newton
 * iterations and the residual on the pose; the motors' angles on the pose, their speeds on the
 * pose and its rates; the rest (accelerations, forces, base wrench, the drives' torques,
 * currents, voltages and powers, and status, which checks that every input is finite) on every
 * input. */
#define FMU_OUTPUT_DEPENDS_ON(out, in)                                                        \
    ((out) >= VR_L_1 && (out) <= VR_L_6           ? (in) <= VR_yaw                            \
     : (out) >= VR_L_dot_1 && (out) <= VR_L_dot_6 ? (in) <= VR_yaw_dot                        \
     : (out) == VR_condition || (out) == VR_residual || (out) == VR_newton_iterations         \
         ? (in) <= VR_yaw                                                                     \
     : (out) >= VR_motor_angle_1 && (out) <= VR_motor_angle_6 ? (in) <= VR_yaw                \
     : (out) >= VR_motor_speed_1 && (out) <= VR_motor_speed_6 ? (in) <= VR_yaw_dot            \
     : (out) >= VR_motor_angle_1 ? 1 /* the drives' torques, currents, powers: every input */ \
     : (out) >= VR_limit_class   ? (in) <= VR_yaw /* the limits: the pose's */                \
                                 : 1)

/* A communication point of the finite-difference history: its pose (with the rates a usual step
 * solved it with: the library's input as it stands), and the chord to it from the point before,
 * kept so that the next step's quadratic does not difference the older pose again (the same
 * quotient, bit for bit). */
typedef struct fd_point {
    stewart_pose pose; /* q at t (q_dot, q_ddot: what a usual step solved with) */
    double slope[6];   /* (q - q before) / interval, with two points committed */
    double t;          /* the communication point */
    double interval;   /* t - t before, with two points committed */
    double padding[6]; /* zero: 256 bytes, so that a slot's offset is its index shifted */
} fd_point;

/* The model's plain values: part of every FMU state, copied and serialised as bytes. */
typedef struct model_values {
    int n_history; /* points committed at earlier communication points (0..2): one,
                                  or one with its chord from the one before */
    int newer;     /* history[newer] is the last point; the other slot is where a
                                  usual step writes its own before the solve (0 or 1) */
    fd_point history[2];
    int input_derivatives; /* fmi2SetRealInputDerivatives called since the last step */
    int solve_status;      /* fmu_status of the solve the outputs come from */
    int advance_discarded; /* the outputs stand after a Taylor advance that was discarded */
    int usual_route;       /* the usual step's route (usual_step.c: model_usual_steps;
                                  step_rules.c: inverse_settle_usual_route) */
} model_values;

/* The model's resources: built at the end of initialisation, never part of a state's plain
 * bytes (the solver data block travels through model_save / model_load). */
typedef struct model_resources {
    stewart_model *model;     /* built from the parameters when initialisation ends */
    stewart_inverse *inverse; /* made with `options` for `model` */
    stewart_limits *limits;   /* the limit check and axis ranges for `model` (limit_outputs) */
    stewart_params params;    /* the parameters `model` was built from */
    stewart_inverse_options options;
    stewart_linearize *linearize; /* for directional derivatives: made for `model` when first
                                     asked, with the fidelity of its forces */
    char message[2 * STEWART_MESSAGE_SIZE];
} model_resources;

#endif
