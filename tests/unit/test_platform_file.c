/* Platform files (stewart/stewart_platform_file.h, docs/geometry.md): a good file sets exactly
 * its fields; every bad one is refused naming the field (and where), with the parameters left as
 * they were; the shipped files (platforms/) build models whose home lengths match the joints;
 * numbers read the same under a decimal-comma locale; units and strokes as neutral +- travel. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "stewart/stewart_check.h"
#include "stewart/stewart_platform_file.h"
#include "stewart/stewart_table.h"
#include "decimal_comma.h"
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
    TEST_ASSERT_EQUAL_INT_MESSAGE(
        STEWART_OK, stewart_params_read_json(&p, text, strlen(text), given, msg, sizeof msg), msg);
    expected.payload_mass = 12.5;
    expected.gravity[2] = -9.80665;
    for (int k = 0; k < 6; ++k)
        expected.stroke_min[k] = 0.35, expected.stroke_max[k] = 0.7 + 0.01 * k;
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
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_ERR_PARAMETER, read_text(&p, text, msg, sizeof msg),
                                  text);
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
    expect_refused("{\"description\": \"5 \xB5m\", \"payload_mass\": 1}",
                   "line 1 column 20: a platform file is UTF-8");
    expect_refused("{\"description\": \"\xC0\xAF\"}", "is UTF-8");
    expect_refused("{\"base_joint[19]\": 1}", "no parameter is named 'base_joint[19]'");
    /* the line and column of the field */
    expect_refused("{\n  \"home_height\": 0.5,\n  \"payload_mass\": -2\n}",
                   "line 3 column 3: payload_mass");
    /* joints: only with geometry 1, and then both sides */
    char joints[1024], line[64];
    strcpy(joints, "{\"base_joint\": [");
    for (int i = 0; i < 18; ++i)
        snprintf(line, sizeof line, "%s%d", i ? ", " : "", i), strcat(joints, line);
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
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK,
                                  stewart_params_read_json(p, text, n, NULL, msg, sizeof msg), msg);
}

/* Each shipped platform builds a model; at home its lengths are |(0, 0, h) + b_k - a_k| of the
 * file's joints and its massless forces hold the platform up (their vertical sum is its weight
 * for massless legs). The thesis file gives the default model's kinematic outputs bit for bit. */
static void test_shipped_platforms(void) {
    const char *names[] = {"thesis.json", "paired_hexapod.json", "genhexkins.json",
                           "non_planar.json"};
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
                const double c = p.platform_joint[3 * k + i] + (i == 2 ? p.home_height : 0) -
                                 p.base_joint[3 * k + i];
                d2 += c * c;
            }
            TEST_ASSERT_DOUBLE_WITHIN(1e-15, sqrt(d2), out.lengths.length[k]);
            TEST_ASSERT_TRUE_MESSAGE(out.lengths.length[k] > p.stroke_min[k] &&
                                         out.lengths.length[k] < p.stroke_max[k],
                                     names[n]);
        }
        TEST_ASSERT_DOUBLE_WITHIN(1e-9 * p.platform_mass * 9.81, -p.platform_mass * p.gravity[2],
                                  -out.base_force[2]);
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


/* Every element once, whatever the spelling; with geometry 1 every joint coordinate. */
static void test_an_element_given_twice_or_joints_in_part_are_refused(void) {
    expect_refused("{\"gravity\": [0, 0, -9.81],\n \"gravity[3]\": -9.8}",
                   "line 2 column 2: gravity[3] is given twice: by \"gravity\" at line 1 and by "
                   "\"gravity[3]\"");
    expect_refused(
        "{\"stroke_min[2]\": 0.41, \"stroke_min\": 0.4}",
        "stroke_min[2] is given twice: by \"stroke_min[2]\" at line 1 and by \"stroke_min\"");
    expect_refused("{\"stroke_min\": 0.4, \"stroke_min[2]\": 0.41}",
                   "by \"stroke_min\" at line 1 and by \"stroke_min[2]\"");
    expect_refused(
        "{\"geometry\": 1, \"base_joint[1]\": 0.6, \"platform_joint[1]\": 0.45}",
        "geometry = 1 and only some of base_joint: base_joint[2] and 16 more are missing");
    char text[2048], item[64];
    strcpy(text, "{\"geometry\": 1, \"base_joint\": [");
    for (int i = 0; i < 18; ++i)
        snprintf(item, sizeof item, "%s%d", i ? ", " : "", i), strcat(text, item);
    strcat(text, "]");
    for (int i = 0; i < 17; ++i)
        snprintf(item, sizeof item, ", \"platform_joint[%d]\": %d", i + 1, i), strcat(text, item);
    strcat(text, "}");
    expect_refused(text, "only some of platform_joint: platform_joint[18] is missing");
}

/* A file in mm and deg, inline or file-wide, gives the very doubles of the file in m and rad: the
 * decimal prefix moves the exponent (12.5 mm reads as 0.0125 does), and deg converts as the
 * table's STEWART_DEG. */
static void test_units_give_the_si_file(void) {
    char si[1024];
    snprintf(si, sizeof si,
             "{\"base_radius\": 0.0125, \"platform_radius\": 0.011, \"home_height\": 0.0175,"
             " \"base_angle\": [0, %.17g, %.17g, %.17g, %.17g, %.17g],"
             " \"stroke_min\": 0.015, \"stroke_max\": 0.021, \"payload_com[3]\": 2.5e-3,"
             " \"base_joint_limit\": %.17g, \"gravity[3]\": -9.81, \"payload_mass\": 3}",
             STEWART_DEG(30.0), STEWART_DEG(120.0), STEWART_DEG(150.0), STEWART_DEG(240.0),
             STEWART_DEG(270.0), STEWART_DEG(40.0));
    const char *inline_units = "{\"base_radius\": \"12.5 mm\", \"platform_radius\": \"11mm\", "
                               "\"home_height\": \"1.75 cm\","
                               " \"base_angle\": [\"0 deg\", \"30 deg\", \"120 deg\", \"150 deg\", "
                               "\"240 deg\", \"270 deg\"],"
                               " \"stroke_min\": \"15000 um\", \"stroke_max\": \"0.021 m\", "
                               "\"payload_com[3]\": \"2.5 mm\","
                               " \"base_joint_limit\": \"40 deg\", \"gravity[3]\": \"-9.81 m/s2\", "
                               "\"payload_mass\": \"3 kg\"}";
    const char *file_units =
        "{\"units\": {\"length\": \"mm\", \"angle\": \"deg\"}, \"base_radius\": 12.5,"
        " \"platform_radius\": 11, \"home_height\": 17.5, \"base_angle\": [0, 30, 120, 150, 240, "
        "270],"
        " \"stroke_min\": 15, \"stroke_max\": 21e0, \"payload_com[3]\": 0.25e1,"
        " \"base_joint_limit\": 40, \"gravity[3]\": -9.81, \"payload_mass\": 3}";
    stewart_params a, b, c;
    char msg[STEWART_MESSAGE_SIZE];
    stewart_params_default(&a), stewart_params_default(&b), stewart_params_default(&c);
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, read_text(&a, si, msg, sizeof msg), msg);
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, read_text(&b, inline_units, msg, sizeof msg), msg);
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, read_text(&c, file_units, msg, sizeof msg), msg);
    TEST_ASSERT_EQUAL_DOUBLE(0.0125, a.base_radius);
    TEST_ASSERT_EQUAL_MEMORY(&a, &b, sizeof a);
    TEST_ASSERT_EQUAL_MEMORY(&a, &c, sizeof a);
    /* the angles against the table's own degrees, and a length in inches (0.0254 m exactly) */
    TEST_ASSERT_EQUAL_DOUBLE(STEWART_DEG(150.0), c.base_angle[3]);
    stewart_params d;
    stewart_params_default(&d);
    TEST_ASSERT_EQUAL_INT_MESSAGE(
        STEWART_OK,
        read_text(&d, "{\"units\": {\"length\": \"in\"}, \"home_height\": 20}", msg, sizeof msg),
        msg);
    TEST_ASSERT_DOUBLE_WITHIN(1e-16, 0.508, d.home_height);
    expect_refused("{\"home_height\": \"0.5 kg\"}",
                   "kg is not a unit of home_height [m]; write it in m, cm, mm");
    expect_refused("{\"home_height\": \"0.5\"}", "must be a number, or a number and its unit");
    expect_refused("{\"payload_mass\": \"3 g\"}",
                   "g is not a unit of payload_mass [kg]; write it in kg");
    expect_refused("{\"units\": {\"length\": \"furlong\"}}",
                   "units.length = \"furlong\" is not a unit of length: one of m, cm");
    expect_refused("{\"units\": {\"mass\": \"g\"}}",
                   "units.mass: a file gives the units of \"length\" and \"angle\" only");
    expect_refused("{\"units\": \"mm\"}", "units = \"mm\" must be an object");
    /* micro in UTF-8, and a leading byte-order mark (as some editors write) */
    stewart_params e;
    stewart_params_default(&e);
    const char *micro =
        "\xEF\xBB\xBF{\"description\": \"\xC2\xB5\", \"payload_com[3]\": \"2500 \xC2\xB5m\"}";
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, read_text(&e, micro, msg, sizeof msg), msg);
    TEST_ASSERT_EQUAL_DOUBLE(a.payload_com[2], e.payload_com[2]);
    expect_refused("{\"units\": {\"length\": \"mm\"}, \"stroke_min\": -4}",
                   "stroke_min[1] = -0.004 m must be > 0 (the file's -4)");
    expect_refused("{\"home_height\": \"1e400 mm\"}",
                   "home_height = 1e400 mm is not a finite double");
}

/* stroke_neutral +- stroke_travel, scalar or per leg, is stroke_min and stroke_max; never both forms. */
static void test_strokes_as_neutral_and_travel(void) {
    stewart_params p;
    char msg[STEWART_MESSAGE_SIZE];
    unsigned char given[256];
    stewart_params_default(&p);
    const char *text = "{\"units\": {\"length\": \"mm\"}, \"stroke_neutral\": 550,"
                       " \"stroke_travel\": [150, 150, 150, 150, 150, 140]}";
    TEST_ASSERT_EQUAL_INT_MESSAGE(
        STEWART_OK, stewart_params_read_json(&p, text, strlen(text), given, msg, sizeof msg), msg);
    for (int k = 0; k < 6; ++k) {
        const double travel = k == 5 ? 0.14 : 0.15;
        TEST_ASSERT_DOUBLE_WITHIN(1e-16, 0.55 - travel, p.stroke_min[k]);
        TEST_ASSERT_DOUBLE_WITHIN(1e-16, 0.55 + travel, p.stroke_max[k]);
    }
    TEST_ASSERT_EQUAL_INT(1, given[stewart_param_find("stroke_min[1]", NULL)]);
    TEST_ASSERT_EQUAL_INT(1, given[stewart_param_find("stroke_max[1]", NULL)]);
    expect_refused(
        "{\"stroke_min\": 0.4, \"stroke_neutral\": 0.55, \"stroke_travel\": 0.1}",
        "the strokes are given twice, as \"stroke_min\" (line 1) and as \"stroke_neutral\"");
    expect_refused("{\"stroke_neutral\": 0.55}", "but not stroke_travel[1]");
    expect_refused("{\"stroke_neutral\": 0.55, \"stroke_travel[2]\": 0.1}",
                   "but not stroke_travel[1]");
    expect_refused("{\"stroke_neutral\": 0.55, \"stroke_travel\": [0.1, 0.1, 0, 0.1, 0.1, 0.1]}",
                   "stroke_travel[3] = 0 m must be > 0");
    expect_refused("{\"stroke_neutral\": 0.55, \"stroke_travel\": 0.6}",
                   "stroke_neutral[1] - stroke_travel[1]: stroke_min[1] = -0.0");
    expect_refused("{\"stroke_neutral\": 0.55, \"stroke_travel\": 0.1, \"stroke_travel[2]\": 0.1}",
                   "stroke_travel[2] is given twice");
}

/* Under a decimal-comma locale (de_DE: "12,5") the reader reads "12.5" as 12.5, not 12: every
 * shipped file gives the parameters it gives under "C". */
static void test_numbers_read_the_same_in_every_locale(void) {
    const char *names[] = {"thesis.json", "paired_hexapod.json", "genhexkins.json",
                           "non_planar.json"};
    stewart_params in_c[4];
    for (int n = 0; n < 4; ++n) read_shipped(names[n], &in_c[n]);
    TEST_ASSERT_TRUE_MESSAGE(
        use_decimal_comma(STEWART_TEST_LOCALE_DIR),
        "no de_DE.UTF-8 locale, and localedef could not build one (Debian: locales)");
    stewart_params p;
    char msg[STEWART_MESSAGE_SIZE];
    stewart_params_default(&p);
    const char *text =
        "{\"payload_mass\": 12.5, \"gravity[3]\": -9.81, \"home_height\": \"512.5 mm\"}";
    const stewart_status s = read_text(&p, text, msg, sizeof msg);
    for (int n = 0; n < 4; ++n) {
        stewart_params q;
        read_shipped(names[n], &q);
        TEST_ASSERT_EQUAL_MEMORY_MESSAGE(&in_c[n], &q, sizeof q, names[n]);
    }
    use_decimal_point();
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, s, msg);
    TEST_ASSERT_EQUAL_DOUBLE(12.5, p.payload_mass);
    TEST_ASSERT_EQUAL_DOUBLE(-9.81, p.gravity[2]);
    TEST_ASSERT_EQUAL_DOUBLE(0.5125, p.home_height);
}

/* Only regular files are read, at once (a FIFO without a writer does not block), up to the cap. */
static void expect_file_refused(const char *path, const char *words) {
    stewart_params p;
    char msg[STEWART_MESSAGE_SIZE];
    stewart_params_default(&p);
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_ERR_PARAMETER,
                                  stewart_params_read_json_file(&p, path, NULL, msg, sizeof msg),
                                  path);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, words), msg);
}

static void test_only_regular_files_of_at_most_the_cap(void) {
    char dir[] = "/tmp/stewart-platform-file-XXXXXX", path[128];
    TEST_ASSERT_NOT_NULL(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/fifo", dir);
    TEST_ASSERT_EQUAL_INT(0, mkfifo(path, 0600));
    expect_file_refused(path, "is a FIFO: a platform file is a regular file");
    unlink(path);
    expect_file_refused("/dev/zero", "is a device");
    expect_file_refused(dir, "is a directory");
    snprintf(path, sizeof path, "%s/missing.json", dir);
    expect_file_refused(path, "cannot open the file: No such file or directory");
    /* one byte over the cap, and a file of exactly the cap (spaces after the object) */
    snprintf(path, sizeof path, "%s/big.json", dir);
    for (int over = 1; over >= 0; --over) {
        FILE *f = fopen(path, "wb");
        TEST_ASSERT_NOT_NULL(f);
        const char *head = "{\"payload_mass\": 2}";
        fputs(head, f);
        for (size_t i = strlen(head); i < STEWART_PLATFORM_FILE_MAX_BYTES + (size_t)over; ++i)
            fputc(' ', f);
        fclose(f);
        stewart_params p;
        char msg[STEWART_MESSAGE_SIZE];
        stewart_params_default(&p);
        const stewart_status s = stewart_params_read_json_file(&p, path, NULL, msg, sizeof msg);
        if (over) {
            TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER, s);
            TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "larger than 1048576 bytes"), msg);
        } else {
            TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, s, msg);
            TEST_ASSERT_EQUAL_DOUBLE(2.0, p.payload_mass);
        }
    }
    unlink(path);
    rmdir(dir);
}

/* The units a file writes in: "units" first, else the one unit of its values; every unit's
 * factor from SI is the inverse of its factor to SI (the reader's), "in" and "deg" too. */
static void test_the_units_a_file_writes_in(void) {
    const char *files[][3] = {
        {"{\"units\": {\"length\": \"um\"}, \"stroke_max\": \"0.7 m\", \"axis_max[4]\": \"1 deg\"}",
         "um", "deg"},
        {"{\"stroke_min\": \"400 mm\", \"stroke_max\": [\"0.6 m\", 0.6, 0.6, 0.6, 0.6, 0.6]}", "",
         ""},
        {"{\"description\": \"12 mm\", \"stroke_min\": [\"400 mm\", 0.4, 0.4, 0.4, 0.4, 0.4]}",
         "mm", ""},
        {"{\"payload_mass\": 3}", "", ""},
    };
    char dir[] = "/tmp/stewart-file-units-XXXXXX", path[128];
    TEST_ASSERT_NOT_NULL(mkdtemp(dir));
    snprintf(path, sizeof path, "%s/p.json", dir);
    for (size_t i = 0; i < sizeof files / sizeof files[0]; ++i) {
        FILE *f = fopen(path, "wb");
        TEST_ASSERT_NOT_NULL(f);
        fputs(files[i][0], f);
        fclose(f);
        stewart_file_units units;
        char msg[STEWART_MESSAGE_SIZE];
        TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK,
                                      stewart_platform_file_units(path, &units, msg, sizeof msg),
                                      msg);
        TEST_ASSERT_EQUAL_STRING_MESSAGE(files[i][1], units.length, files[i][0]);
        TEST_ASSERT_EQUAL_STRING_MESSAGE(files[i][2], units.angle, files[i][0]);
    }
    unlink(path);
    stewart_file_units units;
    char msg[STEWART_MESSAGE_SIZE];
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                          stewart_platform_file_units(dir, &units, msg, sizeof msg));
    rmdir(dir);
    double per_si = 0;
    TEST_ASSERT_EQUAL_STRING("m", stewart_unit_per_si("in", &per_si));
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 1 / 0.0254, per_si);
    TEST_ASSERT_EQUAL_STRING("rad", stewart_unit_per_si("deg", &per_si));
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 180.0 / 3.14159265358979323846, per_si);
    TEST_ASSERT_EQUAL_STRING("m", stewart_unit_per_si("\xC2\xB5m", &per_si));
    TEST_ASSERT_EQUAL_DOUBLE(1e6, per_si);
    TEST_ASSERT_NULL(stewart_unit_per_si("inch", &per_si));
    TEST_ASSERT_NULL(stewart_unit_per_si(NULL, &per_si));
    /* the check's text in those units; a name of the wrong kind gives no text */
    stewart_params p;
    stewart_params_default(&p);
    stewart_model *model = stewart_model_create(&p, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(model, msg);
    stewart_check_report report;
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK,
                                  stewart_check_home(model, NULL, &report, msg, sizeof msg), msg);
    stewart_model_free(model);
    char text[4096] = "x";
    TEST_ASSERT_EQUAL_size_t(0, stewart_check_text_in(&report, "deg", NULL, text, sizeof text));
    TEST_ASSERT_EQUAL_STRING("", text);
    TEST_ASSERT_EQUAL_size_t(0, stewart_check_text_in(&report, NULL, "mm", text, sizeof text));
    TEST_ASSERT_TRUE(stewart_check_text_in(&report, "mm", "urad", text, sizeof text) < sizeof text);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(text, "z 500 mm, roll 0 urad"), text);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(text, "length [mm]"), text);
}

/* A file of the cap, 1 MiB of fields, its first one unknown: the error is the first field's (at
 * line 1), after reading every field once (each field's name checked against those before it in
 * a hash set, so the reading is linear in the fields). */
static void test_a_large_file_reports_its_first_error(void) {
    const size_t cap = STEWART_PLATFORM_FILE_MAX_BYTES;
    char *text = malloc(cap + 1);
    TEST_ASSERT_NOT_NULL(text);
    size_t n = (size_t)snprintf(text, cap, "{\"payload_mas\": 1");
    int fields = 1;
    while (n + 32 < cap)
        n += (size_t)snprintf(text + n, cap - n, ",\"f%d\": %d", fields, fields), ++fields;
    n += (size_t)snprintf(text + n, cap - n, "}");
    TEST_ASSERT_TRUE(fields > 50000);
    stewart_params p;
    char msg[STEWART_MESSAGE_SIZE];
    stewart_params_default(&p);
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                          stewart_params_read_json(&p, text, n, NULL, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg,
                                        "line 1 column 2: no parameter is named 'payload_mas'"),
                                 msg);
    /* the same field names twice: found at the second */
    n = (size_t)snprintf(text, cap, "{\"f1\": 1");
    for (int i = 2; n + 32 < cap; ++i)
        n += (size_t)snprintf(text + n, cap - n, ",\"f%d\": %d", i, i);
    n += (size_t)snprintf(text + n, cap - n, ",\"f1\": 2}");
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER,
                          stewart_params_read_json(&p, text, n, NULL, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "\"f1\" is given twice"), msg);
    free(text);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_a_good_file_sets_its_fields_only);
    RUN_TEST(test_bad_files_are_refused_by_field);
    RUN_TEST(test_shipped_platforms);
    RUN_TEST(test_an_element_given_twice_or_joints_in_part_are_refused);
    RUN_TEST(test_units_give_the_si_file);
    RUN_TEST(test_strokes_as_neutral_and_travel);
    RUN_TEST(test_numbers_read_the_same_in_every_locale);
    RUN_TEST(test_only_regular_files_of_at_most_the_cap);
    RUN_TEST(test_a_large_file_reports_its_first_error);
    RUN_TEST(test_the_units_a_file_writes_in);
    return UNITY_END();
}
