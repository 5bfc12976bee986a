// The pose coordinates' names, once: messages, CSV headers and variable names spell them so.
#pragma once

namespace stewart {

// x, y, z, roll, pitch, yaw (defined in motion.cpp).
extern const char *const kPoseNames[6];

}  // namespace stewart
