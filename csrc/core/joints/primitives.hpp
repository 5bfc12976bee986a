// The building blocks every joint is made of: a point coincidence (3 rows), a perpendicularity of
// two body vectors ("dot-1", 1 row) and a perpendicularity of a body vector to the vector between
// two points ("dot-2", 1 row). Each writes Phi, its Jacobian rows, Phi_t and gamma, computing
// only what the output asks for.
#pragma once

#include "core/joint.hpp"

namespace mbs {

// A body-fixed vector u seen in the world, with the derivatives gamma needs.
struct Attached {
    Vec3 world;  // A u
    Vec3 rate;   // d(A u)/dt = B(p, u) p_dot
    Vec3 quad;   // velocity-quadratic part of d2(A u)/dt2: 2 A(p_dot) u
};

// M u written out: Eigen does not inline this small product at -O2.
inline Vec3 times(const Mat3 &M, const Vec3 &u) {
    return Vec3(M(0, 0) * u[0] + M(0, 1) * u[1] + M(0, 2) * u[2],
                M(1, 0) * u[0] + M(1, 1) * u[1] + M(1, 2) * u[2],
                M(2, 0) * u[0] + M(2, 1) * u[1] + M(2, 2) * u[2]);
}

inline Attached attach(const BodyFrame &f, bool rates, const Vec3 &u) {
    Attached a;
    a.world = times(f.A, u);
    if (rates) {
        a.rate = times(f.rate, u);
        a.quad = times(f.quad, u);
    }
    return a;
}

// Writes row `row` of the outputs; jacobian rows as 7-vectors (r part, p part).
struct RowWriter {
    const JointOutput &out;
    void phi(int row, double value) const {
        if (out.phi) out.phi[row] = value;
    }
    void gamma(int row, double value) const {
        if (out.gamma) out.gamma[row] = value;
    }
    void phi_t(int row, double value) const {
        if (out.phi_t) out.phi_t[row] = value;
    }
    bool want_jac() const { return out.jac_i != nullptr; }
    // Row `row` of a body's Jacobian block (rows of its 7 coordinates).
    double *jac_i(int row) const { return out.jac_i + MBS_BODY_COORDINATES * row; }
    double *jac_j(int row) const { return out.jac_j + MBS_BODY_COORDINATES * row; }
};

inline void put(double *row7, const Vec3 &r, const Eigen::Matrix<double, 1, 4> &p) {
    for (int c = 0; c < 3; ++c) row7[c] = r[c];
    for (int c = 0; c < 4; ++c) row7[3 + c] = p[c];
}

// The normalisation p.p - 1 = 0 of a body with Euler parameters p (rates p_dot, read only for
// gamma): inline, since assembly writes it without a call (a few products).
inline void normalization_rows(const double *p, const double *p_dot, const JointOutput &out) {
    if (out.phi) out.phi[0] = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3] - 1.0;
    if (out.phi_t) out.phi_t[0] = 0.0;
    if (out.gamma) {
        const double *pd = p_dot;
        out.gamma[0] = -2.0 * (pd[0] * pd[0] + pd[1] * pd[1] + pd[2] * pd[2] + pd[3] * pd[3]);
    }
    if (out.jac_i)
        for (int c = 0; c < 7; ++c) out.jac_i[c] = c < 3 ? 0.0 : 2.0 * p[c - 3];
}

// r_i + A_i u_i - r_j - A_j u_j = 0, rows row..row+2.
void point_coincidence(const JointInput &in, const RowWriter &w, int row);
// (A_i a)^T (A_j b) = 0.
void dot1(const JointInput &in, const RowWriter &w, int row, const Vec3 &a, const Vec3 &b);
// The vector between the joint's two points, d = r_j + A_j u_j - r_i - A_i u_i, with its rate and
// velocity-quadratic part: computed once for all the dot-2 rows of a joint.
struct Separation {
    Vec3 d, rate, quad;
};
Separation separation(const JointInput &in, const JointOutput &out);

// (A_i a)^T d = 0; `target` (value, rate, accel) turns it into the driver (A_i a)^T d - f(t) = 0.
void dot2(const JointInput &in, const RowWriter &w, int row, const Vec3 &a, const Separation &d,
          const DriverValue *target = nullptr);

// The Cardan joint's rows: a point coincidence (rows 0..2) and its cross arms axis_i[0], axis_j[0]
// perpendicular (row 3), in one call with the two rows' bodies inlined.
void cardan_rows(const JointInput &in, const JointOutput &out);

// Body j's axis axis_j[2] stays parallel to body i's axis: perpendicular to axis_i[0] and
// axis_i[1] (dot-1 rows row, row + 1). Revolute, cylindrical and prismatic joints.
void parallel_axes(const JointInput &in, const RowWriter &w, int row);
// The cylindrical joint's rows 0..3: parallel axes, and the vector between the points
// perpendicular to axis_i[0] and axis_i[1]. The prismatic joint adds a fifth.
void cylindrical_rows(const JointInput &in, const JointOutput &out, const RowWriter &w);

}  // namespace mbs
