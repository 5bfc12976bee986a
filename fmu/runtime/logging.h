/* Logging: messages reach the master's logger only for enabled categories. A leaf of the runtime:
 * it knows the instance's fields and nothing of the call order or the life cycle. */
#ifndef STEWART_FMU_LOGGING_H
#define STEWART_FMU_LOGGING_H

#include <stddef.h>

#include "instance.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Logs under `category` if logging is on and that category is enabled. printf-style. */
void fmu_log(const fmu_instance *inst, fmu_status status, int category, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
/* Enables (on) or disables the n named categories, or all of them if n is 0 (the caller has
 * checked that the instance may take the call: fmu_set_debug_logging). */
fmu_status fmu_logging_set(fmu_instance *inst, int on, size_t n, const char *const cats[]);
/* Every category on or off (at instantiation). */
void fmu_logging_init(fmu_instance *inst, int on);

#ifdef __cplusplus
}
#endif

#endif
