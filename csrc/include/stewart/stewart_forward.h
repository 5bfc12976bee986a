/*
 * Forward kinematics: six measured actuator lengths (and, when given, their rates and
 * accelerations) to the platform pose (and its rates and accelerations).
 *
 * The position problem L(q) = L_measured is solved by KINSOL's Newton iteration with the analytic
 * 6 x 6 Jacobian. A forward solver remembers its last pose (its history, which _copy, _save and
 * _load carry): a stream of measurements is tracked from it (with a Taylor predictor from its
 * last rates), a first measurement starts from the guess given, else from the home pose. A pose
 * on another assembly mode than the working one (platform below the base, a leg beyond the
 * half-space of one of its Cardans, a singular pose between it and home, a jump larger than the
 * stroke allows), or a pose the lengths do not lead to (neither a proven step from the last pose
 * nor the end of the straight path of lengths from it or from home: far from home two poses can
 * pass the other checks), is never returned as the answer: the solve fails with
 * STEWART_ERR_OTHER_BRANCH and says which.
 */
#ifndef STEWART_STEWART_FORWARD_H
#define STEWART_STEWART_FORWARD_H

#include "stewart/stewart.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A forward solve that converged to another assembly mode than the working one returns
 * STEWART_ERR_OTHER_BRANCH (stewart.h); the output then holds that pose (for inspection), its
 * warnings have STEWART_WARN_OTHER_BRANCH and branch says why. */

/* Bits of stewart_forward_output.branch: why a pose is not on the working assembly mode. */
enum {
    STEWART_BRANCH_BELOW_BASE = 1,      /* a leg leaves its base Cardan on the other side than at
                                            home: downward for a leg rising at home (mirror pose) */
    STEWART_BRANCH_PLATFORM_CARDAN = 2, /* a leg reaches its platform Cardan from the other side
                                            than at home (from above, for a rising leg) */
    STEWART_BRANCH_FLIPPED = 4,         /* the platform's normal points down */
    STEWART_BRANCH_JUMP = 8,            /* tracking: a platform point moved farther than the
                                            shortest stroke range (stroke_max[k] - stroke_min[k])
                                            since the last pose */
    STEWART_BRANCH_SINGULARITY = 16,    /* the leg Jacobian's determinant has the other sign
                                            than at home: a singular pose lies in between */
    STEWART_BRANCH_UNPROVEN = 32        /* passes the checks above, but is neither a proven
                                            step from the last pose nor the pose reached from
                                            home along the straight path of lengths: the lengths
                                            have several such poses */
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
    double warn_condition;     /* as stewart_inverse_options (the same defaults):
                                  STEWART_WARN_NEAR_SINGULAR */
    double singular_condition; /* above it the solve fails with STEWART_ERR_SINGULAR */
} stewart_forward_options;

/* What a forward solve takes. */
typedef struct stewart_forward_input {
    double time;             /* [s]: the tracking predictor advances the last pose to it */
    stewart_lengths lengths; /* measured lengths; their rates and accelerations as derivatives
                                 says */
    int derivatives;         /* 0: lengths only; 1: and length_rate; 2: and length_accel too */
    int use_guess;           /* 1: start from guess and forget the history; 0: track */
    double guess[6];         /* start pose (x, y, z, roll, pitch, yaw) if use_guess */
} stewart_forward_input;

/* What a forward solve gives. */
typedef struct stewart_forward_output {
    stewart_pose pose; /* q; q_dot if rates were given, q_ddot if accelerations were (else 0) */
    double residual;   /* max |L_k(q) - L_k measured| at the last Newton iterate [m]; the pose
                            returned carries one more correction with the exact Jacobian */
    double condition;  /* leg Jacobian condition number at the pose, as the inverse output's */
    double jump;       /* largest platform-point displacement from the last pose [m] (0 if
                            no history) */
    int iterations;    /* KINSOL Newton iterations, over every start tried */
    int warnings;      /* STEWART_WARN_STROKE (a measured length outside the stroke),
                            STEWART_WARN_NEAR_SINGULAR, STEWART_WARN_OTHER_BRANCH */
    int stroke_legs;   /* bit k set: measured length k+1 is outside [stroke_min, stroke_max] */
    int branch;        /* STEWART_BRANCH_* bits; 0 on the working assembly mode */
    int start;         /* STEWART_START_* the solution was reached from */
} stewart_forward_output;

typedef struct stewart_forward stewart_forward;

/* The defaults documented at stewart_forward_options. */
void stewart_forward_options_default(stewart_forward_options *options);
/* STEWART_OK, or STEWART_ERR_PARAMETER with a message naming the option and its value. */
stewart_status stewart_forward_options_check(const stewart_forward_options *options, char *message,
                                             size_t size);

/* A forward solver for model (which must outlive it) with a copy of options: NULL if the options
 * are invalid, an argument is NULL, the model's working assembly mode is undefined or memory is
 * short (message says why). */
stewart_forward *stewart_forward_create(const stewart_model *model,
                                        const stewart_forward_options *options, char *message,
                                        size_t size);
/* Frees the solver (NULL is ignored). */
void stewart_forward_free(stewart_forward *forward);
/* Forgets the last pose: the next solve starts cold. */
void stewart_forward_reset(stewart_forward *forward);
/* Copies the tracking history of src into dst (same model, else STEWART_ERR_ARGUMENT). */
stewart_status stewart_forward_copy(stewart_forward *dst, const stewart_forward *src);
/* The size of the saved history in bytes (the same for every forward solver). */
size_t stewart_forward_state_size(const stewart_forward *forward);
/* Writes the history into buffer (at least stewart_forward_state_size bytes). */
stewart_status stewart_forward_save(const stewart_forward *forward, void *buffer, size_t size);
/* STEWART_ERR_ARGUMENT (solver unchanged, message says why) unless the bytes are a history this
 * library saved: its version and size, flags 0 or 1, every value finite. */
stewart_status stewart_forward_load(stewart_forward *forward, const void *buffer, size_t size);
/* The message of the last call that did not return STEWART_OK, else "". */
const char *stewart_forward_message(const stewart_forward *forward);
/* The model the solver was made for, and its options. */
const stewart_model *stewart_forward_model(const stewart_forward *forward);
const stewart_forward_options *stewart_forward_options_of(const stewart_forward *forward);

/* The pose whose six actuator lengths are input->lengths.length [m] at input->time [s]; the
 * rates and accelerations (input->derivatives) give the pose rates and accelerations through the
 * leg Jacobian. With use_guess the start is guess, and the history is forgotten; without, the
 * last pose is the start (advanced to time by its last rates when time is later), or the home
 * pose if there is none.
 * Without history the answer is the pose reached from home along the straight path of lengths
 * (output->start STEWART_START_LAST when Newton from home found another).
 * On STEWART_OK the output is filled and the pose becomes the last pose.
 * STEWART_ERR_OTHER_BRANCH: output filled with the other mode's pose, history unchanged.
 * Any other error: output untouched, history unchanged, stewart_forward_message says why (naming
 * the leg where one can be blamed). Never writes NaN. */
stewart_status stewart_forward_solve(stewart_forward *forward, const stewart_forward_input *input,
                                     stewart_forward_output *output);

/* The pose of input's lengths on its own, for measured lengths that are not a trajectory: the
 * solver is reset, and Newton starts from input->guess (use_guess) or the home pose. When a
 * start from home lands on another assembly mode, the lengths are walked from home's readings to
 * input's in 8, then 64, equal steps, each solve tracking the one before: a path that stays on
 * the working mode unless the straight path in length space crosses a singular pose. Returns and
 * fills as stewart_forward_solve (output->start is STEWART_START_LAST after a walk); the history
 * is the pose found. */
stewart_status stewart_forward_solve_cold(stewart_forward *forward,
                                          const stewart_forward_input *input,
                                          stewart_forward_output *output);

#ifdef __cplusplus
}
#endif

#endif /* STEWART_STEWART_FORWARD_H */
