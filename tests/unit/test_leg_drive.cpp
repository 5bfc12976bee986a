// The law of one leg's drive (csrc/drives/leg_drive.hpp), shared by the inverse and the plant,
// against its formulas written here: the parameters' mapping, friction with and without
// smoothing, the Stribeck term's skip giving the bits of the exp, the screw's efficiency by the
// direction of power flow (forward at rest), the reflected mass and the whole torque.
#include <cmath>
#include <cstring>
#include <initializer_list>

#include "drives/leg_drive.hpp"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

namespace {

stewart::LegDrive friction_drive(double coulomb, double breakaway, double speed, double viscous) {
    stewart::LegDrive d;
    d.motor_per_leg = 2 * M_PI * 3 / 0.005;
    d.coulomb = coulomb, d.breakaway = breakaway, d.stribeck_speed = speed, d.viscous = viscous;
    return d;
}

double stribeck(double Fc, double Fs, double vs, double b, double v, double s) {
    return (Fc + (Fs - Fc) * std::exp(-(v / vs) * (v / vs))) * s + b * v;
}

}  // namespace

static void test_parameters_of_a_leg(void) {
    stewart_params p;
    stewart_params_default(&p);
    TEST_ASSERT_FALSE(stewart::has_drives(p));
    TEST_ASSERT_EQUAL_DOUBLE(0.0, stewart::leg_drive(p, 2).motor_per_leg);
    p.screw_lead[2] = 0.005, p.gear_ratio[2] = 3, p.rotor_inertia[2] = 1.37e-4;
    p.screw_inertia[2] = 9e-4, p.stribeck_friction[2] = 10, p.coulomb_friction[2] = 30;
    TEST_ASSERT_TRUE(stewart::has_drives(p));
    const stewart::LegDrive d = stewart::leg_drive(p, 2);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 2 * M_PI * 3 / 0.005, d.motor_per_leg);
    TEST_ASSERT_DOUBLE_WITHIN(1e-18, 1.37e-4 + 9e-4 / 9, d.inertia);  // the screw's through N^2
    TEST_ASSERT_EQUAL_DOUBLE(30.0, d.breakaway);                      // at least coulomb: no peak
    TEST_ASSERT_DOUBLE_WITHIN(0.005, 1947.08 + 1e-4 * 3769.91 * 3769.91,
                              stewart::reflected_mass(d));
}

static void test_friction_exact_sign_and_smoothing(void) {
    const stewart::LegDrive d = friction_drive(20, 35, 0.01, 150);
    TEST_ASSERT_EQUAL_DOUBLE(0.0, stewart::friction_force(d, 0.0, 0.0));  // at rest: none
    for (double v : {-0.3, -0.012, -1e-5, 1e-7, 0.004, 0.05}) {
        const double s = v > 0 ? 1.0 : -1.0;
        TEST_ASSERT_DOUBLE_WITHIN(1e-12, stribeck(20, 35, 0.01, 150, v, s),
                                  stewart::friction_force(d, v, 0.0));
        const double eps = 1e-3, smooth = v / std::sqrt(v * v + eps * eps);
        TEST_ASSERT_DOUBLE_WITHIN(1e-12, stribeck(20, 35, 0.01, 150, v, smooth),
                                  stewart::friction_force(d, v, eps));
    }
    TEST_ASSERT_EQUAL_DOUBLE(0.0, stewart::friction_force(d, 0.0, 1e-3));
}

// Past (v/v_s)^2 = 50 the law skips the exp: the same bits as with it, peaks up to 255 coulomb.
static void test_the_stribeck_skip_keeps_every_bit(void) {
    for (double peak_ratio : {0.001, 1.0, 17.0, 255.0})
        for (double x = 7.0; x < 40.0; x *= 1.013) {
            const double Fc = 37.5, Fs = Fc * (1 + peak_ratio), vs = 0.02, v = x * vs;
            const stewart::LegDrive d = friction_drive(Fc, Fs, vs, 0.0);
            const double with_exp = (Fc + (Fs - Fc) * std::exp(-(v / vs) * (v / vs))) * 1.0;
            const double law = stewart::friction_force(d, v, 0.0);
            TEST_ASSERT_EQUAL_MEMORY(&with_exp, &law, sizeof law);
        }
}

static void test_screw_efficiency_by_power_flow(void) {
    stewart::LegDrive d = friction_drive(0, 0, 0, 0);
    d.efficiency = 0.9, d.back_efficiency = 0.7;
    const double r = d.motor_per_leg;
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 1000 / (r * 0.9), stewart::screw_motor_torque(d, 1000, 5));
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, -1000 / (r * 0.9), stewart::screw_motor_torque(d, -1000, -5));
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 1000 * 0.7 / r, stewart::screw_motor_torque(d, 1000, -5));
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, -1000 * 0.7 / r, stewart::screw_motor_torque(d, -1000, 5));
    // at rest: the forward efficiency, the torque that starts a motion either way
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 1000 / (r * 0.9), stewart::screw_motor_torque(d, 1000, 0));
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, -1000 / (r * 0.9), stewart::screw_motor_torque(d, -1000, 0));
    d.back_efficiency = 0;  // self-locking: the load never drives the motor
    TEST_ASSERT_EQUAL_DOUBLE(0.0, stewart::screw_motor_torque(d, 1000, -5));
}

static void test_the_whole_torque(void) {
    stewart::LegDrive d = friction_drive(20, 35, 0.01, 150);
    d.inertia = 2e-4, d.efficiency = 0.8, d.back_efficiency = 0.6;
    const double r = d.motor_per_leg, v = 0.05, a = -3.0;
    const double F = -800;  // the load drives back against the friction's pull
    const double nut = F + stribeck(20, 35, 0.01, 150, v, 1.0);
    TEST_ASSERT_TRUE(nut * v < 0);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 2e-4 * r * a + nut / r * 0.6,
                              stewart::drive_torque(d, F, v, a));
}

// The rates against central differences of the laws themselves along a motion.
static void test_the_rates_are_the_laws_derivatives(void) {
    stewart::LegDrive d = friction_drive(20, 35, 0.01, 150);
    d.inertia = 2e-4, d.efficiency = 0.8, d.back_efficiency = 0.6;
    const double h = 1e-7;
    for (double v : {-0.3, -0.012, -0.004, 0.003, 0.02, 0.2}) {
        const double slope =
            (stewart::friction_force(d, v + h, 0) - stewart::friction_force(d, v - h, 0)) / (2 * h);
        TEST_ASSERT_DOUBLE_WITHIN(1e-5 * (1 + std::fabs(slope)), slope,
                                  stewart::friction_slope(d, v));
        // F(t) = F0 + F1 t, L'(t) = v + a t, L''(t) = a + j t: d torque / dt at t = 0
        for (double F0 : {-900.0, 700.0}) {
            const double F1 = 350, a = -2.5, j = 40;
            auto torque = [&](double t) {
                return stewart::drive_torque(d, F0 + F1 * t, v + a * t + j * t * t / 2, a + j * t);
            };
            const double rate = (torque(h) - torque(-h)) / (2 * h);
            TEST_ASSERT_DOUBLE_WITHIN(1e-5 * (1 + std::fabs(rate)), rate,
                                      stewart::drive_torque_rate(d, F0, F1, v, a, j));
        }
    }
    TEST_ASSERT_EQUAL_DOUBLE(150.0, stewart::friction_slope(d, 0.0));  // at rest: the viscous
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_parameters_of_a_leg);
    RUN_TEST(test_friction_exact_sign_and_smoothing);
    RUN_TEST(test_the_stribeck_skip_keeps_every_bit);
    RUN_TEST(test_screw_efficiency_by_power_flow);
    RUN_TEST(test_the_whole_torque);
    RUN_TEST(test_the_rates_are_the_laws_derivatives);
    return UNITY_END();
}
