// Prismatic joint (5 equations): a cylindrical joint that also keeps body j from turning about
// the axis: (A_i v1)^T (A_j h_j) = 0 with h_j = axis_j[1], the body-j image of v2 at assembly.
#include "core/joints/primitives.hpp"

namespace mbs {

static void evaluate_prismatic(const JointInput &in, const JointOutput &out) {
    const RowWriter w{out};
    dot1(in, w, 0, in.def.axis_i[0], in.def.axis_j[2]);
    dot1(in, w, 1, in.def.axis_i[1], in.def.axis_j[2]);
    const Separation d = separation(in, out);
    dot2(in, w, 2, in.def.axis_i[0], d);
    dot2(in, w, 3, in.def.axis_i[1], d);
    dot1(in, w, 4, in.def.axis_i[0], in.def.axis_j[1]);
}

extern const JointTypeInfo kPrismatic = {"prismatic", 5, 0, 2, evaluate_prismatic};

}  // namespace mbs
