/* The plant's option table (STEWART_PLANT_OPTION_TABLE, stewart/stewart_table.h) against the
 * plant's calls: its defaults are stewart_plant_options_default's, its ranges are those
 * stewart_plant_options_check accepts, end by end, with a message naming the option and the
 * value; fixed steps need an explicit method; names are unique; the setter refuses a bad value
 * naming the option and the value and leaves the options unchanged. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "stewart/stewart_plant.h"
#include "stewart/stewart_table.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

static void test_defaults_are_the_plants(void) {
    stewart_plant_options plant, from_table;
    stewart_plant_options_default(&plant);
    memset(&from_table, 0xff, sizeof from_table);
    char msg[STEWART_MESSAGE_SIZE];
    for (int i = 0; i < stewart_plant_option_count(); ++i) {
        const stewart_option_info *info = stewart_plant_option(i);
        TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK,
                                      stewart_plant_option_set(&from_table, i, info->default_value,
                                                               msg, sizeof msg),
                                      msg);
        TEST_ASSERT_EQUAL_DOUBLE(stewart_plant_option_get(&plant, i), info->default_value);
    }
    /* field by field (the struct may have padding) */
    TEST_ASSERT_EQUAL_INT(plant.fidelity, from_table.fidelity);
    TEST_ASSERT_EQUAL_INT(plant.method, from_table.method);
    TEST_ASSERT_EQUAL_DOUBLE(plant.relative_tolerance, from_table.relative_tolerance);
    TEST_ASSERT_EQUAL_DOUBLE(plant.absolute_tolerance, from_table.absolute_tolerance);
    TEST_ASSERT_TRUE(plant.max_internal_steps == from_table.max_internal_steps);
    TEST_ASSERT_EQUAL_INT(plant.fixed_steps, from_table.fixed_steps);
    /* the values stewart_plant.h documents */
    TEST_ASSERT_EQUAL_INT(STEWART_FULL, from_table.fidelity);
    TEST_ASSERT_EQUAL_INT(STEWART_PLANT_ERK, from_table.method);
    TEST_ASSERT_EQUAL_DOUBLE(1e-10, from_table.relative_tolerance);
    TEST_ASSERT_EQUAL_DOUBLE(1e-12, from_table.absolute_tolerance);
    TEST_ASSERT_TRUE(from_table.max_internal_steps == 10000);
    TEST_ASSERT_EQUAL_INT(0, from_table.fixed_steps);
}

static void test_names_unique_and_ids_the_fmus(void) {
    const char *names[] = {
        "fidelity",    "method", "relative_tolerance", "absolute_tolerance", "max_internal_steps",
        "fixed_steps", "input",  "smoothing_speed"};
    TEST_ASSERT_EQUAL_INT(8, stewart_plant_option_count());
    for (int i = 0; i < stewart_plant_option_count(); ++i) {
        const stewart_option_info *info = stewart_plant_option(i);
        TEST_ASSERT_EQUAL_STRING(names[i], info->name);
        TEST_ASSERT_EQUAL_INT(i, stewart_plant_option_find(info->name));
        /* the StewartPlant FMU's value references (fmu/models/plant/variables.def) */
        TEST_ASSERT_EQUAL_INT(200 + i, info->id);
        for (int j = 0; j < i; ++j)
            TEST_ASSERT_TRUE(strcmp(info->name, stewart_plant_option(j)->name) != 0);
    }
    TEST_ASSERT_NULL(stewart_plant_option(-1));
    TEST_ASSERT_NULL(stewart_plant_option(stewart_plant_option_count()));
    TEST_ASSERT_EQUAL_INT(-1, stewart_plant_option_find("tolerance"));
    TEST_ASSERT_EQUAL_INT(-1, stewart_plant_option_find(NULL));
}

/* The value just beyond an end of option i's range, outward (a whole number for an integer). */
static double beyond(const stewart_option_info *info, double end, double outward) {
    return info->is_integer ? end + outward : nextafter(end, outward * INFINITY);
}

/* stewart_plant_options_check's verdict on the defaults with option i set to value (stored as
 * the field's type, the table setter bypassed), its message in msg. */
static char msg_of_check[STEWART_MESSAGE_SIZE];
static stewart_status check_with(int i, double value) {
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    switch (i) {
        case 0: o.fidelity = (int)value; break;
        case 1: o.method = (int)value; break;
        case 2: o.relative_tolerance = value; break;
        case 3: o.absolute_tolerance = value; break;
        case 4: o.max_internal_steps = (long)value; break;
        case 5: o.fixed_steps = (int)value; break;
        case 6: o.input = (int)value; break;
        default: o.smoothing_speed = value; break;
    }
    return stewart_plant_options_check(&o, msg_of_check, sizeof msg_of_check);
}

/* check_with refuses option i = value naming the option and the value ("name = value"). */
static void expect_refused(int i, double value, const char *value_text) {
    char said[64];
    snprintf(said, sizeof said, "%s = %s", stewart_plant_option(i)->name, value_text);
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_ERR_PARAMETER, check_with(i, value), said);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg_of_check, said), msg_of_check);
}

/* Each end of each range: inside, the table's setter and the plant's check both accept; just
 * outside, both refuse, naming the option (max_internal_steps' upper end is the FMU Integer's
 * 2^31 - 1, below what a long holds: the check refuses a long beyond it too). */
static void test_ranges_are_the_checks(void) {
    TEST_ASSERT_EQUAL_STRING("fixed_steps", stewart_plant_option(5)->name);
    char msg[STEWART_MESSAGE_SIZE];
    for (int i = 0; i < stewart_plant_option_count(); ++i) {
        const stewart_option_info *info = stewart_plant_option(i);
        const double ends[2] = {info->min, info->max}, outward[2] = {-1, 1};
        const int closed[2] = {info->min_closed, info->max_closed};
        for (int side = 0; side < 2; ++side) {
            if (ends[side] == DBL_MAX) continue; /* "finite": tested below */
            const double inside =
                closed[side] ? ends[side] : beyond(info, ends[side], -outward[side]);
            const double outside =
                closed[side] ? beyond(info, ends[side], outward[side]) : ends[side];
            stewart_plant_options o;
            stewart_plant_options_default(&o);
            TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK,
                                          stewart_plant_option_set(&o, i, inside, msg, sizeof msg),
                                          msg);
            TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, check_with(i, inside), info->name);
            TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                                  stewart_plant_option_set(&o, i, outside, msg, sizeof msg));
            TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, info->name), msg);
            TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_ERR_PARAMETER, check_with(i, outside),
                                          info->name);
            TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg_of_check, info->name), msg_of_check);
        }
    }
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                          stewart_plant_option_set(&o, 3, INFINITY, msg, sizeof msg));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER, check_with(3, INFINITY));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                          stewart_plant_option_set(&o, 2, NAN, msg, sizeof msg));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER, check_with(2, NAN));
}

/* The check's messages: the value as given, the reason of a floor, the cross-field rule. */
static void test_check_says_why(void) {
    expect_refused(0, 0, "0");
    expect_refused(1, 4, "4");
    expect_refused(2, 1.0, "1");
    expect_refused(2, NAN, "nan");
    expect_refused(4, 0, "0");
    expect_refused(5, 1001, "1001");
    expect_refused(3, 1e-21, "1e-21");
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg_of_check, "error test fails on rounding"),
                                 msg_of_check);
    expect_refused(3, INFINITY, "inf");
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg_of_check, "finite"), msg_of_check);
    /* fixed steps with each method: only the explicit ones (2, 3) take them */
    for (int method = 0; method <= 3; ++method) {
        stewart_plant_options o;
        stewart_plant_options_default(&o);
        o.method = method;
        o.fixed_steps = 4;
        char msg[STEWART_MESSAGE_SIZE];
        const stewart_status s = stewart_plant_options_check(&o, msg, sizeof msg);
        TEST_ASSERT_EQUAL_INT_MESSAGE(method >= 2 ? STEWART_OK : STEWART_ERR_PARAMETER, s, msg);
        if (method < 2)
            TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "fixed_steps = 4 needs method 2 or 3"), msg);
    }
    char msg[STEWART_MESSAGE_SIZE];
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_plant_options_check(NULL, msg, sizeof msg));
}

static void test_setter_refuses_naming_the_value(void) {
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    char msg[STEWART_MESSAGE_SIZE];
    const int fixed = stewart_plant_option_find("fixed_steps");
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                          stewart_plant_option_set(&o, fixed, 2.5, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "fixed_steps = 2.5"), msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "whole number"), msg);
    TEST_ASSERT_EQUAL_INT(0, o.fixed_steps);
    const int rtol = stewart_plant_option_find("relative_tolerance");
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                          stewart_plant_option_set(&o, rtol, 1.5, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "relative_tolerance = 1.5"), msg);
    TEST_ASSERT_EQUAL_DOUBLE(1e-10, o.relative_tolerance);
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT,
                          stewart_plant_option_set(&o, 99, 1, msg, sizeof msg));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT,
                          stewart_plant_option_set(NULL, fixed, 1, msg, sizeof msg));
    /* a long option holds the largest value the table allows, exactly */
    const int steps = stewart_plant_option_find("max_internal_steps");
    TEST_ASSERT_EQUAL_INT(STEWART_OK,
                          stewart_plant_option_set(&o, steps, 2147483647.0, msg, sizeof msg));
    TEST_ASSERT_TRUE(o.max_internal_steps == 2147483647L);
    TEST_ASSERT_EQUAL_DOUBLE(2147483647.0, stewart_plant_option_get(&o, steps));
    TEST_ASSERT_EQUAL_DOUBLE(0.0, stewart_plant_option_get(NULL, steps));
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_defaults_are_the_plants);
    RUN_TEST(test_names_unique_and_ids_the_fmus);
    RUN_TEST(test_ranges_are_the_checks);
    RUN_TEST(test_check_says_why);
    RUN_TEST(test_setter_refuses_naming_the_value);
    return UNITY_END();
}
