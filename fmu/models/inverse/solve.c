/*
 * The inverse model's solve at a time (model.h): the pose and its rates (the rate inputs, or
 * finite differences of the poses at the last communication points), the library call, and what
 * its result makes of the outputs: the values, the status output (0 ok, 1 stroke, 2 near
 * singular, 3 not solved), the warnings and refusals logged, the limit outputs.
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "logging.h"
#include "model.h"

/* A loop over the six coordinates unrolled where the compiler allows: the vectoriser then pairs
 * them without a loop around them. */
#if defined(__GNUC__) && !defined(__clang__)
#define UNROLLED _Pragma("GCC unroll 6")
#else
#define UNROLLED
#endif

/* What the limit outputs are bound to (FMU_LIMIT_OUTPUT's fields). */
typedef struct inverse_limit_values {
    stewart_limits_output check;
    stewart_axis_ranges ranges;
} inverse_limit_values;

static int taylor_mode(const fmu_values *v) {
    return v->integer[VR_derivatives] == 1 || v->model.input_derivatives;
}

/* The history's last point. */
static inline const fd_point *newer_point(const model_values *m) { return &m->history[m->newer]; }

/* The rates and accelerations of pose->q at `time` from the quadratic through it and the last two
 * poses (two in the history: the newer point and its chord from the older). */
static inline void quadratic_rates(const model_values *restrict m, double time,
                                   stewart_pose *restrict pose) {
    const fd_point *newer = newer_point(m);
    const double h1 = newer->interval, h2 = time - newer->t;
    UNROLLED
    for (int i = 0; i < 6; ++i) {
        const double q1 = newer->pose.q[i], q2 = pose->q[i];
        const double d1 = newer->slope[i], d2 = (q2 - q1) / h2;
        const double dd = (d2 - d1) / (h1 + h2); /* q[t0, t1, t2] */
        pose->q_dot[i] = d2 + h2 * dd;
        pose->q_ddot[i] = 2.0 * dd;
    }
}

/* The pose at `time`: inputs, and derivatives from the inputs or by finite differences of the
 * poses at earlier communication points (quadratic through the last three poses; with only one
 * earlier pose, the chord through both and zero acceleration; none: at rest). Assuming rest at the
 * first point instead would give a motion already under way an acceleration 2 v / h: unbounded as
 * h shrinks. restrict: pose is not part of v, so the compiler takes the coordinates two at a
 * time. */
static void current_pose(const fmu_values *restrict v, double time, stewart_pose *restrict pose) {
    const model_values *m = &v->model;
    for (int i = 0; i < 6; ++i) pose->q[i] = v->real[VR_x + i];
    if (taylor_mode(v)) {
        for (int i = 0; i < 6; ++i) {
            pose->q_dot[i] = v->real[VR_x_dot + i];
            pose->q_ddot[i] = v->real[VR_x_ddot + i];
        }
        return;
    }
    /* Divided differences, so that a coordinate that does not move has zero rate and acceleration
     * however small the steps (the Lagrange weights overflow below h ~ 1e-154 and gave inf * 0). */
    if (m->n_history == 0) {
        for (int i = 0; i < 6; ++i) pose->q_dot[i] = pose->q_ddot[i] = 0.0;
    } else if (m->n_history == 1) {
        const fd_point *newer = newer_point(m);
        const double h = time - newer->t;
        for (int i = 0; i < 6; ++i) {
            pose->q_dot[i] = (pose->q[i] - newer->pose.q[i]) / h;
            pose->q_ddot[i] = 0.0;
        }
    } else {
        quadratic_rates(m, time, pose);
    }
}

void inverse_current_pose(const fmu_values *v, double time, stewart_pose *pose) {
    current_pose(v, time, pose);
}

void inverse_quadratic_rates(const model_values *m, double time, stewart_pose *pose) {
    quadratic_rates(m, time, pose);
}

int inverse_uses_rate_inputs(const fmu_values *v) { return taylor_mode(v); }

static fmu_status map_solve_error(stewart_status s) {
    switch (s) {
        case STEWART_ERR_ARGUMENT:
        case STEWART_ERR_SINGULAR:
        case STEWART_ERR_UNREACHABLE:
        case STEWART_ERR_NOT_CONVERGED: return FMU_DISCARD;
        default: return FMU_ERROR;
    }
}

/* The value reference of the first input that is not finite, or -1. */
int inverse_first_nonfinite_input(const fmu_values *v) {
    for (unsigned vr = VR_x; vr <= VR_yaw_ddot; ++vr)
        if (!isfinite(v->real[vr])) return (int)vr;
    return -1;
}

/* Not solved: status 3, the outputs keep their last valid values; the result stands for the
 * current inputs until they change. */
static fmu_status not_solved(fmu_values *v, fmu_status s) {
    v->integer[VR_status] = 3;
    v->outputs_current = 1;
    v->model.solve_status = s;
    return s;
}

/* Discard naming the first input that is not finite if there is one (FMU_OK if none). The runtime
 * flags a value set that is not finite (inputs_unchecked), so the step looks only then; finite
 * inputs advanced along their Taylor expansion can still overflow, which the library refuses,
 * and its refusal looks again. */
fmu_status inverse_check_inputs(fmu_instance *inst, double time) {
    fmu_values *v = &inst->v;
    const int bad = inverse_first_nonfinite_input(v);
    if (bad < 0) {
        v->inputs_unchecked = 0;
        return FMU_OK;
    }
    fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
            "t = %.17g: input %s = %g is not finite; outputs keep their last valid values", time,
            fmu_variable_by_vr((unsigned)bad)->name, v->real[bad]);
    return not_solved(v, FMU_DISCARD);
}

/* A pose coordinate beyond this cannot be told from overflow in a difference quotient (its
 * square, and any quotient by a step below 1, overflow): the input is the problem, not the step. */
static const double kHugeCoordinate = 1.3407807929942596e154; /* sqrt(DBL_MAX) */

/* Finite differences that are not finite for coordinate i: names the input when it is absurdly
 * large, else the steps (too small for this motion). */
static fmu_status discard_finite_differences(fmu_instance *inst, double time,
                                             const stewart_pose *pose, int i) {
    const model_values *m = &inst->v.model;
    const char *name = fmu_variable_by_vr(VR_x + i)->name;
    const int rate_bad = !isfinite(pose->q_dot[i]);
    /* the input and the last point's pose (the one before is no longer kept: its chord is) */
    double largest = fabs(pose->q[i]);
    if (m->n_history > 0) largest = fmax(largest, fabs(newer_point(m)->pose.q[i]));
    if (largest > kHugeCoordinate)
        fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                "t = %.17g: input %s = %g is too large: no finite-difference %s of it is finite "
                "(a pose coordinate must stay below %g). Outputs keep their last valid values",
                time, name, pose->q[i], rate_bad ? "rate" : "acceleration", kHugeCoordinate);
    else
        fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                "t = %.17g: the finite-difference %s of %s (%g, from the poses at the last "
                "communication points, the last %g s ago) is not finite: the steps are too "
                "small for this motion; use derivatives = 1 or larger steps. Outputs keep "
                "their last valid values",
                time, rate_bad ? "rate" : "acceleration", name,
                rate_bad ? pose->q_dot[i] : pose->q_ddot[i], time - newer_point(m)->t);
    return not_solved(&inst->v, FMU_DISCARD);
}

/* Logs the legs the library flags as outside their stroke. */
static void warn_stroke(const fmu_instance *inst, double time, int stroke_legs) {
    const stewart_params *p = &inst->res.params;
    for (int k = 0; k < STEWART_LEGS; ++k)
        if (stroke_legs & (1 << k))
            fmu_log(inst, FMU_WARNING, LOG_WARNING,
                    "t = %.17g: L[%d] = %g m is outside the stroke [%g, %g] m", time, k + 1,
                    inst->v.real[VR_L_1 + k], p->stroke_min[k], p->stroke_max[k]);
}

/* Logs the axis past its software position limit (axis_min, axis_max); FMU_WARNING. */
static fmu_status warn_axis(const fmu_instance *inst, double time,
                            const stewart_limits_output *check) {
    static const char *const axes[] = {"x", "y", "z", "roll", "pitch", "yaw"};
    const int axis = check->leg[STEWART_LIMIT_AXIS - 1];
    fmu_log(inst, FMU_WARNING, LOG_WARNING,
            "t = %.17g: %s is %g beyond its software position limit (axis_min, axis_max)", time,
            axes[axis >= 1 && axis <= 6 ? axis - 1 : 0], -check->margin[STEWART_LIMIT_AXIS - 1]);
    return FMU_WARNING;
}

/* The limit outputs for pose q (limit_outputs 1: the check; 2: and the axis ranges) and a
 * Warning, logged, when a joint angle or two legs are beyond their limits (strokes and the
 * condition have warnings of their own). */
static fmu_status limit_outputs(fmu_instance *inst, double time, const double q[6]) {
    fmu_values *v = &inst->v;
    const int level = v->integer[VR_limit_outputs];
    if (level == 0) return FMU_OK;
    stewart_limits_input in;
    memset(&in, 0, sizeof in);
    memcpy(in.q, q, sizeof in.q);
    inverse_limit_values values;
    memset(&values, 0, sizeof values);
    stewart_limits_check(inst->res.limits, &in, &values.check);
    if (level == 2) stewart_limits_ranges(inst->res.limits, &in, &values.ranges);
    v->integer[VR_limit_class] = values.check.first;
#define FMU_LIMIT_OUTPUT(vr, id, name, unit, field, desc) \
    if (level == 2 || vr < VR_range_min_1 || vr == VR_limit_margin_6) v->real[vr] = values.field;
#include "variables.def"
    fmu_status fs = FMU_OK;
    for (int c = STEWART_LIMIT_BASE_JOINT; c <= STEWART_LIMIT_INTERFERENCE; ++c)
        if (values.check.failed & (1 << (c - 1))) {
            fs = FMU_WARNING;
            const int i = c - 1;
            if (c == STEWART_LIMIT_INTERFERENCE)
                fmu_log(inst, FMU_WARNING, LOG_WARNING,
                        "t = %.17g: legs %d and %d interfere: %g m closer than the legs are thick "
                        "(leg_diameter, or the bodies' and rods' diameters; 0: touching)",
                        time, values.check.leg[i], values.check.other_leg[i],
                        fabs(values.check.margin[i]));
            else
                fmu_log(inst, FMU_WARNING, LOG_WARNING,
                        "t = %.17g: the %s of leg %d is %g rad beyond its limit", time,
                        c == STEWART_LIMIT_BASE_JOINT ? "base joint" : "platform joint",
                        values.check.leg[i], -values.check.margin[i]);
        }
    if (values.check.failed & (1 << (STEWART_LIMIT_AXIS - 1)))
        fs = warn_axis(inst, time, &values.check);
    return fs;
}

/* The library's refusal of the pose at `time`: Discard or Error, logged. */
fmu_status inverse_not_solved_by_library(fmu_instance *inst, double time, const stewart_pose *pose,
                                         stewart_status s) {
    const fmu_status fs = map_solve_error(s);
    fmu_log(inst, fs, fs == FMU_DISCARD ? LOG_DISCARD : LOG_ERROR,
            "t = %.17g: pose (x, y, z, roll, pitch, yaw) = (%g, %g, %g, %g, %g, %g) not solved "
            "(%s): %s; outputs keep their last valid values",
            time, pose->q[0], pose->q[1], pose->q[2], pose->q[3], pose->q[4], pose->q[5],
            stewart_status_name(s), stewart_inverse_message(inst->res.inverse));
    return not_solved(&inst->v, fs);
}
/* The outputs, status output and warnings of pose q solved at `time` (the library's output `out`
 * with warning bits): the rare case, out of line. */
FMU_RARE_PATH static fmu_status warnings_of(fmu_instance *inst, double time, const double q[6],
                                            const stewart_inverse_output *out) {
    fmu_values *v = &inst->v;
    const model_resources *r = &inst->res;
    inverse_outputs_from(v, out);
    v->outputs_current = 1;
    fmu_status fs = FMU_OK;
    int status = 0;
    if (out->warnings & STEWART_WARN_STROKE) {
        status = 1;
        fs = FMU_WARNING;
        warn_stroke(inst, time, out->stroke_legs);
    }
    if (out->warnings & STEWART_WARN_NEAR_SINGULAR) {
        status = 2;
        fs = FMU_WARNING;
        fmu_log(inst, FMU_WARNING, LOG_WARNING,
                "t = %.17g: near singular pose: condition = %g > warn_condition = %g", time,
                v->real[VR_condition], r->options.warn_condition);
    }
    if (v->integer[VR_limit_outputs] && limit_outputs(inst, time, q) == FMU_WARNING)
        fs = FMU_WARNING;
    v->integer[VR_status] = status;
    v->model.solve_status = fs;
    return fs;
}

fmu_status inverse_solved_checking(fmu_instance *inst, double time, const double q[6],
                                   const stewart_inverse_output *out, int limit_outputs) {
    if (out->warnings || limit_outputs) return warnings_of(inst, time, q, out);
    return inverse_solved_plain(inst, out);
}

fmu_status inverse_solved(fmu_instance *inst, double time, const double q[6],
                          const stewart_inverse_output *out) {
    return inverse_solved_checking(inst, time, q, out, inst->v.integer[VR_limit_outputs]);
}

/* (finite differences that are not finite are named as the FMU's: the library refuses them
 * before any work, since it checks its pose first, so they are looked for only now) */
FMU_RARE_PATH fmu_status inverse_refused(fmu_instance *inst, double time, const stewart_pose *pose,
                                         stewart_status s) {
    if (!taylor_mode(&inst->v))
        for (int i = 0; i < 6; ++i)
            if (!isfinite(pose->q_dot[i]) || !isfinite(pose->q_ddot[i]))
                return discard_finite_differences(inst, time, pose, i);
    return inverse_not_solved_by_library(inst, time, pose, s);
}

fmu_status inverse_solve_at(fmu_instance *inst, double time) {
    fmu_values *v = &inst->v;
    if (v->outputs_current) return v->model.solve_status;
    v->model.advance_discarded = 0;
    /* Every input must be finite, used or not. */
    if (v->inputs_unchecked && inverse_check_inputs(inst, time) != FMU_OK) return FMU_DISCARD;
    stewart_inverse_input in;
    current_pose(v, time, &in.pose);
    stewart_inverse_output out;
    const stewart_status s = stewart_inverse_solve(inst->res.inverse, &in, &out);
    if (s != STEWART_OK) return inverse_refused(inst, time, &in.pose, s);
    return inverse_solved(inst, time, in.pose.q, &out);
}

fmu_status model_refresh_outputs(fmu_instance *inst) {
    return inverse_solve_at(inst, inst->v.time);
}
