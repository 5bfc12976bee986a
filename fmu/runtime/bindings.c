/* A model's values to and from the structs its variables.def binds them to (bindings.h). */
#include "bindings.h"

#include <string.h>

void fmu_start_values(fmu_values *v) {
#define FMU_INPUT(vr, id, name, start, ...) v->real[vr] = start;
#define FMU_OUTPUT(vr, ...) v->real[vr] = 0.0;
#define FMU_OUTPUT_INT(vr, ...) v->integer[vr] = 0;
#define FMU_OPTION_INT(vr, id, name, start, ...) v->integer[vr] = start;
#define FMU_OPTION_REAL(vr, ...) v->real[vr] = 0.0;
#define FMU_PARAM(vr, ...) v->real[vr] = 0.0;
#define FMU_INDEPENDENT(vr, ...) v->real[vr] = 0.0;
#include "variables.def"
    memset(&v->model, 0, sizeof v->model);
}

#ifdef FMU_PARAMS_STRUCT
void fmu_params_to_values(fmu_values *v, const FMU_PARAMS_STRUCT *p) {
#define FMU_PARAM(vr, id, name, field, ...) v->real[vr] = p->field;
#include "variables.def"
}

void fmu_params_from_values(const fmu_values *v, FMU_PARAMS_STRUCT *p) {
#define FMU_PARAM(vr, id, name, field, ...) p->field = v->real[vr];
#include "variables.def"
}
#endif

#ifdef FMU_SETTINGS_STRUCT
void fmu_settings_to_values(fmu_values *v, const FMU_SETTINGS_STRUCT *s) {
#define FMU_OPTION_REAL(vr, id, name, field, ...) v->real[vr] = s->field;
#include "variables.def"
}

void fmu_settings_from_values(const fmu_values *v, FMU_SETTINGS_STRUCT *s) {
#define FMU_OPTION_REAL(vr, id, name, field, ...) s->field = v->real[vr];
#include "variables.def"
}
#endif

#ifdef FMU_OPTION_TABLE
/* An option's variable by the option's type: an int or long option is an Integer, a double one
 * a Real. */
#define OPTION_VARIABLE_int(v, id) (v)->integer[id]
#define OPTION_VARIABLE_long(v, id) (v)->integer[id]
#define OPTION_VARIABLE_double(v, id) (v)->real[id]
/* The Integer of a long option holds it (the table's range is at most an Int32's). */
#define OPTION_VALUE_int(x) (x)
#define OPTION_VALUE_long(x) ((int32_t)(x))
#define OPTION_VALUE_double(x) (x)

void fmu_table_options_to_values(fmu_values *v, const FMU_OPTION_TABLE_STRUCT *o) {
#define OPTION_TO_VALUES(id, name, type, ...) \
    OPTION_VARIABLE_##type(v, id) = OPTION_VALUE_##type(o->name);
    FMU_OPTION_TABLE(OPTION_TO_VALUES)
#undef OPTION_TO_VALUES
}

void fmu_table_options_from_values(const fmu_values *v, FMU_OPTION_TABLE_STRUCT *o) {
#define OPTION_FROM_VALUES(id, name, type, ...) o->name = OPTION_VARIABLE_##type(v, id);
    FMU_OPTION_TABLE(OPTION_FROM_VALUES)
#undef OPTION_FROM_VALUES
}

int fmu_same_table_options(const FMU_OPTION_TABLE_STRUCT *a, const FMU_OPTION_TABLE_STRUCT *b) {
#define SAME_OPTION(id, name, ...) &&a->name == b->name
    return 1 FMU_OPTION_TABLE(SAME_OPTION);
#undef SAME_OPTION
}
#endif
