/*
 * What every model defines (models/<name>/model.c and its helpers), and nothing more: the runtime
 * reaches a model only through these functions, its config.h (identity, sizes, model_values,
 * model_resources) and its variables.def (variables and log categories). The runtime has checked
 * the call order and the arguments' shape before it calls any of them; the model reads and writes
 * the instance's values (inst->v.real / .integer by value reference, inst->v.model) and its
 * resources (inst->res), and logs through fmu_log.
 */
#ifndef STEWART_FMU_MODEL_INTERFACE_H
#define STEWART_FMU_MODEL_INTERFACE_H

#include <stddef.h>

#include "instance.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The start value of every variable and the model's plain values at instantiation and reset
 * (also what the model-description generator prints as start). Writes nothing else. */
void model_start_values(fmu_values *v);
/* After a reset to the start values: forget what the resources remember of earlier solves
 * (warm starts); the resources themselves may be kept for reuse. */
void model_reset(fmu_instance *inst);
/* Initialisation mode (when the outputs are first needed and at its end) and when a state after
 * initialisation is restored (before model_load): check the parameters, build the resources for
 * them (reuse them if the parameters did not change). FMU_ERROR with a message naming the
 * parameter and its value if refused. */
fmu_status model_apply_parameters(fmu_instance *inst);
/* Initialisation mode only, right after model_apply_parameters (never when a state is
 * restored: it brings its own): set what a fresh start begins from. FMU_ERROR with a message
 * naming the parameter and its value if refused. */
fmu_status model_start(fmu_instance *inst);
/* Make the outputs those of the current inputs at inst->v.time unless they already are
 * (inst->v.outputs_current, cleared by the runtime when a variable is set). Returns what that
 * solve gave: OK, Warning, Discard (outputs keep their last valid values) or Error. Never
 * allocates. */
fmu_status model_refresh_outputs(fmu_instance *inst);
/* The step rules over [t, t + h] (the runtime has checked t and h and set inst->v.time = t).
 * OK or Warning: the step is accepted and the runtime moves time to t + h; the outputs are those
 * the master reads at t + h. Discard or Error: nothing the master sees changes except status
 * outputs; the runtime keeps time at t. Never allocates. */
fmu_status model_do_step(fmu_instance *inst, double t, double h);
#if FMU_MODEL_USUAL_STEP
/* Only in a model whose config.h defines FMU_MODEL_USUAL_STEP 1 (and FMU_USUAL_ROUTE(v), the
 * index of the model's usual step for values v, 0 .. its count - 1): its usual doSteps by route,
 * which do_step.h's fmu_usual_step jumps to from the FMI call (step mode, t the unit's time
 * within its slack, t + h = end finite and later: the runtime has checked that; inputs set since
 * the last step and all finite), each with the runtime's time bookkeeping (fmu_step_accepted or
 * fmu_step_not_taken, instance.h) at the end, or the whole of it handed to fmu_run_step (which
 * calls model_do_step) when the model's own usual path does not apply. Never allocate. */
typedef fmu_status (*model_usual_step_fn)(fmu_instance *inst, double t, double h, double end);
extern const model_usual_step_fn model_usual_steps[];
#endif
/* FMI 2 input derivatives (order[i] of variable vr[i]); FMU_ERROR with a message if the model
 * does not take that derivative. */
fmu_status model_set_input_derivatives(fmu_instance *inst, const unsigned vr[], size_t n,
                                       const int order[], const double value[]);
/* Bytes of the model's resources' state (what model_save writes), 0 if there is none yet. */
size_t model_state_size(const fmu_instance *inst);
/* Writes that state into out (size bytes, at least model_state_size). */
fmu_status model_save(const fmu_instance *inst, unsigned char *out, size_t size);
/* The instance's values have just become a state's (inst->v; after initialisation the runtime
 * has applied its parameters first); make the resources match them and load the saved bytes
 * (size 0: the state had none; start afresh). FMU_ERROR with a message if the bytes are
 * refused. */
fmu_status model_load(fmu_instance *inst, const unsigned char *in, size_t size);
/* Why deserialised values and resource bytes cannot be a state of this model, or NULL if they
 * can (then model_load accepts them). May build temporary resources, or keep some in inst->res
 * for the next check; changes nothing else of inst. */
const char *model_check_state(fmu_instance *inst, const fmu_values *v, const unsigned char *in,
                              size_t size, char *why, size_t why_size);
/* Frees the resources (at fmu_free). */
void model_free(fmu_instance *inst);
/* Only in a Model Exchange unit whose config.h defines FMU_ME_ACCEPTED_STATE 1: the master has
 * accepted the current state (CompletedIntegratorStep, or the event update NewDiscreteStates /
 * UpdateDiscreteStates: its state is accepted too); report what holds there and only there, not
 * at the trial states of the derivative calls (warnings). OK or Warning. Never allocates. */
fmu_status model_accepted_state(fmu_instance *inst);
#if FMU_STRING_PARAMETERS
/* Only in a model whose config.h defines FMU_STRING_PARAMETERS 1: where the String parameter vr
 * keeps its value in the plain values (FMU_STRING_SIZE bytes, NUL-terminated), so that a state
 * holds it. */
char *model_string(fmu_values *v, unsigned vr);
#endif
/* Only in a model whose config.h defines FMU_PROVIDES_DIRECTIONAL_DERIVATIVE 1 (the others need
 * not define it: the runtime then answers that the call is not supported). The partial
 * derivatives of the outputs at the current inputs (those the outputs are, or would be, solved
 * at) times the seed: sensitivity[i] = sum_j d unknown[i] / d known[j] * seed[j]. The runtime has
 * checked the call order, that every unknown is a Real output and every known a Real input (or,
 * in a Model Exchange unit, a state).
 * FMU_ERROR with a message naming the output if it has no derivative; FMU_DISCARD if the inputs
 * have none (the solve fails there); messages name `function`, the FMI call being answered
 * (the directional or the adjoint derivative). Never allocates once the model's resources exist. */
fmu_status model_directional_derivative(fmu_instance *inst, const unsigned unknown[],
                                        size_t n_unknown, const unsigned known[], size_t n_known,
                                        const double seed[], double sensitivity[],
                                        const char *function);

#ifdef __cplusplus
}
#endif

#endif
