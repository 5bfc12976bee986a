// Euler-parameter normalisation (1 equation): p.p - 1 = 0.
#include "core/joints/primitives.hpp"

namespace mbs {

static void evaluate_normalization(const JointInput &in, const JointOutput &out) {
    const double *p = in.q_i + 3;
    if (out.phi) out.phi[0] = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3] - 1.0;
    if (out.phi_t) out.phi_t[0] = 0.0;
    if (out.gamma) {
        const double *pd = in.v_i + 3;
        out.gamma[0] = -2.0 * (pd[0] * pd[0] + pd[1] * pd[1] + pd[2] * pd[2] + pd[3] * pd[3]);
    }
    if (out.jac_i)
        for (int c = 0; c < 7; ++c) out.jac_i[c] = c < 3 ? 0.0 : 2.0 * p[c - 3];
}

extern const JointTypeInfo kNormalization = {"normalization", 1, 0, 1, evaluate_normalization};

}  // namespace mbs
