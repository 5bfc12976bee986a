#include "core/dense_lu.hpp"

#include <cmath>
#include <utility>

namespace mbs {

namespace {
// The bodies, inlined into the general entry points and into the square ones below, where the
// sizes are constants (the same operations in the same order, unrolled by the compiler: each
// outer loop's `unroll` pragma makes the inner loops' bounds constant there, and GCC leaves the
// general entry points' loops as they are; the 7 x 7 border of the full step, factor and
// transposed solve: 2.25 k -> 1.43 k instructions).
#define MBS_LU_INLINE inline __attribute__((always_inline))

MBS_LU_INLINE bool factor_body(double *a, int m, int n, int width, int *pivot) {
    double scale = 0;
    for (int i = 0; i < m * width; ++i) {
        const double v = std::fabs(a[i]);
        if (v > scale) scale = v;
    }
    const double tiny = 1e-14 * (scale > 0 ? scale : 1.0);
#pragma GCC unroll 8
    for (int k = 0; k < n; ++k) {
        int p = k;
        double best = std::fabs(a[k * width + k]);
        for (int i = k + 1; i < m; ++i)
            if (std::fabs(a[i * width + k]) > best) best = std::fabs(a[i * width + k]), p = i;
        pivot[k] = p;
        if (!(best > tiny)) return false;
        if (p != k)
            for (int c = 0; c < width; ++c) std::swap(a[k * width + c], a[p * width + c]);
        const double *row_k = a + k * width;
        const double inv = 1.0 / row_k[k];
        for (int i = k + 1; i < m; ++i) {
            double *row_i = a + i * width;
            const double l = row_i[k] * inv;
            row_i[k] = l;
            if (l != 0.0)
                for (int c = k + 1; c < width; ++c) row_i[c] -= l * row_k[c];
        }
    }
    return true;
}

MBS_LU_INLINE void forward_transposed_body(const double *a, int n, int width, const double *g,
                                           double *mu) {
#pragma GCC unroll 8
    for (int k = 0; k < n; ++k) {
        double s = g[k];
        for (int j = 0; j < k; ++j) s -= a[j * width + k] * mu[j];
        mu[k] = s / a[k * width + k];
    }
}

MBS_LU_INLINE void backward_transposed_body(const double *a, int m, int n, int width,
                                            const int *pivot, double *t) {
#pragma GCC unroll 8
    for (int k = n - 1; k >= 0; --k) {
        double s = t[k];
        for (int i = k + 1; i < m; ++i) s -= a[i * width + k] * t[i];
        t[k] = s;
    }
    for (int k = n - 1; k >= 0; --k)
        if (pivot[k] != k) std::swap(t[k], t[pivot[k]]);
}

}  // namespace

#undef MBS_LU_INLINE  // the bodies' attribute only: no other file sees the macro

bool lu_factor(double *a, int m, int n, int width, int *pivot) {
    return factor_body(a, m, n, width, pivot);
}

void lu_forward_transposed(const double *a, int n, int width, const double *g, double *mu) {
    forward_transposed_body(a, n, width, g, mu);
}

void lu_backward_transposed(const double *a, int m, int n, int width, const int *pivot, double *t) {
    backward_transposed_body(a, m, n, width, pivot, t);
}

template <int N>
bool lu_factor_square(double *a, int *pivot) {
    return factor_body(a, N, N, N, pivot);
}

template <int N>
void lu_solve_transposed_square(const double *a, const int *pivot, const double *g, double *mu) {
    forward_transposed_body(a, N, N, g, mu);
    backward_transposed_body(a, N, N, N, pivot, mu);
}

template bool lu_factor_square<7>(double *, int *);
template void lu_solve_transposed_square<7>(const double *, const int *, const double *, double *);

void lu_forward(const double *a, int m, int n, int width, const int *pivot, double *t) {
    for (int k = 0; k < n; ++k)
        if (pivot[k] != k) std::swap(t[k], t[pivot[k]]);
    for (int k = 0; k < n; ++k) {
        const double tk = t[k];
        if (tk != 0.0)
            for (int i = k + 1; i < m; ++i) t[i] -= a[i * width + k] * tk;
    }
}

void lu_backward(const double *a, int n, int width, const double *t, const double *y, double *x) {
    const int carried = width - n;
    for (int k = n - 1; k >= 0; --k) {
        const double *row = a + k * width;
        double s = t[k];
        for (int c = k + 1; c < n; ++c) s -= row[c] * x[c];
        if (y)
            for (int c = 0; c < carried; ++c) s -= row[n + c] * y[c];
        x[k] = s / row[k];
    }
}

}  // namespace mbs
