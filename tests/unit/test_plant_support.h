/* Shared helpers of the plant (forward dynamics) tests: plants, and the energy of the moving
 * bodies computed here from the parameters and the bodies' motion (not by the library). */
#ifndef STEWART_TEST_PLANT_SUPPORT_H
#define STEWART_TEST_PLANT_SUPPORT_H

#include "stewart/stewart_plant.h"

/* A plant at the given fidelity and tolerances; fails the test if it cannot be made. */
stewart_plant *test_plant(const stewart_model *model, int fidelity, double rtol, double atol);

/* Kinetic and potential energy of the moving bodies (13 at full fidelity, the platform alone
 * when massless), from params' masses and inertias (payload_mass must be 0). */
void plant_energy(const stewart_params *params, const stewart_plant *plant, int fidelity,
                  double *kinetic, double *potential);

/* Steps and fails the test with the plant's message unless the status is STEWART_OK. */
void step_ok(stewart_plant *plant, double h, const double f0[6], const double f1[6],
             const double r0[6], const double r1[6]);

/* stewart_plant_step with the forces as arrays (rates both NULL: linear; one NULL: refused; f0
 * or f1 NULL: a NULL input), its output discarded. */
stewart_status plant_step_arrays(stewart_plant *plant, double h, const double f0[6],
                                 const double f1[6], const double r0[6], const double r1[6]);

/* The plant's saved state as its doubles (time, y, angles, forces, warnings, step hint): how
 * many, saved (stewart_plant_save, header dropped) and loaded (the plant's own header, then
 * count doubles: a count that is not plant_state_doubles() makes a wrong size). */
size_t plant_state_doubles(void);
void plant_save_doubles(const stewart_plant *plant, double *state);
stewart_status plant_load_doubles(stewart_plant *plant, const double *state, size_t count);

/* The largest violation of any leg joint as docs/model.md defines them, from the bodies' poses
 * and the platform pose alone: Cardan centres on a_k and on p + R b_k, cross arms perpendicular,
 * cylinder and piston on one axis [m, or dimensionless for the axis terms]. */
double leg_joint_error(const stewart_params *params, const double pose[6],
                       const stewart_plant_body bodies[STEWART_PLANT_BODIES]);

/* The largest difference [N or N m] between the base wrench out reports and minus the sum of
 * the base Cardans' reactions r (forces, and their moments about the base origin from the joint
 * centres of params' base circle, plus the Cardans' torques). */
double base_wrench_error(const stewart_params *params, const stewart_plant_reactions *r,
                         const stewart_plant_output *out);
/* The thesis platform with heavy legs (10 kg rods of 0.05 m radius), so that leg inertia
 * matters in a check. */
void heavy_legs(stewart_params *params);

#endif
