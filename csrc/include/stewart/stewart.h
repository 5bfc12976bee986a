/*
 * Stewart platform inverse kinematics and inverse dynamics: the C API.
 *
 * Conventions (docs/model.md): SI units; world frame at the base centre, z up;
 * pose (x, y, z, roll, pitch, yaw) with R = Rz(yaw) Ry(pitch) Rx(roll); leg k joins base joint
 * a_k to platform joint b_k (docs/geometry.md: on two circles, or any 36 coordinates); actuator
 * length L_k = |p + R b_k - a_k|; actuator force F_k > 0
 * pushes the platform away from the base.
 *
 * Usage: fill a stewart_params (stewart_params_default gives the thesis platform), build an
 * immutable stewart_model from it, make one solver object per direction and independent run from
 * the model and its options, then call it once per input. The three directions share one grammar:
 *   inverse (this header):       stewart_inverse_create, stewart_inverse_solve(inverse, &in, &out)
 *   forward (stewart_forward.h): stewart_forward_create, stewart_forward_solve(forward, &in, &out)
 *   plant   (stewart_plant.h):   stewart_plant_create, stewart_plant_step(plant, &in, &out)
 * and each object has _free, _reset (forget the history), _copy (a rollback point), _state_size,
 * _save and _load (bytes, versioned and checked) and _message (the last error; "" after a
 * success). Warnings travel in the outputs (STEWART_WARN_* bits and stroke_legs). Nothing here
 * keeps global state; a model may be shared read-only by any number of objects.
 *
 * Every parameter and option, with its id, unit, range, default and description, is listed once
 * in stewart/stewart_table.h, which also lets a caller iterate them. The full level is built on
 * the multibody core (mbs/mbs.h; stewart/stewart_full.h shows its mechanism).
 */
#ifndef STEWART_STEWART_H
#define STEWART_STEWART_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define STEWART_LEGS 6
#define STEWART_MESSAGE_SIZE 256

typedef enum stewart_status {
    STEWART_OK = 0,
    STEWART_ERR_ARGUMENT = -1,      /* null pointer, or a pose value that is NaN or infinite */
    STEWART_ERR_PARAMETER = -2,     /* a parameter out of its valid range */
    STEWART_ERR_SINGULAR = -3,      /* the leg Jacobian (or the constraint Jacobian) is singular */
    STEWART_ERR_UNREACHABLE = -4,   /* the pose puts a platform point on its base point */
    STEWART_ERR_NOT_CONVERGED = -5, /* the position Newton problem did not converge */
    STEWART_ERR_UNSUPPORTED = -6,   /* the requested fidelity level is not available */
    STEWART_ERR_MEMORY = -7,
    STEWART_ERR_OTHER_BRANCH = -8 /* forward kinematics reached another assembly mode than the
                                       working one (stewart_forward.h) */
} stewart_status;

typedef enum stewart_fidelity {
    STEWART_KINEMATIC = 0, /* lengths, rates and accelerations only; forces are zero */
    STEWART_MASSLESS = 1,  /* Newton-Euler on the platform, legs as massless two-force members */
    STEWART_FULL = 2       /* the 14-body constraint-and-multiplier model */
} stewart_fidelity;

/* Bits of the warnings of every direction's output: the call succeeded but the result deserves
 * attention. */
enum {
    STEWART_WARN_STROKE = 1,        /* some length is outside [stroke_min, stroke_max]; stroke_legs
                                       says which */
    STEWART_WARN_NEAR_SINGULAR = 2, /* condition number above the options' warn_condition */
    STEWART_WARN_OTHER_BRANCH = 4,  /* forward kinematics: the pose is on another assembly mode */
    STEWART_WARN_JOINT_LIMIT = 8,   /* the plant: a leg beyond base_joint_limit or
                                       platform_joint_limit (stewart/stewart_limits.h) */
    STEWART_WARN_INTERFERENCE = 16  /* the plant: two legs closer than leg_diameter */
};

/* Geometry and mass parameters. Inertias are principal moments about the body's own centre of
 * mass, on the axes of its frame (platform frame for platform and payload; for the leg bodies
 * x along the Cardan cross arm, z along the leg axis from base toward platform). */
typedef struct stewart_params {
    double base_radius;                  /* r_b [m] */
    double platform_radius;              /* r_t [m] */
    double base_angle[STEWART_LEGS];     /* beta_k [rad] */
    double platform_angle[STEWART_LEGS]; /* tau_k [rad], in the platform frame */
    double home_height;                  /* z of the home pose [m] */
    /* Which joints the model uses: 0 the circles above (the default), 1 the coordinates below. */
    double geometry;
    double base_joint[3 * STEWART_LEGS]; /* a_k = (x, y, z) of leg k at 3(k-1) [m], base frame */
    double platform_joint[3 * STEWART_LEGS]; /* b_k [m], platform frame */
    /* The fixed arm of each Cardan (base frame / platform frame), a unit vector; the zero vector
     * (the default) is the horizontal tangent at the joint's azimuth, the thesis' choice. */
    double base_cardan_axis[3 * STEWART_LEGS];
    double platform_cardan_axis[3 * STEWART_LEGS];
    double gravity[3]; /* [m/s^2], world frame */

    double platform_mass;       /* [kg] */
    double platform_com[3];     /* platform centre of mass, platform frame [m] */
    double platform_inertia[3]; /* [kg m^2] */
    double payload_mass;        /* [kg], 0 for none */
    double payload_com[3];      /* payload centre of mass, platform frame [m] */
    double payload_inertia[3];  /* [kg m^2] */

    double cylinder_mass;       /* lower leg body, on the base Cardan [kg] */
    double cylinder_inertia[3]; /* [kg m^2] */
    double cylinder_com;        /* from the base Cardan centre along the leg [m] */
    double piston_mass;         /* upper leg body, on the platform Cardan [kg] */
    double piston_inertia[3];   /* [kg m^2] */
    double piston_com;          /* from the platform Cardan centre toward the base [m] */

    double stroke_min[STEWART_LEGS]; /* shortest allowed actuator length per leg [m] */
    double stroke_max[STEWART_LEGS]; /* longest allowed actuator length per leg [m] */

    double tool_frame[6]; /* pose (x, y, z [m], roll, pitch, yaw [rad]) of the tool frame in the
                               platform frame; poses given and returned are the tool frame's */
    double user_frame[6]; /* pose of the user frame in the base frame; poses given and returned
                               are in it (docs/api.md, "Tool and user frames") */
    /* The convention of every pose given and returned, the frames' included (docs/geometry.md,
     * "Rotation order and frames"): */
    double rotation_order;   /* 0 R = Rz(yaw) Ry(pitch) Rx(roll) (the default), 1 R = Rx(roll)
                                Ry(pitch) Rz(yaw); rates and accelerations are the angles' own */
    double frame_convention; /* 0 base and platform frames z up (the default); 1 z down, x
                                forward, y right: joints, axes, centres of mass and poses are
                                given in frames turned by 180 deg about x (gravity is not) */
    double length_offset[STEWART_LEGS]; /* Cardan-to-Cardan length = sensor reading + offset [m];
                               lengths given and returned are readings */

    /* Limits a controller checks (stewart/stewart_limits.h, docs/limits.md). */
    double base_joint_limit;                         /* largest angle of a leg from its base joint's
                                               neutral axis [rad] */
    double platform_joint_limit;                     /* the same at the platform joint [rad] */
    double base_joint_neutral[3 * STEWART_LEGS];     /* x1, y1, z1, ..., z6: base frame; zero:
                                                        the leg's direction at home */
    double platform_joint_neutral[3 * STEWART_LEGS]; /* the same, platform frame */
    double leg_diameter;                             /* legs whose axes come closer interfere, when
                                               neither body nor rod length is given [m] */
    double leg_body_diameter; /* actuator body: a cylinder from the base joint [m] */
    double leg_body_length;   /* its length (0: no body) [m] */
    double leg_rod_diameter;  /* actuator rod: a cylinder from the platform joint [m] */
    double leg_rod_length;    /* its length (0: no rod) [m] */
    double axis_min[6];       /* software position limits of the tool pose in the user frame (x, y,
                               z [m], roll, pitch, yaw [rad]); -DBL_MAX / DBL_MAX: none */
    double axis_max[6];

    /* The drive of each leg (docs/drives.md): motor, gear, screw, friction, end stops and
     * compliance. screw_lead 0 (the default): no drive, the leg is driven by its force. */
    double screw_lead[STEWART_LEGS];            /* leg travel per screw turn [m] */
    double gear_ratio[STEWART_LEGS];            /* motor turns per screw turn */
    double rotor_inertia[STEWART_LEGS];         /* at motor speed [kg m^2] */
    double screw_inertia[STEWART_LEGS];         /* at screw speed [kg m^2] */
    double screw_efficiency[STEWART_LEGS];      /* motor drives the load, in (0, 1] */
    double screw_back_efficiency[STEWART_LEGS]; /* load drives the motor, [0, 1]; 0 self-locking */
    double torque_constant[STEWART_LEGS];       /* [N m/A] = back-EMF constant [V s/rad] */
    double winding_resistance[STEWART_LEGS];    /* [ohm] */
    double winding_inductance[STEWART_LEGS];    /* [H]; 0: no current state */
    double coulomb_friction[STEWART_LEGS];      /* sliding friction on the leg's axis [N] */
    double viscous_friction[STEWART_LEGS];      /* [N s/m] */
    double stribeck_friction[STEWART_LEGS];     /* breakaway force at rest [N] */
    double stribeck_speed[STEWART_LEGS];        /* [m/s] */
    double end_stop_stiffness[STEWART_LEGS];    /* beyond the strokes [N/m]; 0: none */
    double end_stop_damping[STEWART_LEGS];      /* [N s/m] */
    double leg_stiffness[STEWART_LEGS];         /* axial compliance [N/m]; 0: rigid */
    double leg_damping[STEWART_LEGS];           /* [N s/m] */
    double current_max[STEWART_LEGS];           /* drive limits [A], 0: none */
    double voltage_max[STEWART_LEGS];           /* [V], 0: none */
    double motor_speed_max[STEWART_LEGS];       /* [rad/s], 0: none */

    /* Leg motion limits a move or a cue stays within (0: no limit of that kind). */
    double leg_speed_max[STEWART_LEGS]; /* [m/s] */
    double leg_accel_max[STEWART_LEGS]; /* [m/s^2] */
    double leg_jerk_max[STEWART_LEGS];  /* [m/s^3] */
    double leg_force_max[STEWART_LEGS]; /* pushing or pulling [N] */
} stewart_params;

/* Inverse solver settings; stewart_inverse_options_default gives the values documented here. */
typedef struct stewart_inverse_options {
    int fidelity; /* a stewart_fidelity (int: any value a caller passes is checked); STEWART_MASSLESS */
    double tolerance;          /* Newton residual tolerance (full level), max-norm, relative to
                                    the platform's size: lengths are measured in units of L0, the
                                    power of two with max(base size, platform size,
                                    home_height) / L0 in (0.25, 0.5] (the sizes: the radii, or
                                    the farthest joints, docs/geometry.md; 1 m for the thesis
                                    platform; stewart_model_length_unit). 1e-12; >= 2.5e-16 (the
                                    residual floors at about 2.2e-16 L0) */
    int max_iterations;        /* Newton iteration cap (full level); 20 */
    int modified_newton;       /* 0: exact Newton; 1: Jacobian kept over a step (full); 0 */
    double warn_condition;     /* condition above which STEWART_WARN_NEAR_SINGULAR is set; 1e3 */
    double singular_condition; /* condition above which the solve fails as singular; 1e10 */
} stewart_inverse_options;

/* Platform pose and its first and second time derivatives, each ordered
 * (x, y, z [m], roll, pitch, yaw [rad]). */
typedef struct stewart_pose {
    double q[6];
    double q_dot[6];
    double q_ddot[6];
} stewart_pose;

/* Actuator lengths and their first and second time derivatives, leg k at index k-1. */
typedef struct stewart_lengths {
    double length[STEWART_LEGS];       /* L_k [m] */
    double length_rate[STEWART_LEGS];  /* dL_k/dt [m/s] */
    double length_accel[STEWART_LEGS]; /* d2L_k/dt2 [m/s^2] */
} stewart_lengths;

/* What an inverse solve takes: the pose and its derivatives. */
typedef struct stewart_inverse_input {
    stewart_pose pose;
} stewart_inverse_input;

/* What an inverse solve gives. */
typedef struct stewart_inverse_output {
    stewart_lengths lengths;    /* actuator lengths, rates and accelerations */
    double force[STEWART_LEGS]; /* F_k [N], > 0 pushes the platform away; 0 if kinematic */
    double condition;           /* 1-norm condition number of the leg Jacobian, its angular columns
                               scaled by the platform radius (dimensionless); 0 if kinematic */
    int iterations;             /* Newton iterations of the position problem; 0 below full level */
    double residual;            /* max-norm of the constraint residual after the solve [m]
                               (tolerance x L0 at most) */
    double base_force[3];       /* force the legs put on the base, world frame [N] */
    double base_torque[3];      /* torque of that wrench about the world origin [N m] */
    int warnings;               /* STEWART_WARN_* bits */
    int stroke_legs;            /* bit k set: leg k+1 is outside [stroke_min, stroke_max] */

    /* Each leg's drive (docs/drives.md), leg k at index k-1; 0 on a leg without a drive
     * (screw_lead 0). The motor angle grows as the leg extends; a positive torque extends it. */
    double motor_angle[STEWART_LEGS];      /* 2 pi N L / lead, L the reading [rad] */
    double motor_speed[STEWART_LEGS];      /* [rad/s] */
    double motor_accel[STEWART_LEGS];      /* [rad/s^2] */
    double motor_torque[STEWART_LEGS];     /* J (2 pi N / lead) L'' + the screw's torque for
                                              F_k + friction, efficiency by power flow [N m] */
    double current[STEWART_LEGS];          /* motor_torque / torque_constant [A] */
    double current_rate[STEWART_LEGS];     /* dI/dt [A/s]: 0 from one pose; along a trajectory
                                              from differences of the currents over time
                                              (stewart_inverse_batch_current_rates) */
    double voltage[STEWART_LEGS];          /* R I + L dI/dt + k_t motor_speed [V] */
    double electrical_power[STEWART_LEGS]; /* voltage x current, < 0 regenerating [W] */
    double motor_power[STEWART_LEGS];      /* motor_torque x motor_speed [W] */
    int current_max_legs;                  /* bit k set: |current| of leg k+1 > current_max */
    int voltage_max_legs;                  /* bit k set: |voltage| > voltage_max */
    int motor_speed_max_legs;              /* bit k set: |motor_speed| > motor_speed_max */
} stewart_inverse_output;

typedef struct stewart_model stewart_model;
typedef struct stewart_inverse stewart_inverse;

/* The thesis platform in SI (docs/model.md): the defaults of stewart/stewart_table.h. */
void stewart_params_default(stewart_params *params);
/* STEWART_OK, or STEWART_ERR_PARAMETER with a message naming the parameter and its value. */
stewart_status stewart_params_check(const stewart_params *params, char *message, size_t size);
/* Sets one parameter by its name: the field's name, with the element counted from 1 for arrays
 * ("payload_mass", "base_angle[1]" .. "base_angle[6]", "gravity[3]"), as the FMU's model
 * description and scene files name them; a per-leg parameter that was a scalar ("stroke_min")
 * may also be given by its bare name, which sets all six legs. STEWART_ERR_ARGUMENT for an
 * unknown name (the message gives the nearest name); the value is checked when a model is built
 * (stewart_params_check). */
stewart_status stewart_params_set(stewart_params *params, const char *name, double value,
                                  char *message, size_t size);
void stewart_inverse_options_default(stewart_inverse_options *options);
/* STEWART_OK, or STEWART_ERR_PARAMETER with a message naming the option and its value. */
stewart_status stewart_inverse_options_check(const stewart_inverse_options *options, char *message,
                                             size_t size);

/* NULL if the parameters are invalid (message says why) or memory is short. */
stewart_model *stewart_model_create(const stewart_params *params, char *message, size_t size);
void stewart_model_free(stewart_model *model);
const stewart_params *stewart_model_params(const stewart_model *model);
/* The drive's inertia seen on each leg's axis, (rotor_inertia + screw_inertia / N^2)
 * (2 pi N / screw_lead)^2 [kg]; 0 on a leg without a drive (docs/drives.md). */
void stewart_model_reflected_mass(const stewart_model *model, double reflected_mass[STEWART_LEGS]);

/* An inverse solver for model (which must outlive it) with a copy of options: NULL if the options
 * are invalid (message names the option and its value), an argument is NULL or memory is short
 * (message says which). It holds the state (the full level's warm start) and every workspace a
 * solve needs. */
stewart_inverse *stewart_inverse_create(const stewart_model *model,
                                        const stewart_inverse_options *options, char *message,
                                        size_t size);
/* Frees the solver (NULL is ignored). */
void stewart_inverse_free(stewart_inverse *inverse);
/* Forgets the history (warm start) as if the solver were new. */
void stewart_inverse_reset(stewart_inverse *inverse);
/* Copies the whole state of src into dst (both made from the same model, else
 * STEWART_ERR_ARGUMENT): a rollback point. The options stay dst's. */
stewart_status stewart_inverse_copy(stewart_inverse *dst, const stewart_inverse *src);
/* The size of the state as bytes (what stewart_inverse_copy copies), to save a run and resume it
 * in another process (FMU state serialisation). It depends on the model only. */
size_t stewart_inverse_state_size(const stewart_inverse *inverse);
/* Writes the state into buffer (at least stewart_inverse_state_size bytes). */
stewart_status stewart_inverse_save(const stewart_inverse *inverse, void *buffer, size_t size);
/* STEWART_ERR_ARGUMENT (solver unchanged, stewart_inverse_message says why) unless the bytes are
 * a saved state that fits this model: of its shape, every value finite, the fixed base at its
 * placement, every other body's Euler parameters unit (to 1e-6), and for a state saved after a
 * successful solve, the constraint residual no larger than the state records. */
stewart_status stewart_inverse_load(stewart_inverse *inverse, const void *buffer, size_t size);
/* The message of the last call that did not return STEWART_OK, else "". */
const char *stewart_inverse_message(const stewart_inverse *inverse);
/* The model the solver was made for, and its options. */
const stewart_model *stewart_inverse_model(const stewart_inverse *inverse);
const stewart_inverse_options *stewart_inverse_options_of(const stewart_inverse *inverse);

/* Actuator lengths, rates, accelerations and forces for one pose. On error the output is left
 * unchanged and stewart_inverse_message names the offending value (a pose input too large to
 * solve with is named, e.g. "x_dot", with its value). Never writes NaN. */
stewart_status stewart_inverse_solve(stewart_inverse *inverse, const stewart_inverse_input *input,
                                     stewart_inverse_output *output);

/* The name of a status, e.g. "singular". */
const char *stewart_status_name(stewart_status status);

#ifdef __cplusplus
}
#endif

#endif /* STEWART_STEWART_H */
