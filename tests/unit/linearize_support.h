/* What the linearisation's tests share (test_linearize.c, test_linearize_frames.c): the block
 * errors against central differences, and the inverse side's Jacobian against differences of the
 * inverse solver of platform_fixture.h. */
#ifndef STEWART_TEST_LINEARIZE_SUPPORT_H
#define STEWART_TEST_LINEARIZE_SUPPORT_H

#include "stewart/stewart_linearize.h"

/* Central-difference steps: the truncation error h^2 f'''/6 and the rounding error eps |f| / h
 * are both below 1e-9 of the derivatives at these steps (pose and rates of order 1, forces of
 * order 1e3 N, q_ddot affine in the forces). */
#define LINEARIZE_STEP_STATE 1e-5 /* m, rad, m/s, rad/s */
#define LINEARIZE_STEP_FORCE 1e-2 /* N */
#define LINEARIZE_STEP_ACCEL 1e-4 /* m/s2, rad/s2: forces and L_ddot are affine in them */

/* A block of a Jacobian (one group of rows by one group of columns of one unit each): the
 * largest |exact - difference| and the largest |exact|. */
typedef struct {
    double error, scale;
} block_error;
/* Adds one entry to the block. */
void block_add(block_error *e, double exact, double difference);
/* The block's error relative to its scale, where the rounding of the central difference
 * (16 eps |f| / h for values of magnitude |f|) is not counted: a block that is zero (or nearly)
 * is checked against that rounding alone. */
double block_relative(block_error e, double value_scale, double h);

/* A linearisation of the fixture's model at fidelity (fails the test if it cannot be made). */
stewart_linearize *linearize_make(int fidelity);

/* The worst block error of exact's Jacobian (rows L, L_dot, L_ddot, F, base force, base torque by
 * columns q, q_dot, q_ddot) against central differences of the fixture's inverse solver at
 * fidelity around pose. */
double inverse_jacobian_error(const stewart_linearize_inverse_output *exact,
                              const stewart_pose *pose, int fidelity);

#endif
