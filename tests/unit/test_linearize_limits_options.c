/* The linearisation's and the limits' option tables (STEWART_LINEARIZE_OPTION_TABLE,
 * STEWART_LIMITS_OPTION_TABLE, stewart/stewart_table.h) against the calls that use them: the
 * defaults are the values the headers document (the limits' warn_condition the inverse option's),
 * each end of each range is accepted inside and refused outside by the setter, the check and the
 * create call alike, naming the option and the value; names and lookups agree. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "stewart/stewart.h"
#include "stewart/stewart_limits.h"
#include "stewart/stewart_linearize.h"
#include "stewart/stewart_table.h"
#include "unity.h"

static stewart_model *model;

void setUp(void) {
    stewart_params p;
    char msg[STEWART_MESSAGE_SIZE];
    stewart_params_default(&p);
    model = stewart_model_create(&p, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(model, msg);
}
void tearDown(void) { stewart_model_free(model); }

static void test_defaults_are_the_documented_ones(void) {
    stewart_linearize_options lin;
    stewart_linearize_options_default(&lin);
    TEST_ASSERT_EQUAL_INT(STEWART_FULL, lin.fidelity); /* stewart_linearize.h */
    stewart_limits_options lim;
    stewart_limits_options_default(&lim);
    stewart_inverse_options inverse;
    stewart_inverse_options_default(&inverse);
    TEST_ASSERT_EQUAL_DOUBLE(1e3, lim.warn_condition); /* stewart_limits.h */
    TEST_ASSERT_EQUAL_DOUBLE(inverse.warn_condition, lim.warn_condition);
    for (int i = 0; i < stewart_linearize_option_count(); ++i)
        TEST_ASSERT_EQUAL_DOUBLE(stewart_linearize_option(i)->default_value,
                                 stewart_linearize_option_get(&lin, i));
    for (int i = 0; i < stewart_limits_option_count(); ++i)
        TEST_ASSERT_EQUAL_DOUBLE(stewart_limits_option(i)->default_value,
                                 stewart_limits_option_get(&lim, i));
}

static void test_names_and_lookup(void) {
    TEST_ASSERT_EQUAL_INT(1, stewart_linearize_option_count());
    TEST_ASSERT_EQUAL_STRING("fidelity", stewart_linearize_option(0)->name);
    TEST_ASSERT_EQUAL_INT(0, stewart_linearize_option_find("fidelity"));
    TEST_ASSERT_TRUE(stewart_linearize_option(0)->is_integer);
    TEST_ASSERT_EQUAL_INT(1, stewart_limits_option_count());
    TEST_ASSERT_EQUAL_STRING("warn_condition", stewart_limits_option(0)->name);
    TEST_ASSERT_EQUAL_INT(0, stewart_limits_option_find("warn_condition"));
    TEST_ASSERT_FALSE(stewart_limits_option(0)->is_integer);
    TEST_ASSERT_EQUAL_INT(-1, stewart_linearize_option_find("tolerance"));
    TEST_ASSERT_EQUAL_INT(-1, stewart_limits_option_find(NULL));
    TEST_ASSERT_NULL(stewart_linearize_option(1));
    TEST_ASSERT_NULL(stewart_limits_option(-1));
}

/* The value just beyond an end of a range, outward (a whole number for an integer). */
static double beyond(const stewart_option_info *info, double end, double outward) {
    return info->is_integer ? end + outward : nextafter(end, outward * INFINITY);
}

/* The three verdicts on the linearisation's option 0 = value: setter, check, create. */
static void expect_linearize(double value, int accepted) {
    char msg[STEWART_MESSAGE_SIZE], said[64];
    const stewart_status want = accepted ? STEWART_OK : STEWART_ERR_PARAMETER;
    stewart_linearize_options o;
    stewart_linearize_options_default(&o);
    snprintf(said, sizeof said, "fidelity = %g", value);
    TEST_ASSERT_EQUAL_INT_MESSAGE(want, stewart_linearize_option_set(&o, 0, value, msg, sizeof msg),
                                  said);
    if (!accepted) TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, said), msg);
    o.fidelity = (int)value;
    TEST_ASSERT_EQUAL_INT_MESSAGE(want, stewart_linearize_options_check(&o, msg, sizeof msg), said);
    if (!accepted) TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, said), msg);
    stewart_linearize *l = stewart_linearize_create(model, &o, msg, sizeof msg);
    TEST_ASSERT_EQUAL_INT_MESSAGE(accepted, l != NULL, said);
    stewart_linearize_free(l);
}

static void expect_limits(double value, int accepted) {
    char msg[STEWART_MESSAGE_SIZE], said[64];
    const stewart_status want = accepted ? STEWART_OK : STEWART_ERR_PARAMETER;
    stewart_limits_options o;
    stewart_limits_options_default(&o);
    snprintf(said, sizeof said, "warn_condition = %.17g", value);
    TEST_ASSERT_EQUAL_INT_MESSAGE(want, stewart_limits_option_set(&o, 0, value, msg, sizeof msg),
                                  said);
    o.warn_condition = value;
    TEST_ASSERT_EQUAL_INT_MESSAGE(want, stewart_limits_options_check(&o, msg, sizeof msg), said);
    if (!accepted) TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "warn_condition = "), msg);
    stewart_limits *l = stewart_limits_create(model, &o, msg, sizeof msg);
    TEST_ASSERT_EQUAL_INT_MESSAGE(accepted, l != NULL, said);
    stewart_limits_free(l);
}

static void test_ranges_are_the_checks(void) {
    const stewart_option_info *lin = stewart_linearize_option(0), *lim = stewart_limits_option(0);
    /* the plant's two fidelities, and nothing else */
    TEST_ASSERT_EQUAL_DOUBLE(STEWART_MASSLESS, lin->min);
    TEST_ASSERT_EQUAL_DOUBLE(STEWART_FULL, lin->max);
    expect_linearize(lin->min, 1);
    expect_linearize(lin->max, 1);
    expect_linearize(beyond(lin, lin->min, -1), 0);
    expect_linearize(beyond(lin, lin->max, 1), 0);
    /* a condition number is at least 1, and finite */
    TEST_ASSERT_EQUAL_DOUBLE(1.0, lim->min);
    TEST_ASSERT_TRUE(lim->min_closed);
    expect_limits(lim->min, 1);
    expect_limits(beyond(lim, lim->min, -1), 0);
    expect_limits(DBL_MAX, 1);
    expect_limits(INFINITY, 0);
    expect_limits(NAN, 0);
    char msg[STEWART_MESSAGE_SIZE];
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT,
                          stewart_limits_options_check(NULL, msg, sizeof msg));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT,
                          stewart_linearize_options_check(NULL, msg, sizeof msg));
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_defaults_are_the_documented_ones);
    RUN_TEST(test_names_and_lookup);
    RUN_TEST(test_ranges_are_the_checks);
    return UNITY_END();
}
