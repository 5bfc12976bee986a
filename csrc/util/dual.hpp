// The scalar that carries derivatives (forward-mode automatic differentiation): a value and its
// derivatives along 18 directions, enough for a state and its inputs (pose, pose rates, forces)
// or for a pose and its two rates. Eigen's AutoDiffScalar (Debian's libeigen3-dev), fixed size:
// no allocation. (A hand-written dual that carried only its non-zero blocks of six directions
// took more instructions, 1.38 M against 1.11 M per full-fidelity linearisation: the copies of
// its 160 bytes outweighed the skipped blocks.)
#pragma once

#include <Eigen/Dense>
#include <unsupported/Eigen/AutoDiff>

namespace stewart {

constexpr int kDualDirections = 18;
using DualDerivatives = Eigen::Matrix<double, kDualDirections, 1>;
using Dual = Eigen::AutoDiffScalar<DualDerivatives>;

// The same along the 12 directions of the plant's state (q, q_dot) alone: the linearisation's
// fast path, where the forces enter linearly and need no directions (linearize/plant_jacobian.*).
constexpr int kStateDirections = 12;
using StateDualDerivatives = Eigen::Matrix<double, kStateDirections, 1>;
using StateDual = Eigen::AutoDiffScalar<StateDualDerivatives>;

}  // namespace stewart
