// Euler-parameter normalisation (1 equation): p.p - 1 = 0.
#include "core/joints/primitives.hpp"

namespace mbs {

static void evaluate_normalization(const JointInput &in, const JointOutput &out) {
    normalization_rows(in.q_i + 3, in.v_i ? in.v_i + 3 : nullptr, out);
}

extern const JointTypeInfo kNormalization = {"normalization", 1, 0, 1, evaluate_normalization};

}  // namespace mbs
