// Euler-parameter kinematics (docs/model.md): p = (e0, e), rotation A(p) = E(p) G(p)^T.
// A is written in its homogeneous quadratic form, so its derivative B(p, u) = d(A(p) u)/dp is
// exact off the unit sphere too (Newton steps leave it) and B is linear in p.
#pragma once

#include <Eigen/Dense>

namespace mbs {

using Vec3 = Eigen::Vector3d;
using Vec4 = Eigen::Vector4d;
using Mat3 = Eigen::Matrix3d;
using Mat34 = Eigen::Matrix<double, 3, 4>;
using Row7 = Eigen::Matrix<double, 1, 7>;

inline Mat3 skew(const Vec3 &v) {
    Mat3 s;
    s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return s;
}

// A(p) = (e0^2 - e.e) I + 2 e e^T + 2 e0 skew(e).
inline Mat3 rotation(const double *p) {
    const double e0 = p[0], e1 = p[1], e2 = p[2], e3 = p[3];
    const double s = e0 * e0 - (e1 * e1 + e2 * e2 + e3 * e3);
    Mat3 A;
    A(0, 0) = s + 2 * e1 * e1, A(0, 1) = 2 * (e1 * e2 - e0 * e3), A(0, 2) = 2 * (e1 * e3 + e0 * e2);
    A(1, 0) = 2 * (e2 * e1 + e0 * e3), A(1, 1) = s + 2 * e2 * e2, A(1, 2) = 2 * (e2 * e3 - e0 * e1);
    A(2, 0) = 2 * (e3 * e1 - e0 * e2), A(2, 1) = 2 * (e3 * e2 + e0 * e1), A(2, 2) = s + 2 * e3 * e3;
    return A;
}

// A(p) u without forming A (scalar code: this is the innermost operation of every joint).
inline Vec3 rotate(const double *p, const Vec3 &u) {
    const double e0 = p[0], e1 = p[1], e2 = p[2], e3 = p[3];
    const double s = e0 * e0 - (e1 * e1 + e2 * e2 + e3 * e3);
    const double eu2 = 2.0 * (e1 * u[0] + e2 * u[1] + e3 * u[2]);
    const double c0 = 2.0 * e0;
    return Vec3(s * u[0] + eu2 * e1 + c0 * (e2 * u[2] - e3 * u[1]),
                s * u[1] + eu2 * e2 + c0 * (e3 * u[0] - e1 * u[2]),
                s * u[2] + eu2 * e3 + c0 * (e1 * u[1] - e2 * u[0]));
}

// B(p, u) = d(A(p) u)/dp: column 0 is 2 (e0 u + e x u); columns 1..3 are
// 2 (e u^T - u e^T + (e.u) I - e0 skew(u)).
inline Mat34 rotate_jacobian(const double *p, const Vec3 &u) {
    const double e0 = p[0], e1 = p[1], e2 = p[2], e3 = p[3];
    const double u0 = u[0], u1 = u[1], u2 = u[2];
    const double eu = e1 * u0 + e2 * u1 + e3 * u2;
    Mat34 B;
    B(0, 0) = 2.0 * (e0 * u0 + e2 * u2 - e3 * u1);
    B(1, 0) = 2.0 * (e0 * u1 + e3 * u0 - e1 * u2);
    B(2, 0) = 2.0 * (e0 * u2 + e1 * u1 - e2 * u0);
    B(0, 1) = 2.0 * (e1 * u0 - u0 * e1 + eu);
    B(0, 2) = 2.0 * (e1 * u1 - u0 * e2 + e0 * u2);
    B(0, 3) = 2.0 * (e1 * u2 - u0 * e3 - e0 * u1);
    B(1, 1) = 2.0 * (e2 * u0 - u1 * e1 - e0 * u2);
    B(1, 2) = 2.0 * (e2 * u1 - u1 * e2 + eu);
    B(1, 3) = 2.0 * (e2 * u2 - u1 * e3 + e0 * u0);
    B(2, 1) = 2.0 * (e3 * u0 - u2 * e1 + e0 * u1);
    B(2, 2) = 2.0 * (e3 * u1 - u2 * e2 - e0 * u0);
    B(2, 3) = 2.0 * (e3 * u2 - u2 * e3 + eu);
    return B;
}

// The symmetric bilinear form behind A: C(p, p) u = A(p) u, so d(A u)/dt = 2 C(p, p_dot) u and
// the velocity-quadratic part of d2(A u)/dt2 is 2 C(p_dot, p_dot) u = 2 A(p_dot) u.
inline Vec3 bilinear(const double *p, const double *q, const Vec3 &u) {
    const double s = p[0] * q[0] - (p[1] * q[1] + p[2] * q[2] + p[3] * q[3]);
    const double qu = q[1] * u[0] + q[2] * u[1] + q[3] * u[2];
    const double pu = p[1] * u[0] + p[2] * u[1] + p[3] * u[2];
    const double w1 = p[0] * q[1] + q[0] * p[1], w2 = p[0] * q[2] + q[0] * p[2],
                 w3 = p[0] * q[3] + q[0] * p[3];
    return Vec3(s * u[0] + p[1] * qu + q[1] * pu + (w2 * u[2] - w3 * u[1]),
                s * u[1] + p[2] * qu + q[2] * pu + (w3 * u[0] - w1 * u[2]),
                s * u[2] + p[3] * qu + q[3] * pu + (w1 * u[1] - w2 * u[0]));
}

// v^T B(p, u) as a row, without forming B: 2 (e0 v.u + v.(e x u)), then
// 2 ((v.e) u - (v.u) e + (e.u) v + e0 u x v); written out (Eigen's temporaries cost twice as much),
// into out[4] (a Jacobian row's p part).
inline void rotation_row(const double *p, const Vec3 &u, const Vec3 &v, double *out) {
    const double e0 = p[0], e1 = p[1], e2 = p[2], e3 = p[3];
    const double u0 = u[0], u1 = u[1], u2 = u[2], v0 = v[0], v1 = v[1], v2 = v[2];
    const double vu = v0 * u0 + v1 * u1 + v2 * u2;
    const double ve = v0 * e1 + v1 * e2 + v2 * e3;
    const double eu = e1 * u0 + e2 * u1 + e3 * u2;
    out[0] = 2.0 * (e0 * vu + (v0 * (e2 * u2 - e3 * u1) + v1 * (e3 * u0 - e1 * u2) +
                               v2 * (e1 * u1 - e2 * u0)));
    out[1] = 2.0 * (ve * u0 - vu * e1 + eu * v0 + e0 * (u1 * v2 - u2 * v1));
    out[2] = 2.0 * (ve * u1 - vu * e2 + eu * v1 + e0 * (u2 * v0 - u0 * v2));
    out[3] = 2.0 * (ve * u2 - vu * e3 + eu * v2 + e0 * (u0 * v1 - u1 * v0));
}

// The same as a 1 x 4 row.
inline Eigen::Matrix<double, 1, 4> row_of_rotate_jacobian(const double *p, const Vec3 &u,
                                                          const Vec3 &v) {
    Eigen::Matrix<double, 1, 4> r;
    rotation_row(p, u, v, r.data());
    return r;
}

// G(p) = [-e, e0 I - skew(e)]: body angular velocity w' = 2 G p_dot.
inline Mat34 G_matrix(const double *p) {
    const Vec3 e(p[1], p[2], p[3]);
    Mat34 G;
    G.col(0) = -e;
    G.rightCols<3>() = p[0] * Mat3::Identity() - skew(e);
    return G;
}

// G(p) x (x: 4 values) and G(p)^T y (y: 3 values), written out.
inline void G_times(const double *p, const double *x, double out[3]) {
    out[0] = -p[1] * x[0] + p[0] * x[1] + p[3] * x[2] - p[2] * x[3];
    out[1] = -p[2] * x[0] - p[3] * x[1] + p[0] * x[2] + p[1] * x[3];
    out[2] = -p[3] * x[0] + p[2] * x[1] - p[1] * x[2] + p[0] * x[3];
}
inline void G_transpose_times(const double *p, const double *y, double out[4]) {
    out[0] = -p[1] * y[0] - p[2] * y[1] - p[3] * y[2];
    out[1] = p[0] * y[0] - p[3] * y[1] + p[2] * y[2];
    out[2] = p[3] * y[0] + p[0] * y[1] - p[1] * y[2];
    out[3] = -p[2] * y[0] + p[1] * y[1] + p[0] * y[2];
}

// E(p)^T y (y: 3 values), written out: p_dot = E^T w / 2 for a world angular velocity w.
inline void E_transpose_times(const double *p, const double *y, double out[4]) {
    out[0] = -p[1] * y[0] - p[2] * y[1] - p[3] * y[2];
    out[1] = p[0] * y[0] + p[3] * y[1] - p[2] * y[2];
    out[2] = -p[3] * y[0] + p[0] * y[1] + p[1] * y[2];
    out[3] = p[2] * y[0] - p[1] * y[1] + p[0] * y[2];
}

// E(p) = [-e, e0 I + skew(e)]: world angular velocity w = 2 E p_dot.
inline Mat34 E_matrix(const double *p) {
    const Vec3 e(p[1], p[2], p[3]);
    Mat34 E;
    E.col(0) = -e;
    E.rightCols<3>() = p[0] * Mat3::Identity() + skew(e);
    return E;
}

// C(p, q) as a matrix: C(p, q) u = bilinear(p, q, u).
inline Mat3 bilinear_matrix(const double *p, const double *q) {
    const double p1 = p[1], p2 = p[2], p3 = p[3], q1 = q[1], q2 = q[2], q3 = q[3];
    const double w1 = p[0] * q1 + q[0] * p1, w2 = p[0] * q2 + q[0] * p2, w3 = p[0] * q3 + q[0] * p3;
    const double s = p[0] * q[0] - (p1 * q1 + p2 * q2 + p3 * q3);
    Mat3 C;
    C(0, 0) = s + 2 * p1 * q1, C(0, 1) = p1 * q2 + q1 * p2 - w3, C(0, 2) = p1 * q3 + q1 * p3 + w2;
    C(1, 0) = p2 * q1 + q2 * p1 + w3, C(1, 1) = s + 2 * p2 * q2, C(1, 2) = p2 * q3 + q2 * p3 - w1;
    C(2, 0) = p3 * q1 + q3 * p1 - w2, C(2, 1) = p3 * q2 + q3 * p2 + w1, C(2, 2) = s + 2 * p3 * q3;
    return C;
}

// Euler parameters of a rotation matrix (Shepperd), sign chosen with e0 >= 0.
Vec4 euler_parameters(const Mat3 &R);

}  // namespace mbs
