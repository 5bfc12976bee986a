// Which assembly mode a pose is on, and lengths that no pose can have: the checks around the
// forward Newton solve.
#pragma once

#include "platform/closed_form.hpp"

namespace stewart {

// Sign (+1, -1, or 0 if singular) of the determinant of the leg Jacobian at pose q.
int leg_jacobian_sign(const PlatformGeometry &g, const double q[6]);

// STEWART_BRANCH_* bits of the pose q (0: the working mode: every leg leaves its base Cardan
// upward and reaches its platform Cardan from below, the platform faces up, and the leg
// Jacobian's determinant has working_sign, its sign at home).
int assembly_branch(const PlatformGeometry &g, const double q[6], int working_sign);

// Largest distance a platform attachment point moves between poses a and b [m].
double largest_point_displacement(const PlatformGeometry &g, const double a[6], const double b[6]);

// STEWART_ERR_UNREACHABLE (message names the leg) when two lengths differ by more than any pose
// allows: d_i - d_j = (a_j - a_i) + R (b_i - b_j), so |L_i - L_j| <= |a_i - a_j| + |b_i - b_j|.
stewart_status check_length_pairs(const PlatformGeometry &g, const double length[STEWART_LEGS],
                                  char *msg, size_t size);

}  // namespace stewart
