/*
 * doStep's entry, inline in each FMI layer (fmi2DoStep, fmi3DoStep), so that the usual call goes
 * from the FMI function straight to the model's usual step (so that doStep costs within 5 % of
 * the library call): a few comparisons tell it, and anything else is instance.c's
 * fmu_do_step_otherwise with its checks and messages.
 */
#ifndef STEWART_FMU_DO_STEP_H
#define STEWART_FMU_DO_STEP_H

#include <math.h>

#include "instance.h"
#include "model_interface.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The models that take the usual step themselves (model_usual_steps, with fmu_step_accepted and
 * fmu_step_not_taken) save the runtime's frame around it; the others run it in fmu_run_step. */
#if FMU_MODEL_USUAL_STEP
/* The usual step: inputs set since the last step, all finite (else the step rules in full), and
 * the model's step for its route, told by one indexed jump from the FMI call itself. */
static inline fmu_status fmu_usual_step(fmu_instance *inst, double t, double h, double end) {
    if (fmu_outputs_current_or_inputs_unchecked(&inst->v))
        return fmu_run_step_in_step_mode(inst, t, h);
    return model_usual_steps[FMU_USUAL_ROUTE(&inst->v)](inst, t, h, end);
}
#define FMU_USUAL_STEP(inst, t, h, end) fmu_usual_step(inst, t, h, end)
#else
#define FMU_USUAL_STEP(inst, t, h, end) fmu_run_step(inst, t, h)
#endif

/* The usual call, told in a few comparisons: step mode, a step that advances t to a finite time
 * (t + h > t: h > 0 and t, h not NaN; below infinity: finite). fmu_check_call and check_step
 * (instance.c) accept it too. From the unit's time or later (a master's clock a rounding ahead,
 * or after a Discard) it is after the last step: every step ends after its communication point,
 * and a restored state is checked for that (state.c). */
static inline int fmu_usual_step_shape(const fmu_values *v, double t, double h) {
    const double end = t + h;
    /* (end is not NaN once end > t: !(end >= HUGE_VAL) is end < HUGE_VAL, one comparison less) */
    return v->mode == MODE_STEP && end > t && !(end >= HUGE_VAL);
}

/* Any call but the usual one from the unit's time or later (instance.c): a t within the slack
 * before the unit's time takes the usual step, anything else the checks with their messages. */
fmu_status fmu_do_step_otherwise(fmu_instance *inst, double t, double h);
/* The same for fmu_do_step_reporting (last_successful_time may be NULL). */
fmu_status fmu_do_step_reporting_otherwise(fmu_instance *inst, double t, double h,
                                           double *last_successful_time);

/* The usual call of fmu_do_step, told by its checks: an instance in step mode, a step that
 * advances t to a finite time, t from the unit's time or later. Where the model takes the usual
 * step itself the mode is left to its route, which is 0 (the step rules in full, which check it:
 * fmu_run_step_in_step_mode) outside step mode (FMU_USUAL_ROUTE: the model settles it so, and
 * the runtime sets it to 0 when the mode leaves step mode): one comparison less. */
static inline int fmu_usual_call(const fmu_instance *inst, double t, double h) {
    if (!inst) return 0;
    const double end = t + h;
    return (FMU_MODEL_USUAL_STEP || inst->v.mode == MODE_STEP) && end > t && !(end >= HUGE_VAL) &&
           t >= inst->v.time;
}

/* Checks the step (t, h) against the unit's time, then runs the model's step rules: the usual
 * step (step mode, from the unit's time or after it, or within its slack before it, advancing to
 * a finite time) goes straight to the route's step (fmu_usual_step) if the model's config.h
 * defines FMU_MODEL_USUAL_STEP 1, else to fmu_run_step. The unit's last successful time is in
 * inst->v.last_successful_time after any call with an instance. (FMI 2: no pointer to report
 * it through; fmi2 instances never set last_successful_time_out.) */
static inline fmu_status fmu_do_step(fmu_instance *inst, double t, double h) {
    if (fmu_usual_call(inst, t, h))
        return FMU_USUAL_STEP(inst, t, h, t + h); /* (t + h: the shape's, in a register) */
    return fmu_do_step_otherwise(inst, t, h);
}

/* FMI 3's usual step, on a usual call (fmu_usual_call) with last_successful_time not NULL: the
 * step's end written there first (what it is if the step is accepted) and the instance pointed
 * at it, so that a step not taken writes its own (fmu_step_not_taken): FMI 3's usual step is
 * FMI 2's, with no pointer to keep across the library call. */
static inline fmu_status fmu_usual_step_reporting(fmu_instance *inst, double t, double h,
                                                  double *last_successful_time) {
    *last_successful_time = t + h;
    inst->last_successful_time_out = last_successful_time;
    return FMU_USUAL_STEP(inst, t, h, t + h);
}

/* fmu_do_step that also writes the unit's last successful time to *last_successful_time (if not
 * NULL; FMI 3). */
static inline fmu_status fmu_do_step_reporting(fmu_instance *inst, double t, double h,
                                               double *last_successful_time) {
    if (last_successful_time && fmu_usual_call(inst, t, h))
        return fmu_usual_step_reporting(inst, t, h, last_successful_time);
    return fmu_do_step_reporting_otherwise(inst, t, h, last_successful_time);
}

#ifdef __cplusplus
}
#endif

#endif
