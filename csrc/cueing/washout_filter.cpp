// The washout filters' exact discretisation and outputs (washout_filter.hpp).
#include "cueing/washout_filter.hpp"

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

namespace stewart {
namespace cueing {

void discretise(const FilterDesign &d, double dt, FilterStep &step) {
    // Augmented to 4 x 4 whatever n: rows and columns past n + 1 are zero, and the exponential of
    // a block-diagonal matrix with a zero block leaves the first block's exponential intact.
    Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
    for (int i = 0; i + 1 < d.n; ++i) M(i, i + 1) = 1.0;
    for (int i = 0; i < d.n; ++i) M(d.n - 1, i) = -d.a[i];
    M(d.n - 1, d.n) = 1.0;
    const Eigen::Matrix4d E = (M * dt).exp();
    for (int i = 0; i < d.n; ++i) {
        for (int j = 0; j < d.n; ++j) step.Ad[i][j] = E(i, j);
        step.Bd[i] = E(i, d.n);
    }
}

void advance(const FilterDesign &d, const FilterStep &step, double u, double z[kMaxOrder]) {
    double next[kMaxOrder] = {0, 0, 0};
    for (int i = 0; i < d.n; ++i) {
        next[i] = step.Bd[i] * u;
        for (int j = 0; j < d.n; ++j) next[i] += step.Ad[i][j] * z[j];
    }
    for (int i = 0; i < d.n; ++i) z[i] = next[i];
}

void output(const FilterDesign &d, const double z[kMaxOrder], double u, double y[3]) {
    // z^(0..n+1): the states, z^(n) = u - sum a_i z^(i), z^(n+1) = -sum a_i z^(i+1) (u' = 0).
    double w[kMaxOrder + 2];
    for (int i = 0; i < d.n; ++i) w[i] = z[i];
    w[d.n] = u;
    for (int i = 0; i < d.n; ++i) w[d.n] -= d.a[i] * z[i];
    w[d.n + 1] = 0.0;
    for (int i = 0; i < d.n; ++i) w[d.n + 1] -= d.a[i] * w[i + 1];
    for (int k = 0; k < 3; ++k) y[k] = w[d.m + k];
}

}  // namespace cueing
}  // namespace stewart
