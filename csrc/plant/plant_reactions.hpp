// Forward dynamics, joint reactions: each leg's two Cardans and its cylindrical joint, from the
// Newton-Euler equations of its two bodies with their motion known.
#pragma once

#include "plant/plant_equations.hpp"
#include "stewart/stewart_plant.h"

namespace stewart {
namespace plant {

// The reactions of leg k (conventions in stewart_plant.h). Bodies: the 13 of body_motions, with
// accelerations; force: the actuator force of the leg. False if the 12 x 12 system is singular.
bool leg_reactions(const DynamicsModel &d, int k, const LegConfiguration &leg,
                   const Motion bodies[13], double force, stewart_plant_reactions &out);

}  // namespace plant
}  // namespace stewart
