/* A Unity fixture for tests of one platform: setUp builds the thesis platform into `params`,
 * `model` and `data`; a test may edit `params` and call rebuild_platform(). */
#ifndef STEWART_PLATFORM_FIXTURE_H
#define STEWART_PLATFORM_FIXTURE_H

#include "stewart/stewart.h"

extern stewart_params params;
extern stewart_model *model;
extern stewart_data *data;

void rebuild_platform(void);

#endif
