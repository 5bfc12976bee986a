/* An FMU's outputs against the library's output tables (stewart/stewart_outputs.h): compiled once
 * per model (FMU_MODEL_INVERSE, FMU_MODEL_PLANT, FMU_MODEL_PLANT_ME) with that model's folder on
 * the include path. Its variables.def names, for every column of its tables, the output holding
 * the column's first element (FMU_OUTPUT_COLUMN) or why none does (FMU_OUTPUT_COLUMN_NOT_SHOWN).
 * For each element of a shown column: an output at the next value reference, Real for a double
 * column and bound to that element of the output struct (its field's offset), Integer for an int
 * or long one; the unit the table's (a pose's "m, rad": m for x, y, z, rad for the angles). A
 * column added to a table fails here until the FMU says how it shows it. */
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "stewart/stewart_outputs.h"
#include "unity.h"
#include "variables.h"

void setUp(void) {}
void tearDown(void) {}

/* The struct the model binds its FMU_OUTPUT fields to (model.c); the tables' structs lie in it
 * (CHECK_COLUMN's prefix below). */
#if defined(FMU_MODEL_INVERSE)
typedef stewart_inverse_output binding;
#elif defined(FMU_MODEL_PLANT)
/* model.c's plant_outputs: the step's output and the integrator's counters. */
typedef struct binding {
    stewart_plant_output out;
    stewart_plant_statistics stats;
} binding;
#elif defined(FMU_MODEL_PLANT_ME)
typedef stewart_plant_output binding;
#else
#error "define FMU_MODEL_INVERSE, FMU_MODEL_PLANT or FMU_MODEL_PLANT_ME"
#endif

enum { NOT_AN_OUTPUT = 0, REAL_BOUND, REAL_OTHER, INTEGER };

/* What variables.def says of each value reference. */
typedef struct output {
    int kind;
    const char *name, *unit;
    size_t offset; /* REAL_BOUND: of its field in binding */
} output;

static output outputs[FMU_NVR];

static void read_outputs(void) {
    memset(outputs, 0, sizeof outputs);
#define FMU_OUTPUT(vr, id, name, unit, field, desc) \
    outputs[vr] = (output){REAL_BOUND, name, unit, offsetof(binding, field)};
#define FMU_LIMIT_OUTPUT(vr, id, name, unit, field, desc) \
    outputs[vr] = (output){REAL_OTHER, name, unit, 0};
#define FMU_OUTPUT_INT(vr, id, name, desc) outputs[vr] = (output){INTEGER, name, "", 0};
#include "variables.def"
}

/* The columns variables.def maps: first value reference, or -1 (not shown). */
typedef struct mapping {
    const char *column;
    int first;
} mapping;

static const mapping mappings[] = {
#define FMU_OUTPUT_COLUMN(column, first) {#column, VR_##first},
#define FMU_OUTPUT_COLUMN_NOT_SHOWN(column, why) {#column, -1},
#include "variables.def"
};
enum { MAPPINGS = sizeof mappings / sizeof mappings[0] };

/* Element e's unit of a column's unit: "m, rad" gives m to elements 0..2 and rad to 3..5. */
static void element_unit(const char *unit, int e, char *out, size_t size) {
    const char *comma = strstr(unit, ", ");
    if (!comma) {
        snprintf(out, size, "%s", unit);
        return;
    }
    if (e < 3) snprintf(out, size, "%.*s", (int)(comma - unit), unit);
    else snprintf(out, size, "%s", comma + 2);
}

static int columns_seen;

static void check_column(const char *column, size_t offset, int count, int is_double,
                         const char *unit) {
    int found = -1;
    for (int m = 0; m < MAPPINGS; ++m)
        if (!strcmp(mappings[m].column, column)) {
            TEST_ASSERT_EQUAL_INT_MESSAGE(-1, found, column); /* listed once */
            found = m;
        }
    TEST_ASSERT_TRUE_MESSAGE(found >= 0, column); /* every column is listed */
    ++columns_seen;
    if (mappings[found].first < 0) return;
    for (int e = 0; e < count; ++e) {
        const int vr = mappings[found].first + e;
        char where[96], expected_unit[32];
        snprintf(where, sizeof where, "column %s element %d (value reference %d)", column, e, vr);
        TEST_ASSERT_TRUE_MESSAGE(vr < FMU_NVR, where);
        const output *o = &outputs[vr];
        if (!is_double) {
            TEST_ASSERT_EQUAL_INT_MESSAGE(INTEGER, o->kind, where);
            continue;
        }
        TEST_ASSERT_EQUAL_INT_MESSAGE(REAL_BOUND, o->kind, where);
        TEST_ASSERT_EQUAL_size_t_MESSAGE(offset + e * sizeof(double), o->offset, where);
        element_unit(unit, e, expected_unit, sizeof expected_unit);
        TEST_ASSERT_EQUAL_STRING_MESSAGE(expected_unit, o->unit, where);
    }
}

#define IS_DOUBLE_double 1
#define IS_DOUBLE_int 0
#define IS_DOUBLE_long 0
#define CHECK_COLUMN(prefix, name, member, count, type, unit, description) \
    check_column(#name, offsetof(binding, prefix member), count, IS_DOUBLE_##type, unit);

static void test_every_column_is_shown_as_the_table_says(void) {
    read_outputs();
    columns_seen = 0;
#if defined(FMU_MODEL_PLANT)
#define CHECK_OUT(name, member, count, type, unit, d) \
    CHECK_COLUMN(out., name, member, count, type, unit, d)
#define CHECK_STATS(name, member, count, type, unit, d) \
    CHECK_COLUMN(stats., name, member, count, type, unit, d)
    STEWART_PLANT_OUTPUT_TABLE(CHECK_OUT)
    STEWART_PLANT_STEP_TABLE(CHECK_STATS)
#else
#define CHECK_ROOT(name, member, count, type, unit, d) \
    CHECK_COLUMN(, name, member, count, type, unit, d)
#if defined(FMU_MODEL_INVERSE)
    STEWART_INVERSE_OUTPUT_TABLE(CHECK_ROOT)
#else
    STEWART_PLANT_OUTPUT_TABLE(CHECK_ROOT)
#endif
#endif
    /* no mapping names a column the tables do not have */
    TEST_ASSERT_EQUAL_INT(MAPPINGS, columns_seen);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_every_column_is_shown_as_the_table_says);
    return UNITY_END();
}
