// Cardan (universal) joint (4 equations): points coincide and the cross arms stay perpendicular,
// (A_i s_i)^T (A_j s_j) = 0 with s_i = axis_i[0], s_j = axis_j[0]. Its rows: primitives.cpp
// cardan_rows (the two primitives inlined into one call).
#include "core/joints/primitives.hpp"

namespace mbs {

extern const JointTypeInfo kCardan = {"cardan", 4, 0, 2, cardan_rows};

}  // namespace mbs
