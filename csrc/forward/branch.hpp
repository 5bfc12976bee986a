// Which assembly mode a pose is on, and lengths that no pose can have: the checks around the
// forward Newton solve.
#pragma once

#include "forward/leg_factors.hpp"
#include "kinematics/closed_form.hpp"

namespace stewart {

// The platform attachment points p + R b_k in the world at pose q.
Matrix36 platform_points_world(const PlatformGeometry &g, const double q[6]);

// Sign (+1, -1; 0 if singular) of the determinant of a leg Jacobian (LegJacobian::transposed).
int jacobian_sign(const Matrix6 &transposed);

// The side of each Cardan a leg stays on in the working mode, from the home pose: the base's z
// axis if the leg rises at home (the thesis platform: every leg), -z if it falls (a hanging
// platform), its home direction if it is (nearly) horizontal; the platform's the same in the
// platform frame. Joints at any height: no plane of joints is assumed.
struct BranchSides {
    Matrix36 base;      // world
    Matrix36 platform;  // platform frame
    // +1 where both sides are +z, -1 where both are -z (the checks are then one product and one
    // signed component), 0 otherwise; all_vertical: no 0.
    double vertical[STEWART_LEGS];
    bool all_vertical;
};
BranchSides branch_sides(const PlatformGeometry &g, double home_height);

// STEWART_BRANCH_* bits of a pose given by its rotation R, its platform points (world) and the
// sign of its leg Jacobian's determinant (0: the working mode: every leg leaves its base Cardan and
// reaches its platform Cardan on the sides it has at home, the platform faces up, and the
// determinant has working_sign, its sign at home).
int assembly_branch(const PlatformGeometry &g, const BranchSides &sides, const Eigen::Matrix3d &R,
                    const LegVectors &points, int jacobian_sign, int working_sign);

// Bounds on the lengths of the 15 pairs i < j that hold at every pose: from
// d_i - d_j = (a_j - a_i) + R (b_i - b_j), |L_i - L_j| <= |a_i - a_j| + |b_i - b_j| (difference)
// and L_i + L_j >= | |a_i - a_j| - |b_i - b_j| | (sum).
struct LengthPairBounds {
    double difference[15], sum[15];
    // The tests' thresholds, with a relative slack of a few roundings (lengths computed from a
    // pose at a bound must pass): sum * (1 - 1e-12) - 1e-15 and difference * (1 + 1e-12) + 1e-15.
    double least_sum[15], largest_difference[15];
};
LengthPairBounds length_pair_bounds(const PlatformGeometry &g);

// STEWART_ERR_UNREACHABLE (message names the leg, or the pair) when two lengths break a bound.
stewart_status check_length_pairs(const LengthPairBounds &bounds, const double length[STEWART_LEGS],
                                  char *msg, size_t size);

}  // namespace stewart
