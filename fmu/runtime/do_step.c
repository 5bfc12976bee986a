/* doStep's checks and the step's time bookkeeping around the model's step rules: what do_step.h's
 * inline usual call leaves to a call, shared by every model. */
#include "do_step.h"

#include <float.h>
#include <math.h>

#include "call_table.h"
#include "instance.h"
#include "logging.h"
#include "model_interface.h"

/* How much earlier than the unit's time a communication point may be: a few roundings of the
 * master's clock (start + n h against the sum of its steps). */
static double time_slack(const fmu_values *v) {
    const double last_step = v->has_stepped ? v->time - v->last_step_point : 0.0;
    return 1e-9 * last_step + 8.0 * DBL_EPSILON * fabs(v->time);
}

/* Why (t, h) is not a step from the unit's time, or NULL. Error rather than Discard: Discard asks
 * the master to retry with a smaller step, which cannot help. */
static fmu_status check_step(fmu_instance *inst, double t, double h) {
    const fmu_values *v = &inst->v;
    if (!(isfinite(t) && isfinite(h) && h > 0)) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "DoStep: currentCommunicationPoint = %g and communicationStepSize = %g must be "
                "finite and the step > 0",
                t, h);
        return FMU_ERROR;
    }
    if (!(t + h > t && isfinite(t + h))) {
        /* h below the resolution of t (t + h == t) would not advance time; t + h overflowing
         * would make it infinite. Neither is a step. */
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "DoStep: communicationStepSize = %g does not advance currentCommunicationPoint = "
                "%.17g (t + h = %.17g): the step is below the resolution of t or overflows",
                h, t, t + h);
        return FMU_ERROR;
    }
    if (v->has_stepped && !(t > v->last_step_point)) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "DoStep: currentCommunicationPoint = %.17g is not after the last accepted "
                "communication point %.17g",
                t, v->last_step_point);
        return FMU_ERROR;
    }
    /* A master may pass t a few roundings off the unit's own time (start + n h against the sum
     * of its steps), never earlier by more: that would take the inputs of time v->time for an
     * earlier one. */
    if (t < v->time - time_slack(v)) {
        fmu_log(inst, FMU_ERROR, LOG_ERROR,
                "DoStep: currentCommunicationPoint = %.17g is before the unit's time %.17g (the "
                "end of the last step); to go back, restore an FMU state",
                t, v->time);
        return FMU_ERROR;
    }
    return FMU_OK;
}

fmu_status fmu_step_not_taken(fmu_instance *inst, double t, fmu_status s, double time_before,
                              int outputs_current_before) {
    fmu_values *v = &inst->v;
    v->last_step_status = s;
    if (s == FMU_DISCARD) {
        fmu_values_set_time(v, t);
        v->last_successful_time = t;
    } else {
        /* Error (or Fatal): the model did nothing; time stays where the model is, and the
         * instance enters the Error mode (out of it: Reset or SetFMUState). */
        fmu_values_set_time(v, time_before);
        v->outputs_current = outputs_current_before;
        fmu_fail(inst);
    }
    if (inst->last_successful_time_out) *inst->last_successful_time_out = v->last_successful_time;
    return s;
}

fmu_status fmu_run_step(fmu_instance *inst, double t, double h) {
    fmu_values *v = &inst->v;
    const double time_before = v->time;
    const int outputs_current_before = v->outputs_current;
    if (t != v->time) { /* a rounding off the unit's time, or later (after a Discard) */
        fmu_values_set_time(v, t);
        v->outputs_current = 0;
    }
    const fmu_status s = model_do_step(inst, t, h);
    if (s == FMU_OK || s == FMU_WARNING) return fmu_step_accepted(v, t, h, s);
    return fmu_step_not_taken(inst, t, s, time_before, outputs_current_before);
}

/* t before the unit's time but within its slack, and after the last step. */
static int within_slack(const fmu_values *v, double t) {
    return t >= v->time - time_slack(v) && (!v->has_stepped || t > v->last_step_point);
}

/* The call order and the step (t, h) checked, with their messages: OK or Error. */
FMU_RARE_PATH static fmu_status check_do_step(fmu_instance *inst, double t, double h) {
    if (fmu_check_call(inst, CALL_DO_STEP, "DoStep") != FMU_OK) return FMU_ERROR;
    return check_step(inst, t, h);
}

/* Any other call: the call order and the step checked with their messages, then the step. */
FMU_RARE_PATH static fmu_status checked_step(fmu_instance *inst, double t, double h) {
    if (!inst) return FMU_ERROR;
    /* a refused call, not a failed step: the mode stays as it was */
    if (check_do_step(inst, t, h) != FMU_OK) return FMU_ERROR;
    return fmu_run_step(inst, t, h);
}

FMU_RARE_PATH fmu_status fmu_run_step_in_step_mode(fmu_instance *inst, double t, double h) {
    if (inst->v.mode == MODE_STEP) return fmu_run_step(inst, t, h);
    const fmu_status s = checked_step(inst, t, h); /* refused: the call order, with its message */
    /* (FMI 3's usual call pointed the instance at its last successful time) */
    if (inst->last_successful_time_out)
        *inst->last_successful_time_out = inst->v.last_successful_time;
    return s;
}

FMU_RARE_PATH fmu_status fmu_do_step_otherwise(fmu_instance *inst, double t, double h) {
    if (inst && fmu_usual_step_shape(&inst->v, t, h) && within_slack(&inst->v, t))
        return FMU_USUAL_STEP(inst, t, h, t + h);
    return checked_step(inst, t, h);
}

FMU_RARE_PATH fmu_status fmu_do_step_reporting_otherwise(fmu_instance *inst, double t, double h,
                                                         double *last_successful_time) {
    if (inst) inst->last_successful_time_out = last_successful_time; /* this call's, or NULL */
    if (inst && fmu_usual_step_shape(&inst->v, t, h) && within_slack(&inst->v, t)) {
        if (last_successful_time) *last_successful_time = t + h; /* as fmu_do_step_reporting */
        return FMU_USUAL_STEP(inst, t, h, t + h);
    }
    const fmu_status s = checked_step(inst, t, h);
    if (inst && last_successful_time) *last_successful_time = inst->v.last_successful_time;
    return s;
}
