/*
 * The library's output (stewart_inverse_output) into the output variables: one copy per column of
 * the library's output table (STEWART_INVERSE_OUTPUT_TABLE), to the variables variables.def shows
 * it in (FMU_OUTPUT_COLUMN: the column's first element; the others follow). A column added to the
 * table is copied with no line here; one that variables.def does not list stops the build
 * (COLUMN_FIRST_<name> undeclared), and tests/unit/test_fmu_output_columns.c holds every listed
 * column to its variables (value references, field, unit).
 */
#ifndef STEWART_FMU_INVERSE_OUTPUTS_H
#define STEWART_FMU_INVERSE_OUTPUTS_H

#include "stewart/stewart_outputs.h"
#include "variables.h"

/* The value reference of each column's first element, or -1 for a column no variable shows. */
enum inverse_output_column {
#define FMU_OUTPUT_COLUMN(column, first) COLUMN_FIRST_##column = VR_##first,
#define FMU_OUTPUT_COLUMN_NOT_SHOWN(column, why) COLUMN_FIRST_##column = -1,
#include "variables.def"
};

/* count values of a column from `from` into the variables from value reference `first` (none
 * if first < 0): a double column into Reals, an int one into Integers. */
static inline void copy_double_column(fmu_values *v, int first, const double *from, int count) {
    if (first < 0) return;
    for (int e = 0; e < count; ++e) v->real[first + e] = from[e];
}
static inline void copy_int_column(fmu_values *v, int first, const int *from, int count) {
    if (first < 0) return;
    for (int e = 0; e < count; ++e) v->integer[first + e] = from[e];
}

/* The output variables from the library's output `out`. */
static inline void inverse_outputs_from(fmu_values *restrict v,
                                        const stewart_inverse_output *restrict out) {
#define COPY_COLUMN(name, member, count, type, unit, description) \
    copy_##type##_column(v, COLUMN_FIRST_##name, (const type *)(const void *)&out->member, count);
    STEWART_INVERSE_OUTPUT_TABLE(COPY_COLUMN)
#undef COPY_COLUMN
}

#endif
