// Cylindrical joint (4 equations): body j's axis v_j = axis_j[2] stays parallel to body i's axis
// (perpendicular to v1 = axis_i[0] and v2 = axis_i[1]), and the vector between the two points
// stays on the axis.
#include "core/joints/primitives.hpp"

namespace mbs {

void parallel_axes(const JointInput &in, const RowWriter &w, int row) {
    dot1(in, w, row, in.def.axis_i[0], in.def.axis_j[2]);
    dot1(in, w, row + 1, in.def.axis_i[1], in.def.axis_j[2]);
}

void cylindrical_rows(const JointInput &in, const JointOutput &out, const RowWriter &w) {
    parallel_axes(in, w, 0);
    const Separation d = separation(in, out);
    dot2(in, w, 2, in.def.axis_i[0], d);
    dot2(in, w, 3, in.def.axis_i[1], d);
}

static void evaluate_cylindrical(const JointInput &in, const JointOutput &out) {
    cylindrical_rows(in, out, RowWriter{out});
}

// With a distance driver of it: evaluate_cylindrical_with_distance (primitives.cpp, which
// shares the rows' inlined bodies).

extern const JointTypeInfo kCylindrical = {"cylindrical", 4, 0, 2, evaluate_cylindrical};

}  // namespace mbs
