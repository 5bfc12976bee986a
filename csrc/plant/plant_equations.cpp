// The reduced equations for the plant's scalar, double (plant_equations_impl.hpp has the
// template definitions; linearize/plant_dual.cpp instantiates them for the dual scalar), and the
// model they read.
#include "plant/plant_equations_impl.hpp"

#include "model.hpp"

namespace stewart {
namespace fd {

DynamicsModel dynamics_model(const stewart_model &model, int fidelity) {
    DynamicsModel d;
    const stewart_params &p = model.params;
    const FullLayout &l = model.full_layout;
    d.legs.base_points = model.geometry.base_points;
    d.legs.platform_points = model.geometry.platform_points;
    d.legs.base_arm = l.base_arm;
    d.legs.platform_arm = l.platform_arm;
    d.legs.cylinder_com = p.cylinder_com;
    d.legs.piston_com = p.piston_com;
    d.legs.min_length = model.geometry.min_length;
    d.legs.min_cardan_sin = 1e-9;
    d.with_legs = fidelity == STEWART_FULL;
    d.platform_mass = model.platform.mass;
    d.platform_com = model.platform.com;
    d.platform_inertia = model.platform.inertia;
    d.platform_inertia_inverse = model.platform.inertia.inverse();
    d.cylinder_mass = p.cylinder_mass;
    d.piston_mass = p.piston_mass;
    d.cylinder_inertia = Vec3(p.cylinder_inertia);
    d.piston_inertia = Vec3(p.piston_inertia);
    d.gravity = model.gravity;
    return d;
}

STEWART_PLANT_EQUATIONS_INSTANTIATE(double)

}  // namespace fd
}  // namespace stewart
