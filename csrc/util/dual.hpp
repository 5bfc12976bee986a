// The scalar that carries derivatives (forward-mode automatic differentiation): a value and its
// derivatives along 18 directions, enough for a state and its inputs (pose, pose rates, forces)
// or for a pose and its two rates. Eigen's AutoDiffScalar (Debian's libeigen3-dev).
#pragma once

#include <Eigen/Dense>
#include <unsupported/Eigen/AutoDiff>

namespace stewart {

constexpr int kDualDirections = 18;
using DualDerivatives = Eigen::Matrix<double, kDualDirections, 1>;
using Dual = Eigen::AutoDiffScalar<DualDerivatives>;

// The value of x (x itself for a double).
inline double value_of(double x) { return x; }
inline double value_of(const Dual &x) { return x.value(); }

}  // namespace stewart
