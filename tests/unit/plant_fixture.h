/* A Unity fixture for tests of one plant: setUp builds the thesis platform into `params` and
 * `model`, and `plant`, a full-fidelity plant at tight tolerances; tearDown frees them. */
#ifndef STEWART_PLANT_FIXTURE_H
#define STEWART_PLANT_FIXTURE_H

#include "stewart/stewart.h"
#include "stewart/stewart_plant.h"

extern stewart_params params;
extern stewart_model *model;
extern stewart_plant *plant;
/* Six zero forces (or rates). */
extern const double kZero[6];

#endif
