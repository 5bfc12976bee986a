// The full plant's right-hand side (plant::twist_rate for double) for axisymmetric leg bodies:
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
#include "plant/plant_bodies_impl.hpp"  // leg_configuration inlined into the right-hand side
#include "plant/plant_equations.hpp"

namespace stewart {
namespace plant {

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

// The spin of a leg body about the leg n (its frame x, y = n x x, z = n with x = (s x n) / mu,
// mu = |s x n|, s its Cardan's cross arm turning at omega_s: the platform's, or zero on the
// base). The Cardan lets the body turn relative to s's body about s and x only, so e = s x x is
// normal to their relative angular velocity: e.(n x n_dot + w n - omega_s) = 0, with e.n = -mu
// and e x n = (s.n) x:
//   w = g.n_dot - spin.omega_s,   g = (s.n) x / mu,   spin = e / mu,
// and its rate's velocity-product part (zero accelerations of the platform), from the same
// relation differentiated (x_dot = omega_b x x, s_dot = omega_s x s):
//   w_dot = g.n_ddot + (e_dot.(omega_b - omega_s) + w e.n_dot) / mu.
// The same quantities as plant_bodies_impl.hpp's frame_rates and leg_acceleration_map (g, the
// spin) by a shorter way (so equal to rounding): in the frame (x, y, n), s = sigma n + mu y
// (sigma = s.n; x is normal to s), so e = sigma y - mu n, and with the body's angular velocity
// omega = n x n_dot + w n (n_dot = nu_x x + nu_y y):
//   e_dot = s x (omega x x) + (omega_s x s) x x = -x (s.omega) + s (x.omega_s),
//   s.omega = mu nu_x + sigma w,   x.omega = -nu_y,   e.n_dot = sigma nu_y:
// scalar products only (and w's large value near a locked Cardan kept out of x.omega).
struct Spin {
    double w, w_dot;
    Vec3 g, spin;
};

[[gnu::always_inline]] inline Spin spin_of(const Vec3 &n, const Vec3 &n_dot, const Vec3 &n_ddot,
                                           const Vec3 &s, const Vec3 &omega_s, bool turning,
                                           const Vec3 &x, double mu) {
    Spin r;
    const double inv_mu = 1.0 / mu;
    const Vec3 y = n.cross(x);
    const double sigma = s.dot(n), ratio = sigma * inv_mu;
    r.g = ratio * x;
    r.spin = ratio * y - n;
    const double nu_x = x.dot(n_dot), nu_y = y.dot(n_dot);
    double e_dot_relative;
    if (turning) {
        const double omega_x = x.dot(omega_s), omega_y = y.dot(omega_s), omega_n = n.dot(omega_s);
        r.w = ratio * (nu_x - omega_y) + omega_n;
        const double s_omega = mu * nu_x + sigma * r.w;
        e_dot_relative =
            (s_omega - (sigma * omega_n + mu * omega_y)) * omega_x + (nu_y + omega_x) * s_omega;
    } else {
        r.w = ratio * nu_x;
        e_dot_relative = nu_y * (mu * nu_x + sigma * r.w);
    }
    r.w_dot = ratio * x.dot(n_ddot) + (e_dot_relative + r.w * sigma * nu_y) * inv_mu;
    return r;
}

// The leg's platform point P = position + arm, its rates, and the leg axis's rates (L n = P - a_k
// twice differentiated, as plant_bodies_impl.hpp's axis_rates), for the platform's motion m
// with its accelerations (accelerating) or at zero twist rate.
struct LegRates {
    Vec3 P_dot, P_ddot, n_dot, n_ddot;
};

[[gnu::always_inline]] inline LegRates leg_rates(const LegConfiguration &leg, const Motion &m,
                                                 bool accelerating) {
    LegRates r;
    const Vec3 &n = leg.n, &arm = leg.arm;
    r.P_dot = m.velocity + m.omega.cross(arm);
    r.P_ddot = m.omega.cross(m.omega.cross(arm));
    if (accelerating) r.P_ddot += m.acceleration + m.alpha.cross(arm);
    const double L_dot = n.dot(r.P_dot);
    r.n_dot = (r.P_dot - L_dot * n) * leg.inverse_length;
    const double L_ddot = n.dot(r.P_ddot) + leg.length * r.n_dot.squaredNorm();
    r.n_ddot = (r.P_ddot - L_ddot * n - 2.0 * L_dot * r.n_dot) * leg.inverse_length;
    return r;
}

// Leg k's two bodies and its force F: the point mass it adds at its platform point (weight into
// point_mass), its three rank-one terms into q.M and its generalised forces into q.rhs; with
// Keep, its rates and spins into kept as well.
template <bool Keep>
[[gnu::always_inline]] inline void add_axisymmetric_leg(const DynamicsModel &d, int k,
                                                        const LegConfiguration &leg,
                                                        const Motion &m, double F,
                                                        double &point_mass, Equations &q,
                                                        LegRateTerms &kept) {
    const Vec3 &n = leg.n, &arm = leg.arm;
    const double inv_L = leg.inverse_length;
    // The leg's axis and its rates at zero twist rate (the velocity products).
    const LegRates r = leg_rates(leg, m, false);
    const Vec3 &P_ddot = r.P_ddot, &n_dot = r.n_dot, &n_ddot = r.n_ddot;
    const Spin cyl = spin_of(n, n_dot, n_ddot, d.legs.base_arm.col(k), m.omega, false,
                             leg.cylinder_x, leg.cylinder_sin);
    const Spin pis =
        spin_of(n, n_dot, n_ddot, leg.piston_arm, m.omega, true, leg.piston_x, leg.piston_sin);
    const double w_c = cyl.w, w_dot_c = cyl.w_dot, w_p = pis.w, w_dot_p = pis.w_dot;
    const Vec3 h_c = cyl.g * inv_L, h_p = pis.g * inv_L;  // N g (g is normal to n)
    const Vec3 &spin = pis.spin;
    if (Keep) {
        kept.n_dot = n_dot;
        kept.n_ddot = n_ddot;
        kept.P_ddot = P_ddot;
        kept.h_cylinder = h_c;
        kept.h_piston = h_p;
        kept.spin = spin;
        kept.w_cylinder = w_c;
        kept.w_piston = w_p;
        kept.w_dot_cylinder = w_dot_c;
        kept.w_dot_piston = w_dot_p;
    }

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
    const double s_perp =
        (m_c * cc * cc + m_p * cp * cp + a_c + a_p) * inv_L * inv_L - 2.0 * m_p * cp * inv_L;
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

// The closed-form equations for axisymmetric leg bodies (d.with_legs) into q; with Keep, their
// terms into e.kept.
template <bool Keep>
[[gnu::always_inline]] inline bool axisymmetric_equations(const DynamicsModel &d, const Motion &m,
                                                          const double force[STEWART_LEGS],
                                                          Evaluation &e, Equations &q) {
    e.terms_kept = false;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const LegFault fault = leg_configuration(d.legs, k, m.position, m.rotation, e.legs[k]);
        if (fault != LegFault::None) {
            e.fault = fault;
            e.fault_leg = k;
            return false;
        }
    }
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
        add_axisymmetric_leg<Keep>(d, k, e.legs[k], m, force[k], point_mass, q, e.kept.legs[k]);
        const Vec3 &arm = e.legs[k].arm;
        total += point_mass;
        first += point_mass * arm;
        // its second moment |arm|^2 1 - arm arm^T, the upper triangle only (M's)
        const Vec3 weighted = point_mass * arm;
        const double squared = weighted.dot(arm);
        for (int i = 0; i < 3; ++i)
            for (int j = i; j < 3; ++j) second(i, j) -= weighted[i] * arm[j];
        for (int i = 0; i < 3; ++i) second(i, i) += squared;
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
    if (Keep) {
        e.kept.platform_com = c;
        e.kept.platform_inertia = I_platform;
    }
    return true;
}

// The closed-form twist rate for axisymmetric leg bodies (d.with_legs); with Keep, its terms
// into e.kept.
template <bool Keep>
bool axisymmetric_twist_rate(const DynamicsModel &d, const Motion &m,
                             const double force[STEWART_LEGS], Evaluation &e) {
    Equations q;
    if (!axisymmetric_equations<Keep>(d, m, force, e, q)) return false;
    double x[6];
    solve_ldlt(q, x);
    for (int i = 0; i < 6; ++i) e.twist_rate[i] = x[i];
    e.fault = LegFault::None;
    e.fault_leg = -1;
    if (Keep) e.terms_kept = true;
    return true;
}

bool axisymmetric(const Vec3 &principal) { return principal[0] == principal[1]; }

bool fast_path(const DynamicsModel &d) {
    return d.with_legs && !d.reference_equations && axisymmetric(d.cylinder_inertia) &&
           axisymmetric(d.piston_inertia);
}

// A leg's accelerations with the platform's: the axis's rates, its platform point's
// acceleration, the bodies' spins and their rates.
struct LegAccelerations {
    Vec3 n_dot, n_ddot, P_ddot;
    double w_c, w_dot_c, w_p, w_dot_p;
};

// base_wrench's terms of leg k's two bodies (minus what the base supplies to them beyond
// gravity), from the axis's rates and the bodies' spins: I alpha + omega x I omega of a body is
// a n x n_ddot + c w_dot n + c w n_dot (plant_full_rhs.cpp's header).
[[gnu::always_inline]] inline void subtract_leg_wrench(const DynamicsModel &d, int k,
                                                       const LegConfiguration &leg, const Motion &m,
                                                       const LegAccelerations &r, Vec3 &force,
                                                       Vec3 &torque) {
    const Vec3 &n = leg.n;
    const double cc = d.legs.cylinder_com, cp = d.legs.piston_com;
    const double a_c = d.cylinder_inertia[0], c_c = d.cylinder_inertia[2];
    const double a_p = d.piston_inertia[0], c_p = d.piston_inertia[2];
    const Vec3 cylinder_position = d.legs.base_points.col(k) + cc * n;
    const Vec3 piston_position = m.position + leg.arm - cp * n;
    const Vec3 f_c = d.cylinder_mass * (cc * r.n_ddot - d.gravity);
    const Vec3 f_p = d.piston_mass * (r.P_ddot - cp * r.n_ddot - d.gravity);
    force -= f_c + f_p;
    torque -= cylinder_position.cross(f_c) + piston_position.cross(f_p) +
              (a_c + a_p) * n.cross(r.n_ddot) + (c_c * r.w_dot_c + c_p * r.w_dot_p) * n +
              (c_c * r.w_c + c_p * r.w_p) * r.n_dot;
}

// Leg k's accelerations found anew for the platform's motion m with its accelerations.
LegAccelerations leg_accelerations(const DynamicsModel &d, int k, const LegConfiguration &leg,
                                   const Motion &m) {
    const Vec3 &n = leg.n;
    const LegRates r = leg_rates(leg, m, true);
    const Spin cyl = spin_of(n, r.n_dot, r.n_ddot, d.legs.base_arm.col(k), m.omega, false,
                             leg.cylinder_x, leg.cylinder_sin);
    const Spin pis =
        spin_of(n, r.n_dot, r.n_ddot, leg.piston_arm, m.omega, true, leg.piston_x, leg.piston_sin);
    // the piston's: the platform arm's alpha x s
    const double w_dot_p = pis.w_dot - pis.spin.dot(m.alpha);
    return {r.n_dot, r.n_ddot, r.P_ddot, cyl.w, cyl.w_dot, pis.w, w_dot_p};
}

// The same from the kept velocity-product terms t and the platform's accelerations in m
// (the part linear in them: plant_equations.hpp's LegRateTerms).
[[gnu::always_inline]] inline LegAccelerations leg_accelerations(const LegRateTerms &t,
                                                                 const LegConfiguration &leg,
                                                                 const Motion &m) {
    const Vec3 &n = leg.n;
    const Vec3 P_acc = m.acceleration + m.alpha.cross(leg.arm);
    const Vec3 N_P_acc = (P_acc - n.dot(P_acc) * n) * leg.inverse_length;
    return {t.n_dot,
            t.n_ddot + N_P_acc,
            t.P_ddot + P_acc,
            t.w_cylinder,
            t.w_dot_cylinder + t.h_cylinder.dot(P_acc),
            t.w_piston,
            t.w_dot_piston + t.h_piston.dot(P_acc) - t.spin.dot(m.alpha)};
}

}  // namespace

bool reduced_equations(const DynamicsModel &d, const Motion &m, const double force[STEWART_LEGS],
                       Evaluation &e, double M[6][6], double rhs[6]) {
    if (!fast_path(d)) {
        Eigen::Matrix<double, 6, 6> full;
        Eigen::Matrix<double, 6, 1> b;
        if (!reduced_equations<double>(d, m, force, e, full, b)) return false;
        for (int r = 0; r < 6; ++r) {
            rhs[r] = b[r];
            for (int c = r; c < 6; ++c) M[r][c] = full(r, c);
        }
        return true;
    }
    Equations q;
    const bool defined = e.keep_terms ? axisymmetric_equations<true>(d, m, force, e, q)
                                      : axisymmetric_equations<false>(d, m, force, e, q);
    if (!defined) return false;
    if (e.keep_terms) e.terms_kept = true;
    for (int r = 0; r < 6; ++r) {
        rhs[r] = q.rhs[r];
        for (int c = r; c < 6; ++c) M[r][c] = q.M[r][c];
    }
    return true;
}

void solve_with_rank_ones(const double M[6][6], const double rhs[6], const double (*j)[6],
                          const double *weight, double x[6]) {
    Equations q;
    for (int r = 0; r < 6; ++r) {
        q.rhs[r] = rhs[r];
        for (int c = r; c < 6; ++c) q.M[r][c] = M[r][c];
    }
    for (int k = 0; k < STEWART_LEGS; ++k) add_rank_one(q, weight[k], j[k]);
    solve_ldlt(q, x);
}

bool twist_rate(const DynamicsModel &d, const Motion &m, const double force[STEWART_LEGS],
                Evaluation &e) {
    if (d.drives.input != STEWART_PLANT_INPUT_FORCE) return driven_twist_rate(d, m, force, e);
    if (fast_path(d))
        return e.keep_terms ? axisymmetric_twist_rate<true>(d, m, force, e)
                            : axisymmetric_twist_rate<false>(d, m, force, e);
    // the integrator's massless equations, so that a step's outputs and a later output or
    // derivative at the same state are the same bits
    if (!d.with_legs && !d.reference_equations) return massless_twist_rate(d, m, force, e);
    return twist_rate<double>(d, m, force, e);
}

void base_wrench(const DynamicsModel &d, const Motion &m, const Evaluation &e, Vec3 &force,
                 Vec3 &torque) {
    if (!d.with_legs && !d.reference_equations) {
        // Massless legs put their axial forces on the base at its points a_k, on their lines
        // through the platform points p + arm_k: -(F, p x F + sum arm_k x F_k), which is minus
        // the platform's momentum rates less gravity at the twist rate they cause.
        force = -e.kept.legs_force;
        torque = -(m.position.cross(e.kept.legs_force) + e.kept.legs_moment);
        return;
    }
    if (!fast_path(d)) {
        Motion bodies[13];
        body_motions(d, m, e, bodies);
        base_wrench(d, bodies, force, torque);
        return;
    }
    // The platform as base_wrench's body 0 (body_motions' platform motion).
    const bool kept = e.terms_kept;
    const Vec3 c = kept ? e.kept.platform_com : Vec3(m.rotation * d.platform_com);
    const Mat3 I = kept ? e.kept.platform_inertia
                        : Mat3(m.rotation * d.platform_inertia * m.rotation.transpose());
    const Vec3 acceleration = m.acceleration + m.alpha.cross(c) + m.omega.cross(m.omega.cross(c));
    const Vec3 f = d.platform_mass * (acceleration - d.gravity);
    force = -f;
    torque = -((m.position + c).cross(f) + I * m.alpha + m.omega.cross(I * m.omega));
    for (int k = 0; k < STEWART_LEGS; ++k) {
        const LegConfiguration &leg = e.legs[k];
        const LegAccelerations r =
            kept ? leg_accelerations(e.kept.legs[k], leg, m) : leg_accelerations(d, k, leg, m);
        subtract_leg_wrench(d, k, leg, m, r, force, torque);
    }
}

}  // namespace plant
}  // namespace stewart
