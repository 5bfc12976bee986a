// The joints of a parameter set, whichever way it gives them (docs/geometry.md): geometry 0 puts
// them on two circles (base_radius, base_angle; platform_radius, platform_angle), geometry 1 takes
// the 36 coordinates base_joint, platform_joint. Every level places its legs from this one answer.
#pragma once

#include <Eigen/Dense>

#include "stewart/stewart.h"

namespace stewart {

using Matrix36 = Eigen::Matrix<double, 3, STEWART_LEGS>;

struct JointGeometry {
    Matrix36 base_points;      // a_k, base frame
    Matrix36 platform_points;  // b_k, platform frame
    Matrix36 base_arms;        // unit fixed arm of each base Cardan, base frame
    Matrix36 platform_arms;    // unit fixed arm of each platform Cardan, platform frame
    // The size of each side: the radius (geometry 0) or the largest |a_k|, |b_k| (geometry 1).
    double base_size, platform_size;
};

// The joints of p (p's values must have passed their per-element checks).
JointGeometry joint_geometry(const stewart_params &p);

// STEWART_OK, or STEWART_ERR_PARAMETER with a message naming the field and its value: geometry
// neither 0 nor 1; a Cardan axis neither zero nor unit, or along its leg at home; a zero axis on
// a joint on the z axis (no azimuth, so no tangent); two joints of one side at the same point;
// a leg of zero length at home. Per-element ranges are checked before (stewart_params_check).
stewart_status check_joint_geometry(const stewart_params &p, char *msg, size_t size);

}  // namespace stewart
