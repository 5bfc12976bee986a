/*
 * The inverse model's step rules in full (model_do_step) and the usual step's route. Over a step
 * the unit holds its inputs, or, with their derivatives (derivatives = 1, or FMI 2 input
 * derivatives), advances them along their Taylor expansion to t + h and solves there. With finite
 * differences each accepted step commits its pose to the history the next rates come from.
 */
#include <math.h>
#include <string.h>

#include "model.h"

/* ---------------------------------------------------------------- the usual step's route */

/* What the usual step (do_step.h: model_usual_steps) does with a step whose inputs are set since
 * the last one and finite (model_values.usual_route, settled after every change that rules a
 * usual step out, so that the usual step tests one value; a change that allows one again, such
 * as a discarded advance cleared by a solve, leaves it at the full rules until a full-rules step
 * settles it): the step rules in full (FMI 2 input derivatives given, a discarded advance
 * standing, limit outputs, fewer than two poses in the finite-difference history), or one of the
 * two usual steps. The route for the values as they stand: */
static int usual_route_of(const fmu_values *v) {
    const model_values *m = &v->model;
    if (m->input_derivatives || m->advance_discarded || v->integer[VR_limit_outputs])
        return ROUTE_CHECKED;
    if (v->integer[VR_derivatives]) return ROUTE_ADVANCE;
    return m->n_history == 2 ? ROUTE_HOLD : ROUTE_CHECKED;
}

void inverse_settle_usual_route(fmu_values *v) {
    /* the full rules outside step mode: they check the mode, which the usual call leaves to the
     * route (do_step.h: fmu_usual_call) */
    v->model.usual_route = v->mode == MODE_STEP ? usual_route_of(v) : ROUTE_CHECKED;
}

int inverse_usual_route_valid(const fmu_values *v) {
    return v->model.usual_route == ROUTE_CHECKED ||
           (v->mode == MODE_STEP && v->model.usual_route == usual_route_of(v));
}

/* ---------------------------------------------------------------- the step rules */

/* The pose q at communication point t joins the finite-difference history: the free slot becomes
 * the last point, with its chord from the point before (the quotient inverse_current_pose took). */
static void commit_pose(model_values *m, double t, const double q[6]) {
    const fd_point *newer = &m->history[m->newer];
    fd_point *next = &m->history[m->newer ^ 1];
    const double interval = m->n_history > 0 ? t - newer->t : 0.0;
    for (int i = 0; i < 6; ++i)
        next->slope[i] = m->n_history > 0 ? (q[i] - newer->pose.q[i]) / interval : 0.0;
    memcpy(next->pose.q, q, sizeof next->pose.q);
    memset(next->pose.q_dot, 0, sizeof next->pose.q_dot); /* no rates of an earlier solve */
    memset(next->pose.q_ddot, 0, sizeof next->pose.q_ddot);
    next->t = t;
    next->interval = interval;
    m->newer ^= 1;
    if (m->n_history < 2) ++m->n_history;
}

/* The Taylor advance of the inputs at t to t + h: the pose, its rates (the accelerations held). */
static void advance_pose(const fmu_values *v, double h, stewart_pose *pose) {
    for (int i = 0; i < 6; ++i) {
        const double q = v->real[VR_x + i], qd = v->real[VR_x_dot + i],
                     qdd = v->real[VR_x_ddot + i];
        pose->q[i] = q + h * (qd + 0.5 * h * qdd);
        pose->q_dot[i] = qd + h * qdd;
        pose->q_ddot[i] = qdd;
    }
}

/* The advanced pose becomes the inputs (what the outputs of t + h belong to). */
static void store_advanced_inputs(fmu_values *v, const stewart_pose *pose) {
    memcpy(&v->real[VR_x], pose->q, sizeof pose->q);
    memcpy(&v->real[VR_x_dot], pose->q_dot, sizeof pose->q_dot);
}

/* The library refused the advanced pose at t + h: an input that overflowed is named as the inputs
 * at t + h (the master reads them), else the library's reason; the inputs go back to those of t
 * (a failed solve leaves the outputs at their last valid values and sets status = 3). */
static fmu_status advance_refused(fmu_instance *inst, double time, const stewart_pose *pose,
                                  stewart_status s) {
    fmu_values *v = &inst->v;
    double at_t[12];
    memcpy(at_t, &v->real[VR_x], sizeof at_t);
    store_advanced_inputs(v, pose);
    fmu_status fs = inverse_check_inputs(inst, time);
    if (fs == FMU_OK) fs = inverse_not_solved_by_library(inst, time, pose, s);
    memcpy(&v->real[VR_x], at_t, sizeof at_t);
    return fs;
}

/* The step rules over [t, t + h] (model_do_step without settling the route). */
static fmu_status step_rules(fmu_instance *inst, double t, double h) {
    fmu_values *v = &inst->v;
    model_values *m = &v->model;
    /* A discarded advance left status 3 standing for the master to read; a retry decides anew. */
    if (m->advance_discarded) v->outputs_current = 0;
    m->advance_discarded = 0;
    /* With a Taylor advance the solution at t itself is needed only if the master asked for it,
     * or if an input is not finite (that is reported against t). */
    const int advance = inverse_uses_rate_inputs(v);
    int bad_input = 0;
    if (v->inputs_unchecked) {
        bad_input = inverse_first_nonfinite_input(v) >= 0;
        if (!bad_input) v->inputs_unchecked = 0;
    }
    fmu_status s = FMU_OK;
    if (!advance || v->outputs_current || bad_input) {
        s = inverse_solve_at(inst, t);
        if (s == FMU_DISCARD || s == FMU_ERROR) return s;
    }
    if (!advance) {
        /* Hold: the outputs stay those of the inputs at t until the master sets new inputs. */
        commit_pose(m, t, &v->real[VR_x]);
        return s;
    }
    /* Advance the pose to t + h along its Taylor expansion and solve there; the inputs become the
     * advanced ones only if solved (finite inputs: inputs_unchecked stays clear). */
    v->outputs_current = 0;
    stewart_inverse_input in;
    advance_pose(v, h, &in.pose);
    stewart_inverse_output out;
    const stewart_status ls = stewart_inverse_solve(inst->res.inverse, &in, &out);
    if (ls != STEWART_OK) {
        const fmu_status s2 = advance_refused(inst, t + h, &in.pose, ls);
        m->advance_discarded = 1; /* status 3 and the kept outputs stand until a step or a set */
        return s2;
    }
    /* the pose at t joins the finite-difference history, which derivatives = 1 never reads */
    if (v->integer[VR_derivatives] == 0) commit_pose(m, t, &v->real[VR_x]);
    store_advanced_inputs(v, &in.pose);
    /* the derivatives given through fmi2SetRealInputDerivatives served this step only; the
     * outputs just computed used them, so they stay valid */
    m->input_derivatives = 0;
    return inverse_solved(inst, t + h, in.pose.q, &out);
}

fmu_status model_do_step(fmu_instance *inst, double t, double h) {
    const fmu_status s = step_rules(inst, t, h);
    inverse_settle_usual_route(&inst->v);
    return s;
}
