/* Logging and its categories (the model's FMU_LOG_CATEGORY list). */
#include "logging.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

void fmu_log(const fmu_instance *inst, fmu_status status, int category, const char *fmt, ...) {
    if (!inst || !inst->log_fn || !inst->logging_on || category < 0 ||
        category >= FMU_N_LOG_CATEGORIES || !inst->category_on[category])
        return;
    char buffer[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buffer, sizeof buffer, fmt, ap);
    va_end(ap);
    /* FMI 2 loggers treat the message as a format string and '#' as a variable escape. */
    for (char *c = buffer; *c; ++c)
        if (*c == '%' || *c == '#') *c = ' ';
    inst->log_fn(inst->callbacks, inst->environment, inst->name, status,
                 fmu_log_category_names[category], buffer);
}

void fmu_logging_init(fmu_instance *inst, int on) {
    inst->logging_on = on ? 1 : 0;
    for (int c = 0; c < FMU_N_LOG_CATEGORIES; ++c) inst->category_on[c] = inst->logging_on;
}

fmu_status fmu_logging_set(fmu_instance *inst, int on, size_t n, const char *const cats[]) {
    inst->logging_on = 1; /* so the error below can be reported if categories are on */
    if (n == 0) {
        for (int c = 0; c < FMU_N_LOG_CATEGORIES; ++c) inst->category_on[c] = on;
    } else {
        for (size_t i = 0; i < n; ++i) {
            int found = -1;
            for (int c = 0; c < FMU_N_LOG_CATEGORIES; ++c)
                if (cats && cats[i] && !strcmp(cats[i], fmu_log_category_names[c])) found = c;
            if (found < 0) {
                fmu_log(inst, FMU_ERROR, LOG_ERROR, "SetDebugLogging: unknown log category '%s'",
                        cats && cats[i] ? cats[i] : "(null)");
                return FMU_ERROR;
            }
            inst->category_on[found] = on;
        }
    }
    inst->logging_on = 0;
    for (int c = 0; c < FMU_N_LOG_CATEGORIES; ++c)
        if (inst->category_on[c]) inst->logging_on = 1;
    return FMU_OK;
}
