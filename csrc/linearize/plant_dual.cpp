// The plant's equations (plant/plant_bodies_impl.hpp, plant_equations_impl.hpp) instantiated for
// the dual scalars (and the residual form, which the linearisation alone uses), here rather than
// beside the double ones: in their translation unit the dual code made the compiler inline less
// of the plant's double code (14 % more instructions per step at full fidelity).
#include "plant/plant_bodies_impl.hpp"
#include "plant/plant_equations_impl.hpp"
#include "util/dual.hpp"

namespace stewart {
namespace plant {

STEWART_PLANT_BODIES_INSTANTIATE(Dual)
STEWART_PLANT_EQUATIONS_INSTANTIATE(Dual)
STEWART_PLANT_BODIES_INSTANTIATE(StateDual)
STEWART_PLANT_RESIDUAL_INSTANTIATE(StateDual)

}  // namespace plant
}  // namespace stewart
