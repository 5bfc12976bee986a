/*
 * The scene player's trajectory file: a CSV whose header names the columns t, x, y, z, roll,
 * pitch, yaw, x_dot .. yaw_dot, x_ddot .. yaw_ddot (in any order, others ignored: the table
 * scripts/move.py writes and stewart-solve reads), one sample per row with t increasing, numbers
 * read the same in every locale. Between two rows each component is the quintic Hermite that
 * matches the two rows' pose, rate and acceleration, so the outputs are the file's at its rows
 * and twice continuously differentiable between them; the rates and accelerations are the
 * quintic's own derivatives.
 */
#ifndef STEWART_SCENE_TRAJECTORY_H
#define STEWART_SCENE_TRAJECTORY_H

#include <stddef.h>

#include "instance.h"

/* Values per row: t, then pose, rates and accelerations (6 each). */
enum { TRAJECTORY_COLUMNS = 19 };

/* Reads the file at path into *rows (n rows of TRAJECTORY_COLUMNS, malloc'd; the caller frees
 * it). FMU_ERROR after a message naming the file, the line and the cause: unreadable, a column
 * missing, a row with another number of fields, a field that is not a number or not finite, t
 * not increasing, no rows. */
fmu_status trajectory_read(fmu_instance *inst, const char *path, double **rows, size_t *n);

/* Where t lies on the trajectory. A file ends at rest when every rate of its last row is 0 (its
 * accelerations need not be: a move without a jerk limit stops with a step in acceleration). */
typedef enum {
    TRAJECTORY_ON = 0,     /* within the rows, or past the last of a file that ends at rest */
    TRAJECTORY_BEFORE = 1, /* before the first row */
    TRAJECTORY_PAST = 2    /* past the last row of a file that does not end at rest */
} trajectory_where;

/* The pose, rates and accelerations at t into out[derivative order][component]; past the end of
 * a file that ends at rest, the last row's pose with rates and accelerations 0. Allocates
 * nothing. */
trajectory_where trajectory_at(const double *rows, size_t n, double t, double out[3][6]);

#endif
