// The plant's right-hand side when its legs are driven by motor currents or voltages
// (docs/forward-dynamics.md, "Drives"). Per leg k, with c = 2 pi N / lead (motor angle per leg
// length), J the motor-side inertia, m_r = J c^2 its reflected mass, and L_ddot = j_k nu_dot + a_k
// (j_k = (n, arm x n) the leg Jacobian's row, a_k = j_k_dot nu its velocity product):
//   the screw's torque from the motor side, as a force:  F_i = c k_t i - m_r L_ddot
//   the nut's force on the leg:                          F_nut = e(F_i, L_dot) F_i
//   the leg's force on the mechanism:                    F_k = F_nut - friction(L_dot) + stop(L, L_dot)
// so the reduced equations M nu_dot = rhs + sum j_k^T F_k become
//   (M + sum e_k m_r j_k^T j_k) nu_dot = rhs + sum j_k^T (e_k (c k_t i - m_r a_k) - friction + stop):
// the rotor and screw inertia enter exactly, through the leg length. The efficiency e_k depends on
// the sign of F_i, so on nu_dot: the signs are found by iterating on them (a changed sign is
// solved again), starting from the sign of c k_t i - m_r a_k.
#include <cmath>

#include "drives/plant_drive.hpp"
#include "plant/plant_equations.hpp"
#include "util/message.hpp"

namespace stewart {
namespace plant {

namespace {

constexpr int kMaxSignPasses = 8;  // the efficiencies' sign pattern, solved again at most so often

// The end stop's force on the leg beyond [stop_min, stop_max]: a spring k delta and a damper
// d L_dot limited to +-k delta, so that the force is continuous where the leg meets the stop
// (an explicit integrator steps over a jump of d L_dot only by tiny steps) and never pulls.
inline double stop_force(const DriveModel &d, int k, double L, double L_dot) {
    double depth, speed;  // into the stop
    if (L > d.stop_max[k]) {
        depth = L - d.stop_max[k];
        speed = L_dot;
    } else if (L < d.stop_min[k]) {
        depth = d.stop_min[k] - L;
        speed = -L_dot;
    } else {
        return 0.0;
    }
    const double spring = d.stop_stiffness[k] * depth;
    const double damper = std::fmax(-spring, std::fmin(spring, d.stop_damping[k] * speed));
    const double push = spring + damper;
    return L > d.stop_max[k] ? -push : push;
}

// What a leg's drive puts in the equations, apart from the efficiency.
struct LegDriveRow {
    double j[6];       // the leg Jacobian's row
    double bias;       // c k_t i - m_r a_k: F_i at zero twist rate [N]
    double passive;    // stop - friction [N]
    double smoothed;   // s(L_dot)
    double reflected;  // m_r [kg]
    double a;          // a_k [m/s2]
    bool lossy;        // the efficiency differs with the sign of F_i here
};

}  // namespace

stewart_status drive_model(const stewart_params &p, const stewart_plant_options &o, DriveModel &d,
                           char *msg, size_t size) {
    d = DriveModel();
    if (o.input == STEWART_PLANT_INPUT_FORCE) return STEWART_OK;
    const char *input = o.input == STEWART_PLANT_INPUT_CURRENT ? "current" : "voltage";
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const int leg = k + 1;
        auto refuse = [&](const char *what, double value, const char *need) {
            return set_message(msg, size, STEWART_ERR_PARAMETER,
                               "input %s needs a drive on every leg: %s[%d] = %g %s", input, what,
                               leg, value, need);
        };
        if (!(p.screw_lead[k] > 0)) return refuse("screw_lead", p.screw_lead[k], "must be > 0");
        if (!(p.gear_ratio[k] > 0)) return refuse("gear_ratio", p.gear_ratio[k], "must be > 0");
        if (!(p.torque_constant[k] > 0))
            return refuse("torque_constant", p.torque_constant[k], "must be > 0");
        if (!(p.screw_efficiency[k] > 0 && p.screw_efficiency[k] <= 1))
            return refuse("screw_efficiency", p.screw_efficiency[k], "must be in (0, 1]");
        if (!(p.screw_back_efficiency[k] > 0 && p.screw_back_efficiency[k] <= 1))
            return refuse("screw_back_efficiency", p.screw_back_efficiency[k],
                          "must be in (0, 1] (a self-locking screw, 0, holds the leg in a stuck "
                          "mode the plant does not model)");
        if (p.stribeck_friction[k] > p.coulomb_friction[k] && !(p.stribeck_speed[k] > 0))
            return refuse("stribeck_speed", p.stribeck_speed[k],
                          "must be > 0 with stribeck_friction above coulomb_friction");
        if (o.input == STEWART_PLANT_INPUT_VOLTAGE) {
            if (!(p.winding_resistance[k] > 0))
                return refuse("winding_resistance", p.winding_resistance[k], "must be > 0");
            if (p.winding_inductance[k] > 0) d.inductive = true;
        }
        d.legs[k] = leg_drive(p, k);
        d.reflected_mass[k] = reflected_mass(d.legs[k]);
        d.stop_min[k] = p.stroke_min[k];
        d.stop_max[k] = p.stroke_max[k];
        d.stop_stiffness[k] = p.end_stop_stiffness[k];
        d.stop_damping[k] = p.end_stop_damping[k];
    }
    d.input = o.input;
    d.smoothing_speed = o.smoothing_speed;
    return STEWART_OK;
}

void winding_rates(const DynamicsModel &d, const double voltage[STEWART_LEGS], const Evaluation &e,
                   double rates[STEWART_LEGS]) {
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const LegDrive &drive = d.drives.legs[k];
        const double omega = drive.motor_per_leg * e.drive.length_rate[k];
        rates[k] = drive.inductance > 0 ? (voltage[k] - drive.resistance * e.drive.current[k] -
                                           drive.torque_constant * omega) /
                                              drive.inductance
                                        : 0.0;
    }
}

namespace {

// Each leg's drive row at the motion m (its Jacobian row, bias, passive force, smoothed
// direction, reflected mass, velocity product, whether lossy), the power flow's first guess of
// its sign, and e's drive values that do not depend on the twist rate.
[[gnu::always_inline]] inline void drive_rows(const DynamicsModel &d, const Motion &m,
                                              const double input[STEWART_LEGS], Evaluation &e,
                                              LegDriveRow rows[STEWART_LEGS],
                                              int sign[STEWART_LEGS]) {
    const DriveModel &dm = d.drives;
    const double vs = dm.smoothing_speed;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const LegConfiguration &leg = e.legs[k];
        const LegDrive &drive = dm.legs[k];
        LegDriveRow &r = rows[k];
        const Vec3 arm_n = leg.arm.cross(leg.n);
        for (int i = 0; i < 3; ++i) r.j[i] = leg.n[i], r.j[3 + i] = arm_n[i];
        const Vec3 P_dot = m.velocity + m.omega.cross(leg.arm);
        const double L_dot = leg.n.dot(P_dot);
        r.a = leg.n.dot(m.omega.cross(m.omega.cross(leg.arm))) +
              (P_dot.squaredNorm() - L_dot * L_dot) * leg.inverse_length;
        const double omega = drive.motor_per_leg * L_dot;
        const double current = dm.input == STEWART_PLANT_INPUT_CURRENT ? input[k]
                               : drive.inductance > 0
                                   ? e.winding_current[k]  // a state
                                   : (input[k] - drive.torque_constant * omega) / drive.resistance;
        r.reflected = dm.reflected_mass[k];
        r.bias = drive.motor_per_leg * drive.torque_constant * current - r.reflected * r.a;
        const double friction = friction_force(drive, L_dot, vs);
        const double stop = stop_force(dm, k, leg.length, L_dot);
        r.passive = stop - friction;
        r.smoothed = smooth_sign(L_dot, vs);
        r.lossy = screw_force_factor(drive, r.smoothed) != screw_force_factor(drive, -r.smoothed);
        sign[k] = r.bias >= 0 ? 1 : -1;
        e.drive.current[k] = current;
        e.drive.length_rate[k] = L_dot;
        e.drive.friction[k] = friction;
        e.drive.stop_force[k] = stop;
    }
}

// The twist rate nu_dot of M nu_dot = rhs + the legs' drive forces, each leg's screw efficiency
// (factor) taken for the direction of its power flow, solved again while a lossy leg's
// direction changes. The last pass (after kMaxSignPasses unsettled ones) takes the legs whose
// direction still flips as lossless (sign 0): at the turn of its power flow a leg's loss is then
// left out for this evaluation, and no energy is made. e's ideal forces from the last pass.
[[gnu::always_inline]] inline void solve_power_flow(const DriveModel &dm, const double M[6][6],
                                                    const double rhs[6],
                                                    const LegDriveRow rows[STEWART_LEGS],
                                                    int sign[STEWART_LEGS], Evaluation &e,
                                                    double nu_dot[6], double factor[STEWART_LEGS]) {
    bool any_lossy = false;
    for (int k = 0; k < STEWART_LEGS; ++k) any_lossy |= rows[k].lossy;
    double weight[STEWART_LEGS], j[STEWART_LEGS][6];
    for (int k = 0; k < STEWART_LEGS; ++k)
        for (int i = 0; i < 6; ++i) j[k][i] = rows[k].j[i];
    for (int pass = 0; pass <= kMaxSignPasses; ++pass) {
        double b[6];
        for (int i = 0; i < 6; ++i) b[i] = rhs[i];
        for (int k = 0; k < STEWART_LEGS; ++k) {
            const LegDriveRow &r = rows[k];
            factor[k] = screw_force_factor(dm.legs[k], sign[k] * r.smoothed);
            weight[k] = factor[k] * r.reflected;
            const double force = factor[k] * r.bias + r.passive;
            for (int i = 0; i < 6; ++i) b[i] += r.j[i] * force;
        }
        solve_with_rank_ones(M, b, j, weight, nu_dot);
        bool settled = true;
        for (int k = 0; k < STEWART_LEGS; ++k) {
            const LegDriveRow &r = rows[k];
            double L_ddot = r.a;
            for (int i = 0; i < 6; ++i) L_ddot += r.j[i] * nu_dot[i];
            const double ideal = r.bias + r.reflected * r.a - r.reflected * L_ddot;
            e.drive.ideal_force[k] = ideal;
            const int found = ideal >= 0 ? 1 : -1;
            if (found != sign[k] && sign[k] != 0 && r.lossy && pass < kMaxSignPasses) {
                sign[k] = pass + 1 < kMaxSignPasses ? found : 0;
                settled = false;
            }
        }
        if (settled || !any_lossy) break;
    }
}

}  // namespace

bool driven_twist_rate(const DynamicsModel &d, const Motion &m, const double input[STEWART_LEGS],
                       Evaluation &e) {
    static const double zero[STEWART_LEGS] = {0, 0, 0, 0, 0, 0};
    double M[6][6], rhs[6];
    if (!reduced_equations(d, m, zero, e, M, rhs)) return false;
    LegDriveRow rows[STEWART_LEGS];
    int sign[STEWART_LEGS];
    drive_rows(d, m, input, e, rows, sign);
    double nu_dot[6], factor[STEWART_LEGS];
    solve_power_flow(d.drives, M, rhs, rows, sign, e, nu_dot, factor);
    Vec3 legs_force = Vec3::Zero(), legs_moment = Vec3::Zero();
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const double nut = factor[k] * e.drive.ideal_force[k];
        e.drive.nut_force[k] = nut;
        e.drive.leg_force[k] = nut + rows[k].passive;
        const Vec3 axial = e.drive.leg_force[k] * e.legs[k].n;
        legs_force += axial;
        legs_moment += e.legs[k].arm.cross(axial);
    }
    e.kept.legs_force = legs_force;  // the base wrench of massless legs (base_wrench)
    e.kept.legs_moment = legs_moment;
    for (int i = 0; i < 6; ++i) e.twist_rate[i] = nu_dot[i];
    e.fault = LegFault::None;
    e.fault_leg = -1;
    return true;
}

}  // namespace plant
}  // namespace stewart
