#include "core/dynamics.hpp"

#include "core/assembly.hpp"
#include "core/euler_pairs.hpp"

namespace mbs {

void applied_minus_inertial(const Mechanism &m, const double *q, const double *q_dot,
                            const double *q_ddot, double *out) {
    for (size_t b = 0; b < m.bodies.size(); ++b) {
        const Body &body = m.bodies[b];
        const double *qb = body_r(q, b), *vb = body_r(q_dot, b), *ab = body_r(q_ddot, b);
        double *o = body_r(out, b);
        for (int c = 0; c < 3; ++c) o[c] = body.mass * (m.gravity[c] - ab[c]);
        // 8 G_dot^T J' G_dot p - 4 G^T J' G p_ddot = G_dot^T (8 J' G_dot p) - G^T (4 J' G p_ddot).
        // The two products side by side in the lanes of a vector (euler_pairs.hpp).
        const double *p = qb + 3, *pd = vb + 3, *pdd = ab + 3;
        Lanes w[3];  // (w_dot-side, w_acc-side)
        G_times_two(pd, p, p, pdd, w);
        for (int c = 0; c < 3; ++c) w[c] *= lanes(8.0 * body.inertia[c], 4.0 * body.inertia[c]);
        Lanes r[4];
        G_transpose_times_two(pd, p, w, r);
        for (int c = 0; c < 4; ++c) o[3 + c] = r[c][0] - r[c][1];
    }
}

void joint_reaction(const Mechanism &m, const State &s, int joint, int side, Vec3 &force,
                    Vec3 &torque) {
    const JointDef &j = m.joints[joint];
    const int n = joint_type(j.type).equations;
    // The joint's Jacobian blocks: from the assembled values when they are at q, else evaluated.
    double jac[2 * MBS_BODY_COORDINATES * MBS_BODY_COORDINATES];
    const double *block = s.values.data() + m.first_value[joint];
    if (!s.values_current) {
        evaluate_joint(m, joint, s.q.data(), nullptr, s.drive.data(),
                       JointOutput{nullptr, jac,
                                   j.body_j >= 0 ? jac + MBS_BODY_COORDINATES * n : nullptr,
                                   nullptr, nullptr});
        block = jac;
    }
    const double *rows = block + side * MBS_BODY_COORDINATES * n;  // n rows of one body's 7
    // Generalised reaction -Phi_q^T lambda on the body's 7 coordinates.
    double g[7] = {0, 0, 0, 0, 0, 0, 0};
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < MBS_BODY_COORDINATES; ++c)
            g[c] -= rows[MBS_BODY_COORDINATES * r + c] * s.lambda[m.first_row[joint] + r];
    const int body = side == 0 ? j.body_i : j.body_j;
    const double *p = body_p(s.q.data(), body);
    force = Vec3(g[0], g[1], g[2]);
    // Q_p = 2 G^T n' on the body, so n' = G Q_p / 2 (G p = 0 drops the normalisation part).
    const Vec3 body_torque = 0.5 * G_matrix(p) * Eigen::Map<const Vec4>(g + 3);
    torque = rotate(p, body_torque);
}

double mechanical_energy(const Mechanism &m, const double *q, const double *q_dot) {
    double e = 0;
    for (size_t b = 0; b < m.bodies.size(); ++b) {
        const Body &body = m.bodies[b];
        const Eigen::Map<const Vec3> r(body_r(q, b)), v(body_r(q_dot, b));
        const Vec3 w = 2.0 * G_matrix(body_p(q, b)) * Eigen::Map<const Vec4>(body_p(q_dot, b));
        e += 0.5 * body.mass * v.squaredNorm() + 0.5 * w.dot(body.inertia.asDiagonal() * w) -
             body.mass * m.gravity.dot(r);
    }
    return e;
}

}  // namespace mbs
