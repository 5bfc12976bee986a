#include "linearize/driven_jacobian.hpp"

#include <cmath>
#include <cstring>

#include <Eigen/LU>

#include "drives/plant_drive.hpp"
#include "linearize/plant_jacobian.hpp"

namespace stewart {
namespace lin {

namespace {

// The partial derivatives of one leg's drive force F = e (c k_t i - m_r L_ddot) - friction(L_dot)
// + stop(L, L_dot) (plant_drive_rhs.cpp), e the screw's factor for the power flow's direction.
struct LegLaw {
    double wrt_length = 0, wrt_rate = 0, wrt_accel = 0, wrt_current = 0;
    bool kink = false;
};

// d stop_force / dL and / dL_dot on the branch plant_drive_rhs.cpp's stop_force takes; kink at
// a stroke end or where the damper meets its limit (+-spring).
void stop_partials(const plant::DriveModel &dm, int k, double L, double v, LegLaw &law) {
    const double k_s = dm.stop_stiffness[k], d_s = dm.stop_damping[k];
    if (L == dm.stop_max[k] || L == dm.stop_min[k]) law.kink |= k_s > 0;
    double depth, speed, side;  // into the stop; side: d depth / dL = d speed / dL_dot
    if (L > dm.stop_max[k]) {
        depth = L - dm.stop_max[k], speed = v, side = 1;
    } else if (L < dm.stop_min[k]) {
        depth = dm.stop_min[k] - L, speed = -v, side = -1;
    } else {
        return;
    }
    const double spring = k_s * depth, damper = d_s * speed;
    double push_depth = k_s, push_speed = d_s;                  // push = spring + damper
    if (damper > spring) push_depth = 2 * k_s, push_speed = 0;  // push = 2 spring
    if (damper < -spring) push_depth = 0, push_speed = 0;       // push = 0
    law.kink |= std::fabs(damper) == spring && spring > 0;
    // force = -push beyond stop_max, +push below stop_min: -side push
    law.wrt_length += -side * push_depth * side;
    law.wrt_rate += -side * push_speed * side;
}

// d friction_force / dv with the smoothing speed vs (> 0): (sliding s + b v)'.
double friction_slope(const LegDrive &d, double v, double vs) {
    const double root = std::sqrt(v * v + vs * vs);
    const double s = v / root, s_slope = vs * vs / (root * root * root);
    double sliding = d.coulomb, sliding_slope = 0;
    if (d.breakaway > d.coulomb) {  // friction_force's Stribeck term, cut where it is
        const double x = v / d.stribeck_speed, peak = d.breakaway - d.coulomb;
        if (!(x * x > 50.0 && peak < 256.0 * d.coulomb)) {
            const double term = peak * std::exp(-x * x);
            sliding += term;
            sliding_slope = -2.0 * x / d.stribeck_speed * term;
        }
    }
    return sliding_slope * s + sliding * s_slope + d.viscous;
}

// Leg k's law's partial derivatives at the driven evaluation e (its ideal and nut forces, leg
// speed); false if the power flow's direction the plant took is not that of the ideal force.
bool leg_law(const plant::DriveModel &dm, int k, const plant::Evaluation &e, double L,
             LegLaw &law) {
    const LegDrive &d = dm.legs[k];
    const double vs = dm.smoothing_speed, v = e.drive.length_rate[k];
    const double ideal = e.drive.ideal_force[k], nut = e.drive.nut_force[k];
    const double root = std::sqrt(v * v + vs * vs);
    const double s = v / root, s_slope = vs * vs / (root * root * root);
    const double forward_slope = d.efficiency - 1.0;                           // de/dx, x > 0
    const double back_slope = -(1.0 / d.back_efficiency - 1.0);                // de/dx, x < 0
    const bool lossy = screw_force_factor(d, s) != screw_force_factor(d, -s);  // the plant's test
    const double sign = ideal >= 0 ? 1.0 : -1.0, x = sign * s;
    const double factor = screw_force_factor(d, x);
    if (lossy && std::fabs(nut - factor * ideal) > 1e-12 * (std::fabs(nut) + std::fabs(ideal)))
        return false;  // the plant's last pass took this leg as lossless: its flow flips
    double e_value = factor, e_slope;  // e and de/dx at the point
    if (x > 0) {
        e_slope = forward_slope;
    } else if (x < 0) {
        e_slope = back_slope;
    } else {  // at rest: the slope steps from back_slope to forward_slope
        e_slope = 0.5 * (forward_slope + back_slope);
        law.kink |= ideal != 0 && forward_slope != back_slope;
    }
    if (lossy && ideal == 0) {  // the power flow's turn: e steps from e(-s) to e(s)
        e_value = 0.5 * (screw_force_factor(d, s) + screw_force_factor(d, -s));
        law.kink = true;
    }
    law.wrt_accel = -e_value * dm.reflected_mass[k];
    law.wrt_current = e_value * d.motor_per_leg * d.torque_constant;
    law.wrt_rate = e_slope * sign * s_slope * ideal - friction_slope(d, v, vs);
    stop_partials(dm, k, L, v, law);
    return true;
}

// The windings' current rows (voltage input): di/dt = (V - R i - k_t c L_dot) / L_w on a leg
// with an inductance, zero on the others.
void winding_rows(const plant::DynamicsModel &driven, const double voltage[STEWART_LEGS],
                  const plant::Evaluation &e, const PlantJacobian &p, DrivenJacobian &out) {
    plant::winding_rates(driven, voltage, e, out.state_rate + 12);
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const LegDrive &d = driven.drives.legs[k];
        if (!(d.inductance > 0)) continue;
        const double back_emf = d.torque_constant * d.motor_per_leg / d.inductance;
        for (int j = 0; j < 12; ++j) out.A[12 + k][j] = -back_emf * p.length_rate_wrt_state[k][j];
        out.A[12 + k][12 + k] = -d.resistance / d.inductance;
        out.B[12 + k][k] = 1.0 / d.inductance;
    }
}

}  // namespace

bool driven_jacobian(const plant::DynamicsModel &force_model, const plant::DynamicsModel &driven,
                     const Frames &f, const double q[6], const double q_dot[6],
                     const double input[STEWART_LEGS], const double current[STEWART_LEGS],
                     DrivenJacobian &out, Failure &why) {
    const plant::DriveModel &dm = driven.drives;
    const double no_accel[6] = {0};
    Motion m = motion_of_pose_in_order<double>(f.rotation_order, q, q_dot, no_accel);
    if (!f.identity) m = platform_motion(f, m);
    plant::Evaluation e;
    e.winding_current = current;
    if (!plant::twist_rate(driven, m, input, e)) {
        why.fault = e.fault;
        why.leg = e.fault_leg;
        return false;
    }
    // The force-driven plant at the drives' forces: its q_ddot is the driven one's.
    PlantJacobian p;
    if (!plant_jacobian(force_model, f, q, q_dot, e.drive.leg_force, p, why)) return false;
    Dual L[STEWART_LEGS], L_dot[STEWART_LEGS], L_ddot[STEWART_LEGS];
    if (!leg_lengths(force_model.legs, f, q, q_dot, p.q_ddot, L, L_dot, L_ddot, why)) return false;

    using Matrix6 = Eigen::Matrix<double, 6, 6>;
    using Matrix6x12 = Eigen::Matrix<double, 6, 12>;
    // dF = force_x dx + force_a dq_ddot + force_u du + force_i di_state
    Matrix6x12 force_x = Matrix6x12::Zero();
    Matrix6 force_a = Matrix6::Zero(), force_u = Matrix6::Zero(), force_i = Matrix6::Zero();
    out = DrivenJacobian();
    for (int k = 0; k < STEWART_LEGS; ++k) {
        LegLaw law;
        if (!leg_law(dm, k, e, p.length[k], law)) {
            why.unsettled_leg = k;
            return false;
        }
        if (law.kink) out.not_smooth_legs |= 1 << k;
        const LegDrive &d = dm.legs[k];
        const bool state_current = dm.input == STEWART_PLANT_INPUT_VOLTAGE && d.inductance > 0;
        double rate = law.wrt_rate;  // the current's own dependence on L_dot folded in
        if (dm.input == STEWART_PLANT_INPUT_CURRENT) {
            force_u(k, k) = law.wrt_current;
        } else if (state_current) {
            force_i(k, k) = law.wrt_current;
        } else {  // i = (V - k_t c L_dot) / R
            force_u(k, k) = law.wrt_current / d.resistance;
            rate -= law.wrt_current * d.torque_constant * d.motor_per_leg / d.resistance;
        }
        for (int j = 0; j < 12; ++j)
            force_x(k, j) = law.wrt_length * p.length_wrt_state[k][j] +
                            rate * p.length_rate_wrt_state[k][j] +
                            law.wrt_accel * L_ddot[k].derivatives()[j];
        for (int a = 0; a < 6; ++a) force_a(k, a) = law.wrt_accel * L_ddot[k].derivatives()[12 + a];
        out.leg_force[k] = e.drive.leg_force[k];
    }
    // dq_ddot = P_x dx + P_F dF: (I - P_F force_a) dq_ddot = P_x dx + P_F (force_x dx + ...).
    const Eigen::Map<const Eigen::Matrix<double, 6, 12, Eigen::RowMajor>> P_x(
        &p.q_ddot_wrt_state[0][0]);
    const Eigen::Map<const Eigen::Matrix<double, 6, 6, Eigen::RowMajor>> P_F(
        &p.q_ddot_wrt_force[0][0]);
    const Eigen::PartialPivLU<Matrix6> loop(Matrix6::Identity() - P_F * force_a);
    const Matrix6x12 accel_x = loop.solve(P_x + P_F * force_x);
    const Matrix6 accel_u = loop.solve(P_F * force_u), accel_i = loop.solve(P_F * force_i);

    out.states = dm.inductive ? 18 : 12;
    for (int i = 0; i < 6; ++i) {
        out.state_rate[i] = q_dot[i];
        out.state_rate[6 + i] = p.q_ddot[i];
        out.A[i][6 + i] = 1;
        for (int j = 0; j < 12; ++j) out.A[6 + i][j] = accel_x(i, j);
        for (int k = 0; k < STEWART_LEGS; ++k) {
            out.B[6 + i][k] = accel_u(i, k);
            if (dm.inductive) out.A[6 + i][12 + k] = accel_i(i, k);
        }
    }
    if (dm.inductive) winding_rows(driven, input, e, p, out);
    std::memcpy(out.length, p.length, sizeof out.length);
    std::memcpy(out.length_rate, p.length_rate, sizeof out.length_rate);
    std::memcpy(out.length_wrt_state, p.length_wrt_state, sizeof out.length_wrt_state);
    std::memcpy(out.length_rate_wrt_state, p.length_rate_wrt_state,
                sizeof out.length_rate_wrt_state);
    return true;
}

}  // namespace lin
}  // namespace stewart
