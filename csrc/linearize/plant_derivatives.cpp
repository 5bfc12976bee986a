#include "linearize/plant_derivatives.hpp"

namespace stewart {
namespace lin {

namespace {

// The six values of v, each the variable of direction first + i.
void seed(const double v[6], int first, Dual out[6]) {
    for (int i = 0; i < 6; ++i) out[i] = Dual(v[i], DualDerivatives::Unit(first + i));
}

// The platform's motion (base frame) at the tool's pose (user frame) q with rates and
// accelerations, each the variable of its direction (0-5, 6-11, 12-17).
MotionT<Dual> seeded_motion(const Frames &f, const double q[6], const double q_dot[6],
                            const double q_ddot[6]) {
    Dual qs[6], rates[6], accels[6];
    seed(q, 0, qs);
    seed(q_dot, 6, rates);
    seed(q_ddot, 12, accels);
    const MotionT<Dual> tool = motion_of_pose_in_order<Dual>(f.rotation_order, qs, rates, accels);
    return f.identity ? tool : platform_motion(f, tool);
}

}  // namespace

bool plant_point(const plant::DynamicsModel &d, const double q[6], const double q_dot[6],
                 const double force[STEWART_LEGS], PlantPoint &out, Failure &why) {
    Dual qs[6], rates[6], forces[6], no_accel[6];
    seed(q, 0, qs);
    seed(q_dot, 6, rates);
    seed(force, 12, forces);
    for (Dual &a : no_accel) a = Dual(0.0, DualDerivatives::Zero());
    // With zero pose accelerations, alpha = E_dot angles_dot: the part of the platform's angular
    // acceleration that the angle accelerations do not give.
    const MotionT<Dual> m = motion_of_pose<Dual>(qs, rates, no_accel);
    plant::EvaluationT<Dual> e;
    if (!plant::twist_rate(d, m, forces, e)) {
        why.fault = e.fault;
        why.leg = e.fault_leg;
        return false;
    }
    for (int i = 0; i < 3; ++i) out.q_ddot[i] = e.twist_rate[i];
    // omega_dot = E angles_ddot + E_dot angles_dot.
    const plant::Vec3T<Dual> turn = e.twist_rate.tail<3>() - m.alpha;
    if (!angle_rates_of<Dual>(qs, turn, out.q_ddot + 3, kMinCosPitch)) {
        why.pitch = true;
        return false;
    }
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const plant::LegConfigurationT<Dual> &leg = e.legs[k];
        out.length[k] = leg.length;
        out.length_rate[k] = leg.n.dot(m.velocity + m.omega.cross(leg.arm));
    }
    return true;
}

bool leg_lengths(const plant::LegParameters &p, const Frames &f, const double q[6],
                 const double q_dot[6], const double q_ddot[6], Dual length[STEWART_LEGS],
                 Dual rate[STEWART_LEGS], Dual accel[STEWART_LEGS], Failure &why) {
    const MotionT<Dual> m = seeded_motion(f, q, q_dot, q_ddot);
    for (int k = 0; k < STEWART_LEGS; ++k) {
        plant::LegConfigurationT<Dual> leg;
        const plant::LegFault fault =
            plant::leg_configuration(p, k, m.position, m.rotation, leg, false);
        if (fault != plant::LegFault::None) {
            why.fault = fault;
            why.leg = k;
            return false;
        }
        // L n = P - a twice differentiated: L_dot = n.P_dot, L_ddot = n.P_ddot + |n_dot|^2 L
        // with L n_dot = P_dot - L_dot n.
        const plant::Vec3T<Dual> P_dot = m.velocity + m.omega.cross(leg.arm);
        const plant::Vec3T<Dual> P_ddot =
            m.acceleration + m.alpha.cross(leg.arm) + m.omega.cross(m.omega.cross(leg.arm));
        length[k] = leg.length;
        rate[k] = leg.n.dot(P_dot);
        const plant::Vec3T<Dual> across = P_dot - rate[k] * leg.n;
        accel[k] = leg.n.dot(P_ddot) + across.squaredNorm() * leg.inverse_length;
    }
    return true;
}

bool pose_base_wrench(const plant::DynamicsModel &d, const Frames &frames, const double q[6],
                      const double q_dot[6], const double q_ddot[6], Dual force[3], Dual torque[3],
                      Failure &why) {
    const MotionT<Dual> m = seeded_motion(frames, q, q_dot, q_ddot);
    plant::EvaluationT<Dual> e;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const plant::LegFault fault =
            plant::leg_configuration(d.legs, k, m.position, m.rotation, e.legs[k], d.with_legs);
        if (fault != plant::LegFault::None) {
            why.fault = fault;
            why.leg = k;
            return false;
        }
    }
    MotionT<Dual> bodies[13];
    plant::body_motions(d, m, e, bodies);
    plant::Vec3T<Dual> f, t;
    plant::base_wrench(d, bodies, f, t);
    for (int i = 0; i < 3; ++i) force[i] = f[i], torque[i] = t[i];
    base_wrench_to_given_frame(frames, force, torque);
    return true;
}

}  // namespace lin
}  // namespace stewart
