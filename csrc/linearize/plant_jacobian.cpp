#include "linearize/plant_jacobian.hpp"

#include <Eigen/Cholesky>

namespace stewart {
namespace lin {

namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

// The six values of v, each the variable of direction first + i.
void seed(const double v[6], int first, StateDual out[6]) {
    for (int i = 0; i < 6; ++i) out[i] = StateDual(v[i], StateDualDerivatives::Unit(first + i));
}

}  // namespace

bool plant_jacobian(const fd::DynamicsModel &d, const double q[6], const double q_dot[6],
                    const double force[STEWART_LEGS], PlantJacobian &out, Failure &why) {
    // The twist rate nu_dot in plain numbers: M nu_dot = rhs, the plant's own equations.
    const double no_accel[6] = {0};
    const Motion m = motion_of_pose<double>(q, q_dot, no_accel);
    fd::Evaluation e;
    Matrix6 M;
    Vector6 rhs;
    if (!fd::reduced_equations(d, m, force, e, M, rhs)) {
        why.fault = e.fault;
        why.leg = e.fault_leg;
        return false;
    }
    const Eigen::LLT<Matrix6> llt(M);
    const Vector6 twist_rate = llt.solve(rhs);

    // d nu_dot / dF = M^-1 J^T: leg k pushes with (n_k, arm_k x n_k).
    Matrix6 rate_wrt_force;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        rate_wrt_force.col(k).head<3>() = e.legs[k].n;
        rate_wrt_force.col(k).tail<3>() = e.legs[k].arm.cross(e.legs[k].n);
    }
    rate_wrt_force = llt.solve(rate_wrt_force);

    // d nu_dot / dx = M^-1 d residual / dx at the twist rate held fixed (implicit function
    // theorem on residual(x, nu_dot) = 0, whose slope in nu_dot is -M).
    StateDual qs[6], rates[6], zero[6];
    seed(q, 0, qs);
    seed(q_dot, 6, rates);
    for (StateDual &a : zero) a = StateDual(0.0, StateDualDerivatives::Zero());
    MotionT<StateDual> md = motion_of_pose<StateDual>(qs, rates, zero);
    // With zero angle accelerations alpha = E_dot angles_dot: the part of omega_dot that the angle
    // accelerations do not give.
    const fd::Vec3T<StateDual> angle_bias = md.alpha;
    for (int i = 0; i < 3; ++i) {
        md.acceleration[i] = StateDual(twist_rate[i], StateDualDerivatives::Zero());
        md.alpha[i] = StateDual(twist_rate[3 + i], StateDualDerivatives::Zero());
    }
    fd::EvaluationT<StateDual> ed;
    Eigen::Matrix<StateDual, 6, 1> residual;
    if (!fd::motion_residual(d, md, force, ed, residual)) {
        why.fault = ed.fault;
        why.leg = ed.fault_leg;
        return false;
    }
    Eigen::Matrix<double, 6, kStateDirections> residual_wrt_state;
    for (int i = 0; i < 6; ++i) residual_wrt_state.row(i) = residual[i].derivatives().transpose();
    const Eigen::Matrix<double, 6, kStateDirections> rate_wrt_state =
        llt.solve(residual_wrt_state);

    // q_ddot: the linear part as it is, the angles' from omega_dot = E angles_ddot +
    // E_dot angles_dot.
    StateDual q_ddot[6];
    for (int i = 0; i < 6; ++i)
        q_ddot[i] = StateDual(twist_rate[i], rate_wrt_state.row(i).transpose());
    const fd::Vec3T<StateDual> turn =
        fd::Vec3T<StateDual>(q_ddot[3], q_ddot[4], q_ddot[5]) - angle_bias;
    if (!angle_rates_of<StateDual>(qs, turn, q_ddot + 3, kMinCosPitch)) {
        why.pitch = true;
        return false;
    }
    for (int k = 0; k < STEWART_LEGS; ++k) {
        double angles[3] = {0, 0, 0};  // pitch checked above: always filled
        angle_rates_of<double>(q, rate_wrt_force.col(k).tail<3>(), angles, kMinCosPitch);
        rate_wrt_force.col(k).tail<3>() = Eigen::Vector3d(angles[0], angles[1], angles[2]);
    }
    for (int i = 0; i < 6; ++i) {
        out.q_ddot[i] = q_ddot[i].value();
        for (int j = 0; j < kStateDirections; ++j)
            out.q_ddot_wrt_state[i][j] = q_ddot[i].derivatives()[j];
        for (int k = 0; k < STEWART_LEGS; ++k) out.q_ddot_wrt_force[i][k] = rate_wrt_force(i, k);
    }
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const fd::LegConfigurationT<StateDual> &leg = ed.legs[k];
        const StateDual rate = leg.n.dot(md.velocity + md.omega.cross(leg.arm));
        out.length[k] = leg.length.value();
        out.length_rate[k] = rate.value();
        for (int j = 0; j < kStateDirections; ++j) {
            out.length_wrt_state[k][j] = leg.length.derivatives()[j];
            out.length_rate_wrt_state[k][j] = rate.derivatives()[j];
        }
    }
    return true;
}

}  // namespace lin
}  // namespace stewart
