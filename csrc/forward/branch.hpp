// Which assembly mode a pose is on, and lengths that no pose can have: the checks around the
// forward Newton solve.
#pragma once

#include "kinematics/closed_form.hpp"

namespace stewart {

// The platform attachment points p + R b_k in the world at pose q.
Matrix36 platform_points_world(const PlatformGeometry &g, const double q[6]);

// Sign (+1, -1; 0 if singular) of the determinant of a leg Jacobian (LegJacobian::transposed).
int jacobian_sign(const Matrix6 &transposed);

// STEWART_BRANCH_* bits of a pose given by its rotation R, its platform points and its leg
// Jacobian (0: the working mode: every leg leaves its base Cardan upward and reaches its
// platform Cardan from below, the platform faces up, and the Jacobian's determinant has
// working_sign, its sign at home).
int assembly_branch(const PlatformGeometry &g, const Eigen::Matrix3d &R, const Matrix36 &points,
                    const Matrix6 &jacobian_transposed, int working_sign);

// Bounds on the lengths of the 15 pairs i < j that hold at every pose: from
// d_i - d_j = (a_j - a_i) + R (b_i - b_j), |L_i - L_j| <= |a_i - a_j| + |b_i - b_j| (difference)
// and L_i + L_j >= | |a_i - a_j| - |b_i - b_j| | (sum).
struct LengthPairBounds {
    double difference[15], sum[15];
};
LengthPairBounds length_pair_bounds(const PlatformGeometry &g);

// STEWART_ERR_UNREACHABLE (message names the leg, or the pair) when two lengths break a bound.
stewart_status check_length_pairs(const LengthPairBounds &bounds,
                                  const double length[STEWART_LEGS], char *msg, size_t size);

}  // namespace stewart
