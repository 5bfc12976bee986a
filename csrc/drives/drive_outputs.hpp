// The inverse's drive columns (motor angle, speed, torque, current, voltage, power, limit
// flags) from its lengths, rates, accelerations and forces (docs/drives.md, "Sizing").
#pragma once

#include <cstddef>

#include "drives/leg_drive.hpp"
#include "stewart/stewart_batch.h"
#include "stewart/stewart_linearize.h"

namespace stewart {

// Fills out's drive columns, leg by leg (zeros on a leg without a drive), from out.lengths
// (the readings) and out.force; current_rate 0 (one pose: the current's rate is not known).
void fill_drive_outputs(const LegDrive (&drive)[STEWART_LEGS], const stewart_params &p,
                        stewart_inverse_output &out);

// Bit k set: |value[k]| above limit[k] > 0.
int legs_over(const double (&value)[STEWART_LEGS], const double (&limit)[STEWART_LEGS]);

// Every drive column finite (a huge force through a tiny torque constant overflows).
bool drive_outputs_finite(const stewart_inverse_output &out);

// Zeros in the drive columns of batch rows [first, last) (a model without drives).
void batch_drive_zeros(const stewart_inverse_batch_outputs &out, size_t first, size_t last);

// Batch row j's drive columns from its length, length_rate, length_accel and force columns
// (which must be there); false, and nothing written, if one is not finite.
bool batch_drive_row(const LegDrive (&drive)[STEWART_LEGS], const stewart_params &p,
                     const stewart_inverse_batch_outputs &out, size_t j);

// stewart_inverse_batch_current_rates on checked arguments (t finite and increasing): the first
// row whose rates, voltages or powers overflow (times too close for the currents' change), n if
// none.
size_t trajectory_current_rates(const LegDrive (&drive)[STEWART_LEGS], const stewart_params &p,
                                size_t n, const double *t,
                                const stewart_inverse_batch_outputs &out);

// Row j's current rates (0 on a leg without a drive) into its current_rate, voltage (with
// L dI/dt), electrical_power and voltage_max_legs; false if one of them is not finite.
bool set_current_rates(const LegDrive (&drive)[STEWART_LEGS], const stewart_params &p,
                       const stewart_inverse_batch_outputs &out, size_t j,
                       const double (&rate)[STEWART_LEGS]);

// stewart_inverse_batch_current_rates_from_jerks on checked arguments, lin at the inverse's
// fidelity (massless for the kinematic level, whose forces are 0: forces false).
stewart_status jerk_current_rates(const LegDrive (&drive)[STEWART_LEGS], const stewart_params &p,
                                  stewart_linearize *lin, bool forces, size_t n, const double *q,
                                  const double *q_dot, const double *q_ddot, const double *q_dddot,
                                  const stewart_inverse_batch_outputs &out, char *msg, size_t size);

}  // namespace stewart
