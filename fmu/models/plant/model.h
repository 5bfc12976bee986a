/* The plant model's helpers shared between its files (model.c, model_state.c). */
#ifndef STEWART_FMU_PLANT_MODEL_H
#define STEWART_FMU_PLANT_MODEL_H

#include "model_interface.h"

/* The platform's parameters and the plant settings as the instance's values hold them. */
void plant_params_from_values(const fmu_values *v, stewart_params *p);
void plant_settings_from_values(const fmu_values *v, plant_settings *s);
/* Why the values' parameters and settings cannot build a plant (names the variable), or NULL. */
const char *plant_check_settings(const fmu_values *v, char *why, size_t size);

/* Frees the plant that checks deserialised states (model_state.c); before its model is freed. */
void plant_free_checker(model_resources *r);

/* The plant's own time: the end of its last step (or its start); NaN if it cannot be read. */
double plant_time(const stewart_plant *plant);
/* How far two clocks that should agree may differ by rounding alone at t: a master's t0 + n h
 * against t + h stepped n times differs by a few units in the last place of t. */
double clock_rounding(double t);

#endif
