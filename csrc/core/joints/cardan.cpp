// Cardan (universal) joint (4 equations): points coincide and the cross arms stay perpendicular,
// (A_i s_i)^T (A_j s_j) = 0 with s_i = axis_i[0], s_j = axis_j[0].
#include "core/joints/primitives.hpp"

namespace mbs {

static void evaluate_cardan(const JointInput &in, const JointOutput &out) {
    const RowWriter w{out};
    point_coincidence(in, w, 0);
    dot1(in, w, 3, in.def.axis_i[0], in.def.axis_j[0]);
}

extern const JointTypeInfo kCardan = {"cardan", 4, 0, 2, evaluate_cardan};

}  // namespace mbs
