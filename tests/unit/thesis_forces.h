/* The test oracle for the full level's forces: the thesis' formulation on a second mechanism.
 * Built from the library's internals (tests/unit/thesis_forces.cpp), for the tests only. */
#ifndef STEWART_TEST_THESIS_FORCES_H
#define STEWART_TEST_THESIS_FORCES_H

#include "stewart/stewart.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Actuator forces the thesis' way, on a second mechanism driven by the 7 platform coordinates:
 * the platform wrench from the pose drivers' multipliers, mapped to leg forces by virtual
 * power as a square 6 x 6 solve. Allocates: for checks, not for a stepping loop. The pose is
 * checked as stewart_inverse_solve checks it with the default options (finite inputs, reachable, leg
 * Jacobian condition number <= singular_condition, else STEWART_ERR_SINGULAR), and every force
 * must come out finite; force is written only on STEWART_OK. */
stewart_status stewart_thesis_forces(const stewart_params *params, const stewart_pose *pose,
                                     double force[STEWART_LEGS], char *message, size_t size);

#ifdef __cplusplus
}
#endif

#endif
