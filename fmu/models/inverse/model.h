/*
 * What the inverse-dynamics model's files share:
 *   model.c        values <-> library (parameters, options), the resources, input derivatives
 *   solve.c        the solve at a time: the pose and its rates, the library call, outputs, status
 *                  and warnings
 *   step_rules.c   the step rules in full (hold, Taylor advance, finite-difference history) and
 *                  the usual step's route
 *   usual_step.c   the usual step: the same rules for the common case, shortened
 *   model_state.c  its part of an FMU state; derivatives.c  directional derivatives
 */
#ifndef STEWART_FMU_INVERSE_MODEL_H
#define STEWART_FMU_INVERSE_MODEL_H

#include "model_interface.h"
#include "outputs.h"

/* ---- model.c */

/* The library's parameters and options as the instance's values hold them. */
void inverse_params_from_values(const fmu_values *v, stewart_params *p);
void inverse_options_from_values(const fmu_values *v, stewart_inverse_options *o);

/* ---- solve.c */

/* The pose (and its rates and accelerations) the outputs are solved at for the inputs at time:
 * the rate inputs, or finite differences of the pose over the last communication points. */
void inverse_current_pose(const fmu_values *v, double time, stewart_pose *pose);
/* 1 if the rates come from the *_dot and *_ddot inputs (derivatives = 1 or FMI 2 input
 * derivatives), 0 if from finite differences of the pose. */
int inverse_uses_rate_inputs(const fmu_values *v);
/* The rates and accelerations of pose->q at `time` from the quadratic through it and the last
 * two poses (two in the history). */
void inverse_quadratic_rates(const model_values *m, double time, stewart_pose *pose);
/* Solves for the current inputs at `time` unless the outputs already belong to them. OK /
 * Warning (status 1 or 2) / Discard (status 3, outputs keep their last valid values) / Error. */
fmu_status inverse_solve_at(fmu_instance *inst, double time);
/* The outputs, status output and warnings of pose q solved at `time` (the library's output
 * `out`), with the limit outputs as the parameter says. */
fmu_status inverse_solved(fmu_instance *inst, double time, const double q[6],
                          const stewart_inverse_output *out);
/* The same, with the limit outputs or without (the usual step has none). */
fmu_status inverse_solved_checking(fmu_instance *inst, double time, const double q[6],
                                   const stewart_inverse_output *out, int limit_outputs);
/* The library refused `pose` (the current inputs' at `time`): Discard or Error, logged, status 3,
 * naming a finite difference that is not finite, else the library's reason. */
fmu_status inverse_refused(fmu_instance *inst, double time, const stewart_pose *pose,
                           stewart_status s);
/* The same for a pose whose rates are not finite differences (a Taylor advance). */
fmu_status inverse_not_solved_by_library(fmu_instance *inst, double time, const stewart_pose *pose,
                                         stewart_status s);
/* The value reference of the first input that is not finite, or -1. */
int inverse_first_nonfinite_input(const fmu_values *v);
/* Discard naming the first input that is not finite, if there is one (FMU_OK if none). */
fmu_status inverse_check_inputs(fmu_instance *inst, double time);

/* The outputs of a solve that had nothing to warn of (no limit outputs): copied, status 0. */
static inline fmu_status inverse_solved_plain(fmu_instance *inst,
                                              const stewart_inverse_output *out) {
    fmu_values *v = &inst->v;
    inverse_outputs_from(v, out);
    v->outputs_current = 1;
    v->integer[VR_status] = 0;
    v->model.solve_status = FMU_OK;
    return FMU_OK;
}

/* ---- step_rules.c */

/* The usual step's routes (model_values.usual_route; model_usual_steps, usual_step.c): the step
 * rules in full, or one of the two usual steps. 0 (a state's start) is the full rules. */
enum { ROUTE_CHECKED = 0, ROUTE_ADVANCE = 1, ROUTE_HOLD = 2 };
/* Settles the route after anything it depends on changed (every change that rules a usual step
 * out is followed by this). */
void inverse_settle_usual_route(fmu_values *v);
/* 1 if the usual step's route is the full rules or what the values give (a restored state is
 * checked for it). */
int inverse_usual_route_valid(const fmu_values *v);

#endif
