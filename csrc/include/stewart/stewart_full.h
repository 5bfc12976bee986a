/*
 * The full fidelity level's multibody model, for inspection (and for the FMU's state).
 * Bodies: 0 base (fixed), 1-6 cylinders, 7-12 pistons (leg k = 1..6 in that order), 13 platform
 * (with the payload; its frame at their joint centre of mass on principal axes). Joints:
 * 0 fixes the base; then per leg base Cardan, platform Cardan, cylindrical; then 6
 * actuator-length drivers (driver slot k-1 is leg k; multiplier = -F_k); then the 13
 * normalisations. mbs_joint_first_row gives each joint's rows in mbs_lambda.
 *
 * The mechanism's lengths are in units of stewart_model_length_unit(model) m, L0: the power of
 * two with max(base size, platform size, home_height) / L0 in (0.25, 0.5] (the radii, or the
 * farthest joints from each frame's origin: docs/geometry.md), 1 for the thesis
 * platform (so that the Newton tolerance means the same at every size). Masses are kept: in the
 * mechanism, forces are in units of L0 N, torques L0^2 N m, inertias L0^2 kg m^2, gravity
 * 1/L0 m/s^2.
 */
#ifndef STEWART_STEWART_FULL_H
#define STEWART_STEWART_FULL_H

#include "mbs/mbs.h"
#include "stewart/stewart.h"

#ifdef __cplusplus
extern "C" {
#endif

const mbs_model *stewart_model_mechanism(const stewart_model *model);
/* L0 [m], the mechanism's length unit (above); 0 if model is NULL. */
double stewart_model_length_unit(const stewart_model *model);
/* The state after the last full-level solve. */
const mbs_data *stewart_inverse_mechanism(const stewart_inverse *inverse);

#ifdef __cplusplus
}
#endif

#endif /* STEWART_STEWART_FULL_H */
