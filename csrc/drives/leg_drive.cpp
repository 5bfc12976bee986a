// A leg's drive: its parameters per leg (the friction and screw laws are inline in the header).
#include "drives/leg_drive.hpp"

#include <algorithm>

namespace stewart {

LegDrive leg_drive(const stewart_params &p, int k) {
    LegDrive d;
    if (!(p.screw_lead[k] > 0)) return d;
    const double N = p.gear_ratio[k];
    d.motor_per_leg = 2.0 * M_PI * N / p.screw_lead[k];
    d.inertia = p.rotor_inertia[k] + p.screw_inertia[k] / (N * N);
    d.efficiency = p.screw_efficiency[k];
    d.back_efficiency = p.screw_back_efficiency[k];
    d.torque_constant = p.torque_constant[k];
    d.resistance = p.winding_resistance[k];
    d.inductance = p.winding_inductance[k];
    d.coulomb = p.coulomb_friction[k];
    d.breakaway = std::max(p.stribeck_friction[k], p.coulomb_friction[k]);
    d.stribeck_speed = p.stribeck_speed[k];
    d.viscous = p.viscous_friction[k];
    return d;
}

bool has_drives(const stewart_params &p) {
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (p.screw_lead[k] > 0) return true;
    return false;
}

}  // namespace stewart
