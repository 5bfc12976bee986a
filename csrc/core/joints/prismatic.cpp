// Prismatic joint (5 equations): a cylindrical joint that also keeps body j from turning about
// the axis: (A_i v1)^T (A_j h_j) = 0 with h_j = axis_j[1], the body-j image of v2 at assembly.
#include "core/joints/primitives.hpp"

namespace mbs {

static void evaluate_prismatic(const JointInput &in, const JointOutput &out) {
    const RowWriter w{out};
    cylindrical_rows(in, out, w);
    dot1(in, w, 4, in.def.axis_i[0], in.def.axis_j[1]);
}

extern const JointTypeInfo kPrismatic = {"prismatic", 5, 0, 2, evaluate_prismatic};

}  // namespace mbs
