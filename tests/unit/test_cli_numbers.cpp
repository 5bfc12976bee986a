// The command-line tools' numbers (--param, pose and length CSVs) read the same under a
// decimal-comma locale (de_DE: "0,5") as under "C": the tools' own reading functions, called with
// LC_NUMERIC set to de_DE, give the values written.
#include <cstdio>
#include <string>

#include "cli/forward_table.hpp"
#include "cli/param_assignment.hpp"
#include "cli/pose_table.hpp"
#include "decimal_comma.h"
#include "stewart/stewart_forward.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) { use_decimal_point(); }

static void test_param_values_read_as_written(void) {
    TEST_ASSERT_TRUE_MESSAGE(
        use_decimal_comma(STEWART_TEST_LOCALE_DIR),
        "no de_DE.UTF-8 locale, and localedef could not build one (Debian: locales)");
    std::string name;
    double value = 0;
    TEST_ASSERT_TRUE(stewart::parse_assignment("test", "payload_mass=12.5", name, value));
    TEST_ASSERT_EQUAL_STRING("payload_mass", name.c_str());
    TEST_ASSERT_EQUAL_DOUBLE(12.5, value);
    TEST_ASSERT_TRUE(stewart::parse_assignment("test", "gravity[3]=-9.81e0", name, value));
    TEST_ASSERT_EQUAL_DOUBLE(-9.81, value);
    TEST_ASSERT_TRUE(stewart::parse_assignment("test", "x=+0.25", name, value));
    TEST_ASSERT_EQUAL_DOUBLE(0.25, value);
    TEST_ASSERT_FALSE(stewart::parse_assignment("test", "x=0,25", name, value));
    TEST_ASSERT_FALSE(stewart::parse_assignment("test", "x=", name, value));
    TEST_ASSERT_FALSE(stewart::parse_assignment("test", "x=1.5.", name, value));
}

static void test_csv_rows_read_as_written(void) {
    const std::string dir = STEWART_TEST_LOCALE_DIR;
    const std::string poses = dir + "/cli_numbers_poses.csv",
                      lengths = dir + "/cli_numbers_lengths.csv";
    TEST_ASSERT_TRUE_MESSAGE(
        use_decimal_comma(STEWART_TEST_LOCALE_DIR),
        "no de_DE.UTF-8 locale, and localedef could not build one (Debian: locales)");
    FILE *f = std::fopen(poses.c_str(), "w");
    TEST_ASSERT_NOT_NULL(f);
    std::fputs("t,x,y,z,roll,pitch,yaw\n0,0.0125,0,0.5,0,0,0\n0.1, 0.0125 ,0,0.51,0.02,0,0\n", f);
    std::fclose(f);
    stewart::PoseTable table;
    const std::string error = stewart::read_pose_table(poses, table);
    TEST_ASSERT_EQUAL_STRING("", error.c_str());
    TEST_ASSERT_EQUAL_INT(2, static_cast<int>(table.t.size()));
    TEST_ASSERT_EQUAL_DOUBLE(0.1, table.t[1]);
    TEST_ASSERT_EQUAL_DOUBLE(0.0125, table.poses[1].q[0]);
    TEST_ASSERT_EQUAL_DOUBLE(0.51, table.poses[1].q[2]);
    TEST_ASSERT_EQUAL_DOUBLE(0.02, table.poses[1].q[3]);
    // forward kinematics reads its lengths (the thesis' home: 0.5631 m) and solves the rows
    f = std::fopen(lengths.c_str(), "w");
    TEST_ASSERT_NOT_NULL(f);
    std::fputs(
        "t,L1,L2,L3,L4,L5,L6\n0,0.5,0.5,0.5,0.5,0.5,0.5\n0.1,0.505,0.505,0.505,0.505,0.505,0.505\n",
        f);
    std::fclose(f);
    stewart_params params;
    stewart_params_default(&params);
    stewart_forward_options options;
    stewart_forward_options_default(&options);
    TEST_ASSERT_EQUAL_INT(0, stewart::run_forward(lengths.c_str(),
                                                  (dir + "/cli_numbers_out.csv").c_str(), params,
                                                  options, nullptr));
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_param_values_read_as_written);
    RUN_TEST(test_csv_rows_read_as_written);
    return UNITY_END();
}
