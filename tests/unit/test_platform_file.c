/* Platform files (stewart/stewart_platform_file.h, docs/geometry.md): a good file sets exactly
 * its fields; every bad one is refused naming the field (and where), with the parameters left as
 * they were; the shipped files (platforms/) build models whose home lengths match the joints. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "stewart/stewart_platform_file.h"
#include "stewart/stewart_table.h"
#include "test_support.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

static stewart_status read_text(stewart_params *p, const char *text, char *msg, size_t size) {
    return stewart_params_read_json(p, text, strlen(text), NULL, msg, size);
}

static void test_a_good_file_sets_its_fields_only(void) {
    stewart_params p, expected;
    stewart_params_default(&p);
    stewart_params_default(&expected);
    const char *text =
        "{\n  \"description\": \"a \\\"test\\\" platform\",\n  \"payload_mass\": 12.5,\n"
        "  \"gravity\": [0, 0, -9.80665],\n  \"stroke_min\": 0.35,\n"
        "  \"stroke_max\": [0.7, 0.71, 0.72, 0.73, 0.74, 0.75], \"platform_com[3]\": -1e-2\n}\n";
    char msg[STEWART_MESSAGE_SIZE];
    unsigned char given[256];
    TEST_ASSERT_TRUE(stewart_param_count() <= 256);
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_params_read_json(&p, text, strlen(text), given, msg, sizeof msg), msg);
    expected.payload_mass = 12.5;
    expected.gravity[2] = -9.80665;
    for (int k = 0; k < 6; ++k) expected.stroke_min[k] = 0.35, expected.stroke_max[k] = 0.7 + 0.01 * k;
    expected.platform_com[2] = -1e-2;
    TEST_ASSERT_EQUAL_MEMORY(&expected, &p, sizeof p);
    int count = 0;
    for (int i = 0; i < stewart_param_count(); ++i) count += given[i];
    TEST_ASSERT_EQUAL_INT(5, count);
    TEST_ASSERT_EQUAL_INT(1, given[stewart_param_find("payload_mass", NULL)]);
}

/* Each bad file: refused, the message holds `words`, p unchanged. */
static void expect_refused(const char *text, const char *words) {
    stewart_params p, before;
    stewart_params_default(&p);
    before = p;
    char msg[STEWART_MESSAGE_SIZE];
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_ERR_PARAMETER, read_text(&p, text, msg, sizeof msg), text);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, words), msg);
    TEST_ASSERT_EQUAL_MEMORY(&before, &p, sizeof p);
}

static void test_bad_files_are_refused_by_field(void) {
    expect_refused("", "expected '{'");
    expect_refused("[1, 2]", "expected '{'");
    expect_refused("{\"payload_mass\": 1", "after the value of \"payload_mass\"");
    expect_refused("{\"payload_mass\": 1} x", "after the object");
    expect_refused("{\"payload_mas\": 1}", "nearest is payload_mass");
    expect_refused("{\"payload_mass\": -1}", "payload_mass = -1");
    expect_refused("{\"payload_mass\": \"heavy\"}", "payload_mass = \"heavy\" must be a number");
    expect_refused("{\"payload_mass\": true}", "payload_mass: expected a number");
    expect_refused("{\"payload_mass\": NaN}", "payload_mass: expected a number");
    expect_refused("{\"payload_mass\": 1e999}", "payload_mass = 1e999 is not a finite double");
    expect_refused("{\"payload_mass\": 01}", "after the value of \"payload_mass\"");
    expect_refused("{\"payload_mass\": [1]}", "payload_mass = [1] must be one number");
    expect_refused("{\"gravity\": [0, 0]}", "gravity has 2 values: it needs 3");
    expect_refused("{\"gravity\": 9.81}", "gravity = 9.81 must be a list of its 3 values");
    expect_refused("{\"gravity\": [0, [0], 1]}", "gravity: a list holds numbers only");
    expect_refused("{\"gravity\": [0, null, 1]}", "gravity[2]: expected a number");
    expect_refused("{\"gravity\": {\"z\": 1}}", "gravity: objects are not values here");
    expect_refused("{\"stroke_min\": [0.4, 0.4, 0.4, 0.4, 0.4, -0.4]}", "stroke_min[6] = -0.4");
    expect_refused("{\"payload_mass\": 1, \"payload_mass\": 2}", "\"payload_mass\" is given twice");
    expect_refused("{\"description\": 3}", "description = 3 must be a string");
    expect_refused("{\"pay\\nload\": 1}", "only the escapes");
    expect_refused("{\"base_joint[19]\": 1}", "no parameter is named 'base_joint[19]'");
    /* the line and column of the field */
    expect_refused("{\n  \"home_height\": 0.5,\n  \"payload_mass\": -2\n}", "line 3 column 3: payload_mass");
    /* joints: only with geometry 1, and then both sides */
    char joints[1024], line[64];
    strcpy(joints, "{\"base_joint\": [");
    for (int i = 0; i < 18; ++i) snprintf(line, sizeof line, "%s%d", i ? ", " : "", i), strcat(joints, line);
    strcat(joints, "]}");
    expect_refused(joints, "gives base_joint but not geometry = 1");
    expect_refused("{\"geometry\": 1}", "not base_joint");
    joints[strlen(joints) - 1] = '\0';
    strcat(joints, ", \"geometry\": 1}");
    expect_refused(joints, "not platform_joint");
}

#ifndef STEWART_PLATFORMS_DIR
#error "STEWART_PLATFORMS_DIR: the platforms/ folder"
#endif

/* A shipped file, read whole. */
static void read_shipped(const char *name, stewart_params *p) {
    char path[512], text[16384], msg[STEWART_MESSAGE_SIZE];
    snprintf(path, sizeof path, "%s/%s", STEWART_PLATFORMS_DIR, name);
    FILE *f = fopen(path, "rb");
    TEST_ASSERT_NOT_NULL_MESSAGE(f, path);
    const size_t n = fread(text, 1, sizeof text, f);
    fclose(f);
    TEST_ASSERT_TRUE(n < sizeof text);
    stewart_params_default(p);
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_params_read_json(p, text, n, NULL, msg, sizeof msg), msg);
}

/* Each shipped platform builds a model; at home its lengths are |(0, 0, h) + b_k - a_k| of the
 * file's joints and its massless forces hold the platform up (their vertical sum is its weight
 * for massless legs). The thesis file gives the default model's kinematic outputs bit for bit. */
static void test_shipped_platforms(void) {
    const char *names[] = {"thesis.json", "paired_hexapod.json", "genhexkins.json", "non_planar.json"};
    for (int n = 0; n < 4; ++n) {
        stewart_params p;
        read_shipped(names[n], &p);
        TEST_ASSERT_EQUAL_DOUBLE(1.0, p.geometry);
        stewart_model *m = test_model(&p);
        stewart_inverse *d = test_inverse(m);
        stewart_pose home = {{0, 0, p.home_height, 0, 0, 0}, {0}, {0}};
        stewart_inverse_output out = solve_ok(d, STEWART_MASSLESS, &home);
        for (int k = 0; k < 6; ++k) {
            double d2 = 0;
            for (int i = 0; i < 3; ++i) {
                const double c = p.platform_joint[3 * k + i] + (i == 2 ? p.home_height : 0) - p.base_joint[3 * k + i];
                d2 += c * c;
            }
            TEST_ASSERT_DOUBLE_WITHIN(1e-15, sqrt(d2), out.lengths.length[k]);
            TEST_ASSERT_TRUE_MESSAGE(out.lengths.length[k] > p.stroke_min[k] && out.lengths.length[k] < p.stroke_max[k], names[n]);
        }
        TEST_ASSERT_DOUBLE_WITHIN(1e-9 * p.platform_mass * 9.81, -p.platform_mass * p.gravity[2], -out.base_force[2]);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, out.warnings, names[n]);
        stewart_inverse_free(d);
        stewart_model_free(m);
    }
    stewart_params file, defaults;
    read_shipped("thesis.json", &file);
    stewart_params_default(&defaults);
    stewart_model *mf = test_model(&file), *md = test_model(&defaults);
    stewart_inverse *df = test_inverse(mf), *dd = test_inverse(md);
    for (int n = 0; n < 20; ++n) {
        const stewart_pose pose = combined_pose(0.2 * n);
        const stewart_inverse_output a = solve_ok(df, STEWART_MASSLESS, &pose);
        const stewart_inverse_output b = solve_ok(dd, STEWART_MASSLESS, &pose);
        TEST_ASSERT_EQUAL_MEMORY(&b, &a, sizeof a);
    }
    stewart_inverse_free(df), stewart_inverse_free(dd);
    stewart_model_free(mf), stewart_model_free(md);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_a_good_file_sets_its_fields_only);
    RUN_TEST(test_bad_files_are_refused_by_field);
    RUN_TEST(test_shipped_platforms);
    return UNITY_END();
}
