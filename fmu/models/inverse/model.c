/*
 * The inverse-dynamics model on the FMU runtime: the pose inputs (and their derivatives, given or
 * by finite differences) go to stewart_inverse_solve; its output fills the output variables. The step
 * rules: hold the inputs over a step, or advance them along their Taylor expansion (derivatives =
 * 1 or FMI 2 input derivatives). Library statuses map onto FMU statuses and the status output.
 */
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "logging.h"
#include "model.h"

/* A loop of the usual step unrolled where the compiler allows: the vectoriser then pairs its
 * coordinates without a loop around them. */
#if defined(__GNUC__) && !defined(__clang__)
#define UNROLLED _Pragma("GCC unroll 6")
#else
#define UNROLLED
#endif

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
typedef struct double_pair { double e[2]; } double_pair;

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

/* ---------------------------------------------------------------- values <-> library */

void model_start_values(fmu_values *v) {
    stewart_params p;
    stewart_inverse_options o;
    stewart_params_default(&p);
    stewart_inverse_options_default(&o);
#define FMU_INPUT(vr, id, name, start, unit, row, col, desc) v->real[vr] = start;
#define FMU_OUTPUT(vr, id, name, unit, field, desc) v->real[vr] = 0.0;
#define FMU_OUTPUT_INT(vr, id, name, desc) v->integer[vr] = 0;
#define FMU_OPTION_INT(vr, id, name, start, min, max, desc) v->integer[vr] = start;
#define FMU_OPTION_REAL(vr, id, name, field, unit, desc) v->real[vr] = o.field;
#define FMU_PARAM(vr, id, name, field, unit, display, desc) v->real[vr] = p.field;
#define FMU_INDEPENDENT(vr, id, name, unit, desc) v->real[vr] = 0.0;
#include "variables.def"
#ifdef STEWART_PARAM_TABLE
    v->integer[VR_fidelity] = STEWART_FULL; /* the FMU's default; the library's is massless */
#endif
    v->integer[VR_status] = 3; /* nothing solved yet */
    memset(&v->model, 0, sizeof v->model);
}

void inverse_params_from_values(const fmu_values *v, stewart_params *p) {
    stewart_params_default(p);
#define FMU_PARAM(vr, id, name, field, unit, display, desc) p->field = v->real[vr];
#include "variables.def"
}

void inverse_options_from_values(const fmu_values *v, stewart_inverse_options *o) {
    stewart_inverse_options_default(o);
#define FMU_OPTION_REAL(vr, id, name, field, unit, desc) o->field = v->real[vr];
#include "variables.def"
    o->fidelity = (stewart_fidelity)v->integer[VR_fidelity];
    o->max_iterations = v->integer[VR_max_iterations];
    o->modified_newton = v->integer[VR_modified_newton];
}

/* Field by field (a struct's padding bytes are not values). */
static int same_options(const stewart_inverse_options *a, const stewart_inverse_options *b) {
    return b && a->fidelity == b->fidelity && a->tolerance == b->tolerance &&
           a->max_iterations == b->max_iterations && a->modified_newton == b->modified_newton &&
           a->warn_condition == b->warn_condition &&
           a->singular_condition == b->singular_condition;
}

/* What the limit outputs are bound to (FMU_LIMIT_OUTPUT's fields). */
typedef struct inverse_limit_values {
    stewart_limits_output check;
    stewart_axis_ranges ranges;
} inverse_limit_values;

/* The library writes its output straight into the output variables (no copy) where the ABI lays
 * its struct over real[VR_L_1..] in the outputs' order up to the residual (iterations passes
 * through the slot of the Integer newton_iterations), and the base wrench one slot early (the
 * Integer status sits between), which outputs_in_place moves: every ABI that aligns a double in
 * a struct to 8 bytes (x86-64). Where it does not (i386 aligns it to 4: the residual follows the
 * iteration count at once), a solve writes a local struct and outputs_copied copies it. The
 * definition FMU_INVERSE_COPY_OUTPUTS=1 forces the copy (tests/importer: both paths, bit for
 * bit). The pose inputs are a stewart_pose as they stand on every ABI (doubles only). */
#define OUTPUT_SLOT(field) (VR_L_1 + offsetof(stewart_inverse_output, field) / sizeof(double))
#define OUTPUT_ON_SLOT(field) (offsetof(stewart_inverse_output, field) % sizeof(double) == 0)
#define OUTPUTS_LIE_OVER_VARIABLES                                                              \
    (OUTPUT_SLOT(lengths.length_rate) == VR_L_dot_1 &&                                          \
     OUTPUT_SLOT(lengths.length_accel) == VR_L_ddot_1 && OUTPUT_SLOT(force) == VR_F_1 &&        \
     OUTPUT_ON_SLOT(condition) && OUTPUT_SLOT(condition) == VR_condition &&                     \
     OUTPUT_ON_SLOT(iterations) && OUTPUT_SLOT(iterations) == VR_newton_iterations &&           \
     OUTPUT_ON_SLOT(residual) && OUTPUT_SLOT(residual) == VR_residual &&                        \
     OUTPUT_ON_SLOT(base_force) && OUTPUT_SLOT(base_force) == VR_base_force_1 - 1 &&            \
     OUTPUT_ON_SLOT(base_torque) && OUTPUT_SLOT(base_torque) == VR_base_force_1 + 2 &&          \
     VR_base_torque_1 == VR_base_force_1 + 3 &&                                                 \
     VR_L_1 + (sizeof(stewart_inverse_output) + sizeof(double) - 1) / sizeof(double) <=         \
         VR_base_torque_3 + 1)
#ifndef FMU_INVERSE_COPY_OUTPUTS
#define FMU_INVERSE_COPY_OUTPUTS 0
#endif
enum { kOutputsInPlace = !FMU_INVERSE_COPY_OUTPUTS && OUTPUTS_LIE_OVER_VARIABLES };
#if defined(__x86_64__) && !FMU_INVERSE_COPY_OUTPUTS
_Static_assert(kOutputsInPlace, "stewart_inverse_output no longer lies over the output variables "
                                "on x86-64: the usual step would copy it");
#endif
_Static_assert(sizeof(fd_point) == 256, "a history slot is no longer 256 bytes");
/* The pose inputs' pairs and the history slots' pose and chord pairs lie on 16 bytes in an
 * instance that calloc aligns for any type (load_aligned_pair). */
_Static_assert(_Alignof(max_align_t) >= 16 &&
                   (offsetof(fmu_instance, v) + offsetof(fmu_values, real) +
                    VR_x * sizeof(double)) % 16 == 0 && (VR_x_dot - VR_x) % 2 == 0 &&
                   (VR_x_ddot - VR_x) % 2 == 0 &&
                   (offsetof(fmu_instance, v) + offsetof(fmu_values, model) +
                    offsetof(model_values, history)) % 16 == 0 &&
                   offsetof(fd_point, pose) % 16 == 0 && offsetof(fd_point, slope) % 16 == 0,
               "the pose inputs' or the history's pairs no longer lie on 16 bytes");
_Static_assert(VR_x_dot == VR_x + 6 && VR_x_ddot == VR_x + 12 &&
                   offsetof(stewart_pose, q_dot) == 6 * sizeof(double) &&
                   offsetof(stewart_pose, q_ddot) == 12 * sizeof(double) &&
                   sizeof(stewart_inverse_input) == 18 * sizeof(double),
               "the pose inputs are no longer a stewart_pose");

/* Where a solve writes its output: over the output variables, or `local` where the ABI does not
 * lay the struct over them. */
static inline stewart_inverse_output *output_target(fmu_values *v, stewart_inverse_output *local) {
    return kOutputsInPlace ? (stewart_inverse_output *)(void *)&v->real[VR_L_1] : local;
}

/* An int field of the output a solve wrote at `out` (bytes read through memcpy: in place, the
 * struct's ints lie in double slots). */
#define OUTPUT_INT(out, field)                                                                  \
    output_int((const unsigned char *)(const void *)(out), offsetof(stewart_inverse_output, field))
static inline int output_int(const unsigned char *out, size_t offset) {
    int value;
    memcpy(&value, out + offset, sizeof value);
    return value;
}

/* What a solve wrote over the output variables made theirs: the iteration count, the base
 * wrench moved to its slots. */
static inline void outputs_in_place(fmu_values *v) {
    v->integer[VR_newton_iterations] = OUTPUT_INT(&v->real[VR_L_1], iterations);
    v->real[VR_newton_iterations] = 0.0; /* no Real variable: no stray bytes in a state */
    /* one slot on (the slots overlap: all read first, then written, three pairs each way) */
    double *wrench = &v->real[VR_base_force_1];
    const double_pair f12 = load_pair(wrench - 1), f3m1 = load_pair(wrench + 1),
                      m23 = load_pair(wrench + 3);
    store_pair(wrench, f12);
    store_pair(wrench + 2, f3m1);
    store_pair(wrench + 4, m23);
    v->real[VR_base_force_1 - 1] = 0.0; /* the slot of the Integer status: no Real variable */
}

/* The output of a solve written elsewhere (`out`), copied into the output variables. */
static void outputs_copied(fmu_values *v, const stewart_inverse_output *out) {
    memcpy(&v->real[VR_L_1], out->lengths.length, sizeof out->lengths.length);
    memcpy(&v->real[VR_L_dot_1], out->lengths.length_rate, sizeof out->lengths.length_rate);
    memcpy(&v->real[VR_L_ddot_1], out->lengths.length_accel, sizeof out->lengths.length_accel);
    memcpy(&v->real[VR_F_1], out->force, sizeof out->force);
    v->real[VR_condition] = out->condition;
    v->integer[VR_newton_iterations] = out->iterations;
    v->real[VR_residual] = out->residual;
    memcpy(&v->real[VR_base_force_1], out->base_force, sizeof out->base_force);
    memcpy(&v->real[VR_base_torque_1], out->base_torque, sizeof out->base_torque);
}

/* The output a solve wrote at `out` (output_target) made the output variables. */
static inline void take_outputs(fmu_values *v, const stewart_inverse_output *out) {
    if (kOutputsInPlace)
        outputs_in_place(v);
    else
        outputs_copied(v, out);
}

/* solve_status of a usual step's solve whose output still lies as the library wrote it (the
 * base wrench one slot early, the iteration count in a Real slot): the step leaves outputs_in_place
 * to the first read (outputs_current FMU_OUTPUTS_UNREAD), or to whatever else comes first that
 * finds the outputs current (a step through the full rules, a refused solve, a state). A master
 * that reads the outputs after every step pays the same instructions in its first Get; one that
 * reads them less often pays less (issue 22: doStep within 5 % of the library call). */
enum { SOLVED_UNREAD = FMU_ERROR + 8 };

/* The outputs laid out if a usual step left them as the library wrote them (exactly once: the
 * solve status says so). */
static inline void lay_out_outputs(fmu_values *v) {
    if (v->model.solve_status != SOLVED_UNREAD) return;
    outputs_in_place(v);
    v->integer[VR_status] = 0; /* a usual step's solve has nothing to warn of */
    v->model.solve_status = FMU_OK;
}

/* ---------------------------------------------------------------- the usual step's route */

/* What the usual step (do_step.h: model_usual_steps) does with a step whose inputs are set since
 * the last one and finite (model_values.usual_route, settled after every change that rules a usual step out, so that the
 * usual step tests one value; a change that allows one again, such as a discarded advance
 * cleared by a solve, leaves it at the full rules until a full-rules step settles it): the step
 * rules in full (FMI 2 input derivatives given, a discarded advance
 * standing, limit outputs, fewer than two poses in the finite-difference history), or one of the
 * two usual steps. 0 (a state's start) is the full rules. */
enum { ROUTE_CHECKED = 0, ROUTE_ADVANCE = 1, ROUTE_HOLD = 2 };

/* The route for the values as they stand. */
static int usual_route_of(const fmu_values *v) {
    const model_values *m = &v->model;
    if (m->input_derivatives || m->advance_discarded || v->integer[VR_limit_outputs])
        return ROUTE_CHECKED;
    if (v->integer[VR_derivatives]) return ROUTE_ADVANCE;
    return m->n_history == 2 ? ROUTE_HOLD : ROUTE_CHECKED;
}

/* Settles the route after anything it depends on changed (every change that rules a usual step
 * out is followed by this). */
static void settle_usual_route(fmu_values *v) {
    /* the full rules outside step mode: they check the mode, which the usual call leaves to the
     * route (do_step.h: fmu_usual_call) */
    v->model.usual_route = v->mode == MODE_STEP ? usual_route_of(v) : ROUTE_CHECKED;
}

int inverse_usual_route_valid(const fmu_values *v) {
    return v->model.usual_route == ROUTE_CHECKED ||
           (v->mode == MODE_STEP && v->model.usual_route == usual_route_of(v));
}

/* ---------------------------------------------------------------- parameters */

fmu_status model_apply_parameters(fmu_instance *inst) {
    fmu_values *v = &inst->v;
    model_resources *r = &inst->res;
    if (v->integer[VR_limit_outputs] < 0 || v->integer[VR_limit_outputs] > 2) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "invalid parameter limit_outputs = %d: it must be 0 (none), 1 (the limit check) "
                "or 2 (and the axis ranges)", (int)v->integer[VR_limit_outputs]);
        return FMU_ERROR;
    }
    if (v->integer[VR_derivatives] != 0 && v->integer[VR_derivatives] != 1) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "invalid parameter derivatives = %d: it must be 0 (finite differences) or 1 "
                "(the *_dot and *_ddot inputs)", (int)v->integer[VR_derivatives]);
        return FMU_ERROR;
    }
    stewart_inverse_options o;
    inverse_options_from_values(v, &o);
    if (stewart_inverse_options_check(&o, r->message, sizeof r->message) != STEWART_OK) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "invalid parameter: %s", r->message);
        return FMU_ERROR;
    }
    stewart_params p;
    inverse_params_from_values(v, &p);
    const int new_model = !r->model || memcmp(&p, &r->params, sizeof p) != 0;
    if (new_model || !same_options(&o, stewart_inverse_options_of(r->inverse))) {
        stewart_model *m = new_model ? stewart_model_create(&p, r->message, sizeof r->message)
                                     : r->model;
        if (!m) {
            fmu_log(inst, FMU_ERROR, LOG_ERROR, "invalid parameter: %s", r->message);
            return FMU_ERROR;
        }
        stewart_inverse *d = stewart_inverse_create(m, &o, r->message, sizeof r->message);
        if (!d) {
            if (new_model) stewart_model_free(m);
            fmu_log(inst, FMU_ERROR, LOG_ERROR, "creating the inverse solver: %s", r->message);
            return FMU_ERROR;
        }
        if (!new_model) stewart_inverse_copy(d, r->inverse); /* the warm start goes on */
        stewart_inverse_free(r->inverse);
        r->inverse = d;
        if (new_model) {
            stewart_linearize_free(r->linearize); /* made for the old model */
            r->linearize = NULL;
            stewart_model_free(r->model);
            r->model = m;
            r->params = p;
            fmu_log(inst, FMU_OK, LOG_EVENTS, "model built from the parameters (fidelity %d, "
                    "derivatives %d)", (int)v->integer[VR_fidelity],
                    (int)v->integer[VR_derivatives]);
        }
    }
    /* The limits follow the model and the condition limit (cheap to make: no workspace). */
    if (new_model || !r->limits || r->options.warn_condition != o.warn_condition) {
        stewart_limits_options lo;
        stewart_limits_options_default(&lo);
        lo.warn_condition = o.warn_condition;
        stewart_limits *l = stewart_limits_create(r->model, &lo, r->message, sizeof r->message);
        if (!l) {
            fmu_log(inst, FMU_ERROR, LOG_ERROR, "creating the limit check: %s", r->message);
            return FMU_ERROR;
        }
        stewart_limits_free(r->limits);
        r->limits = l;
    }
    r->options = o;
    settle_usual_route(v);
    return FMU_OK;
}

/* The inverse solver starts from what model_apply_parameters built: nothing more to set. */
fmu_status model_start(fmu_instance *inst) {
    (void)inst;
    return FMU_OK;
}

void model_reset(fmu_instance *inst) {
    if (inst->res.inverse) stewart_inverse_reset(inst->res.inverse);
}

void model_free(fmu_instance *inst) {
    stewart_linearize_free(inst->res.linearize);
    inst->res.linearize = NULL;
    stewart_limits_free(inst->res.limits);
    stewart_inverse_free(inst->res.inverse);
    stewart_model_free(inst->res.model);
    inst->res.limits = NULL;
    inst->res.inverse = NULL;
    inst->res.model = NULL;
}

/* ---------------------------------------------------------------- the solve */

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

int inverse_uses_rate_inputs(const fmu_values *v) { return taylor_mode(v); }

static fmu_status map_solve_error(stewart_status s) {
    switch (s) {
        case STEWART_ERR_ARGUMENT:
        case STEWART_ERR_SINGULAR:
        case STEWART_ERR_UNREACHABLE:
        case STEWART_ERR_NOT_CONVERGED:
            return FMU_DISCARD;
        default:
            return FMU_ERROR;
    }
}

/* The value reference of the first input that is not finite, or -1. */
static int first_nonfinite_input(const fmu_values *v) {
    for (unsigned vr = VR_x; vr <= VR_yaw_ddot; ++vr)
        if (!isfinite(v->real[vr])) return (int)vr;
    return -1;
}

/* Not solved: status 3, the outputs keep their last valid values; the result stands for the
 * current inputs until they change. */
static fmu_status not_solved(fmu_values *v, fmu_status s) {
    lay_out_outputs(v); /* the last valid values, where they are read */
    v->integer[VR_status] = 3;
    v->outputs_current = 1;
    v->model.solve_status = s;
    return s;
}

/* Discard naming the first input that is not finite if there is one (FMU_OK if none). The runtime
 * flags a value set that is not finite (inputs_unchecked), so the step looks only then; finite
 * inputs advanced along their Taylor expansion can still overflow, which the library refuses,
 * and its refusal looks again. */
static fmu_status check_inputs(fmu_instance *inst, double time) {
    fmu_values *v = &inst->v;
    const int bad = first_nonfinite_input(v);
    if (bad < 0) {
        v->inputs_unchecked = 0;
        return FMU_OK;
    }
    fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
            "t = %.17g: input %s = %g is not finite; outputs keep their last valid values",
            time, fmu_variable_by_vr((unsigned)bad)->name, v->real[bad]);
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

/* The limit outputs for pose q (limit_outputs 1: the check; 2: and the axis ranges) and a
 * Warning, logged, when a joint angle or two legs are beyond their limits (strokes and the
 * condition have warnings of their own). */
static fmu_status limit_outputs(fmu_instance *inst, double time, const double q[6]) {
    fmu_values *v = &inst->v;
    const int level = v->integer[VR_limit_outputs];
    if (level == 0) return FMU_OK;
    stewart_limits_input in;
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
    if (values.check.failed & (1 << (STEWART_LIMIT_AXIS - 1))) {
        static const char *const axes[] = {"x", "y", "z", "roll", "pitch", "yaw"};
        const int axis = values.check.leg[STEWART_LIMIT_AXIS - 1];
        fs = FMU_WARNING;
        fmu_log(inst, FMU_WARNING, LOG_WARNING,
                "t = %.17g: %s is %g beyond its software position limit (axis_min, axis_max)",
                time, axes[axis >= 1 && axis <= 6 ? axis - 1 : 0],
                -values.check.margin[STEWART_LIMIT_AXIS - 1]);
    }
    return fs;
}

/* The library's refusal of the pose at `time`: Discard or Error, logged. */
static fmu_status not_solved_by_library(fmu_instance *inst, double time, const stewart_pose *pose,
                                        stewart_status s) {
    const fmu_status fs = map_solve_error(s);
    fmu_log(inst, fs, fs == FMU_DISCARD ? LOG_DISCARD : LOG_ERROR,
            "t = %.17g: pose (x, y, z, roll, pitch, yaw) = (%g, %g, %g, %g, %g, %g) not solved "
            "(%s): %s; outputs keep their last valid values",
            time, pose->q[0], pose->q[1], pose->q[2], pose->q[3], pose->q[4], pose->q[5],
            stewart_status_name(s), stewart_inverse_message(inst->res.inverse));
    return not_solved(&inst->v, fs);
}

/* The outputs, status output and warnings of a solved pose q at `time` (its output written by
 * output_target(v, local); the library's warning bits `warnings`). */
FMU_RARE_PATH static fmu_status warnings_of(fmu_instance *inst, double time, const double q[6],
                                            stewart_inverse_output *local, int warnings) {
    fmu_values *v = &inst->v;
    const model_resources *r = &inst->res;
    const stewart_inverse_output *out = output_target(v, local);
    const int stroke_legs = OUTPUT_INT(out, stroke_legs); /* before the outputs move over it */
    take_outputs(v, out);
    v->outputs_current = 1;
    fmu_status fs = FMU_OK;
    int status = 0;
    if (warnings & STEWART_WARN_STROKE) {
        status = 1;
        fs = FMU_WARNING;
        warn_stroke(inst, time, stroke_legs);
    }
    if (warnings & STEWART_WARN_NEAR_SINGULAR) {
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

/* The outputs (the library's output at `out`, output_target), status and warnings of a solved
 * pose q at `time`; short when there is nothing to warn of or check (the step's usual case, so
 * that the compiler inlines it). */
static inline fmu_status solved_checking(fmu_instance *inst, double time, const double q[6],
                                         const stewart_inverse_output *out, int limit_outputs) {
    fmu_values *v = &inst->v;
    const int warnings = OUTPUT_INT(out, warnings);
    if (warnings || limit_outputs) /* (in place the rare path finds the output itself) */
        return warnings_of(inst, time, q, kOutputsInPlace ? NULL : (stewart_inverse_output *)out,
                           warnings);
    take_outputs(v, out);
    v->outputs_current = 1;
    v->integer[VR_status] = 0;
    v->model.solve_status = FMU_OK;
    return FMU_OK;
}

/* The usual step's library status or the warning bits of its output, in one test (the rare
 * case, either, is told apart out of line). In place the output's bytes are defined whatever the
 * library did (a refused solve leaves the last outputs there, whose bits are then not used). */
static inline int refused_or_warned(stewart_status s, const stewart_inverse_output *out) {
    if (!kOutputsInPlace) return s != STEWART_OK || OUTPUT_INT(out, warnings);
    return ((int)s | OUTPUT_INT(out, warnings)) != 0;
}

/* The outputs of the usual step's solve, which had nothing to warn of (no limit outputs): in
 * place they stay as the library wrote them until read (SOLVED_UNREAD; the status output 0 is
 * written with them, lay_out_outputs). */
static inline fmu_status solved_plain(fmu_instance *inst, const stewart_inverse_output *out) {
    fmu_values *v = &inst->v;
    if (!kOutputsInPlace) return solved_checking(inst, 0.0, NULL, out, 0); /* (no warnings) */
    v->outputs_current = FMU_OUTPUTS_UNREAD;
    v->model.solve_status = SOLVED_UNREAD;
    return FMU_OK;
}

/* solved_checking with the limit outputs as the parameter says. */
static fmu_status solved(fmu_instance *inst, double time, const double q[6],
                         const stewart_inverse_output *out) {
    return solved_checking(inst, time, q, out, inst->v.integer[VR_limit_outputs]);
}

/* The library refused `pose` (the current inputs' at `time`): finite differences that are not
 * finite are named as the FMU's (the library refuses them before any work: it checks its pose
 * first, so they are looked for only now), else the library's reason. */
FMU_RARE_PATH static fmu_status refused(fmu_instance *inst, double time, const stewart_pose *pose,
                                        stewart_status s) {
    if (!taylor_mode(&inst->v))
        for (int i = 0; i < 6; ++i)
            if (!isfinite(pose->q_dot[i]) || !isfinite(pose->q_ddot[i]))
                return discard_finite_differences(inst, time, pose, i);
    return not_solved_by_library(inst, time, pose, s);
}

/* Solves for the current inputs at `time` unless the outputs already belong to them. OK /
 * Warning (status 1 or 2) / Discard (status 3, outputs keep their last valid values) / Error
 * (unsupported fidelity, memory). */
static fmu_status solve_at(fmu_instance *inst, double time) {
    fmu_values *v = &inst->v;
    if (v->outputs_current) {
        lay_out_outputs(v);
        return v->model.solve_status;
    }
    v->model.advance_discarded = 0;
    /* Every input must be finite, used or not. */
    if (v->inputs_unchecked && check_inputs(inst, time) != FMU_OK) return FMU_DISCARD;
    stewart_inverse_input in;
    current_pose(v, time, &in.pose);
    stewart_inverse_output local, *out = output_target(v, &local);
    const stewart_status s = stewart_inverse_solve(inst->res.inverse, &in, out);
    if (s != STEWART_OK) return refused(inst, time, &in.pose, s);
    return solved(inst, time, in.pose.q, out);
}

fmu_status model_refresh_outputs(fmu_instance *inst) {
    fmu_values *v = &inst->v;
    if (v->outputs_current == FMU_OUTPUTS_UNREAD) { /* current: laid out, as the runtime read them */
        lay_out_outputs(v);
        v->outputs_current = 1;
        return FMU_OK;
    }
    return solve_at(inst, v->time);
}

/* ---------------------------------------------------------------- the step rules */

/* The pose q at communication point t joins the finite-difference history: the free slot becomes
 * the last point, with its chord from the point before (the quotient current_pose took). */
static void commit_pose(model_values *m, double t, const double q[6]) {
    const fd_point *newer = newer_point(m);
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
    fmu_status fs = check_inputs(inst, time);
    if (fs == FMU_OK) fs = not_solved_by_library(inst, time, pose, s);
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
    const int advance = taylor_mode(v);
    int bad_input = 0;
    if (v->inputs_unchecked) {
        bad_input = first_nonfinite_input(v) >= 0;
        if (!bad_input) v->inputs_unchecked = 0;
    }
    fmu_status s = FMU_OK;
    if (!advance || v->outputs_current || bad_input) {
        s = solve_at(inst, t);
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
    stewart_inverse_output local, *out = output_target(v, &local);
    const stewart_status ls = stewart_inverse_solve(inst->res.inverse, &in, out);
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
    return solved(inst, t + h, in.pose.q, out);
}

fmu_status model_do_step(fmu_instance *inst, double t, double h) {
    const fmu_status s = step_rules(inst, t, h);
    settle_usual_route(&inst->v);
    return s;
}

/* ---------------------------------------------------------------- the usual step */

/* The library refused the pose advanced in place (the inputs hold it; at_t: the inputs' pose and
 * rates at t): as advance_refused, and the inputs go back to at_t. */
FMU_RARE_PATH static fmu_status advance_in_place_refused(fmu_instance *inst, double time,
                                                         const double at_t[12], stewart_status s) {
    fmu_values *v = &inst->v;
    const stewart_pose *advanced = (const stewart_pose *)(const void *)&v->real[VR_x];
    fmu_status fs = check_inputs(inst, time);
    if (fs == FMU_OK) fs = not_solved_by_library(inst, time, advanced, s);
    memcpy(&v->real[VR_x], at_t, 12 * sizeof(double));
    v->model.advance_discarded = 1; /* status 3 and the kept outputs stand until a step or a set */
    settle_usual_route(v);
    return fs;
}

/* The advance in place refused (the inputs go back to at_t) or solved with warnings (its output
 * at output_target(v, out); no limit outputs on the usual step). */
FMU_RARE_PATH static fmu_status advance_not_plain(fmu_instance *inst, double time,
                                                  const double at_t[12], stewart_status s,
                                                  const stewart_inverse_output *out) {
    if (s != STEWART_OK) return advance_in_place_refused(inst, time, at_t, s);
    return solved_checking(inst, time, &inst->v.real[VR_x],
                           output_target(&inst->v, (stewart_inverse_output *)out), 0);
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
static inline fmu_status advance_in_place(fmu_instance *inst, double h) {
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
    stewart_inverse_output local, *out = output_target(v, &local);
    const stewart_status s = stewart_inverse_solve(
        inst->res.inverse, (const stewart_inverse_input *)(const void *)pose, out);
    if (refused_or_warned(s, out)) /* (in place the rare path finds the output itself) */
        return advance_not_plain(inst, inst->step.end, at_t, s, kOutputsInPlace ? NULL : out);
    return solved_plain(inst, out);
}

#if PAIRED_ARITHMETIC
/* Two coordinates of quadratic_rates (the same roundings), each value loaded once: the pose q
 * (the inputs) and the last point's pose and chord (p1, d1) into the free slot's pose (next:
 * q, q_dot 6 on, q_ddot 12 on) and chord (slope). */
static inline void quadratic_pair(const double *restrict q, const double *restrict p1,
                                  const double *restrict d1_at,
                                  double *restrict next, double *restrict slope, double_pair h2, double_pair h12) {
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
 * output_target(v, out)). */
FMU_RARE_PATH static fmu_status hold_not_plain(fmu_instance *inst, stewart_status s,
                                               const stewart_inverse_output *out) {
    model_values *m = &inst->v.model;
    if (s != STEWART_OK) return refused(inst, inst->step.t, &m->history[m->newer ^ 1].pose, s);
    m->newer ^= 1;
    return solved_checking(inst, inst->step.t, &inst->v.real[VR_x],
                           output_target(&inst->v, (stewart_inverse_output *)out), 0);
}

/* The history slot `at` bytes into the history (0 or sizeof(fd_point)). */
static inline fd_point *history_slot_at(model_values *m, size_t at) {
    return (fd_point *)(void *)((char *)m->history + at);
}

/* Inlined into each usual step whatever the compiler's estimate (each is one function with one
 * library call: a call of its own would add a frame around it). */
#if defined(__GNUC__)
#define ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define ALWAYS_INLINE inline
#endif

/* derivatives = 0 with two earlier poses, the usual step: solve_at(t) (the quadratic's rates)
 * and the pose joins the history (t is inst->step.t, for the rare paths). The free slot of the history takes the pose, its rates (the
 * library's input) and its chord before the solve; the solved pose becomes the last point by
 * the flip of one index, and a refused one leaves the history as it was. */
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
    quadratic_rates(m, t, &next->pose);
    for (int i = 0; i < 6; ++i) /* the quotient quadratic_rates took as d2 */
        next->slope[i] = (next->pose.q[i] - newer->pose.q[i]) / h2;
#endif
    next->t = t;
    next->interval = h2;
    stewart_inverse_output local, *out = output_target(v, &local);
    const stewart_status s = stewart_inverse_solve(
        inst->res.inverse, (const stewart_inverse_input *)(const void *)&next->pose, out);
    if (refused_or_warned(s, out)) /* (in place the rare path finds the output itself) */
        return hold_not_plain(inst, s, kOutputsInPlace ? NULL : out);
    m->newer ^= 1; /* the history is full already */
    return solved_plain(inst, out);
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

OWN_FRAME static fmu_status usual_advance_step(fmu_instance *inst, double t, double h,
                                               double end) {
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
 * by the route, which is 0..2: settle_usual_route writes it, and a restored state whose route is
 * not what its values give is refused, model_state.c). The usual step: no discarded advance
 * standing, no FMI 2 input derivatives, no limit outputs, and with finite differences two
 * earlier poses; anything else the step rules in full. */
const model_usual_step_fn model_usual_steps[] = {
    [ROUTE_CHECKED] = full_rules_step,
    [ROUTE_ADVANCE] = usual_advance_step,
    [ROUTE_HOLD] = usual_hold_step,
};
_Static_assert(sizeof model_usual_steps / sizeof *model_usual_steps == ROUTE_HOLD + 1,
               "a route without its usual step");

fmu_status model_set_input_derivatives(fmu_instance *inst, const unsigned vr[], size_t n,
                                       const int order[], const double value[]) {
    fmu_values *v = &inst->v;
    for (size_t i = 0; i < n; ++i) {
        const int pose = vr[i] <= VR_yaw, rate = vr[i] >= VR_x_dot && vr[i] <= VR_yaw_dot;
        if (!((pose && (order[i] == 1 || order[i] == 2)) || (rate && order[i] == 1))) {
            fmu_log(inst, FMU_ERROR, LOG_ERROR,
                    "SetRealInputDerivatives: derivative of order %d of value reference %u is "
                    "not supported (orders 1 and 2 of the pose inputs, order 1 of *_dot)",
                    order[i], vr[i]);
            return FMU_ERROR;
        }
    }
    /* With derivatives = 0 the *_dot and *_ddot slots hold only what this call and the others
     * before the same step give: an order the master does not give is zero for the step, never
     * a value left from an earlier step. */
    if (n > 0 && !v->model.input_derivatives && v->integer[VR_derivatives] == 0)
        for (unsigned vr_slot = VR_x_dot; vr_slot <= VR_yaw_ddot; ++vr_slot) v->real[vr_slot] = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const unsigned base = vr[i] <= VR_yaw ? vr[i] : vr[i] - VR_x_dot;
        v->real[(order[i] == 1 && vr[i] <= VR_yaw ? VR_x_dot : VR_x_ddot) + base] = value[i];
        if (!isfinite(value[i])) v->inputs_unchecked = 1; /* the step looks at the inputs */
    }
    if (n > 0) v->model.input_derivatives = 1;
    settle_usual_route(v);
    return FMU_OK;
}
