/*
 * A model's variable list (its variables.def) as C: value reference constants VR_<id>, log
 * category ids, and the descriptor table that value binding and the model-description generator
 * iterate. Compiled once per model, with that model's folder on the include path.
 */
#ifndef STEWART_FMU_VARIABLES_H
#define STEWART_FMU_VARIABLES_H

#include <stddef.h>

#include "config.h"

/* A model's config.h defines FMU_STRING_PARAMETERS 1 when its variables.def has String parameters
 * (FMU_OPTION_STRING); it then defines model_string (model_interface.h) and FMU_STRING_SIZE, the
 * bytes each value may take with its terminating NUL. */
#ifndef FMU_STRING_PARAMETERS
#define FMU_STRING_PARAMETERS 0
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef enum { FMU_REAL = 1, FMU_INTEGER = 2, FMU_STRING = 3 } fmu_type;
typedef enum {
    FMU_INPUT_VAR = 1,
    FMU_OUTPUT_VAR = 2,
    FMU_PARAMETER_VAR = 3,
    FMU_INDEPENDENT_VAR = 4
} fmu_causality;

/* Value references: VR_x, VR_L_1, VR_fidelity, ... */
enum fmu_value_reference {
#define FMU_INPUT(vr, id, ...) VR_##id = vr,
#define FMU_OUTPUT(vr, id, ...) VR_##id = vr,
#define FMU_OUTPUT_INT(vr, id, ...) VR_##id = vr,
#define FMU_OPTION_INT(vr, id, ...) VR_##id = vr,
#define FMU_OPTION_REAL(vr, id, ...) VR_##id = vr,
#define FMU_PARAM(vr, id, ...) VR_##id = vr,
#define FMU_INDEPENDENT(vr, id, ...) VR_##id = vr,
#define FMU_OPTION_STRING(vr, id, ...) VR_##id = vr,
#include "variables.def"
#undef FMU_OPTION_STRING /* a model without String parameters leaves it defined */
    VR_END_OF_TABLE_ = -1
};

/* FMU_TIME_VR: the value reference of the independent variable (time), as a constant for the
 * step's bookkeeping (fmu_time_vr below is the same number). */
enum fmu_time_value_reference {
#define FMU_INDEPENDENT(vr, ...) FMU_TIME_VR = vr,
#include "variables.def"
};

/* Log categories: LOG_EVENTS, ... and their count. */
enum fmu_log_category {
#define FMU_LOG_CATEGORY(id, ...) id,
#include "variables.def"
    FMU_N_LOG_CATEGORIES
};

/* One scalar variable as the model description shows it (the start value comes from the model's
 * model_start_values, so that defaults are written once, where the model takes them from). */
typedef struct fmu_variable {
    unsigned vr;
    const char *name;
    fmu_type type;
    fmu_causality causality;
    const char *unit;         /* "" if none */
    const char *display_unit; /* "" if none */
    int has_range;            /* min and max below apply (integers) */
    long min, max;
    const char *description;
} fmu_variable;

/* 1 if x lies within var's declared range (min <= x <= max, the model description's min and
 * max) or var declares none, else 0. NaN is not judged here: a Real input that is not finite is
 * the step's to report, naming it. */
int fmu_within_range(const fmu_variable *var, double x);
/* How an out-of-range value is named in a message: the arguments are the variable's name, the
 * value (as a double: an Int32 converts exactly) and the variable's min and max. */
#define FMU_OUT_OF_RANGE_FORMAT "%s = %.17g is outside its declared range [%ld, %ld]"

/* All variables in table order, and per value reference (NULL where unused). */
extern const fmu_variable fmu_variables[];
extern const size_t fmu_n_variables;
const fmu_variable *fmu_variable_by_vr(unsigned vr);
/* The value reference of the independent variable (time). */
extern const unsigned fmu_time_vr;

extern const char *const fmu_log_category_names[FMU_N_LOG_CATEGORIES];
extern const char *const fmu_log_category_descriptions[FMU_N_LOG_CATEGORIES];

#ifdef __cplusplus
}
#endif

#endif
