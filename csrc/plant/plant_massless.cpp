// The massless plant's right-hand side written out in scalars (plant_equations.hpp,
// massless_twist_rate): the generic path's equations (plant_equations_impl.hpp's assemble with
// with_legs false and twist_rate's one-body solve) in a second, cheaper formulation: the
// platform's gyroscopic moment in its own axes (w_b x I w_b, w_b = R^T w) instead of its world
// inertia R I R^T, and the moments about the centre of mass, where gravity and the centripetal
// force have none (the generic path adds c x F about the origin and takes it off again). The
// legs' arms, axes and lengths are the generic path's bits; the twist rate differs by rounding
// (tests/unit/test_plant_rhs.cpp: within 1e-14 of its terms' scale, one 1 ms step within 1e-13).
#include <cmath>

#include "plant/plant_equations.hpp"

namespace stewart {
namespace plant {

namespace {

// (#pragma GCC unroll: GCC left these 3-loops rolled, at twice the instructions.)

// a x b as Eigen's cross product forms it.
inline void cross(const double a[3], const double b[3], double r[3]) {
    r[0] = a[1] * b[2] - a[2] * b[1];
    r[1] = a[2] * b[0] - a[0] * b[2];
    r[2] = a[0] * b[1] - a[1] * b[0];
}

// Row i of a 3 x 3 column-major product, sum of x0, x1, x2 (the products along the row), as
// Eigen sums it: rows 0 and 1 from the left (a packet of two rows), row 2 as x0 + (x1 + x2)
// (its scalar reduction's tree). That is Eigen with two-wide packets (SSE2, the library's
// x86-64 baseline); a build whose Eigen sums otherwise fails test_plant_rhs.
inline double row_sum(int i, double x0, double x1, double x2) {
    return i < 2 ? x0 + x1 + x2 : x0 + (x1 + x2);
}

// A v for a column-major 3 x 3 A, as Eigen's product.
inline void times(const Mat3 &A, const double v[3], double r[3]) {
#pragma GCC unroll 3
    for (int i = 0; i < 3; ++i) r[i] = row_sum(i, A(i, 0) * v[0], A(i, 1) * v[1], A(i, 2) * v[2]);
}

// A^T v, as Eigen's product of the transposed (row-major) A: every row from the left.
inline void times_transposed(const Mat3 &A, const double v[3], double r[3]) {
#pragma GCC unroll 3
    for (int i = 0; i < 3; ++i) r[i] = A(0, i) * v[0] + A(1, i) * v[1] + A(2, i) * v[2];
}

// Each leg's arm R b, axis n, length, its inverse, and its axial force and moment about the
// origin (place_leg with leg_configuration's axis and length; R b summed from the left as
// plant_bodies' rotate), one leg per element of the arrays.
struct LegLanes {
    double arm[3][STEWART_LEGS], n[3][STEWART_LEGS], length[STEWART_LEGS];
    double inverse_length[STEWART_LEGS], axial[3][STEWART_LEGS], moment[3][STEWART_LEGS];
};

// The legs' lanes at the platform pose (R, position) under the forces. Each leg's arithmetic in
// its own lane: loops over the six legs that the compiler turns into two-wide vector operations
// (-fvect-cost-model in csrc/CMakeLists.txt), each lane the same IEEE operations in the same
// order as one leg alone, so the same bits.
[[gnu::always_inline]] inline void leg_lanes(const DynamicsModel &d, const Mat3 &R,
                                             const Vec3 &position, const double force[STEWART_LEGS],
                                             LegLanes &l) {
    const double (&b)[3][STEWART_LEGS] = d.platform_point_rows;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        double dv[3];
#pragma GCC unroll 3
        for (int i = 0; i < 3; ++i) {
            l.arm[i][k] = R(i, 0) * b[0][k] + R(i, 1) * b[1][k] + R(i, 2) * b[2][k];
            dv[i] = position[i] + l.arm[i][k] - d.base_point_rows[i][k];
        }
        l.length[k] = std::sqrt(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2]);
        l.inverse_length[k] = 1.0 / l.length[k];
#pragma GCC unroll 3
        for (int i = 0; i < 3; ++i) l.n[i][k] = dv[i] * l.inverse_length[k];
        // arm x n, as cross()
        l.moment[0][k] = l.arm[1][k] * l.n[2][k] - l.arm[2][k] * l.n[1][k];
        l.moment[1][k] = l.arm[2][k] * l.n[0][k] - l.arm[0][k] * l.n[2][k];
        l.moment[2][k] = l.arm[0][k] * l.n[1][k] - l.arm[1][k] * l.n[0][k];
#pragma GCC unroll 3
        for (int i = 0; i < 3; ++i) {
            l.axial[i][k] = force[k] * l.n[i][k];
            l.moment[i][k] = force[k] * l.moment[i][k];
        }
    }
}

// The legs' total force and moment about the origin, summed in leg order; e's legs (when it
// fills them) from the lanes.
[[gnu::always_inline]] inline void sum_legs(const LegLanes &l, double legs_force[3],
                                            double legs_moment[3], Evaluation &e) {
    for (int k = 0; k < STEWART_LEGS; ++k) {
#pragma GCC unroll 3
        for (int i = 0; i < 3; ++i) {
            legs_force[i] += l.axial[i][k];
            legs_moment[i] += l.moment[i][k];
        }
    }
    for (int k = 0; k < STEWART_LEGS && e.fill_legs; ++k) {
        LegConfiguration &leg = e.legs[k];
#pragma GCC unroll 3
        for (int i = 0; i < 3; ++i) {
            leg.arm[i] = l.arm[i][k];
            leg.n[i] = l.n[i][k];
        }
        leg.length = l.length[k];
        leg.inverse_length = l.inverse_length[k];
    }
}

// One rigid body about its centre of mass c (world axes): I_b alpha_b = R^T (T_legs - c x
// F_legs) - w_b x I_b w_b (gravity and the centripetal force act at the centre: no moment about
// it), and the origin's a = g + F_legs / m - w x (w x c) - alpha x c, into e's twist rate.
[[gnu::always_inline]] inline void rigid_body_rate(const DynamicsModel &d, const Mat3 &R,
                                                   const double w[3], const double c[3],
                                                   const double gyroscopic[3],
                                                   const double legs_force[3],
                                                   const double legs_moment[3], Evaluation &e) {
    double c_F[3], moment[3], local[3], local_alpha[3], alpha[3], alpha_c[3], wc[3], wwc[3];
    cross(c, legs_force, c_F);
#pragma GCC unroll 3
    for (int i = 0; i < 3; ++i) moment[i] = legs_moment[i] - c_F[i];
    times_transposed(R, moment, local);
#pragma GCC unroll 3
    for (int i = 0; i < 3; ++i) local[i] -= gyroscopic[i];
    times(d.platform_inertia_inverse, local, local_alpha);
    times(R, local_alpha, alpha);
    cross(alpha, c, alpha_c);
    cross(w, c, wc);
    cross(w, wc, wwc);
    const double inverse_mass = 1.0 / d.platform_mass;
#pragma GCC unroll 3
    for (int i = 0; i < 3; ++i) {
        e.twist_rate[i] = d.gravity[i] + legs_force[i] * inverse_mass - wwc[i] - alpha_c[i];
        e.twist_rate[3 + i] = alpha[i];
        e.kept.legs_force[i] = legs_force[i];
        e.kept.legs_moment[i] = legs_moment[i];
    }
}

}  // namespace

bool massless_twist_rate(const DynamicsModel &d, const Motion &m, const double force[STEWART_LEGS],
                         Evaluation &e) {
    const Mat3 &R = m.rotation;
    const double w[3] = {m.omega[0], m.omega[1], m.omega[2]};
    const double com[3] = {d.platform_com[0], d.platform_com[1], d.platform_com[2]};
    double c[3];
    times(R, com, c);
    // The gyroscopic moment in the platform's axes, w_b x (I w_b) with w_b = R^T w: the world's
    // w x (R I R^T w) turned back, without forming the world inertia R I R^T.
    double w_body[3], I_w_body[3], gyroscopic[3];
    times_transposed(R, w, w_body);
    times(d.platform_inertia, w_body, I_w_body);
    cross(w_body, I_w_body, gyroscopic);
    LegLanes lanes;
    leg_lanes(d, R, m.position, force, lanes);
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (!(lanes.length[k] > d.legs.min_length)) {  // the first leg without a direction
            e.fault = LegFault::ZeroLength;
            e.fault_leg = k;
            return false;
        }
    double legs_force[3] = {0, 0, 0}, legs_moment[3] = {0, 0, 0};
    sum_legs(lanes, legs_force, legs_moment, e);
    rigid_body_rate(d, R, w, c, gyroscopic, legs_force, legs_moment, e);
    e.fault = LegFault::None;
    e.fault_leg = -1;
    return true;
}

}  // namespace plant
}  // namespace stewart
