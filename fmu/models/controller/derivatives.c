/* The controller's directional derivatives (model_interface.h). output = 0: F_k = F_ff,k + kp
 * (L_ref,k - L_k) + kd (L_dot_ref,k - L_dot,k) is linear, its derivatives are the gains.
 * output = 1: the cascade's slopes at the current inputs and state (0 through a limit that
 * holds). */
#include "controller.h"
#include "model_interface.h"
#include "variables.h"

/* dF_k / d input vr for the output F_k of force_vr: leg k's own inputs only. */
static double slope(const fmu_values *v, unsigned force_vr, unsigned input_vr) {
    const unsigned leg = force_vr - VR_F_1, block = (input_vr - VR_L_ref_1) / 6;
    if ((input_vr - VR_L_ref_1) % 6 != leg) return 0.0;
    if (controller_current_mode(v)) {
        cascade_drive d;
        cascade_gains g;
        double in[CASCADE_INPUTS];
        controller_drive(v, (int)leg, &d, &g);
        controller_leg_inputs(v, (int)leg, in);
        return cascade_leg(&d, &g, in, v->model.speed_integral[leg]).slope[block];
    }
    const double kp = v->real[VR_kp], kd = v->real[VR_kd];
    const double by_block[5] = {kp, kd, 1.0, -kp, -kd}; /* L_ref, L_dot_ref, F_ff, L, L_dot */
    return by_block[block];
}

fmu_status model_directional_derivative(fmu_instance *inst, const unsigned unknown[],
                                        size_t n_unknown, const unsigned known[], size_t n_known,
                                        const double seed[], double sensitivity[],
                                        const char *function) {
    (void)function; /* a closed form: no call fails */
    for (size_t i = 0; i < n_unknown; ++i) {
        double sum = 0;
        for (size_t j = 0; j < n_known; ++j) sum += slope(&inst->v, unknown[i], known[j]) * seed[j];
        sensitivity[i] = sum;
    }
    return FMU_OK;
}
