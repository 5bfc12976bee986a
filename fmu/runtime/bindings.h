/*
 * A model's values to and from the structs its variables.def binds them to, and its start values:
 * the loops over variables.def that every model needs, written once. Compiled with each model
 * (its config.h and variables.def). A model's config.h names what it binds, and the functions of
 * each exist only where it is named:
 *
 *   FMU_PARAMS_STRUCT         the struct of FMU_PARAM's `field` (stewart_params: the units on the
 *                             library's parameter table)
 *   FMU_SETTINGS_STRUCT       the struct of FMU_OPTION_REAL's `field`
 *   FMU_OPTION_TABLE          the library's option table the unit shows (STEWART_OPTION_TABLE,
 *                             STEWART_PLANT_OPTION_TABLE: its ids are the value references, an
 *                             Integer for an int or long option, a Real for a double one) ...
 *   FMU_OPTION_TABLE_STRUCT   ... and the options struct that table describes
 *
 * An option added to the library's table is then read, written and compared by the unit with no
 * line of the model's own.
 */
#ifndef STEWART_FMU_BINDINGS_H
#define STEWART_FMU_BINDINGS_H

#include "instance.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Every variable's start value as variables.def gives it (an input's and an Integer
 * parameter's `start`), 0 for the others (outputs, Real parameters, the independent variable),
 * and the model's plain values zero. A model then writes its bound defaults (below) and what is
 * its own (a status before any solve). */
void fmu_start_values(fmu_values *v);

#ifdef FMU_PARAMS_STRUCT
/* The FMU_PARAM variables from the fields of p, and back (fields that no variable binds keep
 * their value: start from the defaults). */
void fmu_params_to_values(fmu_values *v, const FMU_PARAMS_STRUCT *p);
void fmu_params_from_values(const fmu_values *v, FMU_PARAMS_STRUCT *p);
#endif

#ifdef FMU_SETTINGS_STRUCT
/* The FMU_OPTION_REAL variables from the fields of s, and back. */
void fmu_settings_to_values(fmu_values *v, const FMU_SETTINGS_STRUCT *s);
void fmu_settings_from_values(const fmu_values *v, FMU_SETTINGS_STRUCT *s);
#endif

#ifdef FMU_OPTION_TABLE
/* Every option of the table from the variable of its id, and back. */
void fmu_table_options_to_values(fmu_values *v, const FMU_OPTION_TABLE_STRUCT *o);
void fmu_table_options_from_values(const fmu_values *v, FMU_OPTION_TABLE_STRUCT *o);
/* 1 if a and b hold the same value of every option of the table (field by field: a struct's
 * padding bytes are not values), else 0. */
int fmu_same_table_options(const FMU_OPTION_TABLE_STRUCT *a, const FMU_OPTION_TABLE_STRUCT *b);
#endif

#ifdef __cplusplus
}
#endif

#endif
