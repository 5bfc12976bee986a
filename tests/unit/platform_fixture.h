/* A Unity fixture for tests of one platform: setUp builds the thesis platform into `params`,
 * `model`, `data` (an inverse solver) and `forward_solver`; a test may edit `params` and call rebuild_platform(). */
#ifndef STEWART_PLATFORM_FIXTURE_H
#define STEWART_PLATFORM_FIXTURE_H

#include "stewart/stewart.h"
#include "stewart/stewart_forward.h"

extern stewart_params params;
extern stewart_model *model;
extern stewart_inverse *data;
extern stewart_forward *forward_solver; /* default forward options; after rebuild_platform NULL
                                        * if the platform is singular at home */

void rebuild_platform(void);

#endif
