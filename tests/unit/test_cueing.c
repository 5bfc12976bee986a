/* The cueing unit's C API (stewart/stewart_cueing.h): options refused by name, rest at home,
 * the classical filter against closed-form responses of its transfer functions, the limiter on a
 * violent input, rollback, bad input, no allocation in a step. The filters against scipy.signal
 * and the limits on every shipped machine: tests/python/test_cueing.py. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "allocation_counter.h"
#include "stewart/stewart_cueing.h"
#include "stewart/stewart_limits.h"
#include "stewart/stewart_table.h"
#include "test_support.h"
#include "unity.h"

static stewart_model *model;
static const double g = 9.81;

void setUp(void) {
    stewart_params p;
    stewart_params_default(&p);
    char msg[STEWART_MESSAGE_SIZE];
    model = stewart_model_create(&p, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(model, msg);
}

void tearDown(void) { stewart_model_free(model); }

static stewart_cueing *make(const stewart_cueing_options *o) {
    char msg[STEWART_MESSAGE_SIZE];
    stewart_cueing *c = stewart_cueing_create(model, o, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(c, msg);
    return c;
}

static stewart_cueing_input rest_input(double dt) {
    stewart_cueing_input in;
    memset(&in, 0, sizeof in);
    in.dt = dt;
    in.specific_force[2] = g;
    return in;
}

/* Every option of the table: its default is the options_default value, each finite end of its
 * range is accepted inside (by the setter, the check and the create call) and refused just
 * outside by the setter, naming the option. */
static void test_option_table_ranges(void) {
    char msg[STEWART_MESSAGE_SIZE];
    stewart_cueing_options d;
    stewart_cueing_options_default(&d);
    TEST_ASSERT_EQUAL_INT(25, stewart_cueing_option_count());
    for (int i = 0; i < stewart_cueing_option_count(); ++i) {
        const stewart_option_info *info = stewart_cueing_option(i);
        TEST_ASSERT_EQUAL_INT(i, stewart_cueing_option_find(info->name));
        TEST_ASSERT_TRUE(info->id >= 800 && info->id < 900);
        TEST_ASSERT_EQUAL_DOUBLE(info->default_value, stewart_cueing_option_get(&d, i));
        const double ends[2] = {info->min, info->max};
        const int closed[2] = {info->min_closed, info->max_closed};
        for (int side = 0; side < 2; ++side) {
            const double end = ends[side], outward = side ? 1.0 : -1.0;
            if (fabs(end) >= DBL_MAX) continue;
            const double inside = closed[side]       ? end
                                  : info->is_integer ? end - outward
                                                     : nextafter(end, -outward * INFINITY);
            const double outside = info->is_integer ? end + outward
                                   : closed[side]   ? nextafter(end, outward * INFINITY)
                                                    : end;
            stewart_cueing_options o = d;
            TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK,
                                          stewart_cueing_option_set(&o, i, inside, msg, sizeof msg),
                                          info->name);
            TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK,
                                          stewart_cueing_options_check(&o, msg, sizeof msg), msg);
            stewart_cueing *c = stewart_cueing_create(model, &o, msg, sizeof msg);
            if (!strcmp(info->name, "warn_condition") && side == 0) {
                /* a condition limit of 1 puts home (condition 11.4) beyond it: refused so */
                TEST_ASSERT_NULL(c);
                TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "home pose is beyond the condition limit"),
                                             msg);
            } else {
                TEST_ASSERT_NOT_NULL_MESSAGE(c, msg);
            }
            stewart_cueing_free(c);
            TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_ERR_PARAMETER,
                                          stewart_cueing_option_set(&o, i, outside, msg,
                                                                    sizeof msg),
                                          info->name);
            TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, info->name), msg);
        }
    }
}

static void test_options_are_refused_by_name(void) {
    char msg[STEWART_MESSAGE_SIZE];
    stewart_cueing_options o;
    stewart_cueing_options_default(&o);
    TEST_ASSERT_EQUAL_INT(STEWART_CUEING_CLASSICAL, o.algorithm);
    TEST_ASSERT_EQUAL_INT(3, o.translation_order);
    TEST_ASSERT_DOUBLE_WITHIN(1e-15, 3.0 * M_PI / 180.0, o.tilt_rate_max);
    o.translation_order = 4;
    TEST_ASSERT_NULL(stewart_cueing_create(model, &o, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "translation_order = 4"), msg);
    stewart_cueing_options_default(&o);
    o.tilt_frequency = 0.0;
    TEST_ASSERT_NULL(stewart_cueing_create(model, &o, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "tilt_frequency = 0"), msg);
    TEST_ASSERT_NULL(stewart_cueing_create(NULL, &o, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL(strstr(msg, "model"));
    /* the table's setter refuses the same value */
    stewart_cueing_options_default(&o);
    const int i = stewart_cueing_option_find("rotation_filter_order");
    TEST_ASSERT_TRUE(i >= 0);
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                          stewart_cueing_option_set(&o, i, 3, msg, sizeof msg));
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_cueing_option_set(&o, i, 1, msg, sizeof msg));
    TEST_ASSERT_EQUAL_INT(1, o.rotation_filter_order);
}

/* A home beyond a limit is refused, naming the limit. */
static void test_home_beyond_a_limit_is_refused(void) {
    stewart_params p;
    stewart_params_default(&p);
    for (int k = 0; k < 6; ++k) p.stroke_max[k] = 0.55; /* home lengths are about 0.56 m */
    char msg[STEWART_MESSAGE_SIZE];
    stewart_model *m = stewart_model_create(&p, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(m, msg);
    stewart_cueing_options o;
    stewart_cueing_options_default(&o);
    TEST_ASSERT_NULL(stewart_cueing_create(m, &o, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "stroke"), msg);
    stewart_model_free(m);
}

static void test_rest_stays_at_home(void) {
    stewart_cueing_options o;
    stewart_cueing_options_default(&o);
    stewart_cueing *c = make(&o);
    stewart_cueing_output out;
    for (int k = 0; k < 1000; ++k) {
        stewart_cueing_input in = rest_input(k ? 1e-3 : 0.0);
        TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_cueing_step(c, &in, &out));
        for (int i = 0; i < 6; ++i) {
            TEST_ASSERT_EQUAL_DOUBLE(i == 2 ? 0.5 : 0.0, out.pose.q[i]);
            TEST_ASSERT_EQUAL_DOUBLE(0.0, out.pose.q_dot[i]);
            TEST_ASSERT_EQUAL_DOUBLE(0.0, out.pose.q_ddot[i]);
        }
        TEST_ASSERT_FALSE(out.limited);
    }
    stewart_cueing_free(c);
}

/* Order 2, zeta = 1: x = k A / (s + w)^2 / s for a step A of surge specific force, so
 * x(t) = k A / w^2 (1 - e^{-wt} (1 + wt)), x' = k A t e^{-wt}, x'' = k A e^{-wt} (1 - wt). A step
 * is its own zero-order hold: the discrete response is exact at the samples. */
static void test_surge_step_against_its_closed_form(void) {
    stewart_cueing_options o;
    stewart_cueing_options_default(&o);
    o.translation_order = 2;
    o.translation_frequency = 3.0;
    o.tilt_max = 0.0; /* no tilt: the surge channel alone */
    stewart_cueing *c = make(&o);
    const double A = 0.2, k = o.surge_scale, w = 3.0, dt = 1e-2;
    stewart_cueing_output out;
    double worst = 0.0;
    for (int n = 1; n <= 500; ++n) {
        stewart_cueing_input in = rest_input(dt);
        in.specific_force[0] = A;
        TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_cueing_step(c, &in, &out));
        const double t = n * dt, e = exp(-w * t);
        const double x = k * A / (w * w) * (1 - e * (1 + w * t));
        worst = fmax(worst, fabs(out.pose.q[0] - x));
        worst = fmax(worst, fabs(out.pose.q_dot[0] - k * A * t * e));
        worst = fmax(worst, fabs(out.pose.q_ddot[0] - k * A * e * (1 - w * t)));
        TEST_ASSERT_FALSE(out.limited);
    }
    TEST_ASSERT_TRUE(worst < 1e-13);
    stewart_cueing_free(c);
}

/* Rotation order 1: angle = k / (s + w) for a step W of roll rate: k W / w (1 - e^{-wt}),
 * rate k W e^{-wt}, acceleration -w k W e^{-wt}. */
static void test_roll_rate_step_against_its_closed_form(void) {
    stewart_cueing_options o;
    stewart_cueing_options_default(&o);
    o.rotation_filter_order = 1;
    o.rotation_frequency = 2.0;
    stewart_cueing *c = make(&o);
    const double W = 0.05, k = o.roll_scale, w = 2.0, dt = 2e-3;
    stewart_cueing_output out;
    double worst = 0.0;
    for (int n = 1; n <= 2000; ++n) {
        stewart_cueing_input in = rest_input(dt);
        in.angular_velocity[0] = W;
        TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_cueing_step(c, &in, &out));
        const double e = exp(-w * n * dt);
        worst = fmax(worst, fabs(out.pose.q[3] - k * W / w * (1 - e)));
        worst = fmax(worst, fabs(out.pose.q_dot[3] - k * W * e));
        worst = fmax(worst, fabs(out.pose.q_ddot[3] + w * k * W * e));
    }
    TEST_ASSERT_TRUE(worst < 1e-13);
    stewart_cueing_free(c);
}

/* A sustained surge specific force tilts the platform nose up (negative pitch) to
 * -asin(k A / g) at the end, never faster than tilt_rate_max. */
static void test_tilt_coordination_settles_and_respects_its_rate(void) {
    stewart_cueing_options o;
    stewart_cueing_options_default(&o);
    stewart_cueing *c = make(&o);
    const double A = 1.0, dt = 1e-2;
    stewart_cueing_output out;
    double last = 0.0;
    for (int n = 1; n <= 6000; ++n) {
        stewart_cueing_input in = rest_input(dt);
        in.specific_force[0] = A;
        TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_cueing_step(c, &in, &out));
        TEST_ASSERT_TRUE(fabs(out.pose.q[4] - last) <= o.tilt_rate_max * dt * (1 + 1e-12) + 1e-15);
        TEST_ASSERT_TRUE(fabs(out.pose.q_dot[4]) <= o.tilt_rate_max * (1 + 1e-12));
        last = out.pose.q[4];
    }
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, -asin(o.surge_scale * A / g), out.pose.q[4]);
    stewart_cueing_free(c);
}

/* 2 g and 200 deg/s square waves: every output pose within every limit, the limiter acting. */
static void test_limiter_keeps_every_sample_within_the_limits(void) {
    stewart_cueing_options o;
    stewart_cueing_options_default(&o);
    o.surge_scale = o.sway_scale = o.heave_scale = 1.0;
    o.roll_scale = o.pitch_scale = o.yaw_scale = 1.0;
    stewart_cueing *c = make(&o);
    stewart_limits_options lo;
    stewart_limits_options_default(&lo);
    char msg[STEWART_MESSAGE_SIZE];
    stewart_limits *limits = stewart_limits_create(model, &lo, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(limits, msg);
    int limited = 0;
    for (int n = 0; n < 5000; ++n) {
        stewart_cueing_input in = rest_input(n ? 2e-3 : 0.0);
        const double sign = (n / 400) % 2 ? 1.0 : -1.0;
        for (int i = 0; i < 3; ++i) {
            in.specific_force[i] += sign * 2 * g * (i == 1 ? -1 : 1);
            in.angular_velocity[i] = sign * 200 * M_PI / 180 * (i == 2 ? -1 : 1);
        }
        stewart_cueing_output out;
        TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_cueing_step(c, &in, &out),
                                      stewart_cueing_message(c));
        stewart_limits_input li = {0};
        memcpy(li.q, out.pose.q, sizeof li.q);
        stewart_limits_output lout;
        TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_limits_check(limits, &li, &lout));
        TEST_ASSERT_EQUAL_INT(STEWART_LIMIT_NONE, lout.first);
        TEST_ASSERT_TRUE(out.scale >= 0.0 && out.scale <= 1.0);
        limited += out.limited;
    }
    TEST_ASSERT_TRUE(limited > 100);
    stewart_limits_free(limits);
    stewart_cueing_free(c);
}

static stewart_cueing_input wavy_input(int n) {
    stewart_cueing_input in = rest_input(1e-3);
    in.specific_force[0] += 3 * sin(0.01 * n);
    in.specific_force[1] += 2 * cos(0.013 * n);
    in.angular_velocity[2] = 0.4 * sin(0.007 * n);
    return in;
}

static void test_rollback_and_copy_repeat_the_steps(void) {
    stewart_cueing_options o;
    stewart_cueing_options_default(&o);
    stewart_cueing *c = make(&o), *twin = make(&o);
    stewart_cueing_output a, b;
    for (int n = 0; n < 500; ++n) stewart_cueing_step(c, &(stewart_cueing_input){0}, &a);
    for (int n = 0; n < 500; ++n) {
        stewart_cueing_input in = wavy_input(n);
        TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_cueing_step(c, &in, &a));
    }
    const size_t size = stewart_cueing_state_size(c);
    unsigned char *bytes = malloc(size);
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_cueing_save(c, bytes, size));
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_cueing_copy(twin, c));
    stewart_cueing_input in = wavy_input(500);
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_cueing_step(c, &in, &a));
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_cueing_step(twin, &in, &b));
    TEST_ASSERT_EQUAL_MEMORY(&a, &b, sizeof a);
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_cueing_load(c, bytes, size));
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_cueing_step(c, &in, &b));
    TEST_ASSERT_EQUAL_MEMORY(&a, &b, sizeof a);
    /* bytes of other options are refused */
    stewart_cueing_options other = o;
    other.surge_scale = 0.25;
    stewart_cueing *third = make(&other);
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_cueing_load(third, bytes, size));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_cueing_copy(third, c));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_cueing_load(c, bytes, size - 1));
    free(bytes);
    stewart_cueing_free(third);
    stewart_cueing_free(twin);
    stewart_cueing_free(c);
}

static void test_bad_input_is_refused_and_changes_nothing(void) {
    stewart_cueing_options o;
    stewart_cueing_options_default(&o);
    stewart_cueing *c = make(&o);
    stewart_cueing_output a, b;
    stewart_cueing_input in = wavy_input(3);
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_cueing_step(c, &in, &a));
    unsigned char before[4096];
    TEST_ASSERT_TRUE(stewart_cueing_state_size(c) <= sizeof before);
    stewart_cueing_save(c, before, stewart_cueing_state_size(c));
    stewart_cueing_input bad = in;
    bad.specific_force[1] = NAN;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_cueing_step(c, &bad, &b));
    TEST_ASSERT_NOT_NULL(strstr(stewart_cueing_message(c), "specific_force y"));
    bad = in;
    bad.dt = -1e-3;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_cueing_step(c, &bad, &b));
    TEST_ASSERT_NOT_NULL(strstr(stewart_cueing_message(c), "dt"));
    bad = in;
    bad.angular_velocity[2] = INFINITY;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_cueing_step(c, &bad, &b));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_cueing_step(c, NULL, &b));
    unsigned char after[4096];
    stewart_cueing_save(c, after, stewart_cueing_state_size(c));
    TEST_ASSERT_EQUAL_MEMORY(before, after, stewart_cueing_state_size(c));
    /* a huge but finite input: a refusal or finite numbers, never NaN */
    bad = in;
    bad.specific_force[0] = 1e300;
    if (stewart_cueing_step(c, &bad, &b) == STEWART_OK)
        for (int i = 0; i < 6; ++i)
            TEST_ASSERT_TRUE(isfinite(b.pose.q[i]) && isfinite(b.pose.q_ddot[i]));
    stewart_cueing_free(c);
}

/* Leg speed and acceleration limits are enforced: every output's leg rates and accelerations, from
 * the kinematic inverse solve of the output pose, within them; the limiter acted; the step
 * allocates nothing with the leg limiter at work. */
static void test_leg_limits_are_enforced(void) {
    stewart_params p;
    stewart_params_default(&p);
    for (int k = 0; k < 6; ++k) p.leg_speed_max[k] = 0.05, p.leg_accel_max[k] = 1.0;
    char msg[STEWART_MESSAGE_SIZE];
    stewart_model *m = test_model(&p);
    stewart_cueing_options o;
    stewart_cueing_options_default(&o);
    stewart_cueing *c = stewart_cueing_create(m, &o, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(c, msg);
    const stewart_inverse_options io = test_options(STEWART_KINEMATIC);
    stewart_inverse *inv = test_inverse_with(m, &io);
    int limited = 0;
    double fastest = 0.0;
    const long before = allocations;
    for (int n = 0; n < 3000; ++n) {
        stewart_cueing_input in = wavy_input(n);
        stewart_cueing_output out;
        TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_cueing_step(c, &in, &out));
        stewart_inverse_input ii = {out.pose};
        stewart_inverse_output io_out;
        TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_inverse_solve(inv, &ii, &io_out));
        for (int k = 0; k < 6; ++k) {
            TEST_ASSERT_TRUE(fabs(io_out.lengths.length_rate[k]) <= 0.05);
            TEST_ASSERT_TRUE(fabs(io_out.lengths.length_accel[k]) <= 1.0);
            fastest = fmax(fastest, fabs(io_out.lengths.length_rate[k]));
        }
        TEST_ASSERT_EQUAL_INT(0, out.leg_limits);
        limited += out.limited;
    }
    TEST_ASSERT_EQUAL_INT(before, allocations);
    TEST_ASSERT_TRUE(limited > 0 && fastest > 0.04);
    stewart_inverse_free(inv);
    stewart_cueing_free(c);
    stewart_model_free(m);
}

static void test_a_step_allocates_nothing(void) {
    stewart_cueing_options o;
    stewart_cueing_options_default(&o);
    o.surge_scale = 2.0;
    stewart_cueing *c = make(&o);
    stewart_cueing_output out;
    stewart_cueing_input in = wavy_input(0);
    stewart_cueing_step(c, &in, &out);
    const long before = allocations;
    for (int n = 0; n < 3000; ++n) {
        in = wavy_input(n);
        in.dt = n % 7 ? 1e-3 : 2e-3; /* a new dt makes the filters' steps again */
        TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_cueing_step(c, &in, &out));
    }
    TEST_ASSERT_EQUAL_INT(before, allocations);
    stewart_cueing_free(c);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_options_are_refused_by_name);
    RUN_TEST(test_option_table_ranges);
    RUN_TEST(test_home_beyond_a_limit_is_refused);
    RUN_TEST(test_rest_stays_at_home);
    RUN_TEST(test_surge_step_against_its_closed_form);
    RUN_TEST(test_roll_rate_step_against_its_closed_form);
    RUN_TEST(test_tilt_coordination_settles_and_respects_its_rate);
    RUN_TEST(test_limiter_keeps_every_sample_within_the_limits);
    RUN_TEST(test_rollback_and_copy_repeat_the_steps);
    RUN_TEST(test_bad_input_is_refused_and_changes_nothing);
    RUN_TEST(test_a_step_allocates_nothing);
    RUN_TEST(test_leg_limits_are_enforced);
    return UNITY_END();
}
