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
 * A margin is > 0 within the limit, 0 on it, < 0 beyond it: the smallest over the legs (pairs,
 * axes). A pose on a limit is within it, except for interference: legs that touch interfere.
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
    STEWART_LIMIT_AXIS = 6
} stewart_limit_class;
#define STEWART_LIMIT_CLASSES 6

/* Settings of a limits object; stewart_limits_options_default gives the values documented here. */
typedef struct stewart_limits_options {
    double warn_condition; /* condition number limit, as the inverse option of that name; 1e3 */
} stewart_limits_options;

/* What a check takes: the pose (x, y, z [m], roll, pitch, yaw [rad]). */
typedef struct stewart_limits_input {
    double q[6];
} stewart_limits_input;

/* What a check gives. Array index = class - 1. */
typedef struct stewart_limits_output {
    int first;                            /* first failing class in check order; NONE if none */
    int failed;                           /* bit (class - 1) set for every failing class */
    double margin[STEWART_LIMIT_CLASSES]; /* smallest margin of each class [m, rad, rad, m, 1,
                                             m or rad] */
    int leg[STEWART_LIMIT_CLASSES];       /* the leg (1..6) of that margin; axis: the axis */
    int other_leg[STEWART_LIMIT_CLASSES]; /* interference: the other leg of the pair; else 0 */
    double condition;                     /* the leg Jacobian's 1-norm condition (inverse's) */
} stewart_limits_output;

/* What an axis-range search gives: per axis (x, y, z, roll, pitch, yaw) the interval it can
 * move over with the other five held, within every limit (proven between the poses it checks),
 * to 1e-6 (m or rad) inside the first limit met on each side. A pose beyond a limit gets
 * [q_i, q_i] on every axis, its first failing class at both ends. Roll, pitch and yaw are
 * searched up to pi away from q_i, the translations up to a length beyond which some leg is
 * surely longer than stroke_max. A side whose proof runs out of steps before any limit ends at
 * its last proven pose with the class that held its steps. */
typedef struct stewart_axis_ranges {
    double min[6], max[6];      /* the interval [pose units] */
    int min_limit[6], max_limit[6]; /* the class met at each end (NONE: the search's end) */
    int min_leg[6], max_leg[6];     /* its leg (1..6; axis: the axis; 0 for NONE) */
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
 * names the component and its value) for a NULL argument or a non-finite pose. */
stewart_status stewart_limits_check(stewart_limits *limits, const stewart_limits_input *input,
                                    stewart_limits_output *output);
/* The axis ranges of one pose (errors as stewart_limits_check). */
stewart_status stewart_limits_ranges(stewart_limits *limits, const stewart_limits_input *input,
                                     stewart_axis_ranges *output);
/* The class's name: "none", "stroke", "base_joint", "platform_joint", "interference",
 * "condition", "axis"; "unknown" for any other value. */
const char *stewart_limit_class_name(int limit_class);

#ifdef __cplusplus
}
#endif

#endif /* STEWART_STEWART_LIMITS_H */
