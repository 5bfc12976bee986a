/* Machines refused when the model is made, naming why: geometries singular at every pose (a side's
 * six joints at one point or on one line: the platform turns about it with no leg changing
 * length, which the test shows with the closed-form lengths), and values far past any machine
 * (joints of 1e300 m or 1e-300 m, home_height = 1e308, gravity[3] = 1e308), each named by its
 * field and magnitude instead of a consequence ("legs 1 and 2 are one leg", a pose input). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "stewart/stewart_platform_file.h"
#include "stewart/stewart_table.h"
#include "test_support.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

/* The thesis platform as joints (geometry 1). */
static stewart_params thesis_joints(void) {
    stewart_params p;
    stewart_params_default(&p);
    p.geometry = 1;
    return p;
}

static void expect_model_refused(const stewart_params *p, const char *words) {
    char msg[STEWART_MESSAGE_SIZE];
    stewart_model *m = stewart_model_create(p, msg, sizeof msg);
    if (m) stewart_model_free(m);
    TEST_ASSERT_NULL_MESSAGE(m, words);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, words), msg);
}

static void expect_model_made(const stewart_params *p) {
    stewart_model *m = test_model(p);
    stewart_model_free(m);
}

/* The largest change of any leg's length between two poses (closed form). */
static double length_change(const stewart_params *p, const stewart_pose *a, const stewart_pose *b) {
    double change = 0;
    for (int k = 0; k < 6; ++k)
        change = fmax(change, fabs(closed_form_length(p, a, k) - closed_form_length(p, b, k)));
    return change;
}

/* p' = c + Rz(phi) (p - c), yaw + phi: the platform turned by phi about the vertical line through c
 * (base frame), from a pose with roll = pitch = 0 or not (Rz(phi) Rz Ry Rx = Rz(yaw + phi) Ry Rx). */
static stewart_pose turned_about_base_line(const stewart_pose *q, const double c[2], double phi) {
    stewart_pose t = *q;
    const double x = q->q[0] - c[0], y = q->q[1] - c[1];
    t.q[0] = c[0] + cos(phi) * x - sin(phi) * y;
    t.q[1] = c[1] + sin(phi) * x + cos(phi) * y;
    t.q[5] += phi;
    return t;
}

static void test_base_joints_at_one_point_or_on_a_line(void) {
    const stewart_pose pose = {{0.02, -0.01, 0.55, 0.1, -0.05, 0.2}, {0}, {0}};
    const double c[2] = {0.1, 0.05};
    stewart_params p = thesis_joints();
    for (int k = 0; k < 6; ++k)
        p.base_joint[3 * k] = c[0], p.base_joint[3 * k + 1] = c[1], p.base_joint[3 * k + 2] = 0;
    expect_model_refused(&p, "base_joint: the six base joints are at one point, (0.1, 0.05, 0) m");
    stewart_pose turned = turned_about_base_line(&pose, c, 0.3);
    TEST_ASSERT_DOUBLE_WITHIN(1e-14, 0.0, length_change(&p, &pose, &turned));
    /* on the vertical line through c, at six heights */
    for (int k = 0; k < 6; ++k) p.base_joint[3 * k + 2] = 0.02 * k;
    expect_model_refused(
        &p, "base_joint: the six base joints lie on one line, through (0.1, 0.05, 0.05) m along "
            "(0, 0, 1) (base frame): the platform turns freely about it at every pose");
    turned = turned_about_base_line(&pose, c, -0.4);
    TEST_ASSERT_DOUBLE_WITHIN(1e-14, 0.0, length_change(&p, &pose, &turned));
    /* off the line by 1 mm: no longer singular everywhere, made */
    p.base_joint[0] += 1e-3;
    p.base_joint[3] += 1e-3; /* legs 1 and 2 apart from legs 3..6, with Cardan axes off z */
    for (int k = 0; k < 6; ++k) p.base_cardan_axis[3 * k] = 1;
    expect_model_made(&p);
    TEST_ASSERT_TRUE(length_change(&p, &pose, &turned) > 1e-6);
}

static void test_platform_joints_on_a_line(void) {
    stewart_params p = thesis_joints();
    /* along x of the platform frame through (0, 0.05, -0.1) */
    for (int k = 0; k < 6; ++k)
        p.platform_joint[3 * k] = 0.1 * k - 0.25, p.platform_joint[3 * k + 1] = 0.05,
                             p.platform_joint[3 * k + 2] = -0.1;
    expect_model_refused(&p, "platform_joint: the six platform joints lie on one line");
    /* geometry 0: six base angles alike put the six joints at one point */
    stewart_params q;
    stewart_params_default(&q);
    for (int k = 0; k < 6; ++k) q.base_angle[k] = 0.5;
    expect_model_refused(&q, "base_radius, base_angle: the six base joints are at one point");
}

/* A file of the thesis' joints times scale (and its other fields as given). */
static stewart_status read_scaled(double scale, const char *extra, stewart_params *p, char *msg,
                                  size_t size) {
    char text[4096];
    size_t n = (size_t)snprintf(text, sizeof text, "{\"geometry\": 1%s", extra);
    stewart_params d;
    stewart_params_default(&d);
    for (int side = 0; side < 2; ++side) {
        n += (size_t)snprintf(text + n, sizeof text - n, ", \"%s\": [",
                              side ? "platform_joint" : "base_joint");
        for (int i = 0; i < 18; ++i)
            n += (size_t)snprintf(text + n, sizeof text - n, "%s%.17g", i ? ", " : "",
                                  scale * (side ? d.platform_joint[i] : d.base_joint[i]));
        n += (size_t)snprintf(text + n, sizeof text - n, "]");
    }
    snprintf(text + n, sizeof text - n, "}");
    stewart_params_default(p);
    return stewart_params_read_json(p, text, strlen(text), NULL, msg, size);
}

static void test_magnitudes_past_any_machine_are_named(void) {
    struct {
        double scale;
        const char *extra, *words;
    } cases[] = {
        {1e300, "",
         "base_joint[1] = 5e+299 m is beyond any machine: its magnitude must be at most 1e+06 m"},
        {1e-300, "", "base_joint: every base joint is within 5e-301 m of its frame's origin"},
        {1.0, ", \"home_height\": 1e308", "home_height = 1e+308 m is beyond any machine"},
        {1.0, ", \"gravity[3]\": 1e308",
         "gravity[3] = 1e+308 m/s2 is beyond any machine: its magnitude must be at most 10000 "
         "m/s2"},
        {1.0, ", \"gravity[3]\": -9.81", NULL},
        {2e3, ", \"home_height\": 1e3, \"stroke_max\": 2e3", NULL}, /* a 1 km machine is made */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        stewart_params p;
        char msg[STEWART_MESSAGE_SIZE];
        TEST_ASSERT_EQUAL_INT_MESSAGE(
            STEWART_OK, read_scaled(cases[i].scale, cases[i].extra, &p, msg, sizeof msg), msg);
        if (cases[i].words) expect_model_refused(&p, cases[i].words);
        else expect_model_made(&p);
    }
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_base_joints_at_one_point_or_on_a_line);
    RUN_TEST(test_platform_joints_on_a_line);
    RUN_TEST(test_magnitudes_past_any_machine_are_named);
    return UNITY_END();
}
