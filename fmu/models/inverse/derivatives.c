/* The inverse model's directional derivatives (model_interface.h): the library's Jacobian of the
 * inverse side (stewart_linearize_inverse) at the pose the outputs are solved at, composed with
 * how that pose follows from the inputs: directly (rates as inputs), or through the finite
 * differences of the pose over the last communication points (rate inputs unused).
 * The outputs of the pose alone that the library has no Jacobian for (the condition number, the
 * limit margins and the axis ranges: minima over legs, piecewise smooth) are differentiated
 * numerically, as FMI 2.0 section 2.1.9 allows: central differences of the library's limit check
 * at the pose, and for a range end the implicit function theorem on the margin that ends it. */
#include <math.h>
#include <string.h>

#include "logging.h"
#include "model.h"
#include "model_interface.h"
#include "variables.h"

/* Row of the library's Jacobian (stewart_linearize_inverse_output.jacobian) for output vr, or -1
 * for an output of the pose alone (pose_gradient). */
static int jacobian_row(unsigned vr) {
    if (vr >= VR_L_1 && vr <= VR_L_6) return (int)(vr - VR_L_1);
    if (vr >= VR_L_dot_1 && vr <= VR_L_dot_6) return 6 + (int)(vr - VR_L_dot_1);
    if (vr >= VR_L_ddot_1 && vr <= VR_L_ddot_6) return 12 + (int)(vr - VR_L_ddot_1);
    if (vr >= VR_F_1 && vr <= VR_F_6) return 18 + (int)(vr - VR_F_1);
    if (vr >= VR_base_force_1 && vr <= VR_base_force_3) return 24 + (int)(vr - VR_base_force_1);
    if (vr >= VR_base_torque_1 && vr <= VR_base_torque_3) return 27 + (int)(vr - VR_base_torque_1);
    return -1;
}

/* d(q_dot, q_ddot)/dq of the finite differences the model uses without rate inputs (model.c:
 * current_pose): the chord through the last pose, or the quadratic through the last two. */
static void difference_weights(const model_values *m, double time, double *rate, double *accel) {
    const fd_point *newer = &m->history[m->newer];
    *rate = *accel = 0;
    if (m->n_history == 1) {
        *rate = 1 / (time - newer->t);
    } else if (m->n_history == 2) {
        const double h1 = newer->interval, h2 = time - newer->t;
        *rate = 1 / h2 + 1 / (h1 + h2);
        *accel = 2 / (h2 * (h1 + h2));
    }
}

/* The linearisation for the current fidelity's forces (massless legs below fidelity 2), made when
 * first asked; Error, logged, if it cannot be made. */
static fmu_status ensure_linearize(fmu_instance *inst, const char *function) {
    model_resources *r = &inst->res;
    const int fidelity = r->options.fidelity == STEWART_FULL ? STEWART_FULL : STEWART_MASSLESS;
    if (r->linearize && stewart_linearize_options_of(r->linearize)->fidelity != fidelity) {
        stewart_linearize_free(r->linearize);
        r->linearize = NULL;
    }
    if (r->linearize) return FMU_OK;
    stewart_linearize_options o;
    stewart_linearize_options_default(&o);
    o.fidelity = fidelity;
    r->linearize = stewart_linearize_create(r->model, &o, r->message, sizeof r->message);
    if (r->linearize) return FMU_OK;
    fmu_log(inst, FMU_ERROR, LOG_ERROR, "%s: %s", function, r->message);
    return FMU_ERROR;
}

/* Central-difference step of the limit check's margins and condition [m or rad]: the margins
 * bend on the scale of centimetres (truncation about 1e-12 of them), rounding adds about
 * 1e-10 of their size. */
#define CHECK_STEP 1e-6

/* d(check value)/dq at q by central differences of the limit check; value(check) picks the
 * margin or the condition. FMU_OK, or Discard (logged) where the check or the result is not
 * finite (a singular pose). */
typedef double (*check_value)(const stewart_limits_output *check, int index);
static double margin_of(const stewart_limits_output *c, int index) { return c->margin[index]; }
static double condition_of(const stewart_limits_output *c, int index) {
    (void)index;
    return c->condition;
}

static fmu_status check_gradient(fmu_instance *inst, const double q[6], check_value value,
                                 int index, double gradient[6], const char *function) {
    for (int j = 0; j < 6; ++j) {
        stewart_limits_input up, down;
        memset(&up, 0, sizeof up);
        memset(&down, 0, sizeof down);
        memcpy(up.q, q, sizeof up.q);
        memcpy(down.q, q, sizeof down.q);
        up.q[j] += CHECK_STEP;
        down.q[j] -= CHECK_STEP;
        stewart_limits_output a, b;
        if (stewart_limits_check(inst->res.limits, &up, &a) != STEWART_OK ||
            stewart_limits_check(inst->res.limits, &down, &b) != STEWART_OK) {
            fmu_log(inst, FMU_DISCARD, LOG_DISCARD, "t = %.17g: %s: %s", inst->v.time, function,
                    stewart_limits_message(inst->res.limits));
            return FMU_DISCARD;
        }
        gradient[j] = (value(&a, index) - value(&b, index)) / (2 * CHECK_STEP);
        if (!isfinite(gradient[j])) {
            fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                    "t = %.17g: %s: no derivative of the %s at this pose (singular leg "
                    "Jacobian)",
                    inst->v.time, function,
                    value == condition_of ? "condition number" : "limit margins");
            return FMU_DISCARD;
        }
    }
    return FMU_OK;
}

/* The limit check and the axis ranges at the pose, made once per request (the ranges' search is
 * the costly part: about 100 us). */
typedef struct pose_ranges {
    int made;
    stewart_limits_output here;
    stewart_axis_ranges ranges;
} pose_ranges;

/* d(range end)/dq. Where the pose is beyond a limit (the range is [q_a, q_a]) or the search
 * ended without meeting a limit, the end moves with q_a alone. Where limit class c ends it, its
 * margin m is zero there (to the search's tolerance): m(q with q_a = end) = 0, so d end/d q_j =
 * -(dm/dq_j) / (dm/dq_a) for j != a, and 0 for the axis itself. */
static fmu_status range_gradient(fmu_instance *inst, const double q[6], int axis, int max_side,
                                 pose_ranges *at, double gradient[6], const char *function) {
    if (!at->made) {
        stewart_limits_input in;
        memset(&in, 0, sizeof in);
        memcpy(in.q, q, sizeof in.q);
        if (stewart_limits_check(inst->res.limits, &in, &at->here) != STEWART_OK ||
            stewart_limits_ranges(inst->res.limits, &in, &at->ranges) != STEWART_OK) {
            fmu_log(inst, FMU_DISCARD, LOG_DISCARD, "t = %.17g: %s: %s", inst->v.time, function,
                    stewart_limits_message(inst->res.limits));
            return FMU_DISCARD;
        }
        at->made = 1;
    }
    const stewart_axis_ranges *ranges = &at->ranges;
    const int limit = max_side ? ranges->max_limit[axis] : ranges->min_limit[axis];
    memset(gradient, 0, 6 * sizeof gradient[0]);
    if (at->here.failed || limit == STEWART_LIMIT_NONE) {
        gradient[axis] = 1;
        return FMU_OK;
    }
    double end[6], m[6];
    memcpy(end, q, sizeof end);
    end[axis] = max_side ? ranges->max[axis] : ranges->min[axis];
    const fmu_status s = check_gradient(inst, end, margin_of, limit - 1, m, function);
    if (s != FMU_OK) return s;
    if (!(fabs(m[axis]) > 0)) {
        fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                "t = %.17g: %s: the %s limit touches the range of axis %d at its end without "
                "crossing it: the end has no derivative",
                inst->v.time, function, stewart_limit_class_name(limit), axis + 1);
        return FMU_DISCARD;
    }
    for (int j = 0; j < 6; ++j)
        if (j != axis) gradient[j] = -m[j] / m[axis];
    return FMU_OK;
}

/* d(output)/dq of an output of the pose alone (jacobian_row < 0), with the outputs as the
 * parameters make them: zero where they are constant (no limit outputs, no condition at
 * fidelity 0). The residual of the exact solution is zero at every pose: what the output shows
 * is the solver's leftover, whose derivative is zero. */
static fmu_status pose_gradient(fmu_instance *inst, unsigned vr, const double q[6], pose_ranges *at,
                                double gradient[6], const char *function) {
    const fmu_values *v = &inst->v;
    const long level = v->integer[VR_limit_outputs];
    memset(gradient, 0, 6 * sizeof gradient[0]);
    if (vr == VR_condition)
        return inst->res.options.fidelity == 0
                   ? FMU_OK
                   : check_gradient(inst, q, condition_of, 0, gradient, function);
    if (vr >= VR_limit_margin_1 && vr <= VR_limit_margin_5)
        return level < 1 ? FMU_OK
                         : check_gradient(inst, q, margin_of, (int)(vr - VR_limit_margin_1),
                                          gradient, function);
    if (vr >= VR_range_min_1 && vr <= VR_range_max_6 && level >= 2) {
        const int max_side = vr >= VR_range_max_1;
        const int axis = (int)(vr - (max_side ? VR_range_max_1 : VR_range_min_1));
        return range_gradient(inst, q, axis, max_side, at, gradient, function);
    }
    return FMU_OK; /* the residual, and ranges not asked for */
}

/* The sensitivity of an output of the library's Jacobian (row `row` of out) to the knowns. */
static double jacobian_sensitivity(const fmu_instance *inst,
                                   const stewart_linearize_inverse_output *out, int row,
                                   const unsigned known[], size_t n_known, const double seed[]) {
    const fmu_values *v = &inst->v;
    /* fidelity 0 gives no forces and no base wrench: they are constant zero */
    if (inst->res.options.fidelity == 0 && row >= 18) return 0;
    const int from_inputs = inverse_uses_rate_inputs(v);
    double rate_weight = 0, accel_weight = 0;
    if (!from_inputs) difference_weights(&v->model, v->time, &rate_weight, &accel_weight);
    const double *d = out->jacobian[row];
    double sum = 0;
    for (size_t j = 0; j < n_known; ++j) {
        const unsigned c = known[j] - VR_x; /* the inputs are q, q_dot, q_ddot in order */
        if (from_inputs) sum += d[c] * seed[j];
        else if (c < 6) sum += (d[c] + rate_weight * d[6 + c] + accel_weight * d[12 + c]) * seed[j];
    }
    return sum;
}

fmu_status model_directional_derivative(fmu_instance *inst, const unsigned unknown[],
                                        size_t n_unknown, const unsigned known[], size_t n_known,
                                        const double seed[], double sensitivity[],
                                        const char *function) {
    fmu_values *v = &inst->v;
    stewart_pose pose;
    inverse_current_pose(v, v->time, &pose);
    int needs_jacobian = 0;
    for (size_t i = 0; i < n_unknown; ++i) needs_jacobian |= jacobian_row(unknown[i]) >= 0;
    stewart_linearize_inverse_output out;
    if (needs_jacobian) {
        if (ensure_linearize(inst, function) != FMU_OK) return FMU_ERROR;
        if (stewart_linearize_inverse(inst->res.linearize, &pose, &out) != STEWART_OK) {
            fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                    "t = %.17g: %s: no derivatives at this pose: %s", v->time, function,
                    stewart_linearize_message(inst->res.linearize));
            return FMU_DISCARD;
        }
    }
    pose_ranges at = {0};
    for (size_t i = 0; i < n_unknown; ++i) {
        const int row = jacobian_row(unknown[i]);
        if (row >= 0) {
            sensitivity[i] = jacobian_sensitivity(inst, &out, row, known, n_known, seed);
            continue;
        }
        double gradient[6];
        const fmu_status s = pose_gradient(inst, unknown[i], pose.q, &at, gradient, function);
        if (s != FMU_OK) return s;
        double sum = 0; /* these outputs follow the pose alone, in either rate mode */
        for (size_t j = 0; j < n_known; ++j)
            if (known[j] - VR_x < 6) sum += gradient[known[j] - VR_x] * seed[j];
        sensitivity[i] = sum;
    }
    return FMU_OK;
}
