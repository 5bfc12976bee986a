/* The variable table (variables.def) as C: value reference constants and a descriptor list. */
#ifndef STEWART_FMU_VARIABLES_H
#define STEWART_FMU_VARIABLES_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Every value reference is below this bound (checked at compile time in variables.c). */
#define FMU_NVR 301

#define FMU_GUID "{5d0f6a3e-9b1c-4c2e-a7f4-3e8b2c7d1a04}"
#define FMU_MODEL_IDENTIFIER "StewartPlatform"

typedef enum { FMU_REAL = 1, FMU_INTEGER = 2 } fmu_type;
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
#include "variables.def"
    VR_END_OF_TABLE_ = -1
};

/* Log categories: LOG_EVENTS, ... and their count. */
enum fmu_log_category {
#define FMU_LOG_CATEGORY(id, ...) id,
#include "variables.def"
    FMU_N_LOG_CATEGORIES
};

typedef struct fmu_variable {
    unsigned vr;
    const char *name;
    fmu_type type;
    fmu_causality causality;
} fmu_variable;

/* All variables in table order, and per value reference (NULL where unused). */
extern const fmu_variable fmu_variables[];
extern const size_t fmu_n_variables;
const fmu_variable *fmu_variable_by_vr(unsigned vr);

extern const char *const fmu_log_category_names[FMU_N_LOG_CATEGORIES];
extern const char *const fmu_log_category_descriptions[FMU_N_LOG_CATEGORIES];

#ifdef __cplusplus
}
#endif

#endif
