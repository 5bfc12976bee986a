/*
 * Many poses in one call: the batch entry point behind the Python package and the sweeps.
 *
 * A batch solves n poses in order with one inverse solver, exactly as n successive
 * stewart_inverse_solve calls would (at the full level each pose starts from the previous one's
 * solution; the kinematic and massless levels run four poses at a time on the vector units, the
 * same numbers to rounding and the same statuses, messages and warnings: docs/api.md), but with
 * the inputs and outputs as row-major arrays, so that a caller holding arrays (numpy) needs no
 * loop per pose. A row that fails gets its status (and, if asked, its message) and zero outputs;
 * the rows after it are still solved. The same for forward kinematics (lengths to poses) and, for
 * the plant, a run over n communication points (forces to motion), which stops at a refused step.
 */
#ifndef STEWART_STEWART_BATCH_H
#define STEWART_STEWART_BATCH_H

#include <stddef.h>

#include "stewart/stewart.h"
#include "stewart/stewart_forward.h"
#include "stewart/stewart_outputs.h"
#include "stewart/stewart_plant.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One batch output column: a pointer to n x count values (stewart_outputs.h). */
#define STEWART_BATCH_COLUMN(name, member, count, type, unit, description) type *name;

/* Where a batch writes its results: arrays of n rows, row-major, one per column of
 * STEWART_INVERSE_OUTPUT_TABLE (length, length_rate, length_accel, force, condition, residual,
 * base_force, base_torque, iterations, warnings, stroke_legs), then status. Every pointer but
 * status may be NULL to skip that output. */
typedef struct stewart_inverse_batch_outputs {
    STEWART_INVERSE_OUTPUT_TABLE(STEWART_BATCH_COLUMN)
    int *status; /* n, the stewart_status of each row (required) */
} stewart_inverse_batch_outputs;

/* The messages of the first failing rows, in row order (optional). */
typedef struct stewart_batch_messages {
    size_t capacity; /* how many messages rows and text can hold */
    size_t count;    /* set by the batch: messages written, at most capacity */
    size_t *rows;    /* capacity entries: the row (from 0) each message belongs to */
    char *text;      /* capacity x STEWART_MESSAGE_SIZE characters, one message each */
} stewart_batch_messages;

/* Solves rows 0..n-1 of q (n x 6), with q_dot and q_ddot (n x 6 each, NULL for zero), in order,
 * continuing from the solver's state (call stewart_inverse_reset first for a fresh start). The
 * output arrays must not overlap the inputs (the closed-form levels write a block of rows before
 * they read all of it).
 * Returns STEWART_OK if every row solved, else the status of the first failing row, whose message
 * stewart_inverse_message then gives and whose index goes to *first_failed (if not NULL; n when
 * every row solved). messages may be NULL. */
stewart_status stewart_inverse_batch(stewart_inverse *inverse, size_t n, const double *q,
                                     const double *q_dot, const double *q_ddot,
                                     const stewart_inverse_batch_outputs *outputs,
                                     stewart_batch_messages *messages, size_t *first_failed);

/* Along a trajectory: rows 0..n-1 of an inverse batch's outputs at the times t (n, finite,
 * increasing) get each drive's current_rate by differences of current over t, as
 * numpy.gradient takes them: central of second order on uneven steps between rows, one-sided of
 * first order at the ends of each run of solved rows (a run of one row: 0). Their voltage gains
 * winding_inductance x current_rate, and electrical_power and voltage_max_legs follow it.
 * Needs the columns current, current_rate, motor_speed, voltage and status (electrical_power and
 * voltage_max_legs if there). STEWART_ERR_ARGUMENT (message names the row and time, outputs
 * untouched) for a NULL or a t that does not increase. A model without drives: nothing to do. */
stewart_status stewart_inverse_batch_current_rates(const stewart_model *model, size_t n,
                                                   const double *t,
                                                   const stewart_inverse_batch_outputs *outputs,
                                                   char *message, size_t size);

/* With the poses' jerks q_dddot (n x 6, d3q/dt3): rows 0..n-1 of an inverse batch's outputs,
 * solved at q, q_dot, q_ddot (NULL: zero) by an inverse of this fidelity, get each drive's
 * current_rate from the drive's law differentiated along the motion: the legs' jerks and the
 * forces' rates are stewart_linearize_inverse's Jacobian at that fidelity times (q_dot, q_ddot,
 * q_dddot) (the kinematic level's forces are 0: their rates too). The power flow's direction
 * and the friction's sign as at the pose (at a change of direction the current steps: its rate
 * there is the side the current is on). Voltage, electrical_power and voltage_max_legs follow.
 * About 200 k (massless) and 900 k (full) instructions a row: the Jacobian's. Needs the columns
 * of stewart_inverse_batch_current_rates and force, length_rate, length_accel. STEWART_ERR_ARGUMENT
 * for a NULL, the linearisation's status for a row whose derivatives it refuses (message names
 * the row; rows before it are done). A model without drives: nothing to do. */
stewart_status stewart_inverse_batch_current_rates_from_jerks(
    const stewart_model *model, int fidelity, size_t n, const double *q, const double *q_dot,
    const double *q_ddot, const double *q_dddot, const stewart_inverse_batch_outputs *outputs,
    char *message, size_t size);

/* The status of a row a batch did not run (stewart_plant_batch after a refused step): positive,
 * unlike every stewart_status. */
#define STEWART_BATCH_NOT_RUN 1

/* Where a forward batch writes its results: arrays of n rows, row-major, one per column of
 * STEWART_FORWARD_OUTPUT_TABLE (pose, pose_rate, pose_accel, residual, condition, jump,
 * iterations, warnings, branch, start, stroke_legs), then status. Every pointer but status may be
 * NULL to skip that output. A failed row holds zeros, but a row on another assembly mode keeps
 * its warnings, branch and stroke_legs. */
typedef struct stewart_forward_batch_outputs {
    STEWART_FORWARD_OUTPUT_TABLE(STEWART_BATCH_COLUMN)
    int *status; /* n, the stewart_status of each row (required) */
} stewart_forward_batch_outputs;

/* Forward kinematics of rows 0..n-1 of lengths (n x 6), with rates and accels (n x 6 each, NULL
 * for none; accels need rates) at times time (n, NULL for all zero: no predictor), in order, as n
 * successive stewart_forward_solve calls would: row 0 from guess (6 values) if not NULL, else
 * from the solver's last pose (stewart_forward_reset first for a cold start), each later row
 * tracking from the last solved one. A failed row gets its status and, if asked, its message;
 * the rows after it are still solved. Returns as stewart_inverse_batch. */
stewart_status stewart_forward_batch(stewart_forward *forward, size_t n, const double *time,
                                     const double *lengths, const double *rates,
                                     const double *accels, const double guess[6],
                                     const stewart_forward_batch_outputs *outputs,
                                     stewart_batch_messages *messages, size_t *first_failed);

/* Forward kinematics of rows 0..n-1 of lengths each on its own, for measured lengths that are not
 * a trajectory: every row through stewart_forward_solve_cold, from guesses[6j..6j+5] when
 * guesses (n x 6) is not NULL, else from the home pose (walking from home's lengths when that
 * start lands on another assembly mode). rates and accels as stewart_forward_batch. Returns as
 * stewart_inverse_batch. */
stewart_status stewart_forward_batch_cold(stewart_forward *forward, size_t n, const double *lengths,
                                          const double *rates, const double *accels,
                                          const double *guesses,
                                          const stewart_forward_batch_outputs *outputs,
                                          stewart_batch_messages *messages, size_t *first_failed);

/* Where a plant batch writes its results: arrays of n rows, row-major, one per column of
 * STEWART_PLANT_OUTPUT_TABLE (pose, pose_rate, length, length_rate, base_force, base_torque,
 * warnings, stroke_legs) and of STEWART_PLANT_STEP_TABLE (steps, rhs_evaluations,
 * nonlinear_iterations, error_test_failures: the statistics of the step into the row, zero for
 * row 0), then status. Every pointer but status may be NULL to skip that output. A row that did
 * not run holds zeros. */
typedef struct stewart_plant_batch_outputs {
    STEWART_PLANT_OUTPUT_TABLE(STEWART_BATCH_COLUMN)
    STEWART_PLANT_STEP_TABLE(STEWART_BATCH_COLUMN)
    int *status; /* n, stewart_status, or STEWART_BATCH_NOT_RUN (required) */
} stewart_plant_batch_outputs;

/* Runs plant through the communication points time (n, increasing) with the forces force (n x 6
 * [N], linear in time between rows), as stewart-simulate does: the state is set at time[0] to
 * start_pose and start_rate (6 values each; NULL: the plant's current pose or pose rates, which
 * for a new plant are home and at rest), then each row j > 0 is one stewart_plant_step from row
 * j-1. Row 0 is the start state. A refused step (or a bad start state, a time that does not
 * increase, a non-finite force) stops the run: that row gets its status, the rows after it
 * STEWART_BATCH_NOT_RUN, and the plant stays at the last row that ran. Returns STEWART_OK or the
 * status of the row that stopped the run, whose index goes to *first_failed (n when every row
 * ran) and whose message ("row j (t = ...): why") to messages (if not NULL). */
stewart_status stewart_plant_batch(stewart_plant *plant, size_t n, const double *time,
                                   const double *force, const double start_pose[6],
                                   const double start_rate[6],
                                   const stewart_plant_batch_outputs *outputs,
                                   stewart_batch_messages *messages, size_t *first_failed);

/* stewart_plant_batch in slices, with the numbers of one call (a caller that checks for
 * interrupts between slices): runs rows first..stop-1 of the same n-row arrays. first = 0 starts
 * the run as stewart_plant_batch does; first > 0 continues it, each row one stewart_plant_step
 * from the row before, where the slice before left the plant (start_pose and start_rate are then
 * unused). Rows outside [first, stop) are not written, but for a refused step: that row gets
 * its status and every row after it up to n-1 STEWART_BATCH_NOT_RUN. Returns, and numbers rows
 * in *first_failed and messages, as stewart_plant_batch (stop when every row of the slice ran). */
stewart_status stewart_plant_batch_rows(stewart_plant *plant, size_t n, size_t first, size_t stop,
                                        const double *time, const double *force,
                                        const double start_pose[6], const double start_rate[6],
                                        const stewart_plant_batch_outputs *outputs,
                                        stewart_batch_messages *messages, size_t *first_failed);

#ifdef __cplusplus
}
#endif

#endif /* STEWART_STEWART_BATCH_H */
