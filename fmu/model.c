/* The model behind both FMI layers (see model.h). */
#include "model.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- state machine (one table) */

#define ANY_MODE (MODE_INSTANTIATED | MODE_INITIALIZATION | MODE_STEP | MODE_TERMINATED | MODE_ERROR)
static const int kAllowed[CALL_COUNT] = {
    [CALL_SET_DEBUG_LOGGING] = ANY_MODE,
    [CALL_SETUP_EXPERIMENT] = MODE_INSTANTIATED,
    [CALL_ENTER_INITIALIZATION] = MODE_INSTANTIATED,
    [CALL_EXIT_INITIALIZATION] = MODE_INITIALIZATION,
    [CALL_DO_STEP] = MODE_STEP,
    [CALL_TERMINATE] = MODE_STEP,
    [CALL_RESET] = ANY_MODE,
    [CALL_GET] = MODE_INITIALIZATION | MODE_STEP | MODE_TERMINATED | MODE_ERROR,
    [CALL_SET] = MODE_INSTANTIATED | MODE_INITIALIZATION | MODE_STEP,
    [CALL_SET_INPUT_DERIVATIVES] = MODE_INSTANTIATED | MODE_INITIALIZATION | MODE_STEP,
    [CALL_GET_STATUS] = MODE_STEP | MODE_TERMINATED | MODE_ERROR,
    [CALL_GET_FMU_STATE] = MODE_INSTANTIATED | MODE_INITIALIZATION | MODE_STEP | MODE_TERMINATED,
    [CALL_SET_FMU_STATE] = MODE_INSTANTIATED | MODE_INITIALIZATION | MODE_STEP | MODE_TERMINATED,
    [CALL_SERIALIZE] = ANY_MODE,
};

static const char *mode_name(int mode) {
    switch (mode) {
        case MODE_INSTANTIATED: return "instantiated";
        case MODE_INITIALIZATION: return "initialization mode";
        case MODE_STEP: return "step mode";
        case MODE_TERMINATED: return "terminated";
        case MODE_ERROR: return "error";
    }
    return "?";
}

fmu_status fmu_check_call(fmu_instance *inst, fmu_call call, const char *function) {
    if (!inst) return FMU_ERROR;
    if (kAllowed[call] & inst->v.mode) return FMU_OK;
    fmu_log(inst, FMU_ERROR, LOG_ERROR, "%s is not allowed in %s", function,
            mode_name(inst->v.mode));
    return FMU_ERROR;
}

/* ---------------------------------------------------------------- logging */

void fmu_log(const fmu_instance *inst, fmu_status status, int category, const char *fmt, ...) {
    if (!inst || !inst->log_fn || !inst->logging_on || category < 0 ||
        category >= FMU_N_LOG_CATEGORIES || !inst->category_on[category])
        return;
    char buffer[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buffer, sizeof buffer, fmt, ap);
    va_end(ap);
    /* FMI 2 loggers treat the message as a format string and '#' as a variable escape. */
    for (char *c = buffer; *c; ++c)
        if (*c == '%' || *c == '#') *c = ' ';
    inst->log_fn(inst, status, fmu_log_category_names[category], buffer);
}

fmu_status fmu_set_debug_logging(fmu_instance *inst, int on, size_t n, const char *const cats[]) {
    if (fmu_check_call(inst, CALL_SET_DEBUG_LOGGING, "SetDebugLogging") != FMU_OK) return FMU_ERROR;
    inst->logging_on = 1; /* so the error below can be reported if categories are on */
    if (n == 0) {
        for (int c = 0; c < FMU_N_LOG_CATEGORIES; ++c) inst->category_on[c] = on;
    } else {
        for (size_t i = 0; i < n; ++i) {
            int found = -1;
            for (int c = 0; c < FMU_N_LOG_CATEGORIES; ++c)
                if (cats && cats[i] && !strcmp(cats[i], fmu_log_category_names[c])) found = c;
            if (found < 0) {
                fmu_log(inst, FMU_ERROR, LOG_ERROR, "SetDebugLogging: unknown log category '%s'",
                        cats && cats[i] ? cats[i] : "(null)");
                return FMU_ERROR;
            }
            inst->category_on[found] = on;
        }
    }
    inst->logging_on = 0;
    for (int c = 0; c < FMU_N_LOG_CATEGORIES; ++c)
        if (inst->category_on[c]) inst->logging_on = 1;
    return FMU_OK;
}

/* ---------------------------------------------------------------- start values */

static void set_start_values(fmu_values *v) {
    stewart_params p;
    stewart_options o;
    stewart_params_default(&p);
    stewart_options_default(&o);
    memset(v, 0, sizeof *v);
#define FMU_INPUT(vr, id, name, start, unit, row, col, desc) v->real[vr] = start;
#define FMU_OUTPUT(vr, id, name, unit, field, desc) v->real[vr] = 0.0;
#define FMU_OUTPUT_INT(vr, id, name, desc) v->integer[vr] = 0;
#define FMU_OPTION_INT(vr, id, name, start, min, max, desc) v->integer[vr] = start;
#define FMU_OPTION_REAL(vr, id, name, field, unit, desc) v->real[vr] = o.field;
#define FMU_PARAM(vr, id, name, field, unit, display, desc) v->real[vr] = p.field;
#define FMU_INDEPENDENT(vr, id, name, unit, desc) v->real[vr] = 0.0;
#include "variables.def"
    v->integer[VR_status] = 3; /* nothing solved yet */
    v->mode = MODE_INSTANTIATED;
}

static void params_from_values(const fmu_values *v, stewart_params *p) {
    stewart_params_default(p);
#define FMU_PARAM(vr, id, name, field, unit, display, desc) p->field = v->real[vr];
#include "variables.def"
}

static void options_from_values(const fmu_values *v, stewart_options *o) {
    stewart_options_default(o);
#define FMU_OPTION_REAL(vr, id, name, field, unit, desc) o->field = v->real[vr];
#include "variables.def"
    o->fidelity = (stewart_fidelity)v->integer[VR_fidelity];
    o->max_iterations = v->integer[VR_max_iterations];
    o->modified_newton = v->integer[VR_modified_newton];
}

static void outputs_to_values(fmu_values *v, const stewart_output *out) {
#define FMU_OUTPUT(vr, id, name, unit, field, desc) v->real[vr] = out->field;
#include "variables.def"
    v->integer[VR_newton_iterations] = out->iterations;
}

/* ---------------------------------------------------------------- lifetime */

fmu_instance *fmu_instantiate(const char *name, fmu_version version, fmu_log_fn log_fn,
                              const void *callbacks, void *environment, int logging_on) {
    fmu_instance *inst = (fmu_instance *)calloc(1, sizeof *inst);
    if (!inst) return NULL;
    const char *n = name ? name : "";
    inst->name = (char *)malloc(strlen(n) + 1);
    if (!inst->name) {
        free(inst);
        return NULL;
    }
    strcpy(inst->name, n);
    inst->version = version;
    inst->log_fn = log_fn;
    inst->callbacks = callbacks;
    inst->environment = environment;
    inst->logging_on = logging_on ? 1 : 0;
    for (int c = 0; c < FMU_N_LOG_CATEGORIES; ++c) inst->category_on[c] = inst->logging_on;
    set_start_values(&inst->v);
    stewart_options_default(&inst->options);
    return inst;
}

void fmu_free(fmu_instance *inst) {
    if (!inst) return;
    stewart_data_free(inst->data);
    stewart_model_free(inst->model);
    free(inst->name);
    free(inst);
}

fmu_status fmu_reset(fmu_instance *inst) {
    if (fmu_check_call(inst, CALL_RESET, "Reset") != FMU_OK) return FMU_ERROR;
    /* The model (immutable) is kept and reused if the parameters come back the same. */
    set_start_values(&inst->v);
    if (inst->data) stewart_data_reset(inst->data);
    fmu_log(inst, FMU_OK, LOG_EVENTS, "reset to the start values");
    return FMU_OK;
}

/* Builds (or keeps) the model for the current parameters and checks the options. */
static fmu_status apply_parameters(fmu_instance *inst) {
    const fmu_values *v = &inst->v;
    if (v->integer[VR_derivatives] != 0 && v->integer[VR_derivatives] != 1) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "invalid parameter derivatives = %d: it must be 0 (finite differences) or 1 "
                "(the *_dot and *_ddot inputs)", (int)v->integer[VR_derivatives]);
        return FMU_ERROR;
    }
    stewart_options o;
    options_from_values(v, &o);
    if (stewart_options_check(&o, inst->message, sizeof inst->message) != STEWART_OK) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "invalid parameter: %s", inst->message);
        return FMU_ERROR;
    }
    /* Non-finite parameters are named here, with their units (the library's message names
     * them alike, without the unit). */
#define FMU_PARAM(vr, id, name, field, unit, display, desc)                                     \
    if (!isfinite(v->real[vr])) {                                                               \
        fmu_log(inst, FMU_ERROR, LOG_ERROR,                                                     \
                "invalid parameter %s = %g %s: every parameter must be finite", name,          \
                v->real[vr], unit);                                                             \
        return FMU_ERROR;                                                                       \
    }
#include "variables.def"
    stewart_params p;
    params_from_values(v, &p);
    if (!inst->model || memcmp(&p, &inst->model_params, sizeof p) != 0) {
        stewart_model *m = stewart_model_create(&p, inst->message, sizeof inst->message);
        if (!m) {
            fmu_log(inst, FMU_ERROR, LOG_ERROR, "invalid parameter: %s", inst->message);
            return FMU_ERROR;
        }
        stewart_data *d = stewart_data_create(m);
        if (!d) {
            stewart_model_free(m);
            fmu_log(inst, FMU_ERROR, LOG_ERROR, "out of memory creating the solver data");
            return FMU_ERROR;
        }
        stewart_data_free(inst->data);
        stewart_model_free(inst->model);
        inst->model = m;
        inst->data = d;
        inst->model_params = p;
        ++inst->model_generation;
        fmu_log(inst, FMU_OK, LOG_EVENTS, "model built from the parameters");
    }
    inst->options = o;
    return FMU_OK;
}

/* ---------------------------------------------------------------- the solve */

static int taylor_mode(const fmu_values *v) {
    return v->integer[VR_derivatives] == 1 || v->input_derivatives;
}

/* The pose at v->time: inputs, and derivatives from the inputs or by finite differences of the
 * poses at earlier communication points (quadratic through the last three poses; with only one
 * earlier pose, the chord through both and zero acceleration; none: at rest). Assuming rest at the
 * first point instead would give a motion already under way an acceleration 2 v / h: unbounded as
 * h shrinks. */
static void current_pose(const fmu_values *v, stewart_pose *pose) {
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
    const double t = v->time;
    if (v->n_history == 0) {
        for (int i = 0; i < 6; ++i) pose->q_dot[i] = pose->q_ddot[i] = 0.0;
    } else if (v->n_history == 1) {
        const double h = t - v->history_t[1];
        for (int i = 0; i < 6; ++i) {
            pose->q_dot[i] = (pose->q[i] - v->history_q[1][i]) / h;
            pose->q_ddot[i] = 0.0;
        }
    } else {
        const double h1 = v->history_t[1] - v->history_t[0], h2 = t - v->history_t[1];
        for (int i = 0; i < 6; ++i) {
            const double q0 = v->history_q[0][i], q1 = v->history_q[1][i], q2 = pose->q[i];
            const double d1 = (q1 - q0) / h1, d2 = (q2 - q1) / h2;
            const double dd = (d2 - d1) / (h1 + h2); /* q[t0, t1, t2] */
            pose->q_dot[i] = d2 + h2 * dd;
            pose->q_ddot[i] = 2.0 * dd;
        }
    }
}

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

/* Solves for the current inputs unless already done. OK / Warning (status 1 or 2) / Discard
 * (status 3, outputs keep their last valid values) / Error (unsupported fidelity, memory). */
static fmu_status solve_current(fmu_instance *inst) {
    fmu_values *v = &inst->v;
    if (v->solved) return v->solve_status;
    /* Every input must be finite, used or not. */
    const int bad = first_nonfinite_input(v);
    if (bad >= 0) {
        v->integer[VR_status] = 3;
        v->solved = 1;
        v->solve_status = FMU_DISCARD;
        fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                "t = %.17g: input %s = %g is not finite; outputs keep their last valid values",
                v->time, fmu_variable_by_vr((unsigned)bad)->name, v->real[bad]);
        return FMU_DISCARD;
    }
    stewart_pose pose;
    current_pose(v, &pose);
    if (!taylor_mode(v))
        for (int i = 0; i < 6; ++i)
            if (!isfinite(pose.q_dot[i]) || !isfinite(pose.q_ddot[i])) {
                v->integer[VR_status] = 3;
                v->solved = 1;
                v->solve_status = FMU_DISCARD;
                fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                        "t = %.17g: the finite-difference %s of %s (%g, from the poses at the last "
                        "communication points, the last %g s ago) is not finite: the steps are too "
                        "small for this motion; use derivatives = 1 or larger steps. Outputs keep "
                        "their last valid values",
                        v->time, isfinite(pose.q_dot[i]) ? "acceleration" : "rate",
                        fmu_variable_by_vr(VR_x + i)->name,
                        isfinite(pose.q_dot[i]) ? pose.q_ddot[i] : pose.q_dot[i],
                        v->time - v->history_t[1]);
                return FMU_DISCARD;
            }
    stewart_output out;
    const stewart_status s = stewart_solve(inst->model, inst->data, &inst->options, &pose, &out);
    if (s != STEWART_OK) {
        const fmu_status fs = map_solve_error(s);
        v->integer[VR_status] = 3;
        v->solved = 1;
        v->solve_status = fs;
        fmu_log(inst, fs, fs == FMU_DISCARD ? LOG_DISCARD : LOG_ERROR,
                "t = %.17g: pose (x, y, z, roll, pitch, yaw) = (%g, %g, %g, %g, %g, %g) not solved "
                "(%s): %s; outputs keep their last valid values",
                v->time, pose.q[0], pose.q[1], pose.q[2], pose.q[3], pose.q[4], pose.q[5],
                stewart_status_name(s), stewart_data_message(inst->data));
        return fs;
    }
    outputs_to_values(v, &out);
    v->solved = 1;
    fmu_status fs = FMU_OK;
    int status = 0;
    if (out.warnings & STEWART_WARN_STROKE) {
        status = 1;
        fs = FMU_WARNING;
        for (int k = 0; k < STEWART_LEGS; ++k)
            if (out.length[k] < inst->model_params.stroke_min ||
                out.length[k] > inst->model_params.stroke_max)
                fmu_log(inst, FMU_WARNING, LOG_WARNING,
                        "t = %.17g: L[%d] = %g m is outside the stroke [%g, %g] m", v->time, k + 1,
                        out.length[k], inst->model_params.stroke_min,
                        inst->model_params.stroke_max);
    }
    if (out.warnings & STEWART_WARN_NEAR_SINGULAR) {
        status = 2;
        fs = FMU_WARNING;
        fmu_log(inst, FMU_WARNING, LOG_WARNING,
                "t = %.17g: near singular pose: condition = %g > warn_condition = %g", v->time,
                out.condition, inst->options.warn_condition);
    }
    v->integer[VR_status] = status;
    v->solve_status = fs;
    return fs;
}

/* ---------------------------------------------------------------- modes */

fmu_status fmu_enter_initialization(fmu_instance *inst, double start_time) {
    if (fmu_check_call(inst, CALL_ENTER_INITIALIZATION, "EnterInitializationMode") != FMU_OK)
        return FMU_ERROR;
    if (!isfinite(start_time)) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "startTime = %g must be finite", start_time);
        return FMU_ERROR;
    }
    inst->v.time = start_time;
    inst->v.real[VR_time] = start_time;
    inst->v.last_successful_time = start_time;
    inst->v.solved = 0;
    inst->v.mode = MODE_INITIALIZATION;
    return FMU_OK;
}

static fmu_status fail(fmu_instance *inst) {
    inst->v.mode = MODE_ERROR;
    return FMU_ERROR;
}

fmu_status fmu_exit_initialization(fmu_instance *inst) {
    if (fmu_check_call(inst, CALL_EXIT_INITIALIZATION, "ExitInitializationMode") != FMU_OK)
        return FMU_ERROR;
    if (apply_parameters(inst) != FMU_OK) return fail(inst);
    inst->v.solved = 0;
    fmu_status s = solve_current(inst);
    if (s == FMU_ERROR) return fail(inst);
    if (s == FMU_DISCARD) s = FMU_WARNING; /* status = 3: the master sees the pose is bad */
    inst->v.mode = MODE_STEP;
    fmu_log(inst, FMU_OK, LOG_EVENTS, "initialised at t = %.17g (fidelity %d, derivatives %d)",
            inst->v.time, (int)inst->v.integer[VR_fidelity], (int)inst->v.integer[VR_derivatives]);
    return s;
}

fmu_status fmu_terminate(fmu_instance *inst) {
    if (fmu_check_call(inst, CALL_TERMINATE, "Terminate") != FMU_OK) return FMU_ERROR;
    inst->v.mode = MODE_TERMINATED;
    return FMU_OK;
}

/* The pose q at communication point t joins the finite-difference history. */
static void commit_pose(fmu_values *v, double t, const double q[6]) {
    v->history_t[0] = v->history_t[1];
    memcpy(v->history_q[0], v->history_q[1], sizeof v->history_q[0]);
    v->history_t[1] = t;
    memcpy(v->history_q[1], q, sizeof v->history_q[1]);
    if (v->n_history < 2) ++v->n_history;
}

fmu_status fmu_do_step(fmu_instance *inst, double t, double h) {
    if (fmu_check_call(inst, CALL_DO_STEP, "DoStep") != FMU_OK) return FMU_ERROR;
    fmu_values *v = &inst->v;
    if (!(isfinite(t) && isfinite(h) && h > 0)) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "DoStep: currentCommunicationPoint = %g and communicationStepSize = %g must be "
                "finite and the step > 0", t, h);
        return FMU_ERROR;
    }
    if (!(t + h > t && isfinite(t + h))) {
        /* h below the resolution of t (t + h == t) would not advance time; t + h overflowing
         * would make it infinite. Neither is a step. */
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "DoStep: communicationStepSize = %g does not advance currentCommunicationPoint = "
                "%.17g (t + h = %.17g): the step is below the resolution of t or overflows", h, t,
                t + h);
        return FMU_ERROR;
    }
    if (v->n_history > 0 && !(t > v->history_t[1])) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "DoStep: currentCommunicationPoint = %.17g is not after the last accepted "
                "communication point %.17g", t, v->history_t[1]);
        return FMU_ERROR;
    }
    /* A master may pass t a few roundings off the unit's own time (start + n h against the sum
     * of its steps), never earlier by more: that would take the pose of time v->time for an
     * earlier one. */
    const double last_step = v->n_history > 0 ? v->time - v->history_t[1] : 0.0;
    if (t < v->time - (1e-9 * last_step + 8.0 * DBL_EPSILON * fabs(v->time))) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "DoStep: currentCommunicationPoint = %.17g is before the unit's time %.17g (the "
                "end of the last step); to go back, restore an FMU state", t, v->time);
        return FMU_ERROR;
    }
    if (t != v->time) { /* a rounding off the unit's time, or later (after a Discard) */
        v->time = t;
        v->real[VR_time] = t;
        v->solved = 0;
    }
    /* With a Taylor advance the solution at t itself is needed only if the master asked for it,
     * if an input is not finite (that is reported against t), or if t + h fails below. */
    const int advance = taylor_mode(v);
    fmu_status s = FMU_OK;
    if (!advance || v->solved || first_nonfinite_input(v) >= 0) {
        s = solve_current(inst);
        if (s == FMU_DISCARD || s == FMU_ERROR) {
            v->last_successful_time = t;
            return s;
        }
    }
    if (advance) {
        /* Advance the pose to t + h along its Taylor expansion; undo it on failure (a failed
         * solve leaves the outputs untouched and only sets status = 3). */
        double saved_in[12];
        const int32_t saved_status = v->integer[VR_status];
        memcpy(saved_in, &v->real[VR_x], sizeof saved_in);
        for (int i = 0; i < 6; ++i) {
            const double q = v->real[VR_x + i], qd = v->real[VR_x_dot + i],
                         qdd = v->real[VR_x_ddot + i];
            v->real[VR_x + i] = q + h * (qd + 0.5 * h * qdd);
            v->real[VR_x_dot + i] = qd + h * qdd;
        }
        v->time = t + h;
        const int solved_at_t = v->solved; /* the outputs at t were computed above or before */
        v->solved = 0;
        const fmu_status s2 = solve_current(inst);
        if (s2 == FMU_DISCARD || s2 == FMU_ERROR) {
            memcpy(&v->real[VR_x], saved_in, sizeof saved_in);
            v->time = t;
            v->last_successful_time = t;
            if (solved_at_t) {
                v->integer[VR_status] = saved_status;
                v->solve_status = s; /* the outputs are still those of the inputs at t */
                v->solved = 1;
                return s2;
            }
            /* Not solved at t yet: do it now, so the outputs are those of the inputs at t and
             * a bad pose at t is reported as such. */
            v->solved = 0;
            s = solve_current(inst);
            return (s == FMU_DISCARD || s == FMU_ERROR) ? s : s2;
        }
        s = s2;
        /* the derivatives given through fmi2SetRealInputDerivatives served this step only;
         * the outputs just computed used them, so they stay valid */
        v->input_derivatives = 0;
        commit_pose(v, t, saved_in);
    } else {
        /* Hold: the outputs stay those of the inputs at t until the master sets new inputs. */
        commit_pose(v, t, &v->real[VR_x]);
        v->time = t + h;
    }
    v->real[VR_time] = v->time;
    v->last_successful_time = v->time;
    return s;
}

/* ---------------------------------------------------------------- get and set */

static fmu_status bad_vr(fmu_instance *inst, const char *what, unsigned vr) {
    fmu_log(inst, FMU_ERROR, LOG_ERROR, "%s: value reference %u is not a variable of that type",
            what, vr);
    return FMU_ERROR;
}

/* Outputs asked for: solve for the current inputs first (they are a direct function of them). */
static fmu_status refresh_outputs(fmu_instance *inst) {
    fmu_values *v = &inst->v;
    if (v->solved || !(v->mode & (MODE_INITIALIZATION | MODE_STEP))) return FMU_OK;
    if (v->mode == MODE_INITIALIZATION && apply_parameters(inst) != FMU_OK) return fail(inst);
    const fmu_status s = solve_current(inst);
    if (s == FMU_ERROR) return fail(inst);
    /* Discard and Warning are reported by status; the values returned are well defined. */
    return FMU_OK;
}

fmu_status fmu_get_real(fmu_instance *inst, const unsigned vr[], size_t n, double value[]) {
    if (fmu_check_call(inst, CALL_GET, "GetReal") != FMU_OK) return FMU_ERROR;
    if (n > 0 && (!vr || !value)) return bad_vr(inst, "GetReal (NULL array)", 0);
    for (size_t i = 0; i < n; ++i) {
        const fmu_variable *var = fmu_variable_by_vr(vr[i]);
        if (!var || var->type != FMU_REAL) return bad_vr(inst, "GetReal", vr[i]);
        if (var->causality == FMU_OUTPUT_VAR && refresh_outputs(inst) != FMU_OK) return FMU_ERROR;
        value[i] = inst->v.real[vr[i]];
    }
    return FMU_OK;
}

fmu_status fmu_get_integer(fmu_instance *inst, const unsigned vr[], size_t n, int32_t value[]) {
    if (fmu_check_call(inst, CALL_GET, "GetInteger") != FMU_OK) return FMU_ERROR;
    if (n > 0 && (!vr || !value)) return bad_vr(inst, "GetInteger (NULL array)", 0);
    for (size_t i = 0; i < n; ++i) {
        const fmu_variable *var = fmu_variable_by_vr(vr[i]);
        if (!var || var->type != FMU_INTEGER) return bad_vr(inst, "GetInteger", vr[i]);
        if (var->causality == FMU_OUTPUT_VAR && refresh_outputs(inst) != FMU_OK) return FMU_ERROR;
        value[i] = inst->v.integer[vr[i]];
    }
    return FMU_OK;
}

/* Inputs may be set in any mode before Terminate; parameters (fixed) only before the end of
 * initialisation; outputs and time never. */
static fmu_status check_settable(fmu_instance *inst, const fmu_variable *var, const char *what,
                                 unsigned vr, fmu_type type) {
    if (!var || var->type != type) return bad_vr(inst, what, vr);
    if (var->causality == FMU_INPUT_VAR) return FMU_OK;
    if (var->causality == FMU_PARAMETER_VAR &&
        (inst->v.mode & (MODE_INSTANTIATED | MODE_INITIALIZATION)))
        return FMU_OK;
    fmu_log(inst, FMU_ERROR, LOG_ERROR, "%s: variable %s cannot be set in %s", what, var->name,
            mode_name(inst->v.mode));
    return FMU_ERROR;
}

fmu_status fmu_set_real(fmu_instance *inst, const unsigned vr[], size_t n, const double value[]) {
    if (fmu_check_call(inst, CALL_SET, "SetReal") != FMU_OK) return FMU_ERROR;
    if (n > 0 && (!vr || !value)) return bad_vr(inst, "SetReal (NULL array)", 0);
    for (size_t i = 0; i < n; ++i)
        if (check_settable(inst, fmu_variable_by_vr(vr[i]), "SetReal", vr[i], FMU_REAL) != FMU_OK)
            return FMU_ERROR;
    for (size_t i = 0; i < n; ++i) inst->v.real[vr[i]] = value[i];
    if (n > 0) inst->v.solved = 0;
    return FMU_OK;
}

fmu_status fmu_set_integer(fmu_instance *inst, const unsigned vr[], size_t n,
                           const int32_t value[]) {
    if (fmu_check_call(inst, CALL_SET, "SetInteger") != FMU_OK) return FMU_ERROR;
    if (n > 0 && (!vr || !value)) return bad_vr(inst, "SetInteger (NULL array)", 0);
    for (size_t i = 0; i < n; ++i)
        if (check_settable(inst, fmu_variable_by_vr(vr[i]), "SetInteger", vr[i], FMU_INTEGER) !=
            FMU_OK)
            return FMU_ERROR;
    for (size_t i = 0; i < n; ++i) inst->v.integer[vr[i]] = value[i];
    if (n > 0) inst->v.solved = 0;
    return FMU_OK;
}

fmu_status fmu_set_input_derivatives(fmu_instance *inst, const unsigned vr[], size_t n,
                                     const int order[], const double value[]) {
    if (fmu_check_call(inst, CALL_SET_INPUT_DERIVATIVES, "SetRealInputDerivatives") != FMU_OK)
        return FMU_ERROR;
    if (n > 0 && (!vr || !order || !value)) return bad_vr(inst, "SetRealInputDerivatives", 0);
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
    if (n > 0 && !inst->v.input_derivatives && inst->v.integer[VR_derivatives] == 0)
        for (unsigned vr_slot = VR_x_dot; vr_slot <= VR_yaw_ddot; ++vr_slot)
            inst->v.real[vr_slot] = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const unsigned base = vr[i] <= VR_yaw ? vr[i] : vr[i] - VR_x_dot;
        inst->v.real[(order[i] == 1 && vr[i] <= VR_yaw ? VR_x_dot : VR_x_ddot) + base] = value[i];
    }
    if (n > 0) {
        inst->v.input_derivatives = 1;
        inst->v.solved = 0;
    }
    return FMU_OK;
}

/* ---------------------------------------------------------------- FMU state */

struct fmu_snapshot {
    fmu_values v;
    stewart_data *data;         /* NULL if the instance had no model yet, or deserialised */
    /* The model data belongs to: the instance's model of that generation. A pointer to the
     * model would not do: a freed model's address can come back for another one. */
    const fmu_instance *owner;
    unsigned long model_generation;
    unsigned char *data_bytes;  /* deserialised: the saved data block (stewart_data_save) */
    size_t data_size;
};

static int data_fits(const fmu_instance *inst, const fmu_snapshot *s) {
    return s->data && s->owner == inst && s->model_generation == inst->model_generation;
}

static void drop_data_bytes(fmu_snapshot *s) {
    free(s->data_bytes);
    s->data_bytes = NULL;
    s->data_size = 0;
}

fmu_status fmu_get_state(fmu_instance *inst, fmu_snapshot **state) {
    if (fmu_check_call(inst, CALL_GET_FMU_STATE, "GetFMUState") != FMU_OK) return FMU_ERROR;
    if (!state) return bad_vr(inst, "GetFMUState (NULL state pointer)", 0);
    fmu_snapshot *s = *state;
    if (s && s->data && !data_fits(inst, s)) { /* reused snapshot of another model */
        stewart_data_free(s->data);
        s->data = NULL;
    }
    if (!s) {
        s = (fmu_snapshot *)calloc(1, sizeof *s);
        if (!s) {
            fmu_log(inst, FMU_ERROR, LOG_ERROR, "GetFMUState: out of memory");
            return FMU_ERROR;
        }
    }
    if (inst->data && !s->data) s->data = stewart_data_create(inst->model);
    if (inst->data && (!s->data || stewart_data_copy(s->data, inst->data) != STEWART_OK)) {
        fmu_free_state(inst, &s);
        *state = NULL;
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "GetFMUState: cannot copy the solver data");
        return FMU_ERROR;
    }
    drop_data_bytes(s);
    s->owner = inst;
    s->model_generation = inst->model_generation;
    s->v = inst->v;
    *state = s;
    return FMU_OK;
}

fmu_status fmu_set_state(fmu_instance *inst, const fmu_snapshot *s) {
    if (fmu_check_call(inst, CALL_SET_FMU_STATE, "SetFMUState") != FMU_OK) return FMU_ERROR;
    if (!s) return bad_vr(inst, "SetFMUState (NULL state)", 0);
    inst->v = s->v;
    if (inst->v.mode & (MODE_STEP | MODE_TERMINATED)) {
        /* the snapshot was taken after initialisation: make sure a model for its parameters
         * exists (allocation here is fine: this is not a step) */
        if (apply_parameters(inst) != FMU_OK) return fail(inst);
    }
    if (inst->data) {
        if (data_fits(inst, s))
            stewart_data_copy(inst->data, s->data);
        else if (!s->data_bytes ||
                 stewart_data_load(inst->data, s->data_bytes, s->data_size) != STEWART_OK)
            stewart_data_reset(inst->data); /* nothing that fits this model: start afresh */
    }
    return FMU_OK;
}

fmu_status fmu_free_state(fmu_instance *inst, fmu_snapshot **state) {
    (void)inst;
    if (!state || !*state) return FMU_OK;
    stewart_data_free((*state)->data);
    drop_data_bytes(*state);
    free(*state);
    *state = NULL;
    return FMU_OK;
}

/* Serialised form: magic, sizeof(fmu_values), the values, then the size of the solver data
 * block's saved state and its bytes (stewart_data_save; 0 bytes before a model exists). */
static const unsigned char kMagic[8] = {'S', 'T', 'W', 'F', 'M', 'U', '0', '2'};
enum { HEADER = sizeof kMagic + sizeof(uint64_t) + sizeof(fmu_values) + sizeof(uint64_t) };

static size_t data_bytes_of(const fmu_snapshot *s) {
    return s->data ? stewart_data_state_size(s->data) : s->data_size;
}

size_t fmu_serialized_size(const fmu_snapshot *s) { return HEADER + (s ? data_bytes_of(s) : 0); }

fmu_status fmu_serialize_state(fmu_instance *inst, const fmu_snapshot *s, unsigned char *out,
                               size_t size) {
    if (fmu_check_call(inst, CALL_SERIALIZE, "SerializeFMUState") != FMU_OK) return FMU_ERROR;
    if (!s || !out || size < fmu_serialized_size(s)) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "SerializeFMUState: buffer of %zu bytes, need %zu",
                size, fmu_serialized_size(s));
        return FMU_ERROR;
    }
    const uint64_t n = sizeof(fmu_values), data_size = data_bytes_of(s);
    memcpy(out, kMagic, sizeof kMagic);
    memcpy(out + sizeof kMagic, &n, sizeof n);
    memcpy(out + sizeof kMagic + sizeof n, &s->v, sizeof s->v);
    memcpy(out + HEADER - sizeof data_size, &data_size, sizeof data_size);
    if (s->data) {
        if (stewart_data_save(s->data, out + HEADER, data_size) != STEWART_OK) {
            fmu_log(inst, FMU_ERROR, LOG_ERROR, "SerializeFMUState: cannot save the solver data");
            return FMU_ERROR;
        }
    } else if (data_size) {
        memcpy(out + HEADER, s->data_bytes, data_size);
    }
    return FMU_OK;
}

/* Why deserialised values cannot be a state of this FMU, or NULL if they can: bytes that pass
 * here never give a NaN output, a status outside 0..3 or an impossible mode. */
static const char *corrupt_values(const fmu_values *v) {
    const int modes = MODE_INSTANTIATED | MODE_INITIALIZATION | MODE_STEP | MODE_TERMINATED;
    if (!(v->mode & modes) || (v->mode & ~modes) || (v->mode & (v->mode - 1)))
        return "mode is not one of instantiated, initialization, step, terminated";
    if (v->n_history < 0 || v->n_history > 2) return "finite-difference history is not 0..2 poses";
    if ((v->input_derivatives & ~1) || (v->solved & ~1) || v->solve_status < FMU_OK ||
        v->solve_status > FMU_ERROR)
        return "a flag is out of range";
    if (!isfinite(v->time) || !isfinite(v->last_successful_time)) return "time is not finite";
    for (int j = 2 - v->n_history; j < 2; ++j) {
        if (!(v->history_t[j] < v->time) || (j == 0 && !(v->history_t[0] < v->history_t[1])))
            return "finite-difference history is not before the current time and ordered";
        for (int i = 0; i < 6; ++i)
            if (!isfinite(v->history_q[j][i])) return "finite-difference history is not finite";
    }
#define FMU_OUTPUT(vr, id, name, unit, field, desc) \
    if (!isfinite(v->real[vr])) return "output " name " is not finite";
#include "variables.def"
    if (v->integer[VR_status] < 0 || v->integer[VR_status] > 3) return "status is not 0..3";
    if (v->integer[VR_newton_iterations] < 0) return "newton_iterations is negative";
    if (v->mode & (MODE_STEP | MODE_TERMINATED)) {
        /* parameters and options: exactly what initialisation accepted (apply_parameters) */
        if (v->integer[VR_derivatives] != 0 && v->integer[VR_derivatives] != 1)
            return "option derivatives is out of range";
        stewart_options o;
        options_from_values(v, &o);
        if (stewart_options_check(&o, NULL, 0) != STEWART_OK) return "an option is out of range";
        stewart_params p;
        params_from_values(v, &p);
        if (stewart_params_check(&p, NULL, 0) != STEWART_OK) return "a parameter is invalid";
    }
    return NULL;
}

fmu_status fmu_deserialize_state(fmu_instance *inst, const unsigned char *in, size_t size,
                                 fmu_snapshot **state) {
    if (fmu_check_call(inst, CALL_SERIALIZE, "DeserializeFMUState") != FMU_OK) return FMU_ERROR;
    uint64_t n = 0, data_size = 0;
    if (in && size >= HEADER) {
        memcpy(&n, in + sizeof kMagic, sizeof n);
        memcpy(&data_size, in + HEADER - sizeof data_size, sizeof data_size);
    }
    if (!in || !state || size < HEADER || memcmp(in, kMagic, sizeof kMagic) ||
        n != sizeof(fmu_values) || data_size != size - HEADER) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "DeserializeFMUState: %zu bytes are not a state of this FMU", size);
        return FMU_ERROR;
    }
    fmu_snapshot *s = *state;
    if (!s) s = (fmu_snapshot *)calloc(1, sizeof *s);
    if (!s) return FMU_ERROR;
    stewart_data_free(s->data);
    s->data = NULL;
    s->owner = NULL;
    drop_data_bytes(s);
    memcpy(&s->v, in + sizeof kMagic + sizeof n, sizeof s->v);
    if (data_size) {
        s->data_bytes = (unsigned char *)malloc(data_size);
        if (!s->data_bytes) {
            fmu_free_state(inst, &s);
            *state = NULL;
            fmu_log(inst, FMU_ERROR, LOG_ERROR, "DeserializeFMUState: out of memory");
            return FMU_ERROR;
        }
        memcpy(s->data_bytes, in + HEADER, data_size);
        s->data_size = data_size;
    }
    const char *corrupt = corrupt_values(&s->v);
    if (corrupt) {
        fmu_free_state(inst, &s);
        *state = NULL;
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "DeserializeFMUState: corrupt state: %s", corrupt);
        return FMU_ERROR;
    }
    *state = s;
    return FMU_OK;
}
