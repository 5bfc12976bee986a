/* The controller's directional derivatives (model_interface.h): F_k = F_ff,k + kp (L_ref,k -
 * L_k) + kd (L_dot_ref,k - L_dot_k) is linear, its derivatives are the gains. */
#include "model_interface.h"
#include "variables.h"

/* dF_k / d input vr: 1, +-kp, +-kd for leg k's own inputs, 0 for the other legs'. */
static double gain(const fmu_values *v, unsigned force_vr, unsigned input_vr) {
    const unsigned leg = force_vr - VR_F_1, block = (input_vr - VR_L_ref_1) / 6;
    if ((input_vr - VR_L_ref_1) % 6 != leg) return 0.0;
    const double kp = v->real[VR_kp], kd = v->real[VR_kd];
    const double by_block[5] = {kp, kd, 1.0, -kp, -kd}; /* L_ref, L_dot_ref, F_ff, L, L_dot */
    return by_block[block];
}

fmu_status model_directional_derivative(fmu_instance *inst, const unsigned unknown[],
                                        size_t n_unknown, const unsigned known[], size_t n_known,
                                        const double seed[], double sensitivity[],
                                        const char *function) {
    (void)function; /* a constant gain: no call fails */
    for (size_t i = 0; i < n_unknown; ++i) {
        double sum = 0;
        for (size_t j = 0; j < n_known; ++j) sum += gain(&inst->v, unknown[i], known[j]) * seed[j];
        sensitivity[i] = sum;
    }
    return FMU_OK;
}
