/* The inverse FMU (StewartPlatform, linked statically, white box) against the library's tables:
 * every option of the option table (stewart_table.h), set through the unit, reaches the inverse
 * solver the unit builds (read from the option's variable, and compared with the solver's so that
 * a changed option rebuilds it; an unchanged one does not); every column of the output table
 * (stewart_outputs.h) that variables.def shows reaches its output variables, bit for bit as the
 * library's own solve of the same pose gives it. An option or a column that the unit leaves out
 * fails here. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "instance.h"
#include "stewart/stewart_outputs.h"
#include "stewart/stewart_table.h"
#include "test_support.h"
#include "unity.h"
#include "values.h"

void setUp(void) {}
void tearDown(void) {}

/* The last message the unit logged. */
static char last_message[1024];
static void remember(const void *callbacks, void *environment, const char *instance_name,
                     fmu_status status, const char *category, const char *message) {
    (void)callbacks;
    (void)environment;
    (void)instance_name;
    (void)status;
    (void)category;
    snprintf(last_message, sizeof last_message, "%s", message);
}

/* Initialises the unit (Reset first if it ran), setting n_int Integer and n_real Real variables. */
static void initialise(fmu_instance *inst, unsigned n_int, const unsigned *int_vr,
                       const int32_t *int_value, unsigned n_real, const unsigned *real_vr,
                       const double *real_value) {
    if (inst->v.mode != MODE_INSTANTIATED) TEST_ASSERT_EQUAL_INT(FMU_OK, fmu_reset(inst));
    TEST_ASSERT_EQUAL_INT(FMU_OK, fmu_set_integer(inst, int_vr, n_int, int_value));
    TEST_ASSERT_EQUAL_INT(FMU_OK, fmu_set_real(inst, real_vr, n_real, real_value));
    TEST_ASSERT_EQUAL_INT(FMU_OK, fmu_enter_initialization(inst, 1, 0.0));
    TEST_ASSERT_EQUAL_INT_MESSAGE(FMU_OK, fmu_exit_initialization(inst), last_message);
}

/* A valid value of option i other than `now`: one step up, or down at the top of its range. */
static double other_value(const stewart_option_info *info, double now) {
    if (info->is_integer) return now + 1 <= info->max ? now + 1 : now - 1;
    return now * 2 <= info->max ? now * 2 : now / 2;
}

static void test_every_option_reaches_the_solver(void) {
    fmu_instance *inst = fmu_instantiate("options", FMU_VERSION_2, remember, NULL, NULL, 1);
    TEST_ASSERT_NOT_NULL(inst);
    initialise(inst, 0, NULL, NULL, 0, NULL, NULL);
    stewart_inverse_options start = *stewart_inverse_options_of(inst->res.inverse);
    /* the same values again: the solver stays (the comparison sees them equal) */
    const stewart_inverse *first = inst->res.inverse;
    initialise(inst, 0, NULL, NULL, 0, NULL, NULL);
    TEST_ASSERT_EQUAL_PTR(first, inst->res.inverse);
    const int n = stewart_inverse_option_count();
    TEST_ASSERT_TRUE(n >= 6);
    for (int i = 0; i < n; ++i) {
        const stewart_option_info *info = stewart_inverse_option(i);
        const fmu_variable *var = fmu_variable_by_vr((unsigned)info->id);
        TEST_ASSERT_NOT_NULL_MESSAGE(var, info->name); /* the option is a variable of the unit */
        TEST_ASSERT_EQUAL_STRING(info->name, var->name);
        TEST_ASSERT_EQUAL_INT_MESSAGE(info->is_integer ? FMU_INTEGER : FMU_REAL, var->type,
                                      info->name);
        const double value = other_value(info, stewart_inverse_option_get(&start, i));
        const unsigned vr = (unsigned)info->id;
        const int32_t as_integer = (int32_t)value;
        /* from the start options, so that option i is the one difference the unit must see */
        initialise(inst, 0, NULL, NULL, 0, NULL, NULL);
        const stewart_model *model = inst->res.model;
        if (info->is_integer) initialise(inst, 1, &vr, &as_integer, 0, NULL, NULL);
        else initialise(inst, 0, NULL, NULL, 1, &vr, &value);
        const stewart_inverse_options *now = stewart_inverse_options_of(inst->res.inverse);
        for (int j = 0; j < n; ++j) { /* option i changed in the solver, the others not */
            char what[96];
            snprintf(what, sizeof what, "option %s set, option %s in the solver", info->name,
                     stewart_inverse_option(j)->name);
            TEST_ASSERT_EQUAL_DOUBLE_MESSAGE(j == i ? value : stewart_inverse_option_get(&start, j),
                                             stewart_inverse_option_get(now, j), what);
        }
        TEST_ASSERT_EQUAL_PTR_MESSAGE(model, inst->res.model, info->name); /* the same model */
    }
    fmu_free(inst);
}

/* The columns variables.def shows: the first value reference of each, -1 if not shown. */
static int first_of(const char *column) {
#define FMU_OUTPUT_COLUMN(name, first) \
    if (!strcmp(column, #name)) return VR_##first;
#define FMU_OUTPUT_COLUMN_NOT_SHOWN(name, why) \
    if (!strcmp(column, #name)) return -1;
#include "variables.def"
    TEST_FAIL_MESSAGE(column); /* a column variables.def does not list */
    return -1;
}

static void test_every_column_reaches_its_outputs(void) {
    fmu_instance *inst = fmu_instantiate("outputs", FMU_VERSION_2, remember, NULL, NULL, 1);
    TEST_ASSERT_NOT_NULL(inst);
    /* a pose away from home with rates and accelerations (derivatives = 1: the inputs') */
    const stewart_pose pose = combined_pose(0.3);
    unsigned real_vr[18];
    double inputs[18];
    for (unsigned k = 0; k < 6; ++k) {
        inputs[k] = pose.q[k];
        inputs[6 + k] = pose.q_dot[k];
        inputs[12 + k] = pose.q_ddot[k];
    }
    for (unsigned k = 0; k < 18; ++k) real_vr[k] = VR_x + k;
    const unsigned int_vr[] = {VR_derivatives};
    const int32_t derivatives[] = {1};
    initialise(inst, 1, int_vr, derivatives, 18, real_vr, inputs);
    double real[FMU_NVR];
    int32_t integer[FMU_NVR];
    unsigned all[FMU_NVR];
    for (unsigned vr = 0; vr < FMU_NVR; ++vr) all[vr] = vr;
    /* every Real and Integer output through the getters (variables that do not exist read 0) */
    for (unsigned vr = 0; vr < FMU_NVR; ++vr) {
        const fmu_variable *var = fmu_variable_by_vr(vr);
        real[vr] = integer[vr] = 0;
        if (var && var->type == FMU_REAL)
            TEST_ASSERT_EQUAL_INT(FMU_OK, fmu_get_real(inst, &all[vr], 1, &real[vr]));
        if (var && var->type == FMU_INTEGER)
            TEST_ASSERT_EQUAL_INT(FMU_OK, fmu_get_integer(inst, &all[vr], 1, &integer[vr]));
    }
    /* the library's own solve of the same pose with the unit's parameters and options */
    stewart_inverse *d = stewart_inverse_create(inst->res.model, &inst->res.options, NULL, 0);
    TEST_ASSERT_NOT_NULL(d);
    stewart_inverse_input in = {pose};
    stewart_inverse_output out;
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_inverse_solve(d, &in, &out));
    int shown = 0;
#define CHECK_COLUMN(name, member, count, type, unit, description)                           \
    {                                                                                        \
        const int first = first_of(#name);                                                   \
        const type *from = (const type *)(const void *)&out.member;                          \
        for (int e = 0; first >= 0 && e < count; ++e, ++shown) {                             \
            char what[64];                                                                   \
            snprintf(what, sizeof what, "column %s element %d", #name, e);                   \
            if (IS_DOUBLE_##type)                                                            \
                TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&from[e], &real[first + e], sizeof(double), \
                                                 what);                                      \
            else TEST_ASSERT_EQUAL_INT_MESSAGE((int)from[e], integer[first + e], what);      \
        }                                                                                    \
    }
#define IS_DOUBLE_double 1
#define IS_DOUBLE_int 0
    STEWART_INVERSE_OUTPUT_TABLE(CHECK_COLUMN)
    TEST_ASSERT_TRUE(shown > 0);
    stewart_inverse_free(d);
    fmu_free(inst);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_every_option_reaches_the_solver);
    RUN_TEST(test_every_column_reaches_its_outputs);
    return UNITY_END();
}
