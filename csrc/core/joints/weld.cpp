// Weld (fixed joint, 6 equations): points coincide and the joint frames stay aligned:
// x_i.y_j = x_i.z_j = y_i.z_j = 0 with the frames in axis_i[0..2] and axis_j[0..2].
#include "core/joints/primitives.hpp"

namespace mbs {

static void evaluate_weld(const JointInput &in, const JointOutput &out) {
    const RowWriter w{out};
    point_coincidence(in, w, 0);
    dot1(in, w, 3, in.def.axis_i[0], in.def.axis_j[1]);
    dot1(in, w, 4, in.def.axis_i[0], in.def.axis_j[2]);
    dot1(in, w, 5, in.def.axis_i[1], in.def.axis_j[2]);
}

extern const JointTypeInfo kWeld = {"weld", 6, 0, 2, evaluate_weld};

}  // namespace mbs
