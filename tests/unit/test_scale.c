/* Issue 15 item 6: "any finite radius". The thesis platform with every length scaled by s from
 * 1 mm to 10 km (masses kept, inertias by s^2) solves home and a tilted pose at the full level
 * with the default options. At rest the forces of similar platforms are the same (statics has no
 * length scale: every moment arm scales alike), so each scale is checked against s = 1, and the
 * full level against the massless one within the legs' weight. Also with the smallest tolerance
 * accepted (2.5e-16), which before the tolerance was relative failed from about 1 m. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "test_support.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

static stewart_params scaled(double s) {
    stewart_params p;
    stewart_params_default(&p);
    p.base_radius *= s, p.platform_radius *= s, p.home_height *= s;
    p.cylinder_com *= s, p.piston_com *= s, p.leg_diameter *= s;
    for (int k = 0; k < 6; ++k) p.stroke_min[k] *= s, p.stroke_max[k] *= s;
    for (int c = 0; c < 3; ++c) {
        p.platform_com[c] *= s, p.payload_com[c] *= s;
        p.platform_inertia[c] *= s * s, p.payload_inertia[c] *= s * s;
        p.cylinder_inertia[c] *= s * s, p.piston_inertia[c] *= s * s;
    }
    return p;
}

static stewart_pose pose_at(double s, int tilted) {
    stewart_pose p = {{0, 0, 0.5 * s, 0, 0, 0}, {0}, {0}};
    if (tilted) {
        p.q[0] = 0.02 * s, p.q[1] = -0.01 * s, p.q[2] = 0.52 * s;
        p.q[3] = 5 * M_PI / 180, p.q[4] = -3 * M_PI / 180, p.q[5] = 4 * M_PI / 180;
    }
    return p;
}

static double tolerance = 1e-12;

static stewart_status solve_at(double s, int tilted, stewart_fidelity f,
                               stewart_inverse_output *out, char *message, size_t size) {
    const stewart_params p = scaled(s);
    stewart_model *m = test_model(&p);
    stewart_inverse *d = test_inverse(m);
    const stewart_pose pose = pose_at(s, tilted);
    stewart_inverse_options o = test_options(f);
    o.tolerance = tolerance;
    const stewart_status status = solve_as(d, &o, &pose, out);
    snprintf(message, size, "scale %g, %s pose, fidelity %d, tolerance %g: %s", s,
             tilted ? "tilted" : "home", (int)f, tolerance, stewart_inverse_message(d));
    stewart_inverse_free(d);
    stewart_model_free(m);
    return status;
}

static void check_scales(void) {
    const double scales[] = {1e-3, 1e-2, 0.1, 1, 10, 100, 1e3, 1e4};
    const stewart_params unit = scaled(1);
    const double legs_weight = 6 * (unit.cylinder_mass + unit.piston_mass) * 9.81;
    char msg[2 * STEWART_MESSAGE_SIZE];
    for (int tilted = 0; tilted <= 1; ++tilted) {
        stewart_inverse_output reference;
        TEST_ASSERT_EQUAL_INT_MESSAGE(
            STEWART_OK, solve_at(1, tilted, STEWART_FULL, &reference, msg, sizeof msg), msg);
        double largest = 0;
        for (int k = 0; k < 6; ++k) largest = fmax(largest, fabs(reference.force[k]));
        for (size_t i = 0; i < sizeof scales / sizeof scales[0]; ++i) {
            stewart_inverse_output full, massless;
            TEST_ASSERT_EQUAL_INT_MESSAGE(
                STEWART_OK, solve_at(scales[i], tilted, STEWART_FULL, &full, msg, sizeof msg), msg);
            TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK,
                                          solve_at(scales[i], tilted, STEWART_MASSLESS, &massless,
                                                   msg, sizeof msg),
                                          msg);
            for (int k = 0; k < 6; ++k) {
                TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-7 * largest, reference.force[k], full.force[k],
                                                  msg);
                TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(legs_weight, massless.force[k], full.force[k],
                                                  msg);
                TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-9 * scales[i],
                                                  0.5 * scales[i] * reference.lengths.length[k] /
                                                      0.5,
                                                  full.lengths.length[k], msg);
            }
        }
    }
}

static void test_full_level_from_1_mm_to_10_km(void) {
    tolerance = 1e-12; /* the default */
    check_scales();
}

/* The tolerance is relative to the platform's size: the smallest accepted one holds at any size. */
static void test_smallest_tolerance_at_every_size(void) {
    tolerance = 2.5e-16;
    check_scales();
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_full_level_from_1_mm_to_10_km);
    RUN_TEST(test_smallest_tolerance_at_every_size);
    return UNITY_END();
}
