/* The inverse-dynamics model's own helpers shared between its files (model.c, model_state.c). */
#ifndef STEWART_FMU_INVERSE_MODEL_H
#define STEWART_FMU_INVERSE_MODEL_H

#include "model_interface.h"

/* The library's parameters and options as the instance's values hold them. */
void inverse_params_from_values(const fmu_values *v, stewart_params *p);
void inverse_options_from_values(const fmu_values *v, stewart_inverse_options *o);

/* The pose (and its rates and accelerations) the outputs are solved at for the inputs at time:
 * the rate inputs, or finite differences of the pose over the last communication points. */
void inverse_current_pose(const fmu_values *v, double time, stewart_pose *pose);
/* 1 if the rates come from the *_dot and *_ddot inputs (derivatives = 1 or FMI 2 input
 * derivatives), 0 if from finite differences of the pose. */
int inverse_uses_rate_inputs(const fmu_values *v);

/* 1 if the usual step's route (model_values.usual_route) is the full rules or what the values
 * give (a restored state is checked for it). */
int inverse_usual_route_valid(const fmu_values *v);

#endif
