// Inverse of a 6x6 matrix by Gauss-Jordan elimination with partial pivoting. Eigen's LU takes its
// general blocked path even for fixed 6x6 sizes; this straight loop is several times faster.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <utility>

namespace stewart {

// Returns false (inv undefined) when a pivot is exactly zero or not finite.
inline bool invert_6x6(const Eigen::Matrix<double, 6, 6> &A, Eigen::Matrix<double, 6, 6> &inv) {
    double a[6][6], b[6][6];
    for (int r = 0; r < 6; ++r)
        for (int c = 0; c < 6; ++c) {
            a[r][c] = A(r, c);
            b[r][c] = r == c ? 1.0 : 0.0;
        }
    for (int c = 0; c < 6; ++c) {
        int pivot = c;
        for (int r = c + 1; r < 6; ++r)
            if (std::fabs(a[r][c]) > std::fabs(a[pivot][c])) pivot = r;
        if (!(std::fabs(a[pivot][c]) > 0.0) || !std::isfinite(a[pivot][c])) return false;
        if (pivot != c)
            for (int j = 0; j < 6; ++j) {
                std::swap(a[pivot][j], a[c][j]);
                std::swap(b[pivot][j], b[c][j]);
            }
        const double scale = 1.0 / a[c][c];
        for (int j = 0; j < 6; ++j) {
            a[c][j] *= scale;
            b[c][j] *= scale;
        }
        for (int r = 0; r < 6; ++r) {
            if (r == c) continue;
            const double f = a[r][c];
            for (int j = 0; j < 6; ++j) {
                a[r][j] -= f * a[c][j];
                b[r][j] -= f * b[c][j];
            }
        }
    }
    for (int r = 0; r < 6; ++r)
        for (int c = 0; c < 6; ++c) inv(r, c) = b[r][c];
    return true;
}

}  // namespace stewart
