/*
 * Many poses in one call: the batch entry point behind the Python package and the sweeps.
 *
 * A batch solves n poses in order with one data block, exactly as n successive stewart_solve
 * calls would (at the full level each pose starts from the previous one's solution), but with
 * the inputs and outputs as row-major arrays, so that a caller holding arrays (numpy) needs no
 * loop per pose. A row that fails gets its status (and, if asked, its message) and zero outputs;
 * the rows after it are still solved.
 */
#ifndef STEWART_STEWART_BATCH_H
#define STEWART_STEWART_BATCH_H

#include <stddef.h>

#include "stewart/stewart.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Where a batch writes its results: arrays of n rows, row-major. Every pointer but status may be
 * NULL to skip that output. */
typedef struct stewart_batch_outputs {
    double *length;        /* n x 6, L_k [m] */
    double *length_rate;   /* n x 6, dL_k/dt [m/s] */
    double *length_accel;  /* n x 6, d2L_k/dt2 [m/s^2] */
    double *force;         /* n x 6, F_k [N] */
    double *condition;     /* n, leg Jacobian condition number */
    double *residual;      /* n, constraint residual [m] */
    double *base_force;    /* n x 3, force on the base, world frame [N] */
    double *base_torque;   /* n x 3, its torque about the world origin [N m] */
    int *iterations;       /* n, Newton iterations (full level) */
    int *warnings;         /* n, STEWART_WARN_* bits */
    int *status;           /* n, the stewart_status of each row (required) */
} stewart_batch_outputs;

/* The messages of the first failing rows, in row order (optional). */
typedef struct stewart_batch_messages {
    size_t capacity;  /* how many messages rows and text can hold */
    size_t count;     /* set by the batch: messages written, at most capacity */
    size_t *rows;     /* capacity entries: the row (from 0) each message belongs to */
    char *text;       /* capacity x STEWART_MESSAGE_SIZE characters, one message each */
} stewart_batch_messages;

/* Solves rows 0..n-1 of q (n x 6), with q_dot and q_ddot (n x 6 each, NULL for zero), in order,
 * continuing from the data block's state (call stewart_data_reset first for a fresh start).
 * Options are checked once: if they are bad, nothing is solved. Returns STEWART_OK if every row
 * solved, else the status of the first failing row, whose message stewart_data_message then gives
 * and whose index goes to *first_failed (if not NULL; n when every row solved). messages may be
 * NULL. */
stewart_status stewart_solve_batch(const stewart_model *model, stewart_data *data,
                                   const stewart_options *options, size_t n, const double *q,
                                   const double *q_dot, const double *q_ddot,
                                   const stewart_batch_outputs *outputs,
                                   stewart_batch_messages *messages, size_t *first_failed);

#ifdef __cplusplus
}
#endif

#endif /* STEWART_STEWART_BATCH_H */
