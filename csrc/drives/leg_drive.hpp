// The drive of one leg: motor, gear and screw, friction on the leg's axis (docs/drives.md).
// Shared by the inverse (sizing: the torque, current and voltage a motion needs) and the plant
// (the motion a current or voltage gives), so both use one law.
//
// Conventions: the motor angle grows as the leg extends, theta = 2 pi N L / lead, and a positive
// torque extends the leg. The screw's efficiency acts on the axial force the nut transmits (the
// leg force plus the leg-side friction): forward (tau = F lead / (2 pi N eta)) when the motor
// drives the load, backward (tau = F lead eta_back / (2 pi N)) when the load drives the motor.
// Rotor and screw inertia act on the motor's side (the screw's through the gear, / N^2).
#pragma once

#include <cmath>

#include "stewart/stewart.h"

namespace stewart {

struct LegDrive {
    double motor_per_leg = 0;    // motor angle per leg length, 2 pi N / lead [rad/m]; 0: no drive
    double inertia = 0;          // at the motor: rotor + screw / N^2 [kg m^2]
    double efficiency = 1;       // motor drives the load
    double back_efficiency = 1;  // load drives the motor
    double torque_constant = 0;  // [N m/A] = back-EMF constant [V s/rad]
    double resistance = 0;       // [ohm]
    double inductance = 0;       // [H]
    double coulomb = 0;          // sliding friction [N]
    double breakaway = 0;        // friction at rest, at least coulomb [N]
    double stribeck_speed = 0;   // [m/s]
    double viscous = 0;          // [N s/m]
};

// Leg k's drive (0-based) from the parameters; motor_per_leg 0 if the leg has none.
LegDrive leg_drive(const stewart_params &p, int k);

// 1 if any leg has a drive (screw_lead > 0).
bool has_drives(const stewart_params &p);

// The leg's inertia seen at the leg: inertia (2 pi N / lead)^2 [kg].
inline double reflected_mass(const LegDrive &d) {
    return d.inertia * d.motor_per_leg * d.motor_per_leg;
}

// Friction on the leg's axis at leg speed v, opposing it [N]:
// (F_c + (F_s - F_c) exp(-(v/v_s)^2)) s(v) + b v, where s(v) = sign(v) (0 at rest) if
// smoothing_speed is 0, else v / sqrt(v^2 + smoothing_speed^2).
inline double friction_force(const LegDrive &d, double v, double smoothing_speed) {
    const double s = smoothing_speed > 0 ? v / std::sqrt(v * v + smoothing_speed * smoothing_speed)
                     : v > 0             ? 1.0
                     : v < 0             ? -1.0
                                         : 0.0;
    double sliding = d.coulomb;
    if (d.breakaway > d.coulomb) {  // the Stribeck peak (stewart_params_check: its speed > 0)
        const double x = v / d.stribeck_speed, peak = d.breakaway - d.coulomb;
        // Far past the peak its term is below 2^-60 coulomb (exp(-50) 256 < 2^-60), which
        // rounds away in the sum: the same bits without the exp.
        if (!(x * x > 50.0 && peak < 256.0 * d.coulomb)) sliding += peak * std::exp(-x * x);
    }
    return sliding * s + d.viscous * v;
}

// The motor torque that makes the nut push the leg with axial force nut_force (> 0 extends) at
// motor speed omega, through the screw's efficiency in the direction power flows. At rest the
// forward efficiency is taken (the larger torque: the one that starts a motion).
inline double screw_motor_torque(const LegDrive &d, double nut_force, double omega) {
    const double ideal = nut_force / d.motor_per_leg;  // lossless: tau omega = F v
    return ideal * omega < 0 ? ideal * d.back_efficiency : ideal / d.efficiency;
}

// The motor torque that moves the leg at speed v and acceleration a against the leg force
// leg_force (> 0 pushes the platform away): the drive's inertia, J (2 pi N / lead) a, plus the
// screw's torque for the leg force and the friction at v (exact sign: 0 at rest).
inline double drive_torque(const LegDrive &d, double leg_force, double v, double a) {
    return d.inertia * d.motor_per_leg * a +
           screw_motor_torque(d, leg_force + friction_force(d, v, 0.0), d.motor_per_leg * v);
}

// d friction_force / dv at exact sign (smoothing_speed 0), v != 0; at rest the Stribeck term's
// slope vanishes and only the viscous one is left (the sign's step has no slope).
inline double friction_slope(const LegDrive &d, double v) {
    double slope = d.viscous;
    if (v != 0 && d.breakaway > d.coulomb) {
        const double x = v / d.stribeck_speed;
        const double peak = d.breakaway - d.coulomb;
        slope -= peak * std::exp(-x * x) * 2.0 * std::fabs(x) / d.stribeck_speed;
    }
    return slope;
}

// d drive_torque / dt along a motion: the leg force's rate force_rate, the leg's speed v,
// acceleration a and jerk. The power flow's direction held where drive_torque takes it (at a
// change of direction the torque steps; this is the rate on the side drive_torque is on).
inline double drive_torque_rate(const LegDrive &d, double leg_force, double force_rate, double v,
                                double a, double jerk) {
    const double nut = leg_force + friction_force(d, v, 0.0);
    const double nut_rate = force_rate + friction_slope(d, v) * a;
    const double ideal = nut / d.motor_per_leg, omega = d.motor_per_leg * v;
    const double through = ideal * omega < 0 ? d.back_efficiency : 1.0 / d.efficiency;
    return d.inertia * d.motor_per_leg * jerk + nut_rate / d.motor_per_leg * through;
}

}  // namespace stewart
