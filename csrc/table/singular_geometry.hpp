// Geometries singular at every pose, refused when the model is made: a side whose six joints lie
// on one line (or at one point) lets the platform turn about that line (or point) without any leg
// changing length, whatever the pose.
#pragma once

#include <cstddef>

#include "stewart/stewart.h"

namespace stewart {

// STEWART_OK, or STEWART_ERR_PARAMETER naming the side, the line or point and the fields. The
// joints must have passed check_joint_geometry.
stewart_status check_not_singular_everywhere(const stewart_params &p, char *msg, size_t size);

}  // namespace stewart
