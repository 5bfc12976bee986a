// Revolute joint (5 equations): points coincide and the axes (axis_i[2] on i, axis_j[2] on j)
// stay parallel.
#include "core/joints/primitives.hpp"

namespace mbs {

static void evaluate_revolute(const JointInput &in, const JointOutput &out) {
    const RowWriter w{out};
    point_coincidence(in, w, 0);
    parallel_axes(in, w, 3);
}

extern const JointTypeInfo kRevolute = {"revolute", 5, 0, 2, evaluate_revolute};

}  // namespace mbs
