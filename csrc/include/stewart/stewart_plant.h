/*
 * Stewart platform forward dynamics (the plant): apply the six actuator forces, integrate the
 * motion. Same conventions as stewart.h (SI, pose (x, y, z, roll, pitch, yaw) with
 * R = Rz(yaw) Ry(pitch) Rx(roll), leg order, F_k > 0 pushes platform and base apart).
 *
 * The independent coordinates are the platform pose (a quaternion inside) and its twist; every
 * leg body follows in closed form, so the joints hold exactly (docs/forward-dynamics.md).
 * Usage: build a stewart_model (stewart.h), create one stewart_plant per run (the life cycle of
 * every direction: create, free, reset, copy, state_size, save/load, message), optionally set the
 * start state, then call stewart_plant_step(plant, &input, &output) once per communication step
 * with the forces at both ends of the step. No global state; no heap allocation in a step.
 */
#ifndef STEWART_STEWART_PLANT_H
#define STEWART_STEWART_PLANT_H

#include "stewart/stewart.h"

#ifdef __cplusplus
extern "C" {
#endif

#define STEWART_PLANT_BODIES 13 /* platform (with payload), 6 cylinders, 6 pistons */

typedef enum stewart_plant_method {
    STEWART_PLANT_ADAMS = 0, /* CVODE Adams-Moulton, fixed-point iteration: no Jacobian */
    STEWART_PLANT_BDF = 1,   /* CVODE BDF, Newton with a dense difference-quotient Jacobian */
    STEWART_PLANT_ERK = 2,   /* ARKODE explicit Runge-Kutta, Zonneveld 4(3), 5 stages */
    STEWART_PLANT_ERK5 = 3   /* ARKODE explicit Runge-Kutta, Dormand-Prince 5(4), 7 stages */
} stewart_plant_method;

/* What drives the legs (stewart_plant_options.input). With FORCE the drives' parameters are not
 * used: the input is the leg's axial force, as without drives. With CURRENT or VOLTAGE every leg
 * needs a drive (screw_lead > 0, torque_constant > 0; VOLTAGE also winding_resistance > 0): the
 * motor's torque turns the screw, the rotor's and screw's inertia, the screw's efficiency,
 * friction and the end stops act on the leg (docs/drives-plant.md). With VOLTAGE and a
 * winding_inductance > 0 the windings' currents are states of the plant (zero after
 * stewart_plant_set_state, saved with the state; stewart_plant_derivatives refuses them). */
typedef enum stewart_plant_input_kind {
    STEWART_PLANT_INPUT_FORCE = 0,   /* F_k [N] */
    STEWART_PLANT_INPUT_CURRENT = 1, /* motor current i_k [A] */
    STEWART_PLANT_INPUT_VOLTAGE = 2  /* motor terminal voltage V_k [V] */
} stewart_plant_input_kind;

/* Integrator settings; stewart_plant_options_default gives the values documented here. */
typedef struct stewart_plant_options {
    int fidelity;              /* STEWART_MASSLESS or STEWART_FULL; STEWART_FULL */
    int method;                /* a stewart_plant_method; STEWART_PLANT_ERK */
    double relative_tolerance; /* CVODE reltol; 1e-10 */
    double absolute_tolerance; /* CVODE abstol, on every state [m, -, m/s, rad/s]; 1e-12 */
    long max_internal_steps;   /* CVODE steps allowed within one communication step; 10000 */
    int fixed_steps;           /* 0: adaptive steps (the tolerances); N in 1..1000: N equal steps of
                                the explicit Runge-Kutta method per communication step, no error
                                control (a fixed amount of work, ERK and ERK5 only: 5N + 1
                                right-hand sides per step with ERK, 6N + 2 with ERK5); 0 */
    int input;                 /* a stewart_plant_input_kind: what the step's force_start/force_end
                                arrays carry per leg (forces, motor currents or motor voltages);
                                STEWART_PLANT_INPUT_FORCE */
    double smoothing_speed;    /* [m/s] leg speed below which friction and the screw's losses fade
                                out (v / sqrt(v^2 + smoothing_speed^2)); 1e-4 */
} stewart_plant_options;

/* Integrator counters: of the last step, and summed since the plant was created or reset. The
   counts are ARKODE's and CVODE's: where the written-out ERK 4(3) starts a step from the right-hand
   side its last step ended with (same state, same forces), rhs_evaluations counts that carried
   evaluation as ARKODE would have made it, so a step repeated after a rollback counts the same. */
typedef struct stewart_plant_statistics {
    long steps, rhs_evaluations, nonlinear_iterations, error_test_failures, jacobian_evaluations;
    long total_steps, total_rhs_evaluations, total_nonlinear_iterations, total_error_test_failures,
        total_jacobian_evaluations;
    int last_order;        /* method order of the last internal step */
    double last_step_size; /* [s] */
} stewart_plant_statistics;

/* What a step takes: its length and the actuator forces over it. */
typedef struct stewart_plant_input {
    double h;                              /* communication step [s], > 0 */
    double force_start[STEWART_LEGS];      /* F_k at the current time t [N] */
    double force_end[STEWART_LEGS];        /* F_k at t + h [N] */
    int derivatives;                       /* 0: forces linear over the step; 1: cubic Hermite
                                                with the rates below */
    double force_rate_start[STEWART_LEGS]; /* dF_k/dt at t [N/s] (derivatives = 1) */
    double force_rate_end[STEWART_LEGS];   /* dF_k/dt at t + h [N/s] (derivatives = 1) */
} stewart_plant_input;

/* What a step gives: the state at its end (or, from stewart_plant_output_get, the current one). */
typedef struct stewart_plant_output {
    double time;             /* [s] */
    stewart_pose pose;       /* q (x, y, z [m], roll, pitch, yaw [rad]) and q_dot; q_ddot is 0 (the
                                plant does not output accelerations) */
    stewart_lengths lengths; /* length and length_rate; length_accel is 0 */
    double base_force[3];    /* force the moving bodies put on the base, world frame [N] */
    double base_torque[3];   /* its torque about the world origin [N m] */
    int warnings;            /* STEWART_WARN_STROKE, _JOINT_LIMIT, _INTERFERENCE (end stops and
                                contacts are not modelled: warnings only) */
    int stroke_legs;         /* bit k set: leg k+1 is outside [stroke_min, stroke_max] */
    /* The legs' forces and drives (with input force: force is the input, the drive's 0). */
    double force[STEWART_LEGS];            /* axial force on the mechanism, > 0 extends [N] */
    double current[STEWART_LEGS];          /* motor current [A] */
    double voltage[STEWART_LEGS];          /* the input with voltage input; with current input
                                              R i + k_t omega [V] (L di/dt not included) */
    double motor_speed[STEWART_LEGS];      /* omega = 2 pi N L_dot / lead [rad/s] */
    double motor_torque[STEWART_LEGS];     /* k_t i [N m] */
    double electrical_power[STEWART_LEGS]; /* voltage * current [W], < 0: the drive regenerates */
    int current_max_legs;     /* bit k set: |current| of leg k+1 above its current_max (> 0) */
    int voltage_max_legs;     /* bit k set: |voltage| above voltage_max (> 0) */
    int motor_speed_max_legs; /* bit k set: |motor_speed| above motor_speed_max (> 0) */
} stewart_plant_output;

/* One moving body at the current state, world frame: its centre of mass, orientation (columns =
 * body axes, row-major 3x3), velocity of the centre of mass and angular velocity. */
typedef struct stewart_plant_body {
    double position[3];
    double rotation[9];
    double velocity[3];
    double omega[3];
} stewart_plant_body;

/* Joint reactions at the current state, world frame, per leg (k = 0..5):
 *   base Cardan: the force and torque the base puts on the cylinder (torque about the Cardan
 *     centre: along the axis perpendicular to both cross arms, the only one a Cardan holds);
 *   platform Cardan: the force and torque the platform puts on the piston, about its centre;
 *   cylindrical joint: the force and torque the cylinder puts on the piston, the actuator force
 *     excluded (force and torque perpendicular to the leg axis; torque about the platform Cardan
 *     centre).
 * With massless legs the Cardans carry the axial force only and the cylindrical joint nothing. */
typedef struct stewart_plant_reactions {
    double base_cardan_force[STEWART_LEGS][3], base_cardan_torque[STEWART_LEGS][3];
    double platform_cardan_force[STEWART_LEGS][3], platform_cardan_torque[STEWART_LEGS][3];
    double cylindrical_force[STEWART_LEGS][3], cylindrical_torque[STEWART_LEGS][3];
} stewart_plant_reactions;

typedef struct stewart_plant stewart_plant;

void stewart_plant_options_default(stewart_plant_options *options);
/* STEWART_OK, or STEWART_ERR_PARAMETER with a message naming the option and its value. */
stewart_status stewart_plant_options_check(const stewart_plant_options *options, char *message,
                                           size_t size);

/* A plant on a model (the model must outlive it), at rest at the model's home pose at time 0.
 * NULL if the options are invalid or memory is short (message says why). */
stewart_plant *stewart_plant_create(const stewart_model *model,
                                    const stewart_plant_options *options, char *message,
                                    size_t size);
/* Frees the plant (NULL is ignored). */
void stewart_plant_free(stewart_plant *plant);
/* Back to rest at the home pose at time 0, the counters zero, as if the plant were new. */
void stewart_plant_reset(stewart_plant *plant);
/* Copies the state of src into dst (same model, else STEWART_ERR_ARGUMENT): a rollback point. */
stewart_status stewart_plant_copy(stewart_plant *dst, const stewart_plant *src);
/* The state (time, platform pose and twist, last forces, warnings, first step size) as bytes, to
 * roll back a step or save a run: its size, save, and load (versioned; STEWART_ERR_ARGUMENT,
 * plant unchanged, message naming the cause, unless the bytes are a state a step leaves). */
size_t stewart_plant_state_size(const stewart_plant *plant);
stewart_status stewart_plant_save(const stewart_plant *plant, void *buffer, size_t size);
stewart_status stewart_plant_load(stewart_plant *plant, const void *buffer, size_t size);
/* The message of the last call that did not return STEWART_OK, else "". */
const char *stewart_plant_message(const stewart_plant *plant);

/* Sets time, pose and pose rates (d/dt of x .. yaw). STEWART_ERR_ARGUMENT for a non-finite value
 * or pitch at +-90 degrees; STEWART_ERR_UNREACHABLE for a pose with a zero-length leg or a locked
 * Cardan. On error the plant keeps its previous state. */
stewart_status stewart_plant_set_state(stewart_plant *plant, double time, const double pose[6],
                                       const double pose_rate[6]);

/* Integrates from the current time t to t + input->h with the forces of input, and writes the
 * outputs at the end of the step (the base wrench under force_end). On error (non-finite input,
 * h <= 0, a zero-length leg or locked Cardan reached, integrator failure, outputs that overflow)
 * the step is refused, the state stays at t, the output is untouched and stewart_plant_message
 * says why. Warnings travel in the output. */
stewart_status stewart_plant_step(stewart_plant *plant, const stewart_plant_input *input,
                                  stewart_plant_output *output);

/* The outputs at the current state, with the base wrench for the given forces (those acting at
 * the current time; NULL: the force_end of the last step, zero before any step).
 * STEWART_ERR_ARGUMENT (output untouched) if a force is not finite or an output would overflow. */
stewart_status stewart_plant_output_get(const stewart_plant *plant,
                                        const double force[STEWART_LEGS],
                                        stewart_plant_output *output);

/* What the derivative call takes: a state of its own (the plant's is neither used nor changed)
 * and the forces acting on it. */
typedef struct stewart_plant_derivative_input {
    double time;                /* [s], copied to the output (the equations do not depend on it) */
    stewart_pose pose;          /* q and q_dot: the state (the tool's pose in the user frame, as
                                    every pose the plant takes); q_ddot is ignored */
    double force[STEWART_LEGS]; /* F_k [N] */
} stewart_plant_derivative_input;

/* The right-hand side of the equations of motion at the input's state, for a master that
 * integrates them itself (FMI Model Exchange): output->pose holds q, q_dot and the pose
 * accelerations q_ddot; lengths hold length, length_rate and length_accel (lengths as the sensors
 * read them: less length_offset); base wrench, stroke warnings as stewart_plant_output_get. On error the output is untouched and
 * stewart_plant_message names the value: STEWART_ERR_ARGUMENT (a non-finite state or force, an
 * output that overflows), STEWART_ERR_SINGULAR (pitch at +-90 degrees, a locked Cardan),
 * STEWART_ERR_UNREACHABLE (a zero-length leg). Never allocates. */
stewart_status stewart_plant_derivatives(stewart_plant *plant,
                                         const stewart_plant_derivative_input *input,
                                         stewart_plant_output *output);

/* The joint reactions at the current state under the given forces (NULL: as output_get).
 * STEWART_ERR_ARGUMENT (reactions untouched) if a force is not finite or a value overflows. */
stewart_status stewart_plant_reactions_get(const stewart_plant *plant,
                                           const double force[STEWART_LEGS],
                                           stewart_plant_reactions *reactions);

/* The 13 moving bodies at the current state: platform, cylinders 1..6, pistons 1..6 (massless:
 * the platform, the rest zero). STEWART_ERR_ARGUMENT (bodies untouched) if a value overflows. */
stewart_status stewart_plant_bodies(const stewart_plant *plant,
                                    stewart_plant_body bodies[STEWART_PLANT_BODIES]);

/* The plant's time [s] (NaN if plant is NULL). */
double stewart_plant_time(const stewart_plant *plant);

/* The integrator's counters. */
void stewart_plant_statistics_get(const stewart_plant *plant, stewart_plant_statistics *stats);

#ifdef __cplusplus
}
#endif

#endif /* STEWART_STEWART_PLANT_H */
