/*
 * Forward kinematics: six measured actuator lengths (and, when given, their rates and
 * accelerations) to the platform pose (and its rates and accelerations).
 *
 * The position problem L(q) = L_measured is solved by KINSOL's Newton iteration with the analytic
 * 6 x 6 Jacobian. A data block remembers its last pose: a stream of measurements is tracked from
 * it (with a Taylor predictor from its last rates), a first measurement starts from the guess
 * given, else from the home pose. A pose on another assembly mode than the working one (platform
 * below the base, a leg beyond the half-space of one of its Cardans, a singular pose between it
 * and home, a jump larger than the stroke allows) is never returned as the answer: the solve
 * fails with STEWART_ERR_OTHER_BRANCH and says which.
 */
#ifndef STEWART_STEWART_FORWARD_H
#define STEWART_STEWART_FORWARD_H

#include "stewart/stewart.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A forward solve that converged to another assembly mode than the working one returns
 * STEWART_ERR_OTHER_BRANCH (stewart.h); the result then holds that pose (for inspection), its
 * warnings have STEWART_WARN_OTHER_BRANCH and branch says why. */

/* Bits of stewart_forward_result.branch: why a pose is not on the working assembly mode. */
enum {
    STEWART_BRANCH_BELOW_BASE = 1,       /* a leg leaves its base Cardan downward (mirror pose) */
    STEWART_BRANCH_PLATFORM_CARDAN = 2,  /* a leg reaches its platform Cardan from above */
    STEWART_BRANCH_FLIPPED = 4,          /* the platform's normal points down */
    STEWART_BRANCH_JUMP = 8,             /* tracking: a platform point moved farther than the
                                            stroke (stroke_max - stroke_min) since the last pose */
    STEWART_BRANCH_SINGULARITY = 16      /* the leg Jacobian's determinant has the other sign
                                            than at home: a singular pose lies in between */
};

/* Which start the solution was reached from. */
enum {
    STEWART_START_HOME = 0,      /* no history, no guess: (0, 0, home_height, 0, 0, 0) */
    STEWART_START_GUESS = 1,     /* the caller's guess */
    STEWART_START_PREDICTOR = 2, /* tracking: last pose advanced by its rates to this time */
    STEWART_START_LAST = 3       /* tracking: the last pose (the predictor failed or was not set) */
};

/* Settings of stewart_forward_solve; stewart_forward_options_default gives the values here. */
typedef struct stewart_forward_options {
    double tolerance;          /* max-norm of L(q) - L_measured at which Newton stops [m]; 1e-12;
                                  >= 2.5e-16 (rounding of lengths of order 1 m) */
    int max_iterations;        /* Newton iteration cap per start; 20 */
    double warn_condition;     /* as stewart_options (the same defaults): STEWART_WARN_NEAR_SINGULAR */
    double singular_condition; /* above it the solve fails with STEWART_ERR_SINGULAR */
} stewart_forward_options;

typedef struct stewart_forward_result {
    stewart_pose pose;   /* q; q_dot if rates were given, q_ddot if accelerations were (else 0) */
    int iterations;      /* KINSOL Newton iterations, over every start tried */
    double residual;     /* max |L_k(q) - L_k measured| at the last Newton iterate [m]; the pose
                            returned carries one more correction with the exact Jacobian */
    double condition;    /* leg Jacobian condition number at the pose, as stewart_output's */
    int warnings;        /* STEWART_WARN_STROKE (a measured length outside the stroke),
                            STEWART_WARN_NEAR_SINGULAR, STEWART_WARN_OTHER_BRANCH */
    int branch;          /* STEWART_BRANCH_* bits; 0 on the working assembly mode */
    double jump;         /* largest platform-point displacement from the last pose [m] (0 if
                            no history) */
    int start;           /* STEWART_START_* the solution was reached from */
} stewart_forward_result;

void stewart_forward_options_default(stewart_forward_options *options);
/* STEWART_OK, or STEWART_ERR_PARAMETER with a message naming the option and its value. */
stewart_status stewart_forward_options_check(const stewart_forward_options *options,
                                             char *message, size_t size);

/* The pose whose six actuator lengths are `lengths` [m] at time `time` [s]. rates [m/s] and
 * accels [m/s^2] (each 6 values or NULL; accels need rates) give the pose rates and
 * accelerations through the leg Jacobian. guess (6 values or NULL) is the start, and forgets the
 * history; without it the data block's last pose is the start (advanced to `time` by its last
 * rates when `time` is later), or the home pose if there is none.
 * On STEWART_OK the result is filled and the pose becomes the data block's last pose.
 * STEWART_ERR_OTHER_BRANCH: result filled with the other mode's pose, history unchanged.
 * Any other error: result untouched, history unchanged, stewart_data_message says why (naming
 * the leg where one can be blamed). Never writes NaN. */
stewart_status stewart_forward_solve(const stewart_model *model, stewart_data *data,
                                     const stewart_forward_options *options, double time,
                                     const double lengths[STEWART_LEGS],
                                     const double rates[STEWART_LEGS],
                                     const double accels[STEWART_LEGS], const double guess[6],
                                     stewart_forward_result *result);

/* Forgets the data block's last pose: the next forward solve starts cold. */
void stewart_forward_reset(stewart_data *data);

#ifdef __cplusplus
}
#endif

#endif /* STEWART_STEWART_FORWARD_H */
