/*
 * The inverse model's usual step (model_usual_steps, called by do_step.h straight from the FMI
 * call): the step rules of step_rules.c for the common case, shortened so that doStep costs
 * little more than the library call it wraps. Inputs set since the last step and finite, no FMI 2
 * input derivatives, no discarded advance standing, no limit outputs, and either derivatives = 1
 * (the pose advanced in the inputs themselves) or finite differences with two earlier poses (the
 * quadratic's rates written into the history's free slot). The same roundings as the full rules:
 * a usual step and a full-rules step give the same outputs bit for bit.
 */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "model.h"

/* Two doubles moved and computed as one where the compiler has SSE2 pairs (GNU C vector
 * extension; each element rounds as the scalar expression would); moved as bytes elsewhere. */
#if defined(__GNUC__) && defined(__SSE2__)
#define PAIRED_ARITHMETIC 1
typedef double double_pair __attribute__((vector_size(2 * sizeof(double))));
/* the same at any double's alignment, and allowed to alias the doubles it is read from */
typedef double unaligned_pair
    __attribute__((vector_size(2 * sizeof(double)), aligned(sizeof(double)), may_alias));

/* The pair at p. */
static inline double_pair load_pair(const double *p) { return *(const unaligned_pair *)p; }

/* Writes r to p. */
static inline void store_pair(double *p, double_pair r) { *(unaligned_pair *)p = r; }

/* The pair at p, 16-byte aligned (the history slots: the instance comes from calloc, and the
 * offsets are asserted below), so that SSE2 takes it as an arithmetic operand without a load. */
typedef double aligned_pair __attribute__((vector_size(2 * sizeof(double)), may_alias));
static inline double_pair load_aligned_pair(const double *p) { return *(const aligned_pair *)p; }
#else
#define PAIRED_ARITHMETIC 0
typedef struct double_pair {
    double e[2];
} double_pair;

/* The pair at p. */
static inline double_pair load_pair(const double *p) {
    double_pair r;
    memcpy(&r, p, sizeof r);
    return r;
}

/* Writes r to p. */
static inline void store_pair(double *p, double_pair r) { memcpy(p, &r, sizeof r); }
#define load_aligned_pair load_pair
#endif

_Static_assert(sizeof(fd_point) == 256, "a history slot is no longer 256 bytes");
/* The pose inputs' pairs and the history slots' pose and chord pairs lie on 16 bytes in an
 * instance that calloc aligns for any type (load_aligned_pair). */
_Static_assert(
    _Alignof(max_align_t) >= 16 &&
        (offsetof(fmu_instance, v) + offsetof(fmu_values, real) + VR_x * sizeof(double)) % 16 ==
            0 &&
        (VR_x_dot - VR_x) % 2 == 0 && (VR_x_ddot - VR_x) % 2 == 0 &&
        (offsetof(fmu_instance, v) + offsetof(fmu_values, model) +
         offsetof(model_values, history)) %
                16 ==
            0 &&
        offsetof(fd_point, pose) % 16 == 0 && offsetof(fd_point, slope) % 16 == 0,
    "the pose inputs' or the history's pairs no longer lie on 16 bytes");
_Static_assert(VR_x_dot == VR_x + 6 && VR_x_ddot == VR_x + 12 &&
                   offsetof(stewart_pose, q_dot) == 6 * sizeof(double) &&
                   offsetof(stewart_pose, q_ddot) == 12 * sizeof(double) &&
                   sizeof(stewart_inverse_input) == 18 * sizeof(double),
               "the pose inputs are no longer a stewart_pose");

/* Inlined into each usual step whatever the compiler's estimate (each is one function with one
 * library call: a call of its own would add a frame around it). */
#if defined(__GNUC__)
#define ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define ALWAYS_INLINE inline
#endif

/* The usual step's library status or the warning bits of its output (the rare case, either, is
 * told apart out of line). */
static inline int refused_or_warned(stewart_status s, const stewart_inverse_output *out) {
    return s != STEWART_OK || out->warnings;
}

/* The library refused the pose advanced in place (the inputs hold it; at_t: the inputs' pose and
 * rates at t): as advance_refused, and the inputs go back to at_t. */
FMU_RARE_PATH static fmu_status advance_in_place_refused(fmu_instance *inst, double time,
                                                         const double at_t[12], stewart_status s) {
    fmu_values *v = &inst->v;
    const stewart_pose *advanced = (const stewart_pose *)(const void *)&v->real[VR_x];
    fmu_status fs = inverse_check_inputs(inst, time);
    if (fs == FMU_OK) fs = inverse_not_solved_by_library(inst, time, advanced, s);
    memcpy(&v->real[VR_x], at_t, 12 * sizeof(double));
    v->model.advance_discarded = 1; /* status 3 and the kept outputs stand until a step or a set */
    inverse_settle_usual_route(v);
    return fs;
}

/* The advance in place refused (the inputs go back to at_t) or solved with warnings (its output
 * `out`; no limit outputs on the usual step). */
FMU_RARE_PATH static fmu_status advance_not_plain(fmu_instance *inst, double time,
                                                  const double at_t[12], stewart_status s,
                                                  const stewart_inverse_output *out) {
    if (s != STEWART_OK) return advance_in_place_refused(inst, time, at_t, s);
    return inverse_solved_checking(inst, time, &inst->v.real[VR_x], out, 0);
}

#if PAIRED_ARITHMETIC
/* Two coordinates of the pose inputs (pose: q, then q_dot 6 on, q_ddot 12 on) kept in at_t (q,
 * q_dot) and advanced over h in place, as advance_pose: the same roundings. */
static inline void advance_pair(double *pose, double *at_t, double_pair h, double_pair half_h) {
    const double_pair q = load_aligned_pair(pose), qd = load_aligned_pair(pose + 6),
                      qdd = load_aligned_pair(pose + 12);
    store_pair(at_t, q);
    store_pair(at_t + 6, qd);
    store_pair(pose, q + h * (qd + half_h * qdd));
    store_pair(pose + 6, qd + h * qdd);
}
#endif

/* derivatives = 1, the usual step: model_do_step's advance with the pose advanced in the inputs
 * themselves (the library's input as they stand), the inputs at t kept aside in case it fails. */
static ALWAYS_INLINE fmu_status advance_in_place(fmu_instance *inst, double h) {
    fmu_values *v = &inst->v;
    double *pose = &v->real[VR_x];
    double at_t[12];
#if PAIRED_ARITHMETIC
    /* two coordinates at a time, each loaded once (the compiler's own pairing loaded some twice) */
    const double_pair h2 = {h, h}, half_h2 = 0.5 * h2; /* each element 0.5 * h, as half_h */
    advance_pair(pose, at_t, h2, half_h2);
    advance_pair(pose + 2, at_t + 2, h2, half_h2);
    advance_pair(pose + 4, at_t + 4, h2, half_h2);
#else
    const double half_h = 0.5 * h;
    for (int i = 0; i < 6; ++i) { /* as advance_pose: the same roundings */
        const double q = pose[i], qd = pose[6 + i], qdd = pose[12 + i];
        at_t[i] = q;
        at_t[6 + i] = qd;
        pose[i] = q + h * (qd + half_h * qdd);
        pose[6 + i] = qd + h * qdd;
    }
#endif
    stewart_inverse_output out;
    out.warnings = 0; /* (read with the status, also when the library leaves out unwritten) */
    const stewart_status s =
        stewart_inverse_solve(inst->res.inverse, (const stewart_inverse_input *)(const void *)pose,
                              &out);
    if (refused_or_warned(s, &out)) return advance_not_plain(inst, inst->step.end, at_t, s, &out);
    return inverse_solved_plain(inst, &out);
}

#if PAIRED_ARITHMETIC
/* Two coordinates of quadratic_rates (the same roundings), each value loaded once: the pose q
 * (the inputs) and the last point's pose and chord (p1, d1) into the free slot's pose (next:
 * q, q_dot 6 on, q_ddot 12 on) and chord (slope). */
static inline void quadratic_pair(const double *restrict q, const double *restrict p1,
                                  const double *restrict d1_at, double *restrict next,
                                  double *restrict slope, double_pair h2, double_pair h12) {
    const double_pair q1 = load_aligned_pair(p1), q2 = load_pair(q), d1 = load_aligned_pair(d1_at);
    store_pair(next, q2); /* first: q2's register is then free for the difference (no copy) */
    const double_pair d2 = (q2 - q1) / h2;
    const double_pair dd = (d2 - d1) / h12; /* q[t0, t1, t2] */
    store_pair(next + 6, d2 + h2 * dd);
    store_pair(next + 12, dd + dd); /* 2 dd, exactly */
    store_pair(slope, d2);
}
#endif

/* The library refused the pose hold_with_quadratic wrote into the history's free slot at
 * inst->step.t (found again here, so that the usual step keeps no pointer to it, nor t, across
 * the library call), or solved it with warnings (the pose joins the history; the output at
 * `out`). */
FMU_RARE_PATH static fmu_status hold_not_plain(fmu_instance *inst, stewart_status s,
                                               const stewart_inverse_output *out) {
    model_values *m = &inst->v.model;
    if (s != STEWART_OK)
        return inverse_refused(inst, inst->step.t, &m->history[m->newer ^ 1].pose, s);
    m->newer ^= 1;
    return inverse_solved_checking(inst, inst->step.t, &inst->v.real[VR_x], out, 0);
}

/* The history slot `at` bytes into the history (0 or sizeof(fd_point)). */
static inline fd_point *history_slot_at(model_values *m, size_t at) {
    return (fd_point *)(void *)((char *)m->history + at);
}

/* derivatives = 0 with two earlier poses, the usual step: inverse_solve_at(t) (the quadratic's
 * rates) and the pose joins the history (t is inst->step.t, for the rare paths). The free slot
 * of the history takes the pose, its rates (the library's input) and its chord before the solve;
 * the solved pose becomes the last point by the flip of one index, and a refused one leaves the
 * history as it was. */
static ALWAYS_INLINE fmu_status hold_with_quadratic(fmu_instance *inst, double t) {
    fmu_values *v = &inst->v;
    model_values *m = &v->model;
    /* the slots by byte offset, the free one an exclusive or away (by index the compiler
     * extended and shifted each index and formed two more addresses) */
    const size_t newer_at = (size_t)(unsigned)m->newer * sizeof(fd_point); /* newer: 0 or 1 */
    const fd_point *newer = history_slot_at(m, newer_at);
    fd_point *next = history_slot_at(m, newer_at ^ sizeof(fd_point));
    const double h2 = t - newer->t;
#if PAIRED_ARITHMETIC
    const double h1 = newer->interval;
    const double_pair h2_2 = {h2, h2}, h12_2 = {h1 + h2, h1 + h2};
    const double *q = &v->real[VR_x];
    quadratic_pair(q, newer->pose.q, newer->slope, next->pose.q, next->slope, h2_2, h12_2);
    quadratic_pair(q + 2, newer->pose.q + 2, newer->slope + 2, next->pose.q + 2, next->slope + 2,
                   h2_2, h12_2);
    quadratic_pair(q + 4, newer->pose.q + 4, newer->slope + 4, next->pose.q + 4, next->slope + 4,
                   h2_2, h12_2);
#else
    memcpy(next->pose.q, &v->real[VR_x], sizeof next->pose.q);
    inverse_quadratic_rates(m, t, &next->pose);
    for (int i = 0; i < 6; ++i) /* the quotient inverse_quadratic_rates took as d2 */
        next->slope[i] = (next->pose.q[i] - newer->pose.q[i]) / h2;
#endif
    next->t = t;
    next->interval = h2;
    stewart_inverse_output out;
    out.warnings = 0; /* (read with the status, also when the library leaves out unwritten) */
    const stewart_status s =
        stewart_inverse_solve(inst->res.inverse,
                              (const stewart_inverse_input *)(const void *)&next->pose, &out);
    if (refused_or_warned(s, &out)) return hold_not_plain(inst, s, &out);
    m->newer ^= 1; /* the history is full already */
    return inverse_solved_plain(inst, &out);
}

/* The usual step's two paths, each with the time bookkeeping (fmu_step_accepted or
 * fmu_step_not_taken): out of line, so that the FMI call hands over to them without a frame
 * of its own and each keeps only what it needs across the library call. */
#if defined(__GNUC__)
#define OWN_FRAME __attribute__((noinline))
#else
#define OWN_FRAME
#endif

/* The step's end: accepted (OK, Warning) or not, from the step's end and t the usual step kept
 * in the instance (inst->step). The usual step leaves the unit's time as it was (t,
 * or within the slack of it) until here, so that is the time before it. stepped_before: a step
 * was accepted before (the hold step: its history's points were committed by steps, which a
 * restored state is checked for, model_state.c). */
static inline fmu_status step_end(fmu_instance *inst, fmu_status s, int stepped_before) {
    if (s == FMU_OK || s == FMU_WARNING)
        return fmu_step_accepted_kept(&inst->v, &inst->step, s, stepped_before);
    return fmu_step_not_taken(inst, inst->step.t, s, inst->v.time, 0);
}

/* Keeps the step's end and t in the instance (inst->step), as one pair, for step_end and the rare
 * paths: the usual steps then keep no register across the library call but the instance's. */
static inline void keep_step(fmu_instance *inst, double t, double end) {
#if PAIRED_ARITHMETIC
    const double_pair end_and_t = {end, t};
    store_pair(&inst->step.end, end_and_t);
#else
    inst->step.end = end;
    inst->step.t = t;
#endif
}

OWN_FRAME static fmu_status usual_advance_step(fmu_instance *inst, double t, double h, double end) {
    keep_step(inst, t, end);
    return step_end(inst, advance_in_place(inst, h), 0);
}

OWN_FRAME static fmu_status usual_hold_step(fmu_instance *inst, double t, double h, double end) {
    (void)h;
    keep_step(inst, t, end);
    return step_end(inst, hold_with_quadratic(inst, t), 1);
}

/* The step rules in full, as a route's step (end is t + h). */
static fmu_status full_rules_step(fmu_instance *inst, double t, double h, double end) {
    (void)end;
    return fmu_run_step_in_step_mode(inst, t, h); /* (the route outside step mode too) */
}

/* The step each route takes on inputs set and finite (model_interface.h; do_step.h jumps to it
 * by the route, which is 0..2: inverse_settle_usual_route writes it, and a restored state whose
 * route is not what its values give is refused, model_state.c). The usual step: no discarded
 * advance standing, no FMI 2 input derivatives, no limit outputs, and with finite differences
 * two earlier poses; anything else the step rules in full. */
const model_usual_step_fn model_usual_steps[] = {
    [ROUTE_CHECKED] = full_rules_step,
    [ROUTE_ADVANCE] = usual_advance_step,
    [ROUTE_HOLD] = usual_hold_step,
};
_Static_assert(sizeof model_usual_steps / sizeof *model_usual_steps == ROUTE_HOLD + 1,
               "a route without its usual step");
