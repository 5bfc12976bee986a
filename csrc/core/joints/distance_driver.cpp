// Distance driver (1 equation): the distance along a cylindrical or prismatic joint's axis
// between its two points, (A_i v_i)^T (r_j + A_j u_j - r_i - A_i u_i) - f(t) = 0: an actuator
// length. Its multiplier is minus the actuator force pushing body j away from body i.
#include "core/joints/primitives.hpp"

namespace mbs {

static void evaluate_distance_driver(const JointInput &in, const JointOutput &out) {
    dot2(in, RowWriter{out}, 0, in.def.axis_i[2], separation(in, out), in.drive);
}

extern const JointTypeInfo kDistanceDriver = {"distance driver", 1, 1, 2, evaluate_distance_driver};

}  // namespace mbs
