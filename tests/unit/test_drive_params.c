/* The drive parameters' rules across fields (stewart_params_check): each refusal names the
 * parameter, its leg and its value; the drives a datasheet gives are taken. */
#include <string.h>

#include "stewart/stewart.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

static char message[STEWART_MESSAGE_SIZE];

/* The thesis platform with a drive on every leg: 5 mm lead, a motor of 0.5 N.m/A. */
static stewart_params with_drives(void) {
    stewart_params p;
    stewart_params_default(&p);
    for (int k = 0; k < STEWART_LEGS; ++k) {
        p.screw_lead[k] = 0.005;
        p.torque_constant[k] = 0.5;
    }
    return p;
}

/* Refused, with each of the texts in the message. */
static void assert_refused(const stewart_params *p, const char *const *texts, int count) {
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER, stewart_params_check(p, message, sizeof message));
    for (int i = 0; i < count; ++i)
        if (!strstr(message, texts[i])) TEST_FAIL_MESSAGE(message);
}

static void test_a_drive_with_every_parameter_is_taken(void) {
    stewart_params p = with_drives();
    for (int k = 0; k < STEWART_LEGS; ++k) {
        p.gear_ratio[k] = 3;
        p.rotor_inertia[k] = 1.37e-4;
        p.screw_inertia[k] = 2e-5;
        p.screw_efficiency[k] = 0.9;
        p.screw_back_efficiency[k] = 0.0; /* self-locking */
        p.winding_resistance[k] = 1.2;
        p.winding_inductance[k] = 3e-3;
        p.coulomb_friction[k] = 50;
        p.stribeck_friction[k] = 80;
        p.stribeck_speed[k] = 0.01;
        p.viscous_friction[k] = 200;
        p.end_stop_stiffness[k] = 1e8;
        p.end_stop_damping[k] = 1e4;
        p.current_max[k] = 20;
        p.voltage_max[k] = 320;
        p.motor_speed_max[k] = 600;
    }
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_params_check(&p, message, sizeof message),
                                  message);
    p.stribeck_friction[2] = 30; /* below coulomb: no peak, no speed needed */
    p.stribeck_speed[2] = 0;
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_params_check(&p, message, sizeof message),
                                  message);
}

/* The legs' axial compliance is not modelled: a stiffness or damping given is refused, not
 * ignored (the legs would stay rigid). */
static void test_leg_compliance_is_refused(void) {
    stewart_params p = with_drives();
    p.leg_stiffness[4] = 1e8;
    const char *texts[] = {"leg_stiffness[5] = 1e+08 N/m", "not modelled"};
    assert_refused(&p, texts, 2);
    p = with_drives();
    p.leg_damping[0] = 1e3;
    const char *damping[] = {"leg_damping[1] = 1000 N.s/m", "not modelled"};
    assert_refused(&p, damping, 2);
}

static void test_a_drive_needs_a_torque_constant(void) {
    stewart_params p = with_drives();
    p.torque_constant[3] = 0;
    const char *texts[] = {"torque_constant[4] = 0 N.m/A", "leg 4", "screw_lead[4] = 0.005"};
    assert_refused(&p, texts, 3);
}

static void test_motor_parameters_need_a_drive(void) {
    struct {
        const char *name;
        double value;
        const char *text;
    } cases[] = {
        {"gear_ratio[2]", 3, "gear_ratio[2] = 3, but leg 2 has no drive"},
        {"rotor_inertia[2]", 1.37e-4, "rotor_inertia[2] = 0.000137 kg.m2, but leg 2"},
        {"screw_efficiency[2]", 0.9, "screw_efficiency[2] = 0.9, but leg 2"},
        {"screw_back_efficiency[2]", 0, "screw_back_efficiency[2] = 0, but leg 2"},
        {"torque_constant[2]", 0.5, "torque_constant[2] = 0.5 N.m/A, but leg 2"},
        {"winding_inductance[2]", 0.003, "winding_inductance[2] = 0.003 H, but leg 2"},
        {"current_max[2]", 20, "current_max[2] = 20 A, but leg 2"},
        {"motor_speed_max[2]", 600, "motor_speed_max[2] = 600 rad/s, but leg 2"},
        {"coulomb_friction[2]", 40, "coulomb_friction[2] = 40 N, but leg 2"},
        {"end_stop_stiffness[2]", 1e8, "end_stop_stiffness[2] = 1e+08 N/m, but leg 2"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        stewart_params p = with_drives();
        p.screw_lead[1] = 0;
        p.torque_constant[1] = 0;
        TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_params_set(&p, cases[i].name, cases[i].value,
                                                             message, sizeof message));
        const char *texts[] = {cases[i].text, "screw_lead[2] = 0"};
        assert_refused(&p, texts, 2);
    }
}

static void test_a_stribeck_peak_needs_its_speed(void) {
    stewart_params p = with_drives();
    p.coulomb_friction[5] = 50;
    p.stribeck_friction[5] = 80;
    const char *texts[] = {"stribeck_speed[6] = 0 m/s", "leg 6", "stribeck_friction[6] = 80 N",
                           "coulomb_friction[6] = 50 N"};
    assert_refused(&p, texts, 4);
    p.stribeck_speed[5] = 0.02;
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_params_check(&p, message, sizeof message));
}

static void test_damping_needs_its_spring(void) {
    stewart_params p = with_drives();
    p.leg_damping[0] = 1000;
    const char *leg[] = {"leg_damping[1] = 1000 N.s/m", "leg_stiffness[1] = 0"};
    assert_refused(&p, leg, 2);
    p.leg_damping[0] = 0;
    p.end_stop_damping[4] = 5e3;
    const char *stop[] = {"end_stop_damping[5] = 5000 N.s/m", "end_stop_stiffness[5] = 0"};
    assert_refused(&p, stop, 2);
}

static void test_efficiencies_out_of_range_are_refused_by_name(void) {
    stewart_params p = with_drives();
    p.screw_efficiency[2] = 0; /* (0, 1]: a screw that passes no power forward */
    const char *zero[] = {"screw_efficiency[3] = 0"};
    assert_refused(&p, zero, 1);
    p.screw_efficiency[2] = 1.1;
    const char *above[] = {"screw_efficiency[3] = 1.1"};
    assert_refused(&p, above, 1);
    p.screw_efficiency[2] = 0.9;
    p.screw_back_efficiency[0] = -0.1;
    const char *back[] = {"screw_back_efficiency[1] = -0.1"};
    assert_refused(&p, back, 1);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_a_drive_with_every_parameter_is_taken);
    RUN_TEST(test_a_drive_needs_a_torque_constant);
    RUN_TEST(test_leg_compliance_is_refused);
    RUN_TEST(test_motor_parameters_need_a_drive);
    RUN_TEST(test_a_stribeck_peak_needs_its_speed);
    RUN_TEST(test_damping_needs_its_spring);
    RUN_TEST(test_efficiencies_out_of_range_are_refused_by_name);
    return UNITY_END();
}
