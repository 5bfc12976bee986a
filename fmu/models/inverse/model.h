/* The inverse-dynamics model's own helpers shared between its files (model.c, model_state.c). */
#ifndef STEWART_FMU_INVERSE_MODEL_H
#define STEWART_FMU_INVERSE_MODEL_H

#include "model_interface.h"

/* The library's parameters and options as the instance's values hold them. */
void inverse_params_from_values(const fmu_values *v, stewart_params *p);
void inverse_options_from_values(const fmu_values *v, stewart_inverse_options *o);

#endif
