// A leg's drive: its parameters per leg, friction, and the screw's efficiency law.
#include "drives/leg_drive.hpp"

#include <algorithm>
#include <cmath>

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

double friction_force(const LegDrive &d, double v, double smoothing_speed) {
    const double s = smoothing_speed > 0 ? v / std::sqrt(v * v + smoothing_speed * smoothing_speed)
                     : v > 0             ? 1.0
                     : v < 0             ? -1.0
                                         : 0.0;
    double sliding = d.coulomb;
    if (d.breakaway > d.coulomb) {  // the Stribeck peak (stewart_params_check: its speed > 0)
        const double x = v / d.stribeck_speed;
        sliding += (d.breakaway - d.coulomb) * std::exp(-x * x);
    }
    return sliding * s + d.viscous * v;
}

double screw_motor_torque(const LegDrive &d, double nut_force, double omega) {
    const double ideal = nut_force / d.motor_per_leg;  // lossless: tau omega = F v
    return ideal * omega < 0 ? ideal * d.back_efficiency : ideal / d.efficiency;
}

}  // namespace stewart
