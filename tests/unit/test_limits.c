/* The limits object's C API (stewart/stewart_limits.h): its life cycle, refusals by name, and
 * outputs that are never NaN, also at poses far beyond every limit or with a leg of zero length.
 * The margins themselves are checked against numpy in tests/python/test_limits.py. */
#include <math.h>
#include <string.h>

#include "stewart/stewart_limits.h"
#include "unity.h"

static stewart_model *model;
static stewart_limits *limits;

void setUp(void) {
    stewart_params p;
    stewart_params_default(&p);
    char msg[STEWART_MESSAGE_SIZE];
    model = stewart_model_create(&p, msg, sizeof msg);
    stewart_limits_options o;
    stewart_limits_options_default(&o);
    limits = stewart_limits_create(model, &o, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(limits, msg);
}

void tearDown(void) {
    stewart_limits_free(limits);
    stewart_model_free(model);
}

static void test_options_and_arguments_are_refused_by_name(void) {
    char msg[STEWART_MESSAGE_SIZE];
    stewart_limits_options o;
    stewart_limits_options_default(&o);
    TEST_ASSERT_EQUAL_DOUBLE(1e3, o.warn_condition);
    o.warn_condition = 0.5;
    TEST_ASSERT_NULL(stewart_limits_create(model, &o, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL(strstr(msg, "warn_condition = 0.5"));
    o.warn_condition = NAN;
    TEST_ASSERT_NULL(stewart_limits_create(model, &o, msg, sizeof msg));
    TEST_ASSERT_NULL(stewart_limits_create(NULL, &o, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL(strstr(msg, "model"));

    stewart_limits_input in = {{0, 0, 0.5, 0, 0, 0}};
    stewart_limits_output out;
    stewart_axis_ranges ranges;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_limits_check(limits, NULL, &out));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_limits_check(limits, &in, NULL));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_limits_check(NULL, &in, &out));
    in.q[4] = INFINITY;
    memset(&out, 0x5a, sizeof out);
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_limits_check(limits, &in, &out));
    TEST_ASSERT_NOT_NULL(strstr(stewart_limits_message(limits), "pitch is inf"));
    TEST_ASSERT_EACH_EQUAL_HEX8(0x5a, &out, sizeof out); /* untouched */
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_limits_ranges(limits, &in, &ranges));
    in.q[4] = 0;
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_limits_ranges(limits, &in, &ranges));
    TEST_ASSERT_EQUAL_STRING("", stewart_limits_message(limits));
}

static void test_class_names(void) {
    const char *names[] = {"none", "stroke", "base_joint", "platform_joint", "interference",
                           "condition", "axis"};
    for (int c = 0; c <= STEWART_LIMIT_CLASSES; ++c)
        TEST_ASSERT_EQUAL_STRING(names[c], stewart_limit_class_name(c));
    TEST_ASSERT_EQUAL_STRING("unknown", stewart_limit_class_name(7));
}

static void assert_no_nan(const stewart_limits_output *out, const stewart_axis_ranges *r) {
    for (int c = 0; c < STEWART_LIMIT_CLASSES; ++c) TEST_ASSERT_FALSE(isnan(out->margin[c]));
    TEST_ASSERT_FALSE(isnan(out->condition));
    for (int a = 0; a < 6; ++a) {
        TEST_ASSERT_TRUE(isfinite(r->min[a]) && isfinite(r->max[a]));
        TEST_ASSERT_TRUE(r->min[a] <= r->max[a]);
    }
}

/* Far away, huge, and a platform joint on its base joint (leg 1 of zero length). */
static void test_extreme_poses_give_no_nan(void) {
    stewart_params p;
    stewart_params_default(&p);
    /* leg 1's platform joint on its base joint: base (0.5, 0, 0), platform at 330 degrees */
    const double c = cos(-30.0 * 3.14159265358979323846 / 180.0),
                 s = sin(-30.0 * 3.14159265358979323846 / 180.0);
    const stewart_limits_input poses[] = {{{0, 0, 0.5, 0, 0, 0}},
                                          {{1e300, -1e300, 1e300, 1e10, -1e10, 3}},
                                          {{0.5 - 0.5 * c, -0.5 * s, 0, 0, 0, 0}},
                                          {{0, 0, 0, 0, 0, 0}}};
    for (size_t i = 0; i < sizeof poses / sizeof poses[0]; ++i) {
        stewart_limits_output out;
        stewart_axis_ranges r;
        TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_limits_check(limits, &poses[i], &out));
        TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_limits_ranges(limits, &poses[i], &r));
        assert_no_nan(&out, &r);
        TEST_ASSERT_EQUAL_INT(i == 0 ? STEWART_LIMIT_NONE : STEWART_LIMIT_STROKE, out.first);
    }
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_options_and_arguments_are_refused_by_name);
    RUN_TEST(test_class_names);
    RUN_TEST(test_extreme_poses_give_no_nan);
    return UNITY_END();
}
