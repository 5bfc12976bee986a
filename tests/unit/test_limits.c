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
    const char *names[] = {"none",         "stroke",    "base_joint", "platform_joint",
                           "interference", "condition", "axis",       "leg_speed",
                           "leg_accel",    "leg_jerk",  "leg_force"};
    TEST_ASSERT_EQUAL_INT(sizeof names / sizeof names[0], STEWART_LIMIT_CLASSES + 1);
    for (int c = 0; c <= STEWART_LIMIT_CLASSES; ++c)
        TEST_ASSERT_EQUAL_STRING(names[c], stewart_limit_class_name(c));
    TEST_ASSERT_EQUAL_STRING("unknown", stewart_limit_class_name(STEWART_LIMIT_CLASSES + 1));
}

/* The leg classes' data: flags out of range and non-finite values refused by name with the
 * output untouched; a pose alone (zero-initialised input) leaves them +inf and never met; a leg
 * of zero length has no rate. */
static void test_leg_class_data_is_refused_by_name(void) {
    stewart_limits_input in = {{0, 0, 0.5, 0, 0, 0}};
    stewart_limits_output out;
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_limits_check(limits, &in, &out));
    for (int c = STEWART_LIMIT_LEG_SPEED; c <= STEWART_LIMIT_LEG_FORCE; ++c) {
        TEST_ASSERT_TRUE(isinf(out.margin[c - 1]) && out.margin[c - 1] > 0);
        TEST_ASSERT_EQUAL_INT(0, out.leg[c - 1]);
    }
    const struct {
        int derivatives, has_force, component;
        double value;
        const char *named;
    } bad[] = {
        {4, 0, -1, 0, "derivatives = 4"},         {-1, 0, -1, 0, "derivatives = -1"},
        {0, 2, -1, 0, "has_force = 2"},           {1, 0, 4, NAN, "pitch_dot is nan"},
        {3, 0, 17, INFINITY, "yaw_dddot is inf"}, {0, 1, 18 + 2, -INFINITY, "force[3] is -inf"}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        stewart_limits_input b = in;
        b.derivatives = bad[i].derivatives;
        b.has_force = bad[i].has_force;
        if (bad[i].component >= 18) b.force[bad[i].component - 18] = bad[i].value;
        else if (bad[i].component >= 12) b.q_dddot[bad[i].component - 12] = bad[i].value;
        else if (bad[i].component >= 0) b.q_dot[bad[i].component] = bad[i].value;
        memset(&out, 0x5a, sizeof out);
        TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_limits_check(limits, &b, &out));
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(stewart_limits_message(limits), bad[i].named),
                                     stewart_limits_message(limits));
        TEST_ASSERT_EACH_EQUAL_HEX8(0x5a, &out, sizeof out);
    }
    /* Rates so large that the legs' accelerations overflow: refused, not inf - inf. */
    stewart_limits_input huge = in;
    huge.derivatives = 2;
    huge.q_dot[5] = 1e200;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_limits_check(limits, &huge, &out));
    TEST_ASSERT_NOT_NULL(strstr(stewart_limits_message(limits), "overflow"));
    /* A platform joint on its base joint (z = 0, yaw 30 deg on the thesis platform). */
    stewart_limits_input flat = {{0, 0, 0, 0, 0, M_PI / 6}};
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_limits_check(limits, &flat, &out));
    flat.derivatives = 1;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_UNREACHABLE, stewart_limits_check(limits, &flat, &out));
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
    RUN_TEST(test_leg_class_data_is_refused_by_name);
    RUN_TEST(test_extreme_poses_give_no_nan);
    return UNITY_END();
}
