// The reduced equations for the plant's scalar, double (plant_equations_impl.hpp has the
// template definitions; linearize/plant_dual.cpp instantiates them for the dual scalar). The
// model they read is made in plant_api.cpp (dynamics_model), where the model's layout is known.
#include "plant/plant_equations_impl.hpp"

namespace stewart {
namespace plant {

STEWART_PLANT_EQUATIONS_INSTANTIATE(double)

}  // namespace plant
}  // namespace stewart
