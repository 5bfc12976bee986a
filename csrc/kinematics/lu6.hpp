// The one small LU of the library: partial pivoting of a row-major 6 x 6 matrix, sizes fixed at
// compile time and every loop unrolled (at -O2 the rolled loops cost three times the arithmetic):
// the closed forms' leg-Jacobian inverse, forward kinematics' Newton steps, condition number and
// assembly-mode sign. (core/dense_lu's run-time sizes cost twice as much at 6 x 6; Eigen's
// fixed-size PartialPivLU takes its blocked path.)
#pragma once

#include <cmath>
#include <utility>

namespace stewart {

// max |a_ij| (the scale of the singularity test).
inline double lu6_largest(const double a[36]) {
    double largest = 0;
    for (int i = 0; i < 36; ++i)
        if (std::fabs(a[i]) > largest) largest = std::fabs(a[i]);  // std::fmax is a libm call
    return largest;
}

// P a = L U in place (multipliers below the diagonal): row k swapped with row pivot[k] at step k,
// order the rows' order after all swaps ((P b)_i = b[order[i]]). False if a pivot is below
// 1e-14 times largest (max |a_ij|, lu6_largest) or not finite.
inline bool lu6_factor(double a[36], int pivot[6], int order[6], double largest) {
    const double tiny = 1e-14 * largest;
#pragma GCC unroll 6
    for (int i = 0; i < 6; ++i) order[i] = i;
#pragma GCC unroll 6
    for (int k = 0; k < 6; ++k) {
        int p = k;
#pragma GCC unroll 6
        for (int i = k + 1; i < 6; ++i)
            if (std::fabs(a[6 * i + k]) > std::fabs(a[6 * p + k])) p = i;
        pivot[k] = p;
        if (!(std::fabs(a[6 * p + k]) > tiny) || !std::isfinite(a[6 * p + k])) return false;
        if (p != k) {
#pragma GCC unroll 6
            for (int c = 0; c < 6; ++c) std::swap(a[6 * k + c], a[6 * p + c]);
            std::swap(order[k], order[p]);
        }
        const double inv = 1.0 / a[7 * k];
#pragma GCC unroll 6
        for (int i = k + 1; i < 6; ++i) {
            const double l = a[6 * i + k] * inv;
            a[6 * i + k] = l;
#pragma GCC unroll 6
            for (int c = k + 1; c < 6; ++c) a[6 * i + c] -= l * a[6 * k + c];
        }
    }
    return true;
}

// x <- (P^T L U)^-1 b from lu6_factor's a and order (x may be b).
inline void lu6_solve(const double a[36], const int order[6], const double b[6], double x[6]) {
    double y[6];
#pragma GCC unroll 6
    for (int i = 0; i < 6; ++i) y[i] = b[order[i]];
#pragma GCC unroll 6
    for (int k = 0; k < 6; ++k)
#pragma GCC unroll 6
        for (int i = k + 1; i < 6; ++i) y[i] -= a[6 * i + k] * y[k];
#pragma GCC unroll 6
    for (int k = 5; k >= 0; --k) {
#pragma GCC unroll 6
        for (int c = k + 1; c < 6; ++c) y[k] -= a[6 * k + c] * y[c];
        y[k] /= a[7 * k];
    }
#pragma GCC unroll 6
    for (int i = 0; i < 6; ++i) x[i] = y[i];
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
