/*
 * Linearisation: the plant's A, B, C, D at an operating point, and the Jacobians of the inverse
 * side (lengths and forces with respect to pose, rates and accelerations). Same conventions as
 * stewart.h (SI, pose (x, y, z, roll, pitch, yaw) with R = Rz(yaw) Ry(pitch) Rx(roll)).
 *
 * The plant in minimal coordinates: the state is the pose and its rates, x = (q, q_dot) (12),
 * the input the six leg forces, u = F, and
 *     x_dot = f(x, u) = (q_dot, q_ddot(q, q_dot, F)),   y = g(x) = (q, q_dot, L, L_dot) (24),
 * linearised as dx_dot = A dx + B du, dy = C dx + D du (D = 0: no output depends on the forces).
 * With tool and user frames (tool_frame, user_frame) q is the tool's pose in the user frame, as
 * every pose of the library takes and gives; lengths, forces and the base wrench are as the
 * inverse solver gives them (the base wrench in the base frame).
 * The derivatives are exact: forward-mode automatic differentiation through the plant's own
 * equations of motion (csrc/plant/plant_equations.cpp), not finite differences.
 *
 * Usage: build a stewart_model (stewart.h), create one stewart_linearize (the life cycle of every
 * direction: create, free, reset, copy, state_size, save/load, message), then call
 * stewart_linearize_plant or stewart_linearize_inverse as often as needed. A linearisation keeps
 * no history (reset, copy, save and load exist for the one grammar and carry only the options).
 * No global state; no heap allocation in a call.
 */
#ifndef STEWART_STEWART_LINEARIZE_H
#define STEWART_STEWART_LINEARIZE_H

#include <stddef.h>

#include "stewart/stewart.h"
#include "stewart/stewart_plant.h"

#ifdef __cplusplus
extern "C" {
#endif

#define STEWART_LINEARIZE_STATES 12          /* x = (q, q_dot) */
#define STEWART_LINEARIZE_INPUTS 6           /* u = (F_1 .. F_6) */
#define STEWART_LINEARIZE_OUTPUTS 24         /* y = (q, q_dot, L, L_dot) */
#define STEWART_LINEARIZE_INVERSE_ROWS 30    /* (L, L_dot, L_ddot, F, base_force, base_torque) */
#define STEWART_LINEARIZE_INVERSE_COLUMNS 18 /* (q, q_dot, q_ddot) */

typedef struct stewart_linearize stewart_linearize;

/* Settings of a linearisation; stewart_linearize_options_default gives the values here. */
typedef struct stewart_linearize_options {
    int fidelity; /* the plant's: STEWART_MASSLESS or STEWART_FULL; STEWART_FULL */
} stewart_linearize_options;

/* The operating point of stewart_linearize_plant. */
typedef struct stewart_linearize_input {
    stewart_pose pose;          /* q and q_dot (q_ddot is not used: it follows from F) */
    double force[STEWART_LEGS]; /* F_k [N], > 0 pushes platform and base apart */
} stewart_linearize_input;

/* The plant linearised; matrices row-major, rows and columns in the order of x, u and y above. */
typedef struct stewart_linearize_output {
    double state_rate[STEWART_LINEARIZE_STATES];                   /* f(x, u) = (q_dot, q_ddot) */
    double output[STEWART_LINEARIZE_OUTPUTS];                      /* g(x) = (q, q_dot, L, L_dot) */
    double A[STEWART_LINEARIZE_STATES][STEWART_LINEARIZE_STATES];  /* df/dx */
    double B[STEWART_LINEARIZE_STATES][STEWART_LINEARIZE_INPUTS];  /* df/du */
    double C[STEWART_LINEARIZE_OUTPUTS][STEWART_LINEARIZE_STATES]; /* dg/dx */
    double D[STEWART_LINEARIZE_OUTPUTS][STEWART_LINEARIZE_INPUTS]; /* dg/du (zero) */
    int warnings;                                                  /* STEWART_WARN_STROKE */
    int stroke_legs; /* bit k set: leg k+1 is outside [stroke_min, stroke_max] */
} stewart_linearize_output;

/* The inverse side at a pose (q, q_dot, q_ddot): the lengths, the forces of the fidelity
 * (massless legs, or the full model's legs with mass), the base wrench, and their Jacobian. */
typedef struct stewart_linearize_inverse_output {
    stewart_lengths lengths;    /* L, L_dot, L_ddot */
    double force[STEWART_LEGS]; /* F [N] */
    double base_force[3];       /* force the moving bodies put on the base, world [N] */
    double base_torque[3];      /* its torque about the world origin [N m] */
    /* d(L, L_dot, L_ddot, F, base_force, base_torque) / d(q, q_dot, q_ddot), row-major */
    double jacobian[STEWART_LINEARIZE_INVERSE_ROWS][STEWART_LINEARIZE_INVERSE_COLUMNS];
    int warnings;    /* STEWART_WARN_STROKE */
    int stroke_legs; /* bit k set: leg k+1 is outside [stroke_min, stroke_max] */
} stewart_linearize_inverse_output;

/* The base wrench alone at a pose (q, q_dot, q_ddot) with its Jacobian: rows 24-29 of
 * stewart_linearize_inverse's, without the forces (one dual evaluation: the Model Exchange plant's
 * base-wrench derivatives compose it with the plant's A and B). */
typedef struct stewart_linearize_wrench_output {
    double base_force[3];  /* force the moving bodies put on the base, world [N] */
    double base_torque[3]; /* its torque about the world origin [N m] */
    /* d(base_force, base_torque) / d(q, q_dot, q_ddot), row-major */
    double jacobian[6][STEWART_LINEARIZE_INVERSE_COLUMNS];
} stewart_linearize_wrench_output;

/* Fills o with the defaults documented in stewart_linearize_options. */
void stewart_linearize_options_default(stewart_linearize_options *o);

/* STEWART_OK, or STEWART_ERR_PARAMETER (message names the option and its value). */
stewart_status stewart_linearize_options_check(const stewart_linearize_options *o, char *msg,
                                               size_t size);

/* A linearisation of model's plant, or NULL (msg says why: a NULL argument, an option out of
 * range, no memory). The model must outlive it. */
stewart_linearize *stewart_linearize_create(const stewart_model *model,
                                            const stewart_linearize_options *options, char *msg,
                                            size_t size);

/* The options l was made with (NULL for NULL). */
const stewart_linearize_options *stewart_linearize_options_of(const stewart_linearize *l);

/* Frees l (NULL is fine). */
void stewart_linearize_free(stewart_linearize *l);

/* Clears the message (a linearisation has no other history). */
void stewart_linearize_reset(stewart_linearize *l);

/* Copies src's options and message into dst (made for the same model). */
stewart_status stewart_linearize_copy(stewart_linearize *dst, const stewart_linearize *src);

/* Bytes stewart_linearize_save writes (0 for NULL). */
size_t stewart_linearize_state_size(const stewart_linearize *l);

/* Writes the state (versioned bytes: the options) into buffer of size bytes. */
stewart_status stewart_linearize_save(const stewart_linearize *l, void *buffer, size_t size);

/* Reads bytes from stewart_linearize_save; refuses, by name, bytes that are not such a state,
 * leaving l unchanged. */
stewart_status stewart_linearize_load(stewart_linearize *l, const void *buffer, size_t size);

/* The last error's message ("" after a success). */
const char *stewart_linearize_message(const stewart_linearize *l);

/* The plant's A, B, C, D at in. STEWART_ERR_ARGUMENT for an input that is not finite or a pitch
 * of +-90 degrees (roll and yaw rates undefined), STEWART_ERR_UNREACHABLE for a zero-length leg,
 * STEWART_ERR_SINGULAR for a locked Cardan (full fidelity); out is untouched on an error. */
stewart_status stewart_linearize_plant(stewart_linearize *l, const stewart_linearize_input *in,
                                       stewart_linearize_output *out);

/* The inverse side's lengths, forces and Jacobian at pose. Errors as stewart_linearize_plant,
 * and STEWART_ERR_SINGULAR where the forces are not defined (the legs cannot hold the pose). */
stewart_status stewart_linearize_inverse(stewart_linearize *l, const stewart_pose *pose,
                                         stewart_linearize_inverse_output *out);

/* The base wrench and its Jacobian at pose. Errors as stewart_linearize_plant. */
stewart_status stewart_linearize_base_wrench(stewart_linearize *l, const stewart_pose *pose,
                                             stewart_linearize_wrench_output *out);

/* The plant driven by its motors (stewart_plant_options.input CURRENT or VOLTAGE, docs/drives.md)
 * linearised: x = (q, q_dot) (12), or (q, q_dot, i_1 .. i_6) (18) with voltage input and a
 * winding_inductance > 0 on some leg (the windings' currents are then states; a leg without
 * inductance keeps a zero row and column for its current); u = the six currents [A] or voltages
 * [V]; y = (q, q_dot, L, L_dot) (24) as stewart_linearize_plant's, D = 0. The rotor's and screw's
 * reflected inertia, the screw's efficiency in the direction of the power flow, friction and the
 * end stops are in A and B, as the plant's right-hand side has them (smoothing_speed
 * regularises friction and the efficiency near rest; the direction of each leg's power flow is
 * held where the plant finds it). Where the right-hand side has a kink the derivative does not
 * exist; there the leg is flagged (STEWART_WARN_NOT_SMOOTH, not_smooth_legs) and its terms are:
 * at rest (L_dot = 0) with a screw force and efficiencies whose slopes differ forward and back,
 * and at a zero screw force of a moving leg (the power flow's turn), the mean of the two
 * one-sided derivatives (what central differences give); on a stroke end or where an end stop's
 * damper meets its limit, the side the plant's equations take. */
#define STEWART_LINEARIZE_DRIVEN_STATES 18 /* at most: (q, q_dot, i_1 .. i_6) */
/* A warnings bit (beside stewart.h's STEWART_WARN_*): a derivative taken as the mean of its
 * one-sided values where the equations have a kink. */
#define STEWART_WARN_NOT_SMOOTH 32

typedef struct stewart_linearize_driven_input {
    stewart_pose pose;            /* q and q_dot (q_ddot is not used) */
    double input[STEWART_LEGS];   /* the motors' currents [A] or voltages [V] */
    double current[STEWART_LEGS]; /* the windings' currents [A] (states with an inductance;
                                      not used otherwise) */
} stewart_linearize_driven_input;

typedef struct stewart_linearize_driven_output {
    int states;                                         /* 12, or 18 with the windings' currents */
    double state_rate[STEWART_LINEARIZE_DRIVEN_STATES]; /* (q_dot, q_ddot[, di/dt]) */
    double output[STEWART_LINEARIZE_OUTPUTS];           /* (q, q_dot, L, L_dot) */
    /* rows and columns beyond `states` are zero */
    double A[STEWART_LINEARIZE_DRIVEN_STATES][STEWART_LINEARIZE_DRIVEN_STATES];
    double B[STEWART_LINEARIZE_DRIVEN_STATES][STEWART_LINEARIZE_INPUTS];
    double C[STEWART_LINEARIZE_OUTPUTS][STEWART_LINEARIZE_DRIVEN_STATES];
    double D[STEWART_LINEARIZE_OUTPUTS][STEWART_LINEARIZE_INPUTS]; /* zero */
    double leg_force[STEWART_LEGS]; /* the drives' axial forces on the mechanism [N] */
    int warnings;                   /* STEWART_WARN_STROKE, STEWART_WARN_NOT_SMOOTH */
    int stroke_legs;                /* bit k set: leg k+1 is outside [stroke_min, stroke_max] */
    int not_smooth_legs; /* bit k set: leg k+1's derivatives are the one-sided ones' mean */
} stewart_linearize_driven_output;

/* The driven plant's A, B, C, D at in, with the drives of plant_options (its input, CURRENT or
 * VOLTAGE, and smoothing_speed; the fidelity is the linearisation's). Errors as
 * stewart_linearize_plant; STEWART_ERR_PARAMETER for plant_options the plant refuses (a leg
 * without a drive) or input FORCE (stewart_linearize_plant linearises that); STEWART_ERR_SINGULAR
 * where the plant's power flow does not settle (a leg's direction flips in its own iteration). */
stewart_status stewart_linearize_driven(stewart_linearize *l,
                                        const stewart_plant_options *plant_options,
                                        const stewart_linearize_driven_input *in,
                                        stewart_linearize_driven_output *out);

#ifdef __cplusplus
}
#endif

#endif /* STEWART_STEWART_LINEARIZE_H */
