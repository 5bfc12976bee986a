// The leg bodies for the plant's scalar, double (plant_bodies_impl.hpp has the definitions;
// linearize/plant_dual.cpp instantiates them for the dual scalar).
#include "plant/plant_bodies_impl.hpp"

namespace stewart {
namespace plant {

STEWART_PLANT_BODIES_INSTANTIATE(double)

}  // namespace plant
}  // namespace stewart
