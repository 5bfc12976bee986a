// LU with partial pivoting of a row-major 6 x 6 matrix, sizes fixed at compile time: the custom
// linear solver of the forward Newton problem and the sign of its determinant. (core/dense_lu's
// run-time sizes cost twice as much at 6 x 6, where it dominated a tracking solve.)
#pragma once

#include <cmath>
#include <utility>

namespace stewart {

// P a = L U in place (multipliers below the diagonal). False if a pivot is below 1e-14 times the
// largest entry, or not finite.
inline bool lu6_factor(double a[36], int pivot[6]) {
    double scale = 0;
    for (int i = 0; i < 36; ++i)
        if (std::fabs(a[i]) > scale) scale = std::fabs(a[i]);  // std::fmax is a libm call here
    const double tiny = 1e-14 * scale;
    for (int k = 0; k < 6; ++k) {
        int p = k;
        for (int i = k + 1; i < 6; ++i)
            if (std::fabs(a[6 * i + k]) > std::fabs(a[6 * p + k])) p = i;
        pivot[k] = p;
        if (!(std::fabs(a[6 * p + k]) > tiny) || !std::isfinite(a[6 * p + k])) return false;
        if (p != k)
            for (int c = 0; c < 6; ++c) std::swap(a[6 * k + c], a[6 * p + c]);
        const double inv = 1.0 / a[7 * k];
        for (int i = k + 1; i < 6; ++i) {
            const double l = a[6 * i + k] * inv;
            a[6 * i + k] = l;
            for (int c = k + 1; c < 6; ++c) a[6 * i + c] -= l * a[6 * k + c];
        }
    }
    return true;
}

// x <- (P^T L U)^-1 x.
inline void lu6_solve(const double a[36], const int pivot[6], double x[6]) {
    for (int k = 0; k < 6; ++k)
        if (pivot[k] != k) std::swap(x[k], x[pivot[k]]);
    for (int k = 0; k < 6; ++k)
        for (int i = k + 1; i < 6; ++i) x[i] -= a[6 * i + k] * x[k];
    for (int k = 5; k >= 0; --k) {
        for (int c = k + 1; c < 6; ++c) x[k] -= a[6 * k + c] * x[c];
        x[k] /= a[7 * k];
    }
}

// Sign of the determinant from the factors: +1 or -1.
inline int lu6_determinant_sign(const double a[36], const int pivot[6]) {
    int sign = 1;
    for (int k = 0; k < 6; ++k) {
        if (pivot[k] != k) sign = -sign;
        if (a[7 * k] < 0) sign = -sign;
    }
    return sign;
}

}  // namespace stewart
