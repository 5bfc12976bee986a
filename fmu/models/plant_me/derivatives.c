/* The Model Exchange plant's directional derivatives (model_interface.h) at the states and forces
 * set: the library's linearised plant (stewart_linearize_plant: A, B, C) for the state
 * derivatives, lengths and length rates, and for the base wrench the inverse side's Jacobian
 * W = d wrench / d(q, q_dot, q_ddot) (stewart_linearize_inverse) composed with the plant's:
 * d wrench = W_x dx + W_a (A dx + B dF). Knowns: the states x .. yaw_dot and the forces. */
#include <string.h>

#include "logging.h"
#include "model_interface.h"
#include "variables.h"

#define N_STATES STEWART_LINEARIZE_STATES
#define N_COLUMNS (STEWART_LINEARIZE_STATES + STEWART_LINEARIZE_INPUTS)

/* The column of a known (the runtime let only states and forces through): 0-11 the states, 12-17
 * the forces. */
static int known_column(unsigned vr) {
    if (vr >= VR_x && vr <= VR_yaw_dot) return (int)(vr - VR_x);
    return N_STATES + (int)(vr - VR_F_1);
}

static int is_base_wrench(unsigned vr) { return vr >= VR_base_force_1 && vr <= VR_base_torque_3; }

/* The derivatives of a Real output (a state derivative among them) with respect to the 18
 * knowns; w is read for the base wrench only. */
static void unknown_row(unsigned vr, const stewart_linearize_output *p,
                       const stewart_linearize_inverse_output *w, double row[N_COLUMNS]) {
    memset(row, 0, N_COLUMNS * sizeof row[0]);
    if (vr >= VR_x && vr <= VR_yaw_dot) { /* a state, and x_dot .. yaw_dot the derivatives too */
        row[vr - VR_x] = 1;
    } else if (vr >= VR_x_ddot && vr <= VR_yaw_ddot) {
        const unsigned i = 6 + vr - VR_x_ddot;
        memcpy(row, p->A[i], sizeof p->A[i]);
        memcpy(row + N_STATES, p->B[i], sizeof p->B[i]);
    } else if (vr >= VR_L_1 && vr <= VR_L_dot_6) { /* L, L_dot: outputs 12 .. 23, D = 0 */
        memcpy(row, p->C[12 + vr - VR_L_1], sizeof p->C[0]);
    } else { /* the base wrench, the only other Real output */
        const double *d = w->jacobian[24 + vr - VR_base_force_1]; /* by (q, q_dot, q_ddot) */
        for (int j = 0; j < N_STATES; ++j) row[j] = d[j];
        for (int a = 0; a < 6; ++a) { /* through q_ddot = state_rate[6 + a] */
            for (int j = 0; j < N_STATES; ++j) row[j] += d[12 + a] * p->A[6 + a][j];
            for (int k = 0; k < STEWART_LEGS; ++k) row[N_STATES + k] += d[12 + a] * p->B[6 + a][k];
        }
    }
}

/* The status (logged) of a linearisation that failed: Discard, the state has no derivatives. */
static fmu_status failed(fmu_instance *inst) {
    fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
            "t = %.17g: GetDirectionalDerivative: no derivatives at this state: %s",
            inst->v.time, stewart_linearize_message(inst->res.linearize));
    return FMU_DISCARD;
}

fmu_status model_directional_derivative(fmu_instance *inst, const unsigned unknown[],
                                        size_t n_unknown, const unsigned known[], size_t n_known,
                                        const double seed[], double sensitivity[]) {
    const fmu_values *v = &inst->v;
    int wrench = 0;
    for (size_t i = 0; i < n_unknown; ++i) wrench |= is_base_wrench(unknown[i]);
    stewart_linearize_input in;
    for (int i = 0; i < 6; ++i) {
        in.pose.q[i] = v->real[VR_x + i];
        in.pose.q_dot[i] = v->real[VR_x_dot + i];
        in.pose.q_ddot[i] = 0;
        in.force[i] = v->real[VR_F_1 + i];
    }
    stewart_linearize_output p;
    stewart_status s = stewart_linearize_plant(inst->res.linearize, &in, &p);
    if (s != STEWART_OK) return failed(inst);
    stewart_linearize_inverse_output w;
    if (wrench) {
        stewart_pose pose = in.pose;
        memcpy(pose.q_ddot, p.state_rate + 6, sizeof pose.q_ddot);
        s = stewart_linearize_inverse(inst->res.linearize, &pose, &w);
        if (s != STEWART_OK) return failed(inst);
    }
    double row[N_COLUMNS];
    for (size_t i = 0; i < n_unknown; ++i) {
        unknown_row(unknown[i], &p, &w, row);
        double sum = 0;
        for (size_t j = 0; j < n_known; ++j) sum += row[known_column(known[j])] * seed[j];
        sensitivity[i] = sum;
    }
    return FMU_OK;
}
