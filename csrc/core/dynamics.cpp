#include "core/dynamics.hpp"

#include "core/assembly.hpp"

namespace mbs {

void applied_minus_inertial(const Mechanism &m, const double *q, const double *q_dot,
                            const double *q_ddot, double *out) {
    for (size_t b = 0; b < m.bodies.size(); ++b) {
        const Body &body = m.bodies[b];
        const double *qb = q + 7 * b, *vb = q_dot + 7 * b, *ab = q_ddot + 7 * b;
        double *o = out + 7 * b;
        for (int c = 0; c < 3; ++c) o[c] = body.mass * (m.gravity[c] - ab[c]);
        const Mat34 G = G_matrix(qb + 3), G_dot = G_matrix(vb + 3);
        const Eigen::Map<const Vec4> p(qb + 3), p_ddot(ab + 3);
        const Vec3 J = body.inertia;
        const Vec4 rot = 8.0 * G_dot.transpose() * (J.asDiagonal() * (G_dot * p)) -
                         4.0 * G.transpose() * (J.asDiagonal() * (G * p_ddot));
        for (int c = 0; c < 4; ++c) o[3 + c] = rot[c];
    }
}

void joint_reaction(const Mechanism &m, const State &s, int joint, int side, Vec3 &force,
                    Vec3 &torque) {
    const JointDef &j = m.joints[joint];
    const int n = joint_type(j.type).equations;
    double jac[2][7 * 7];
    evaluate_joint(m, joint, s.q.data(), nullptr, s.drive.data(),
                   JointOutput{nullptr, jac[0], j.body_j >= 0 ? jac[1] : nullptr, nullptr, nullptr});
    // Generalised reaction -Phi_q^T lambda on the body's 7 coordinates.
    double g[7] = {0, 0, 0, 0, 0, 0, 0};
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < 7; ++c) g[c] -= jac[side][7 * r + c] * s.lambda[m.first_row[joint] + r];
    const int body = side == 0 ? j.body_i : j.body_j;
    const double *p = s.q.data() + 7 * body + 3;
    force = Vec3(g[0], g[1], g[2]);
    // Q_p = 2 G^T n' on the body, so n' = G Q_p / 2 (G p = 0 drops the normalisation part).
    const Vec3 body_torque = 0.5 * G_matrix(p) * Eigen::Map<const Vec4>(g + 3);
    torque = rotate(p, body_torque);
}

double mechanical_energy(const Mechanism &m, const double *q, const double *q_dot) {
    double e = 0;
    for (size_t b = 0; b < m.bodies.size(); ++b) {
        const Body &body = m.bodies[b];
        const Eigen::Map<const Vec3> r(q + 7 * b), v(q_dot + 7 * b);
        const Vec3 w = 2.0 * G_matrix(q + 7 * b + 3) * Eigen::Map<const Vec4>(q_dot + 7 * b + 3);
        e += 0.5 * body.mass * v.squaredNorm() + 0.5 * w.dot(body.inertia.asDiagonal() * w) -
             body.mass * m.gravity.dot(r);
    }
    return e;
}

}  // namespace mbs
