// The full plant's right-hand side (fd::twist_rate for double) for axisymmetric leg bodies:
// the same reduced equations as plant_equations_impl.hpp's template, written in closed form.
//
// A leg body whose principal inertia is (a, a, c) about its axes (x, y, z = n) has the world
// inertia a 1 + (c - a) n n^T, whatever its x axis. Its angular velocity is n x n_dot + w n and
// its angular acceleration n x n_ddot + w_dot n + w n_dot (w the spin rate about the leg), so
//   I alpha + omega x I omega = a n x n_ddot + c w_dot n + c w n_dot,
// and, with the acceleration maps of plant_bodies.hpp (alpha = [n]x N P_ddot + n (h . P_ddot
// - spin . alpha_platform), N = (1 - n n^T) / L, h = N g), the leg's two bodies put on
// u = (P_ddot, alpha_platform) the mass
//   m_p 1 + s (1 - n n^T) + c_c h_c h_c^T + c_p q q^T,  q = (h_p, -spin),
//   s = (m_c cc^2 + m_p cp^2 + a_c + a_p) / L^2 - 2 m_p cp / L.
// Mapped to the twist rate (P_ddot = v_dot + omega_dot x arm) that is a point mass m_p + s at the
// leg's platform point and three rank-one terms: no rotation matrix, no 3 x 3 product. The
// platform and the six point masses are summed as one body's blocks; M is filled in its upper
// triangle and solved by a written-out LDL^T. Equal to the template's result to rounding
// (tests/unit/test_plant_full_rhs.cpp holds the bound on random states); leg bodies that are not
// axisymmetric, the massless model and the dual scalar take the template.
#include "plant/plant_equations.hpp"

namespace stewart {
namespace fd {

namespace {

// The upper triangle of the symmetric 6 x 6 mass matrix, and the right-hand side.
struct Equations {
    double M[6][6];
    double rhs[6];
};

// M += weight j j^T on the upper triangle.
[[gnu::always_inline]] inline void add_rank_one(Equations &q, double weight, const double j[6]) {
    for (int r = 0; r < 6; ++r) {
        const double wr = weight * j[r];
        for (int c = r; c < 6; ++c) q.M[r][c] += wr * j[c];
    }
}

// The spin rate w of a leg body's frame (x, y = n x x, z = n; x = (s x n) / mu, mu = |s x n|,
// s its Cardan's cross arm) and its rate's velocity-product part w_dot (zero accelerations of
// the platform), as plant_bodies_impl.hpp's frame_rates: w = (-x.s_dot + (y x s).n_dot) / mu.
// g = (y x s) / mu is returned (the spin acceleration's share of n_ddot).
[[gnu::always_inline]] inline void spin_rates(const Vec3 &n, const Vec3 &n_dot, const Vec3 &n_ddot,
                                              const Vec3 &s, const Vec3 &s_dot,
                                              const Vec3 &s_ddot, const Vec3 &x, double mu,
                                              double &w, double &w_dot, Vec3 &g) {
    const double inv_mu = 1.0 / mu;
    const Vec3 y = n.cross(x);
    const Vec3 u_dot = s_dot.cross(n) + s.cross(n_dot);
    const double mu_dot = x.dot(u_dot);
    const Vec3 x_dot = (u_dot - mu_dot * x) * inv_mu;
    const Vec3 y_dot = n_dot.cross(x) + n.cross(x_dot);
    const Vec3 y_cross_s = y.cross(s);
    w = (-x.dot(s_dot) + y_cross_s.dot(n_dot)) * inv_mu;
    const double numerator_dot = -x_dot.dot(s_dot) - x.dot(s_ddot) +
                                 (y_dot.cross(s) + y.cross(s_dot)).dot(n_dot) +
                                 y_cross_s.dot(n_ddot);
    w_dot = (numerator_dot - w * mu_dot) * inv_mu;
    g = y_cross_s * inv_mu;
}

// The same for the base Cardan's fixed arm (s_dot = s_ddot = 0).
[[gnu::always_inline]] inline void fixed_spin_rates(const Vec3 &n, const Vec3 &n_dot,
                                                    const Vec3 &n_ddot, const Vec3 &s,
                                                    const Vec3 &x, double mu, double &w,
                                                    double &w_dot, Vec3 &g) {
    const double inv_mu = 1.0 / mu;
    const Vec3 y = n.cross(x);
    const Vec3 u_dot = s.cross(n_dot);
    const double mu_dot = x.dot(u_dot);
    const Vec3 x_dot = (u_dot - mu_dot * x) * inv_mu;
    const Vec3 y_dot = n_dot.cross(x) + n.cross(x_dot);
    g = y.cross(s) * inv_mu;
    w = g.dot(n_dot);
    w_dot = (y_dot.cross(s).dot(n_dot) * inv_mu - w * mu_dot * inv_mu) + g.dot(n_ddot);
}

// Leg k's two bodies and its force F: the point mass it adds at its platform point (weight into
// point_mass), its three rank-one terms into q.M and its generalised forces into q.rhs.
[[gnu::always_inline]] inline void add_axisymmetric_leg(const DynamicsModel &d, int k,
                                                        const LegConfiguration &leg,
                                                        const Motion &m, double F,
                                                        double &point_mass, Equations &q) {
    const Vec3 &n = leg.n, &arm = leg.arm;
    const double L = leg.length, inv_L = leg.inverse_length;
    // The leg's axis and its rates at zero twist rate (the velocity products).
    const Vec3 P_dot = m.velocity + m.omega.cross(arm);
    const Vec3 P_ddot = m.omega.cross(m.omega.cross(arm));
    const double L_dot = n.dot(P_dot);
    const Vec3 n_dot = (P_dot - L_dot * n) * inv_L;
    const double L_ddot = n.dot(P_ddot) + L * n_dot.squaredNorm();
    const Vec3 n_ddot = (P_ddot - L_ddot * n - 2.0 * L_dot * n_dot) * inv_L;

    double w_c, w_dot_c, w_p, w_dot_p;
    Vec3 g_c, g_p;
    fixed_spin_rates(n, n_dot, n_ddot, d.legs.base_arm.col(k), leg.cylinder_x, leg.cylinder_sin,
                     w_c, w_dot_c, g_c);
    const Vec3 &s = leg.piston_arm;
    const Vec3 s_dot = m.omega.cross(s);
    const Vec3 s_ddot = m.omega.cross(s_dot);
    spin_rates(n, n_dot, n_ddot, s, s_dot, s_ddot, leg.piston_x, leg.piston_sin, w_p, w_dot_p,
               g_p);
    const Vec3 h_c = (g_c - n.dot(g_c) * n) * inv_L;  // N g
    const Vec3 h_p = (g_p - n.dot(g_p) * n) * inv_L;
    const Vec3 spin = s.cross(leg.piston_x) / leg.piston_sin;

    const double m_c = d.cylinder_mass, m_p = d.piston_mass;
    const double cc = d.legs.cylinder_com, cp = d.legs.piston_com;
    const double a_c = d.cylinder_inertia[0], c_c = d.cylinder_inertia[2];
    const double a_p = d.piston_inertia[0], c_p = d.piston_inertia[2];

    // Generalised forces on u: the bodies' applied minus inertial wrenches (gravity, velocity
    // products) through the transposed maps, and F along the leg.
    const Vec3 f_p = m_p * (d.gravity - P_ddot + cp * n_ddot);
    const Vec3 z = (m_c * cc) * (d.gravity - cc * n_ddot) - cp * f_p - (a_c + a_p) * n_ddot;
    const Vec3 f_point = f_p + (z - n.dot(z) * n) * inv_L -
                         ((c_c * w_c + c_p * w_p) * inv_L) * n_dot.cross(n) -
                         (c_c * w_dot_c) * h_c - (c_p * w_dot_p) * h_p + F * n;
    const Vec3 torque = arm.cross(f_point) + (c_p * w_dot_p) * spin;
    for (int i = 0; i < 3; ++i) {
        q.rhs[i] += f_point[i];
        q.rhs[3 + i] += torque[i];
    }

    // The mass: the point mass and the rank-one terms, each mapped by S^T (p, r) = (p, arm x p + r).
    const double s_perp = (m_c * cc * cc + m_p * cp * cp + a_c + a_p) * inv_L * inv_L -
                          2.0 * m_p * cp * inv_L;
    point_mass = m_p + s_perp;
    double j[6];
    const Vec3 arm_n = arm.cross(n), arm_h_c = arm.cross(h_c), arm_h_p = arm.cross(h_p) - spin;
    for (int i = 0; i < 3; ++i) j[i] = n[i], j[3 + i] = arm_n[i];
    add_rank_one(q, -s_perp, j);
    for (int i = 0; i < 3; ++i) j[i] = h_c[i], j[3 + i] = arm_h_c[i];
    add_rank_one(q, c_c, j);
    for (int i = 0; i < 3; ++i) j[i] = h_p[i], j[3 + i] = arm_h_p[i];
    add_rank_one(q, c_p, j);
}

// x = M^-1 rhs for the symmetric positive definite M given by its upper triangle (LDL^T).
[[gnu::always_inline]] inline void solve_ldlt(Equations &q, double x[6]) {
    double Lw[6][6], D_inverse[6];
    for (int j = 0; j < 6; ++j) {
        double D = q.M[j][j];
        for (int k = 0; k < j; ++k) D -= Lw[j][k] * Lw[j][k] * D_inverse[k];
        D_inverse[j] = 1.0 / D;
        // Lw[i][j] = L_ij D_j (the unscaled column), L_ij = Lw[i][j] / D_j
        for (int i = j + 1; i < 6; ++i) {
            double v = q.M[j][i];
            for (int k = 0; k < j; ++k) v -= Lw[i][k] * Lw[j][k] * D_inverse[k];
            Lw[i][j] = v;
        }
    }
    double y[6];
    for (int i = 0; i < 6; ++i) {
        double v = q.rhs[i];
        for (int k = 0; k < i; ++k) v -= Lw[i][k] * D_inverse[k] * y[k];
        y[i] = v;
    }
    for (int i = 5; i >= 0; --i) {
        double v = y[i] * D_inverse[i];
        for (int k = i + 1; k < 6; ++k) v -= Lw[k][i] * D_inverse[i] * x[k];
        x[i] = v;
    }
}

// The closed-form twist rate for axisymmetric leg bodies (d.with_legs).
bool axisymmetric_twist_rate(const DynamicsModel &d, const Motion &m,
                             const double force[STEWART_LEGS], Evaluation &e) {
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const LegFault fault = leg_configuration(d.legs, k, m.position, m.rotation, e.legs[k]);
        if (fault != LegFault::None) {
            e.fault = fault;
            e.fault_leg = k;
            return false;
        }
    }
    Equations q;
    for (auto &row : q.M)
        for (double &v : row) v = 0;
    // The platform (and payload), centre of mass at c from the origin, as in the template.
    const Mat3 &R = m.rotation;
    const Vec3 c = R * d.platform_com;
    const Mat3 I_platform = R * d.platform_inertia * R.transpose();
    const double mass = d.platform_mass;
    const Vec3 f_platform = mass * (d.gravity - m.omega.cross(m.omega.cross(c)));
    const Vec3 t_platform = c.cross(f_platform) - m.omega.cross(I_platform * m.omega);
    for (int i = 0; i < 3; ++i) q.rhs[i] = f_platform[i], q.rhs[3 + i] = t_platform[i];

    // Point masses (the platform's and the legs') summed: total mass, first and second moments.
    double total = mass;
    Vec3 first = mass * c;
    Mat3 second = mass * (c.squaredNorm() * Mat3::Identity() - c * c.transpose());
    for (int k = 0; k < STEWART_LEGS; ++k) {
        double point_mass;
        add_axisymmetric_leg(d, k, e.legs[k], m, force[k], point_mass, q);
        const Vec3 &arm = e.legs[k].arm;
        total += point_mass;
        first += point_mass * arm;
        second += point_mass * (arm.squaredNorm() * Mat3::Identity() - arm * arm.transpose());
    }
    // [total 1, -[first]x; [first]x, I_platform + second]
    second += I_platform;
    for (int i = 0; i < 3; ++i) {
        q.M[i][i] += total;
        for (int j = i; j < 3; ++j) q.M[3 + i][3 + j] += second(i, j);
    }
    q.M[0][4] += first[2], q.M[0][5] -= first[1];
    q.M[1][3] -= first[2], q.M[1][5] += first[0];
    q.M[2][3] += first[1], q.M[2][4] -= first[0];

    double x[6];
    solve_ldlt(q, x);
    for (int i = 0; i < 6; ++i) e.twist_rate[i] = x[i];
    e.fault = LegFault::None;
    e.fault_leg = -1;
    return true;
}

bool axisymmetric(const Vec3 &principal) { return principal[0] == principal[1]; }

}  // namespace

bool twist_rate(const DynamicsModel &d, const Motion &m, const double force[STEWART_LEGS],
                Evaluation &e) {
    if (d.with_legs && !d.reference_equations && axisymmetric(d.cylinder_inertia) &&
        axisymmetric(d.piston_inertia))
        return axisymmetric_twist_rate(d, m, force, e);
    return twist_rate<double>(d, m, force, e);
}

}  // namespace fd
}  // namespace stewart
