/* The plant driven by its motors linearised (stewart_linearize_driven) on every shipped
 * *_drives.json machine, checked against central differences of the plant's own right-hand side
 * (stewart_plant_derivatives with the same input), at rest and moving, both fidelities, current
 * and voltage input; and the winding's current rows against their closed form
 * di/dt = (V - R i - k_t c L_dot) / L_w written here.
 *
 * Steps and tolerance: the right-hand side is smooth in the state but for the regularised sign
 * s(v) = v / sqrt(v^2 + v_s^2) of friction and of the screw's efficiency, whose third derivative
 * is of order 1 / v_s^3 near rest: a central difference with step h in the rates has a relative
 * truncation error of order (h / v_s)^2, 1e-6 at h = 1e-3 v_s (1e-7 m/s at v_s = 1e-4 m/s). The
 * inputs enter affinely (the power flow's direction held), so their step (1e-3 A or V) leaves
 * rounding alone. Rounding (16 eps |f| / h) is taken off by block_relative; the tolerance,
 * 1e-5, is ten times the truncation bound. At rest the screw's efficiency has a kink (its slope
 * steps forward to back): there the linearisation gives the one-sided derivatives' mean, which is
 * what the central difference converges to, and flags the legs. */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "linearize_support.h"
#include "stewart/stewart_linearize.h"
#include "stewart/stewart_platform_file.h"
#include "stewart/stewart_plant.h"
#include "test_support.h"
#include "unity.h"

#ifndef STEWART_PLATFORMS_DIR
#error "STEWART_PLATFORMS_DIR: the platforms/ folder"
#endif

static const double kStepState = 1e-7; /* m, rad, m/s, rad/s: 1e-3 of the smoothing speed */
static const double kStepRest = 1e-8;  /* the same at rest, at the efficiency's kink */
static const double kStepInput = 1e-3; /* A, V */
static const double kRelative = 1e-5;
static const double kSmoothing = 1e-4; /* the plant's default smoothing_speed [m/s] */


static void read_platform(const char *name, stewart_params *p) {
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

/* The shipped files' drives have neither friction nor a winding: the test's own, to exercise
 * them (a servo motor's 0.8 ohm, 3 mH; a ball screw's friction). */
static void add_winding_and_friction(stewart_params *p, double inductance) {
    for (int k = 0; k < 6; ++k) {
        p->winding_resistance[k] = 0.8;
        p->winding_inductance[k] = inductance;
        p->coulomb_friction[k] = 60 + 5 * k;
        p->stribeck_friction[k] = 90;
        p->stribeck_speed[k] = 0.01;
        p->viscous_friction[k] = 400;
    }
}

static stewart_plant_options plant_options(int fidelity, int input) {
    stewart_plant_options o;
    stewart_plant_options_default(&o);
    o.fidelity = fidelity;
    o.input = input;
    o.smoothing_speed = kSmoothing;
    return o;
}

/* (q_dot, q_ddot) of the plant's right-hand side at (q, q_dot) under u. */
static void plant_rate(stewart_plant *plant, const double x[12], const double u[6], double f[12]) {
    stewart_plant_derivative_input in;
    memset(&in, 0, sizeof in);
    memcpy(in.pose.q, x, 6 * sizeof x[0]);
    memcpy(in.pose.q_dot, x + 6, 6 * sizeof x[0]);
    memcpy(in.force, u, 6 * sizeof u[0]);
    stewart_plant_output out;
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_plant_derivatives(plant, &in, &out),
                                  stewart_plant_message(plant));
    memcpy(f, out.pose.q_dot, 6 * sizeof f[0]);
    memcpy(f + 6, out.pose.q_ddot, 6 * sizeof f[0]);
}

/* The operating point: near home, at rest or moving, inputs that leave every leg's screw force
 * well away from zero. */
static void operating_point(const stewart_params *p, int moving, double x[12]) {
    /* home's tool pose in the user frame, for frames that translate only */
    for (int i = 0; i < 6; ++i)
        TEST_ASSERT_TRUE(i < 3 || (p->tool_frame[i] == 0 && p->user_frame[i] == 0));
    const double home_z = p->home_height + p->tool_frame[2] - p->user_frame[2];
    const double home_x = p->tool_frame[0] - p->user_frame[0];
    const double home_y = p->tool_frame[1] - p->user_frame[1];
    const double q[6] = {home_x + 0.002, home_y - 0.001, home_z + 0.003, 0.004, -0.003, 0.005};
    const double q_dot[6] = {0.03, -0.02, 0.04, 0.02, -0.03, 0.025};
    memset(x, 0, 12 * sizeof x[0]);
    memcpy(x, q, sizeof q);
    if (moving) memcpy(x + 6, q_dot, sizeof q_dot);
}

/* A, B and the state rate against central differences of the plant's right-hand side. */
static void check_against_plant(const stewart_params *p, const char *name, int fidelity, int input,
                                int moving) {
    char msg[STEWART_MESSAGE_SIZE], what[256];
    stewart_model *m = stewart_model_create(p, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(m, msg);
    stewart_linearize_options lo;
    stewart_linearize_options_default(&lo);
    lo.fidelity = fidelity;
    stewart_linearize *l = stewart_linearize_create(m, &lo, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(l, msg);
    const stewart_plant_options po = plant_options(fidelity, input);
    stewart_plant *plant = stewart_plant_create(m, &po, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(plant, msg);

    stewart_linearize_driven_input in;
    memset(&in, 0, sizeof in);
    double x[12], u[6];
    operating_point(p, moving, x);
    memcpy(in.pose.q, x, sizeof in.pose.q);
    memcpy(in.pose.q_dot, x + 6, sizeof in.pose.q_dot);
    for (int k = 0; k < 6; ++k) /* a few amperes, or volts of the order R i */
        u[k] = in.input[k] = (input == STEWART_PLANT_INPUT_CURRENT ? 1.0 : 0.8) * (2.0 + 0.5 * k);
    stewart_linearize_driven_output o;
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_linearize_driven(l, &po, &in, &o),
                                  stewart_linearize_message(l));
    TEST_ASSERT_EQUAL_INT(12, o.states);

    double f0[12];
    plant_rate(plant, x, u, f0);
    double rate_scale = 0;
    for (int i = 0; i < 12; ++i) rate_scale = fmax(rate_scale, fabs(f0[i]));
    for (int i = 0; i < 12; ++i) {
        snprintf(what, sizeof what, "%s fidelity %d input %d moving %d: state rate %d", name,
                 fidelity, input, moving, i);
        TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(1e-9 * rate_scale, f0[i], o.state_rate[i], what);
    }
    block_error by_state = {0, 0}, by_input = {0, 0};
    for (int j = 0; j < 18; ++j) {
        const double h = j >= 12 ? kStepInput : moving ? kStepState : kStepRest;
        double xp[12], xm[12], up[6], um[6], fp[12], fm[12];
        memcpy(xp, x, sizeof xp), memcpy(xm, x, sizeof xm);
        memcpy(up, u, sizeof up), memcpy(um, u, sizeof um);
        if (j < 12) xp[j] += h, xm[j] -= h;
        else up[j - 12] += h, um[j - 12] -= h;
        plant_rate(plant, xp, up, fp);
        plant_rate(plant, xm, um, fm);
        for (int i = 6; i < 12; ++i) {
            const double difference = (fp[i] - fm[i]) / (2 * h);
            if (j < 12) block_add(&by_state, o.A[i][j], difference);
            else block_add(&by_input, o.B[i][j - 12], difference);
        }
    }
    const double state_error =
        block_relative(by_state, rate_scale, moving ? kStepState : kStepRest);
    const double input_error = block_relative(by_input, rate_scale, kStepInput);
    snprintf(what, sizeof what,
             "%s fidelity %d input %d moving %d: A %.3g, B %.3g beyond rounding (raw %.3g, %.3g; "
             "scales %.3g, %.3g)",
             name, fidelity, input, moving, state_error, input_error, by_state.error,
             by_input.error, by_state.scale, by_input.scale);
    printf("%s\n", what);
    TEST_ASSERT_TRUE_MESSAGE(state_error < kRelative && input_error < kRelative, what);
    /* At rest every leg with a screw force has the efficiency's kink (0.9 forward, 0.8889 back:
     * slopes -0.1 and -0.125); moving, none. */
    TEST_ASSERT_EQUAL_INT_MESSAGE(moving ? 0 : 63, o.not_smooth_legs, what);
    TEST_ASSERT_EQUAL_INT_MESSAGE(moving ? 0 : STEWART_WARN_NOT_SMOOTH,
                                  o.warnings & STEWART_WARN_NOT_SMOOTH, what);
    stewart_plant_free(plant);
    stewart_linearize_free(l);
    stewart_model_free(m);
}

static int is_drives_file(const char *name) {
    const size_t n = strlen(name), tail = strlen("_drives.json");
    return n > tail && strcmp(name + n - tail, "_drives.json") == 0;
}

static void test_shipped_drives_against_differences(void) {
    DIR *dir = opendir(STEWART_PLATFORMS_DIR);
    TEST_ASSERT_NOT_NULL(dir);
    int files = 0;
    for (struct dirent *entry; (entry = readdir(dir)) != NULL;) {
        if (!is_drives_file(entry->d_name)) continue;
        ++files;
        stewart_params shipped, wound;
        read_platform(entry->d_name, &shipped);
        wound = shipped;
        add_winding_and_friction(&wound, 0.0);
        for (int fidelity = STEWART_MASSLESS; fidelity <= STEWART_FULL; ++fidelity)
            for (int moving = 0; moving <= 1; ++moving) {
                check_against_plant(&shipped, entry->d_name, fidelity, STEWART_PLANT_INPUT_CURRENT,
                                    moving);
                check_against_plant(&wound, entry->d_name, fidelity, STEWART_PLANT_INPUT_CURRENT,
                                    moving);
                check_against_plant(&wound, entry->d_name, fidelity, STEWART_PLANT_INPUT_VOLTAGE,
                                    moving);
            }
    }
    closedir(dir);
    TEST_ASSERT_TRUE(files >= 2);
}

/* Voltage input with an inductance: the windings' currents are states 12-17. Their rows against
 * di/dt = (V - R i - k_t c L_dot) / L_w, c = 2 pi N / lead, written here; the mechanical rows'
 * current columns against the current-driven plant's B at the same currents (the current is then
 * the input), and its A. */
static void test_winding_rows_closed_form(void) {
    DIR *dir = opendir(STEWART_PLATFORMS_DIR);
    TEST_ASSERT_NOT_NULL(dir);
    char name[256] = "";
    for (struct dirent *entry; (entry = readdir(dir)) != NULL;)
        if (is_drives_file(entry->d_name)) snprintf(name, sizeof name, "%s", entry->d_name);
    closedir(dir);
    stewart_params p;
    read_platform(name, &p);
    add_winding_and_friction(&p, 3e-3);
    char msg[STEWART_MESSAGE_SIZE];
    stewart_model *m = stewart_model_create(&p, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(m, msg);
    stewart_linearize_options lo;
    stewart_linearize_options_default(&lo);
    lo.fidelity = STEWART_FULL;
    stewart_linearize *l = stewart_linearize_create(m, &lo, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(l, msg);
    const stewart_plant_options voltage = plant_options(STEWART_FULL, STEWART_PLANT_INPUT_VOLTAGE);
    const stewart_plant_options current = plant_options(STEWART_FULL, STEWART_PLANT_INPUT_CURRENT);
    stewart_linearize_driven_input in, by_current;
    memset(&in, 0, sizeof in);
    double x[12];
    operating_point(&p, 1, x);
    memcpy(in.pose.q, x, sizeof in.pose.q);
    memcpy(in.pose.q_dot, x + 6, sizeof in.pose.q_dot);
    for (int k = 0; k < 6; ++k) in.input[k] = 10.0 - k, in.current[k] = 2.0 + 0.5 * k;
    by_current = in;
    memcpy(by_current.input, in.current, sizeof in.current);
    stewart_linearize_driven_output o, oc;
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_linearize_driven(l, &voltage, &in, &o),
                                  stewart_linearize_message(l));
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK,
                                  stewart_linearize_driven(l, &current, &by_current, &oc),
                                  stewart_linearize_message(l));
    TEST_ASSERT_EQUAL_INT(18, o.states);
    double fastest = 0;
    for (int k = 0; k < 6; ++k) {
        const double R = p.winding_resistance[k], Lw = p.winding_inductance[k];
        const double kt = p.torque_constant[k];
        const double c = 2 * M_PI * p.gear_ratio[k] / p.screw_lead[k];
        const double L_dot = o.output[18 + k];
        fastest = fmax(fastest, fabs(L_dot));
        const double rate = (in.input[k] - R * in.current[k] - kt * c * L_dot) / Lw;
        TEST_ASSERT_DOUBLE_WITHIN(1e-12 * fabs(rate) + 1e-9, rate, o.state_rate[12 + k]);
        for (int j = 0; j < 6; ++j) {
            TEST_ASSERT_DOUBLE_WITHIN(1e-12 * R / Lw, j == k ? -R / Lw : 0.0, o.A[12 + k][12 + j]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-12 / Lw, j == k ? 1.0 / Lw : 0.0, o.B[12 + k][j]);
        }
        for (int j = 0; j < 12; ++j) {
            const double expected = -kt * c / Lw * o.C[18 + k][j];
            TEST_ASSERT_DOUBLE_WITHIN(1e-12 * (fabs(expected) + kt * c / Lw), expected,
                                      o.A[12 + k][j]);
        }
    }
    TEST_ASSERT_TRUE(fastest > 1e-2); /* the back-EMF term is there */
    double scale_a = 0, scale_b = 0;
    for (int i = 6; i < 12; ++i) {
        for (int j = 0; j < 12; ++j) scale_a = fmax(scale_a, fabs(oc.A[i][j]));
        for (int k = 0; k < 6; ++k) scale_b = fmax(scale_b, fabs(oc.B[i][k]));
    }
    for (int i = 6; i < 12; ++i) {
        TEST_ASSERT_DOUBLE_WITHIN(1e-12 * fabs(oc.state_rate[i]) + 1e-12, oc.state_rate[i],
                                  o.state_rate[i]);
        for (int j = 0; j < 12; ++j)
            TEST_ASSERT_DOUBLE_WITHIN(1e-12 * scale_a, oc.A[i][j], o.A[i][j]);
        for (int k = 0; k < 6; ++k) {
            TEST_ASSERT_DOUBLE_WITHIN(1e-12 * scale_b, oc.B[i][k], o.A[i][12 + k]);
            TEST_ASSERT_EQUAL_DOUBLE(0.0, o.B[i][k]); /* the voltage acts through the current */
        }
    }
    stewart_linearize_free(l);
    stewart_model_free(m);
}

/* Force input has its own linearisation; a leg without a drive cannot be driven. */
static void test_refusals(void) {
    stewart_params p;
    stewart_params_default(&p);
    char msg[STEWART_MESSAGE_SIZE];
    stewart_model *m = stewart_model_create(&p, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(m, msg);
    stewart_linearize_options lo;
    stewart_linearize_options_default(&lo);
    stewart_linearize *l = stewart_linearize_create(m, &lo, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(l, msg);
    stewart_linearize_driven_input in;
    memset(&in, 0, sizeof in);
    in.pose.q[2] = p.home_height;
    stewart_linearize_driven_output o;
    stewart_plant_options po = plant_options(STEWART_MASSLESS, STEWART_PLANT_INPUT_FORCE);
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER, stewart_linearize_driven(l, &po, &in, &o));
    TEST_ASSERT_NOT_NULL(strstr(stewart_linearize_message(l), "stewart_linearize_plant"));
    po.input = STEWART_PLANT_INPUT_CURRENT;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER, stewart_linearize_driven(l, &po, &in, &o));
    TEST_ASSERT_NOT_NULL(strstr(stewart_linearize_message(l), "screw_lead[1]"));
    stewart_linearize_free(l);
    stewart_model_free(m);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_shipped_drives_against_differences);
    RUN_TEST(test_winding_rows_closed_form);
    RUN_TEST(test_refusals);
    return UNITY_END();
}
