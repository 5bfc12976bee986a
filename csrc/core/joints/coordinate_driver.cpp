// Coordinate driver (1 equation): q_i[c] - f(t) = 0. The pose driver is seven of them.
#include "core/joints/primitives.hpp"

namespace mbs {

static void drive_coordinate(const JointInput &in, const JointOutput &out, int row, int c,
                             const DriverValue &f) {
    if (out.phi) out.phi[row] = in.q_i[c] - f.value;
    if (out.phi_t) out.phi_t[row] = -f.rate;
    if (out.gamma) out.gamma[row] = f.accel;
    if (out.jac_i)
        for (int k = 0; k < 7; ++k)
            out.jac_i[MBS_BODY_COORDINATES * row + k] = (k == c) ? 1.0 : 0.0;
}

static void evaluate_coordinate_driver(const JointInput &in, const JointOutput &out) {
    drive_coordinate(in, out, 0, in.def.coordinate, in.drive[0]);
}

static void evaluate_pose_driver(const JointInput &in, const JointOutput &out) {
    for (int c = 0; c < 7; ++c) drive_coordinate(in, out, c, c, in.drive[c]);
}

extern const JointTypeInfo kCoordinateDriver = {"coordinate driver", 1, 1, 1,
                                                evaluate_coordinate_driver};
extern const JointTypeInfo kPoseDriver = {"pose driver", 7, 7, 1, evaluate_pose_driver};

}  // namespace mbs
