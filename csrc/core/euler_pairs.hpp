// Two of euler.hpp's small products at once, one in each lane of a two-double vector (GCC/Clang
// vector extensions: SSE2 on x86-64, NEON on ARM). Each lane does exactly the scalar function's
// operations in its order (no FMA contraction without -mfma/-ffp-contract=fast), so the results
// are the scalar functions' bits; the joints' rows pair body i's term with body j's.
#pragma once

#include "core/euler.hpp"

namespace mbs {

typedef double Lanes __attribute__((vector_size(16)));

// (a, b) in the two lanes.
inline Lanes lanes(double a, double b) { return Lanes{a, b}; }

// rotation(pa) into Aa and rotation(pb) into Ab.
inline void rotation_two(const double *pa, const double *pb, Mat3 &Aa, Mat3 &Ab) {
    const Lanes e0 = lanes(pa[0], pb[0]), e1 = lanes(pa[1], pb[1]), e2 = lanes(pa[2], pb[2]),
                e3 = lanes(pa[3], pb[3]);
    const Lanes two = lanes(2.0, 2.0);
    const Lanes s = e0 * e0 - (e1 * e1 + e2 * e2 + e3 * e3);
    Lanes A[3][3];
    A[0][0] = s + two * e1 * e1, A[0][1] = two * (e1 * e2 - e0 * e3);
    A[0][2] = two * (e1 * e3 + e0 * e2), A[1][0] = two * (e2 * e1 + e0 * e3);
    A[1][1] = s + two * e2 * e2, A[1][2] = two * (e2 * e3 - e0 * e1);
    A[2][0] = two * (e3 * e1 - e0 * e2), A[2][1] = two * (e3 * e2 + e0 * e1);
    A[2][2] = s + two * e3 * e3;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) Aa(r, c) = A[r][c][0], Ab(r, c) = A[r][c][1];
}

// times(Ma, ua) into a and times(Mb, ub) into b.
inline void times_two(const Mat3 &Ma, const Vec3 &ua, const Mat3 &Mb, const Vec3 &ub, Vec3 &a,
                      Vec3 &b) {
    const Lanes u0 = lanes(ua[0], ub[0]), u1 = lanes(ua[1], ub[1]), u2 = lanes(ua[2], ub[2]);
    for (int r = 0; r < 3; ++r) {
        const Lanes v = lanes(Ma(r, 0), Mb(r, 0)) * u0 + lanes(Ma(r, 1), Mb(r, 1)) * u1 +
                        lanes(Ma(r, 2), Mb(r, 2)) * u2;
        a[r] = v[0], b[r] = v[1];
    }
}

// rotation_row(pa, ua, va, out_a) and rotation_row(pb, ub, vb, out_b).
inline void rotation_row_two(const double *pa, const Vec3 &ua, const Vec3 &va, double *out_a,
                             const double *pb, const Vec3 &ub, const Vec3 &vb, double *out_b) {
    const Lanes e0 = lanes(pa[0], pb[0]), e1 = lanes(pa[1], pb[1]), e2 = lanes(pa[2], pb[2]),
                e3 = lanes(pa[3], pb[3]);
    const Lanes u0 = lanes(ua[0], ub[0]), u1 = lanes(ua[1], ub[1]), u2 = lanes(ua[2], ub[2]);
    const Lanes v0 = lanes(va[0], vb[0]), v1 = lanes(va[1], vb[1]), v2 = lanes(va[2], vb[2]);
    const Lanes two = lanes(2.0, 2.0);
    const Lanes vu = v0 * u0 + v1 * u1 + v2 * u2;
    const Lanes ve = v0 * e1 + v1 * e2 + v2 * e3;
    const Lanes eu = e1 * u0 + e2 * u1 + e3 * u2;
    const Lanes r0 = two * (e0 * vu + (v0 * (e2 * u2 - e3 * u1) + v1 * (e3 * u0 - e1 * u2) +
                                       v2 * (e1 * u1 - e2 * u0)));
    const Lanes r1 = two * (ve * u0 - vu * e1 + eu * v0 + e0 * (u1 * v2 - u2 * v1));
    const Lanes r2 = two * (ve * u1 - vu * e2 + eu * v1 + e0 * (u2 * v0 - u0 * v2));
    const Lanes r3 = two * (ve * u2 - vu * e3 + eu * v2 + e0 * (u0 * v1 - u1 * v0));
    out_a[0] = r0[0], out_a[1] = r1[0], out_a[2] = r2[0], out_a[3] = r3[0];
    out_b[0] = r0[1], out_b[1] = r1[1], out_b[2] = r2[1], out_b[3] = r3[1];
}

// rotate_jacobian(pa, ua) into Ba and rotate_jacobian(pb, ub) into Bb.
inline void rotate_jacobian_two(const double *pa, const Vec3 &ua, const double *pb, const Vec3 &ub,
                                Mat34 &Ba, Mat34 &Bb) {
    const Lanes e0 = lanes(pa[0], pb[0]), e1 = lanes(pa[1], pb[1]), e2 = lanes(pa[2], pb[2]),
                e3 = lanes(pa[3], pb[3]);
    const Lanes u0 = lanes(ua[0], ub[0]), u1 = lanes(ua[1], ub[1]), u2 = lanes(ua[2], ub[2]);
    const Lanes two = lanes(2.0, 2.0);
    const Lanes eu = e1 * u0 + e2 * u1 + e3 * u2;
    Lanes B[3][4];
    B[0][0] = two * (e0 * u0 + e2 * u2 - e3 * u1);
    B[1][0] = two * (e0 * u1 + e3 * u0 - e1 * u2);
    B[2][0] = two * (e0 * u2 + e1 * u1 - e2 * u0);
    B[0][1] = two * (e1 * u0 - u0 * e1 + eu);
    B[0][2] = two * (e1 * u1 - u0 * e2 + e0 * u2);
    B[0][3] = two * (e1 * u2 - u0 * e3 - e0 * u1);
    B[1][1] = two * (e2 * u0 - u1 * e1 - e0 * u2);
    B[1][2] = two * (e2 * u1 - u1 * e2 + eu);
    B[1][3] = two * (e2 * u2 - u1 * e3 + e0 * u0);
    B[2][1] = two * (e3 * u0 - u2 * e1 + e0 * u1);
    B[2][2] = two * (e3 * u1 - u2 * e2 - e0 * u0);
    B[2][3] = two * (e3 * u2 - u2 * e3 + eu);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) Ba(r, c) = B[r][c][0], Bb(r, c) = B[r][c][1];
}

// G_times(pa, xa, out_a) and G_times(pb, xb, out_b).
inline void G_times_two(const double *pa, const double *xa, const double *pb, const double *xb,
                        Lanes out[3]) {
    const Lanes p0 = lanes(pa[0], pb[0]), p1 = lanes(pa[1], pb[1]), p2 = lanes(pa[2], pb[2]),
                p3 = lanes(pa[3], pb[3]);
    const Lanes x0 = lanes(xa[0], xb[0]), x1 = lanes(xa[1], xb[1]), x2 = lanes(xa[2], xb[2]),
                x3 = lanes(xa[3], xb[3]);
    out[0] = -p1 * x0 + p0 * x1 + p3 * x2 - p2 * x3;
    out[1] = -p2 * x0 - p3 * x1 + p0 * x2 + p1 * x3;
    out[2] = -p3 * x0 + p2 * x1 - p1 * x2 + p0 * x3;
}

// E_transpose_times(p, ya, out_a) and E_transpose_times(p, yb, out_b): one body, two vectors.
inline void E_transpose_times_two(const double *p, const double *ya, const double *yb,
                                  double *out_a, double *out_b) {
    const Lanes p0 = lanes(p[0], p[0]), p1 = lanes(p[1], p[1]), p2 = lanes(p[2], p[2]),
                p3 = lanes(p[3], p[3]);
    const Lanes y0 = lanes(ya[0], yb[0]), y1 = lanes(ya[1], yb[1]), y2 = lanes(ya[2], yb[2]);
    const Lanes r[4] = {-p1 * y0 - p2 * y1 - p3 * y2, p0 * y0 + p3 * y1 - p2 * y2,
                        -p3 * y0 + p0 * y1 + p1 * y2, p2 * y0 - p1 * y1 + p0 * y2};
    for (int c = 0; c < 4; ++c) out_a[c] = r[c][0], out_b[c] = r[c][1];
}

// G_transpose_times(pa, lane 0 of y, out_a) and G_transpose_times(pb, lane 1 of y, out_b).
inline void G_transpose_times_two(const double *pa, const double *pb, const Lanes y[3],
                                  Lanes out[4]) {
    const Lanes p0 = lanes(pa[0], pb[0]), p1 = lanes(pa[1], pb[1]), p2 = lanes(pa[2], pb[2]),
                p3 = lanes(pa[3], pb[3]);
    out[0] = -p1 * y[0] - p2 * y[1] - p3 * y[2];
    out[1] = p0 * y[0] - p3 * y[1] + p2 * y[2];
    out[2] = p3 * y[0] + p0 * y[1] - p1 * y[2];
    out[3] = -p2 * y[0] + p1 * y[1] + p0 * y[2];
}

}  // namespace mbs
