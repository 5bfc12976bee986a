/* The Model Exchange plant's directional derivatives (model_interface.h) at the states and forces
 * set: the library's linearised plant (stewart_linearize_plant: A, B, C) for the state
 * derivatives, lengths and length rates, and for the base wrench its Jacobian
 * W = d wrench / d(q, q_dot, q_ddot) (stewart_linearize_base_wrench) composed with the plant's:
 * d wrench = W_x dx + W_a (A dx + B dF). Knowns: the states x .. yaw_dot and the forces.
 * With current or voltage input (the F[k] carry the motors' currents or voltages) the driven
 * plant's (stewart_linearize_driven: the drives' law in A and B, the inputs its columns).
 * The linearisation is kept (model_resources.derivatives) for the states and forces it was made
 * at: the adjoint, one directional derivative per known, and a master that asks column by
 * column linearise once per point. */
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
 * knowns; the base wrench's rows are the cache's own. */
static void unknown_row(unsigned vr, const plant_me_derivatives *c, double row[N_COLUMNS]) {
    const stewart_linearize_output *p = &c->plant;
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
        memcpy(row, c->wrench[vr - VR_base_force_1], sizeof c->wrench[0]);
    }
}

/* The status (logged) of a linearisation that failed: Discard, the state has no derivatives. */
static fmu_status failed(fmu_instance *inst, const char *function) {
    fmu_log(inst, FMU_DISCARD, LOG_DISCARD, "t = %.17g: %s: no derivatives at this state: %s",
            inst->v.time, function, stewart_linearize_message(inst->res.linearize));
    return FMU_DISCARD;
}

/* The base wrench's rows by (x, F) into c, from its Jacobian by (q, q_dot, q_ddot) through
 * q_ddot = state_rate[6..11]. */
static stewart_status wrench_rows(stewart_linearize *l, const stewart_linearize_input *in,
                                  plant_me_derivatives *c) {
    stewart_pose pose = in->pose;
    memcpy(pose.q_ddot, c->plant.state_rate + 6, sizeof pose.q_ddot);
    stewart_linearize_wrench_output w;
    const stewart_status s = stewart_linearize_base_wrench(l, &pose, &w);
    if (s != STEWART_OK) return s;
    for (int r = 0; r < 6; ++r) {
        const double *d = w.jacobian[r];
        double *row = c->wrench[r];
        for (int j = 0; j < N_STATES; ++j) row[j] = d[j];
        for (int k = 0; k < STEWART_LEGS; ++k) row[N_STATES + k] = 0;
        for (int a = 0; a < 6; ++a) {
            for (int j = 0; j < N_STATES; ++j) row[j] += d[12 + a] * c->plant.A[6 + a][j];
            for (int k = 0; k < STEWART_LEGS; ++k)
                row[N_STATES + k] += d[12 + a] * c->plant.B[6 + a][k];
        }
    }
    return STEWART_OK;
}

/* The driven plant's linearisation at in (its forces the inputs: currents or voltages) as the
 * force-driven one's layout: the windings' currents are no states here (stewart_plant_derivatives
 * refuses an inductance), so its A, B, C are 12 states wide. */
static stewart_status linearise_driven(fmu_instance *inst, const stewart_linearize_input *in,
                                       stewart_linearize_output *out) {
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    o.fidelity = inst->res.fidelity;
    o.input = inst->res.input;
    o.smoothing_speed = inst->res.smoothing_speed;
    stewart_linearize_driven_input driven;
    memset(&driven, 0, sizeof driven);
    driven.pose = in->pose;
    memcpy(driven.input, in->force, sizeof driven.input);
    stewart_linearize_driven_output *d = &inst->res.derivatives.driven;
    const stewart_status s = stewart_linearize_driven(inst->res.linearize, &o, &driven, d);
    if (s != STEWART_OK) return s;
    if (d->states != N_STATES) return STEWART_ERR_ARGUMENT; /* refused by the equations first */
    memset(out, 0, sizeof *out);
    for (int i = 0; i < N_STATES; ++i) {
        out->state_rate[i] = d->state_rate[i];
        memcpy(out->A[i], d->A[i], sizeof out->A[i]);
        memcpy(out->B[i], d->B[i], sizeof out->B[i]);
    }
    memcpy(out->output, d->output, sizeof out->output);
    for (int r = 0; r < STEWART_LINEARIZE_OUTPUTS; ++r)
        memcpy(out->C[r], d->C[r], sizeof out->C[r]);
    out->warnings = d->warnings;
    out->stroke_legs = d->stroke_legs;
    return STEWART_OK;
}

/* The cache made current for the states and forces set (the base wrench's rows only if wrench):
 * the linearisation runs only when they changed since it was made. */
static stewart_status linearised(fmu_instance *inst, int wrench) {
    const fmu_values *v = &inst->v;
    plant_me_derivatives *c = &inst->res.derivatives;
    stewart_linearize_input in;
    double point[N_COLUMNS];
    for (int i = 0; i < 6; ++i) {
        in.pose.q[i] = point[i] = v->real[VR_x + i];
        in.pose.q_dot[i] = point[6 + i] = v->real[VR_x_dot + i];
        in.pose.q_ddot[i] = 0;
        in.force[i] = point[N_STATES + i] = v->real[VR_F_1 + i];
    }
    if (!c->valid || memcmp(point, c->point, sizeof point) != 0) {
        c->valid = 0;
        const stewart_status s = inst->res.input == STEWART_PLANT_INPUT_FORCE
                                     ? stewart_linearize_plant(inst->res.linearize, &in, &c->plant)
                                     : linearise_driven(inst, &in, &c->plant);
        if (s != STEWART_OK) return s;
        memcpy(c->point, point, sizeof point);
        c->valid = 1;
        c->has_wrench = 0;
    }
    if (wrench && !c->has_wrench) {
        const stewart_status s = wrench_rows(inst->res.linearize, &in, c);
        if (s != STEWART_OK) return s;
        c->has_wrench = 1;
    }
    return STEWART_OK;
}

fmu_status model_directional_derivative(fmu_instance *inst, const unsigned unknown[],
                                        size_t n_unknown, const unsigned known[], size_t n_known,
                                        const double seed[], double sensitivity[],
                                        const char *function) {
    int wrench = 0;
    for (size_t i = 0; i < n_unknown; ++i) wrench |= is_base_wrench(unknown[i]);
    if (linearised(inst, wrench) != STEWART_OK) return failed(inst, function);
    double row[N_COLUMNS];
    for (size_t i = 0; i < n_unknown; ++i) {
        unknown_row(unknown[i], &inst->res.derivatives, row);
        double sum = 0;
        for (size_t j = 0; j < n_known; ++j) sum += row[known_column(known[j])] * seed[j];
        sensitivity[i] = sum;
    }
    return FMU_OK;
}
