/* The descriptor table of a model, generated from its variables.def (see variables.h). */
#include "variables.h"

#define FMU_INPUT(vr, id, name, start, unit, row, col, desc) \
    {vr, name, FMU_REAL, FMU_INPUT_VAR, unit, "", 0, 0, 0, desc},
#define FMU_OUTPUT(vr, id, name, unit, field, desc) \
    {vr, name, FMU_REAL, FMU_OUTPUT_VAR, unit, "", 0, 0, 0, desc},
#define FMU_OUTPUT_INT(vr, id, name, desc) \
    {vr, name, FMU_INTEGER, FMU_OUTPUT_VAR, "", "", 0, 0, 0, desc},
#define FMU_OPTION_INT(vr, id, name, start, min, max, desc) \
    {vr, name, FMU_INTEGER, FMU_PARAMETER_VAR, "", "", 1, min, max, desc},
#define FMU_OPTION_REAL(vr, id, name, field, unit, desc) \
    {vr, name, FMU_REAL, FMU_PARAMETER_VAR, unit, "", 0, 0, 0, desc},
#define FMU_PARAM(vr, id, name, field, unit, display, desc) \
    {vr, name, FMU_REAL, FMU_PARAMETER_VAR, unit, display, 0, 0, 0, desc},
#define FMU_INDEPENDENT(vr, id, name, unit, desc) \
    {vr, name, FMU_REAL, FMU_INDEPENDENT_VAR, unit, "", 0, 0, 0, desc},
#define FMU_OPTION_STRING(vr, id, name, desc) \
    {vr, name, FMU_STRING, FMU_PARAMETER_VAR, "", "", 0, 0, 0, desc},
const fmu_variable fmu_variables[] = {
#include "variables.def"
};
#undef FMU_OPTION_STRING
const size_t fmu_n_variables = sizeof fmu_variables / sizeof fmu_variables[0];

#define FMU_INDEPENDENT(vr, ...) const unsigned fmu_time_vr = vr;
#include "variables.def"

/* Index into fmu_variables + 1 per value reference (0: unused); every vr must be < FMU_NVR. */
#define FMU_INPUT(vr, ...) [vr] = __COUNTER__ - fmu_counter_base_,
#define FMU_OUTPUT FMU_INPUT
#define FMU_OUTPUT_INT FMU_INPUT
#define FMU_OPTION_INT FMU_INPUT
#define FMU_OPTION_REAL FMU_INPUT
#define FMU_PARAM FMU_INPUT
#define FMU_INDEPENDENT FMU_INPUT
#define FMU_OPTION_STRING FMU_INPUT
enum { fmu_counter_base_ = __COUNTER__ };
static const unsigned short kIndex[FMU_NVR] = {
#include "variables.def"
};
#undef FMU_OPTION_STRING

const fmu_variable *fmu_variable_by_vr(unsigned vr) {
    if (vr >= FMU_NVR || kIndex[vr] == 0) return NULL;
    return &fmu_variables[kIndex[vr] - 1];
}

int fmu_within_range(const fmu_variable *var, double x) {
    return !var->has_range || !(x < (double)var->min || x > (double)var->max);
}

#define FMU_LOG_CATEGORY(id, name, description) [id] = name,
const char *const fmu_log_category_names[FMU_N_LOG_CATEGORIES] = {
#include "variables.def"
};
#define FMU_LOG_CATEGORY(id, name, description) [id] = description,
const char *const fmu_log_category_descriptions[FMU_N_LOG_CATEGORIES] = {
#include "variables.def"
};
