// The massless plant's right-hand side written out in scalars (plant_equations.hpp,
// massless_twist_rate): the generic path's arithmetic (plant_equations_impl.hpp's assemble with
// with_legs false and twist_rate's one-body solve) operation for operation and in Eigen's order
// of summation, so the same bits, without Eigen's temporaries and product kernels (they cost
// the massless step more than the arithmetic). tests/unit/test_plant_rhs.cpp checks the bits.
#include <cmath>

#include "plant/plant_equations.hpp"

namespace stewart {
namespace fd {

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

}  // namespace

bool massless_twist_rate(const DynamicsModel &d, const Motion &m, const double force[STEWART_LEGS],
                         Evaluation &e) {
    const Mat3 &R = m.rotation;
    const double w[3] = {m.omega[0], m.omega[1], m.omega[2]};
    const double com[3] = {d.platform_com[0], d.platform_com[1], d.platform_com[2]};
    double c[3];
    times(R, com, c);
    // The platform's world inertia (R I) R^T, and I omega.
    const Mat3 &I = d.platform_inertia;
    Mat3 RI, I_world;
    #pragma GCC unroll 3
    for (int i = 0; i < 3; ++i)
        #pragma GCC unroll 3
        for (int j = 0; j < 3; ++j)
            RI(i, j) = row_sum(i, R(i, 0) * I(0, j), R(i, 1) * I(1, j), R(i, 2) * I(2, j));
    #pragma GCC unroll 3
    for (int i = 0; i < 3; ++i)
        #pragma GCC unroll 3
        for (int j = 0; j < 3; ++j)
            I_world(i, j) = row_sum(i, RI(i, 0) * R(j, 0), RI(i, 1) * R(j, 1), RI(i, 2) * R(j, 2));
    double I_omega[3];
    times(I_world, w, I_omega);
    // Applied and velocity-product force at the centre of mass, moments about the origin.
    double wc[3], wwc[3], head[3], tail[3], c_f[3], w_Iw[3];
    cross(w, c, wc);
    cross(w, wc, wwc);
    const double mass = d.platform_mass;
    #pragma GCC unroll 3
    for (int i = 0; i < 3; ++i) head[i] = mass * (d.gravity[i] - wwc[i]);
    cross(c, head, c_f);
    cross(w, I_omega, w_Iw);
    #pragma GCC unroll 3
    for (int i = 0; i < 3; ++i) tail[i] = c_f[i] - w_Iw[i];
    // The legs' axial forces (place_leg with leg_configuration's axis and length; R b summed from
    // the left as plant_bodies' rotate sums it).
    const LegParameters &legs = d.legs;
    for (int k = 0; k < STEWART_LEGS; ++k) {
        LegConfiguration &leg = e.legs[k];
        double arm[3], dv[3];
        #pragma GCC unroll 3
        for (int i = 0; i < 3; ++i)
            arm[i] = R(i, 0) * legs.platform_points(0, k) + R(i, 1) * legs.platform_points(1, k) +
                     R(i, 2) * legs.platform_points(2, k);
        #pragma GCC unroll 3
        for (int i = 0; i < 3; ++i) dv[i] = m.position[i] + arm[i] - legs.base_points(i, k);
        const double length = std::sqrt(dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2]);
        if (!(length > legs.min_length)) {
            e.fault = LegFault::ZeroLength;
            e.fault_leg = k;
            return false;
        }
        const double inverse_length = 1.0 / length;
        double n[3], arm_n[3];
        #pragma GCC unroll 3
        for (int i = 0; i < 3; ++i) n[i] = dv[i] * inverse_length;
        cross(arm, n, arm_n);
        const double F = force[k];
        #pragma GCC unroll 3
        for (int i = 0; i < 3; ++i) {
            head[i] += F * n[i];
            tail[i] += F * arm_n[i];
            leg.arm[i] = arm[i];
            leg.n[i] = n[i];
        }
        leg.length = length;
        leg.inverse_length = inverse_length;
    }
    // One rigid body: I_c alpha = T - c x F (moments about the origin), a = F/m - alpha x c.
    double c_F[3], moment[3], local[3], local_alpha[3], alpha[3], alpha_c[3];
    cross(c, head, c_F);
    #pragma GCC unroll 3
    for (int i = 0; i < 3; ++i) moment[i] = tail[i] - c_F[i];
    times_transposed(R, moment, local);
    times(d.platform_inertia_inverse, local, local_alpha);
    times(R, local_alpha, alpha);
    cross(alpha, c, alpha_c);
    #pragma GCC unroll 3
    for (int i = 0; i < 3; ++i) {
        e.twist_rate[i] = head[i] / mass - alpha_c[i];
        e.twist_rate[3 + i] = alpha[i];
    }
    e.fault = LegFault::None;
    e.fault_leg = -1;
    return true;
}

}  // namespace fd
}  // namespace stewart
