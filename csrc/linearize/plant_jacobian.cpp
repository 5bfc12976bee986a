#include "linearize/plant_jacobian.hpp"

namespace stewart {
namespace lin {

namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

// The six values of v, each the variable of direction first + i.
void seed(const double v[6], int first, StateDual out[6]) {
    for (int i = 0; i < 6; ++i) out[i] = StateDual(v[i], StateDualDerivatives::Unit(first + i));
}

// The tool's pose accelerations q_ddot (user frame; pose q) when the platform moves with p, whose
// acceleration and alpha hold the twist rate: the linear ones as they are, the angles' from
// alpha = E angles_ddot + E_dot angles_dot (angle_bias = E_dot angles_dot). False at the tool's
// pitch +-90 deg.
template <class S>
bool pose_accelerations(const Frames &f, const MotionT<S> &p, const S q[6],
                        const plant::Vec3T<S> &angle_bias, S q_ddot[6]) {
    if (f.identity) {
        for (int i = 0; i < 3; ++i) q_ddot[i] = p.acceleration[i];
        return angle_rates_of<S>(q, p.alpha - angle_bias, q_ddot + 3, kMinCosPitch);
    }
    const MotionT<S> tool = tool_motion(f, p);
    for (int i = 0; i < 3; ++i) q_ddot[i] = tool.acceleration[i];
    return angle_rates_in_order<S>(f.rotation_order, q, tool.alpha - angle_bias, q_ddot + 3,
                                   kMinCosPitch);
}

}  // namespace

bool plant_rate(const plant::DynamicsModel &d, const Frames &f, const double q[6],
                const double q_dot[6], const double force[STEWART_LEGS], PlantRate &r,
                Failure &why) {
    // The twist rate nu_dot in plain numbers: M nu_dot = rhs, the plant's own equations. With
    // zero pose accelerations the tool's alpha is E_dot angles_dot.
    const double no_accel[6] = {0};
    // the tool's (angles in the frames' order), then the platform's
    r.platform = motion_of_pose_in_order<double>(f.rotation_order, q, q_dot, no_accel);
    r.angle_bias = r.platform.alpha;
    if (!f.identity) r.platform = platform_motion(f, r.platform);
    plant::Evaluation e;
    Matrix6 M;
    Vector6 rhs;
    if (!plant::reduced_equations(d, r.platform, force, e, M, rhs)) {
        why.fault = e.fault;
        why.leg = e.fault_leg;
        return false;
    }
    r.mass.compute(M);
    r.twist_rate = r.mass.solve(rhs);

    // d nu_dot / dF = M^-1 J^T: leg k pushes with (n_k, arm_k x n_k).
    for (int k = 0; k < STEWART_LEGS; ++k) {
        r.twist_rate_wrt_force.col(k).head<3>() = e.legs[k].n;
        r.twist_rate_wrt_force.col(k).tail<3>() = e.legs[k].arm.cross(e.legs[k].n);
    }
    r.twist_rate_wrt_force = r.mass.solve(r.twist_rate_wrt_force);

    Motion p = r.platform;
    p.acceleration = r.twist_rate.head<3>();
    p.alpha = r.twist_rate.tail<3>();
    if (!pose_accelerations<double>(f, p, q, r.angle_bias, r.q_ddot)) {
        why.pitch = true;
        return false;
    }
    // The pose accelerations are linear in the twist rate but for the velocity terms: a column
    // of the twist rate's map with no angular velocity and no bias is a column of q_ddot's.
    p.omega.setZero();
    for (int k = 0; k < STEWART_LEGS; ++k) {
        p.acceleration = r.twist_rate_wrt_force.col(k).head<3>();
        p.alpha = r.twist_rate_wrt_force.col(k).tail<3>();
        double column[6];
        pose_accelerations<double>(f, p, q, Eigen::Vector3d::Zero(), column);  // pitch checked
        for (int i = 0; i < 6; ++i) r.q_ddot_wrt_force[i][k] = column[i];
    }
    return true;
}

void plant_rate_add_force(PlantRate &r, const double change[STEWART_LEGS]) {
    const Eigen::Map<const Vector6> dF(change);
    r.twist_rate += r.twist_rate_wrt_force * dF;
    for (int i = 0; i < 6; ++i)
        for (int k = 0; k < STEWART_LEGS; ++k) r.q_ddot[i] += r.q_ddot_wrt_force[i][k] * change[k];
}

bool plant_jacobian(const plant::DynamicsModel &d, const Frames &f, const double q[6],
                    const double q_dot[6], const double force[STEWART_LEGS], PlantJacobian &out,
                    Failure &why) {
    PlantRate r;
    return plant_rate(d, f, q, q_dot, force, r, why) &&
           plant_jacobian(d, f, q, q_dot, force, r, out, why);
}

bool plant_jacobian(const plant::DynamicsModel &d, const Frames &f, const double q[6],
                    const double q_dot[6], const double force[STEWART_LEGS], const PlantRate &r,
                    PlantJacobian &out, Failure &why) {
    // d nu_dot / dx = M^-1 d residual / dx at the twist rate held fixed (implicit function
    // theorem on residual(x, nu_dot) = 0, whose slope in nu_dot is -M), x the tool's state.
    StateDual qs[6], rates[6], zero[6];
    seed(q, 0, qs);
    seed(q_dot, 6, rates);
    for (StateDual &a : zero) a = StateDual(0.0, StateDualDerivatives::Zero());
    MotionT<StateDual> md =  // the tool's, then the platform's
        motion_of_pose_in_order<StateDual>(f.rotation_order, qs, rates, zero);
    const plant::Vec3T<StateDual> angle_bias = md.alpha;
    if (!f.identity) md = platform_motion(f, md);
    for (int i = 0; i < 3; ++i) {
        md.acceleration[i] = StateDual(r.twist_rate[i], StateDualDerivatives::Zero());
        md.alpha[i] = StateDual(r.twist_rate[3 + i], StateDualDerivatives::Zero());
    }
    plant::EvaluationT<StateDual> ed;
    Eigen::Matrix<StateDual, 6, 1> residual;
    if (!plant::motion_residual(d, md, force, ed, residual)) {
        why.fault = ed.fault;
        why.leg = ed.fault_leg;
        return false;
    }
    Eigen::Matrix<double, 6, kStateDirections> residual_wrt_state;
    for (int i = 0; i < 6; ++i) residual_wrt_state.row(i) = residual[i].derivatives().transpose();
    const Eigen::Matrix<double, 6, kStateDirections> rate_wrt_state =
        r.mass.solve(residual_wrt_state);

    // The twist rate with its derivatives, then q_ddot through the frames and the angles
    // (angle_bias = E_dot angles_dot of the tool: zero angle accelerations).
    for (int i = 0; i < 3; ++i) {
        md.acceleration[i] = StateDual(r.twist_rate[i], rate_wrt_state.row(i).transpose());
        md.alpha[i] = StateDual(r.twist_rate[3 + i], rate_wrt_state.row(3 + i).transpose());
    }
    StateDual q_ddot[6];
    if (!pose_accelerations<StateDual>(f, md, qs, angle_bias, q_ddot)) {
        why.pitch = true;
        return false;
    }
    for (int i = 0; i < 6; ++i) {
        out.q_ddot[i] = q_ddot[i].value();
        for (int j = 0; j < kStateDirections; ++j)
            out.q_ddot_wrt_state[i][j] = q_ddot[i].derivatives()[j];
        for (int k = 0; k < STEWART_LEGS; ++k)
            out.q_ddot_wrt_force[i][k] = r.q_ddot_wrt_force[i][k];
    }
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const plant::LegConfigurationT<StateDual> &leg = ed.legs[k];
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
