// Spherical joint (3 equations): the two attachment points coincide.
#include "core/joints/primitives.hpp"

namespace mbs {

static void evaluate_spherical(const JointInput &in, const JointOutput &out) {
    point_coincidence(in, RowWriter{out}, 0);
}

extern const JointTypeInfo kSpherical = {"spherical", 3, 0, 2, evaluate_spherical};

}  // namespace mbs
