/*
 * The limits a hexapod controller checks before it moves, and the axis ranges they leave: the C
 * API (docs/limits.md).
 *
 * A limits object is made from a model and its options like the three directions' objects
 * (stewart_limits_create, _free, _message) and answers two questions about a pose:
 *   stewart_limits_check(limits, &in, &out)   which limit class fails first, the margin to each
 *   stewart_limits_ranges(limits, &in, &out)  how far each axis can move, the other five held
 * It keeps no history (no _reset, _copy, _save or _load: there is nothing to keep), never
 * allocates after _create and never writes NaN.
 *
 * The limit classes, in the order a pose is checked (STEWART_LIMIT_*):
 *   stroke          per leg, L_k within [stroke_min, stroke_max]; margin [m]
 *   base joint      per leg, the angle between the leg (base toward platform) and the base
 *                   joint's neutral axis at most base_joint_limit; margin [rad]
 *   platform joint  the same at the platform joint (neutral axis in the platform frame) [rad]
 *   interference    per pair of legs, the shortest distance between the legs' parts (the
 *                   joint-to-joint segments leg_diameter thick, or an actuator's body and rod:
 *                   leg_body_*, leg_rod_*) less their radii, above 0; margin [m]
 *   condition       the leg Jacobian's condition number at most warn_condition; margin
 *                   1/condition - 1/warn_condition [1] (finite through a singularity)
 *   axis            software position limits: each axis of the tool pose (user frame) within
 *                   [axis_min, axis_max]; margin [m or rad, the axis']
 *   leg speed       per leg, |dL_k/dt| at most leg_speed_max; margin [m/s]
 *   leg accel       per leg, |d2L_k/dt2| at most leg_accel_max; margin [m/s^2]
 *   leg jerk        per leg, |d3L_k/dt3| at most leg_jerk_max; margin [m/s^3]
 *   leg force       per leg, |F_k| at most leg_force_max; margin [N]
 * A margin is > 0 within the limit, 0 on it, < 0 beyond it: the smallest over the legs (pairs,
 * axes). A pose on a limit is within it, except for interference: legs that touch interfere.
 * The leg classes need what the input gives besides the pose (its time derivatives, the legs'
 * forces): a class whose data is not given, or whose limit is 0 (none) for a leg, has margin
 * +inf there and is never met.
 */
#ifndef STEWART_STEWART_LIMITS_H
#define STEWART_STEWART_LIMITS_H

#include <stddef.h>

#include "stewart/stewart.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Limit classes, in check order; STEWART_LIMIT_NONE: within every limit (or, at an end of an
 * axis range, the axis' own end). */
typedef enum stewart_limit_class {
    STEWART_LIMIT_NONE = 0,
    STEWART_LIMIT_STROKE = 1,
    STEWART_LIMIT_BASE_JOINT = 2,
    STEWART_LIMIT_PLATFORM_JOINT = 3,
    STEWART_LIMIT_INTERFERENCE = 4,
    STEWART_LIMIT_CONDITION = 5,
    STEWART_LIMIT_AXIS = 6,
    STEWART_LIMIT_LEG_SPEED = 7,
    STEWART_LIMIT_LEG_ACCEL = 8,
    STEWART_LIMIT_LEG_JERK = 9,
    STEWART_LIMIT_LEG_FORCE = 10
} stewart_limit_class;
#define STEWART_LIMIT_CLASSES 10

/* Settings of a limits object; stewart_limits_options_default gives the values documented here. */
typedef struct stewart_limits_options {
    double warn_condition; /* condition number limit, as the inverse option of that name; 1e3 */
} stewart_limits_options;

/* What a check takes: the pose (x, y, z [m], roll, pitch, yaw [rad]; the tool's in the user
 * frame, as every pose of the API) and, for the leg classes, optionally its time derivatives and
 * the legs' forces. A zero-initialised input ({{x, y, z, roll, pitch, yaw}}) is the pose alone.
 * The axis ranges use q only. */
typedef struct stewart_limits_input {
    double q[6];
    int derivatives;            /* how many derivatives of q follow: 0 none, 1 q_dot (leg speed),
                            2 and q_ddot (leg acceleration), 3 and q_dddot (leg jerk) */
    double q_dot[6];            /* dq/dt [m/s, rad/s] */
    double q_ddot[6];           /* d2q/dt2 [m/s^2, rad/s^2] */
    double q_dddot[6];          /* d3q/dt3 [m/s^3, rad/s^3] */
    int has_force;              /* 1: force holds the legs' forces (leg force class); 0: none */
    double force[STEWART_LEGS]; /* F_k [N] (the inverse's; its sign is not used) */
} stewart_limits_input;

/* What a check gives. Array index = class - 1. */
typedef struct stewart_limits_output {
    int first;                            /* first failing class in check order; NONE if none */
    int failed;                           /* bit (class - 1) set for every failing class */
    double margin[STEWART_LIMIT_CLASSES]; /* smallest margin of each class [m, rad, rad, m, 1,
                                             m or rad, m/s, m/s^2, m/s^3, N] */
    int leg[STEWART_LIMIT_CLASSES];       /* the leg (1..6) of that margin; axis: the axis */
    int other_leg[STEWART_LIMIT_CLASSES]; /* interference: the other leg of the pair; else 0 */
    double condition;                     /* the leg Jacobian's 1-norm condition (inverse's) */
    /* Each leg's own margin to each class, [class - 1][leg - 1] (margin is their smallest):
     * interference, the smallest over the pairs the leg is in (+inf if it is in none that is
     * checked); condition and axis, properties of the pose, the class margin at every leg. */
    double leg_margin[STEWART_LIMIT_CLASSES][STEWART_LEGS];
} stewart_limits_output;

/* What an axis-range search gives: per axis (x, y, z, roll, pitch, yaw) the interval it can
 * move over with the other five held, within every limit (proven between the poses it checks),
 * to 1e-6 (m or rad) inside the first limit met on each side. A pose beyond a limit gets
 * [q_i, q_i] on every axis, its first failing class at both ends. Roll, pitch and yaw are
 * searched up to pi away from q_i, the translations up to a length beyond which some leg is
 * surely longer than stroke_max. A side whose proof runs out of steps before any limit ends at
 * its last proven pose with the class that held its steps. */
typedef struct stewart_axis_ranges {
    double min[6], max[6];                  /* the interval [pose units] */
    int min_limit[6], max_limit[6];         /* the class met at each end (NONE: the search's end) */
    int min_leg[6], max_leg[6];             /* its leg (1..6; axis: the axis; 0 for NONE) */
    int min_other_leg[6], max_other_leg[6]; /* interference: the pair's other leg; else 0 */
} stewart_axis_ranges;

typedef struct stewart_limits stewart_limits;

/* The defaults documented at stewart_limits_options. */
void stewart_limits_options_default(stewart_limits_options *options);
/* STEWART_OK, or STEWART_ERR_PARAMETER with a message naming the option and its value. */
stewart_status stewart_limits_options_check(const stewart_limits_options *options, char *message,
                                            size_t size);
/* A limits object for model (which must outlive it) with a copy of options: NULL if an option is
 * out of range (message names it and its value), an argument is NULL or memory is short. */
stewart_limits *stewart_limits_create(const stewart_model *model,
                                      const stewart_limits_options *options, char *message,
                                      size_t size);
/* Frees the object (NULL is ignored). */
void stewart_limits_free(stewart_limits *limits);
/* The message of the last call that did not return STEWART_OK, else "". */
const char *stewart_limits_message(const stewart_limits *limits);

/* Checks one pose against every limit class. STEWART_ERR_ARGUMENT (output untouched, message
 * names the component and its value) for a NULL argument, a non-finite pose, derivative or
 * force, derivatives outside 0..3 or has_force outside 0..1, or leg rates too large to compute
 * (they overflow); STEWART_ERR_UNREACHABLE (message names the leg) when derivatives are given
 * and a leg has zero length (no direction, so no rate). */
stewart_status stewart_limits_check(stewart_limits *limits, const stewart_limits_input *input,
                                    stewart_limits_output *output);
/* The axis ranges of one pose (errors as stewart_limits_check). */
stewart_status stewart_limits_ranges(stewart_limits *limits, const stewart_limits_input *input,
                                     stewart_axis_ranges *output);
/* The class's name: "none", "stroke", "base_joint", "platform_joint", "interference",
 * "condition", "axis", "leg_speed", "leg_accel", "leg_jerk", "leg_force"; "unknown" for any
 * other value. */
const char *stewart_limit_class_name(int limit_class);

#ifdef __cplusplus
}
#endif

#endif /* STEWART_STEWART_LIMITS_H */
