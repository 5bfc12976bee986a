// Fixed body (7 equations): its coordinates equal constants, q_i - q_fixed = 0.
#include "core/joints/primitives.hpp"

namespace mbs {

static void evaluate_fixed_body(const JointInput &in, const JointOutput &out) {
    for (int k = 0; k < 7; ++k) {
        if (out.phi) out.phi[k] = in.q_i[k] - in.def.q_fixed[k];
        if (out.phi_t) out.phi_t[k] = 0.0;
        if (out.gamma) out.gamma[k] = 0.0;
        if (out.jac_i)
            for (int c = 0; c < 7; ++c)
                out.jac_i[MBS_BODY_COORDINATES * k + c] = (c == k) ? 1.0 : 0.0;
    }
}

extern const JointTypeInfo kFixedBody = {"fixed body", 7, 0, 1, evaluate_fixed_body};

}  // namespace mbs
