/* Every joint and driver type: its analytic Jacobian against central differences of Phi, and
 * Phi_t and gamma against the first and second time derivatives of Phi along a random path
 * q(t) = q0 + t v + t^2/2 a with drivers f(t) = f0 + t f1 + t^2/2 f2 (d2Phi/dt2 = Phi_q a - gamma). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mbs/mbs.h"
#include "unity.h"

#define N 14 /* two free bodies */

void setUp(void) {}
void tearDown(void) {}

static double uniform(void) { return 2.0 * rand() / (double)RAND_MAX - 1.0; }

static void random_vector(double *v, int n, double scale) {
    for (int i = 0; i < n; ++i) v[i] = scale * uniform();
}

static void random_configuration(double *q) {
    for (int b = 0; b < 2; ++b) {
        random_vector(q + MBS_BODY_R(b), 3, 1.0);
        double *p = q + MBS_BODY_P(b), n = 0;
        random_vector(p, 4, 1.0);
        for (int i = 0; i < 4; ++i) n += p[i] * p[i];
        for (int i = 0; i < 4; ++i) p[i] /= sqrt(n);
    }
}

enum kind {
    SPHERICAL,
    CARDAN,
    CYLINDRICAL,
    REVOLUTE,
    PRISMATIC,
    WELD,
    DISTANCE,
    ANGLE,
    POSE,
    FIXED
};

/* Two free bodies, the joint under test, and coordinate drivers to make the system square. */
static mbs_model *build(enum kind k, int *drivers) {
    mbs_model *m = mbs_model_create();
    double I[3] = {1, 2, 2.5}, q[7] = {0, 0, 0, 1, 0, 0, 0};
    double u_i[3] = {0.3, -0.2, 0.5}, u_j[3] = {-0.4, 0.1, 0.2};
    double s_i[3] = {0.2, 1.0, -0.3}, s_j[3] = {1.0, 0.1, 0.4};
    int bi = mbs_add_body(m, "i", 1.0, I, q);
    q[0] = 0.5, q[3] = cos(0.3), q[5] = sin(0.3);
    int bj = mbs_add_body(m, "j", 2.0, I, q);
    int n = 0, joint;
    int slot = -1;
    switch (k) {
        case SPHERICAL: n = mbs_add_spherical(m, bi, u_i, bj, u_j) >= 0 ? 3 : -1; break;
        case CARDAN: n = mbs_add_cardan(m, bi, u_i, s_i, bj, u_j, s_j) >= 0 ? 4 : -1; break;
        case CYLINDRICAL:
            n = mbs_add_cylindrical(m, bi, u_i, s_i, bj, u_j, s_j) >= 0 ? 4 : -1;
            break;
        case REVOLUTE: n = mbs_add_revolute(m, bi, u_i, s_i, bj, u_j, s_j) >= 0 ? 5 : -1; break;
        case PRISMATIC: n = mbs_add_prismatic(m, bi, u_i, s_i, bj, u_j, s_j) >= 0 ? 5 : -1; break;
        case WELD: n = mbs_add_weld(m, bi, u_i, bj, u_j) >= 0 ? 6 : -1; break;
        case DISTANCE:
            joint = mbs_add_cylindrical(m, bi, u_i, s_i, bj, u_j, s_j);
            n = mbs_add_distance_driver(m, joint, &slot) >= 0 ? 5 : -1;
            break;
        case ANGLE:
            joint = mbs_add_revolute(m, bi, u_i, s_i, bj, u_j, s_j);
            n = mbs_add_angle_driver(m, joint, &slot) >= 0 ? 6 : -1;
            break;
        case POSE:
            n = mbs_add_pose_driver(m, bj, &slot) >= 0 ? 6 : -1;
            break;                                                     /* 7 - its normalisation */
        case FIXED: n = mbs_fix_body(m, bi) == MBS_OK ? 6 : -1; break; /* 7 - its normalisation */
    }
    TEST_ASSERT_TRUE_MESSAGE(n > 0, mbs_model_message(m));
    *drivers = (slot >= 0) ? (k == POSE ? 7 : 1) : 0;
    /* Fill with coordinate drivers: 2 normalisations + n equations + fill = 14. */
    for (int c = 0; c < 12 - n; ++c) {
        int s;
        TEST_ASSERT_TRUE(mbs_add_coordinate_driver(m, (c < 7 && k != FIXED) ? bi : bj, c % 7, &s) >=
                         0);
        ++*drivers;
    }
    char msg[MBS_MESSAGE_SIZE];
    TEST_ASSERT_EQUAL_MESSAGE(MBS_OK, mbs_model_finalize(m, msg, sizeof msg), msg);
    TEST_ASSERT_EQUAL(N, mbs_equation_count(m));
    return m;
}

static void set_drivers(mbs_data *d, int count, const double f[][3], double t) {
    for (int k = 0; k < count; ++k)
        mbs_set_driver(d, k, f[k][0] + t * f[k][1] + 0.5 * t * t * f[k][2], f[k][1] + t * f[k][2],
                       f[k][2]);
}

static void check_kind(enum kind k) {
    int drivers;
    mbs_model *m = build(k, &drivers);
    mbs_data *d = mbs_data_create(m, MBS_LINEAR_DENSE);
    TEST_ASSERT_NOT_NULL(d);
    for (int trial = 0; trial < 20; ++trial) {
        double q[N], v[N], a[N], f[N][3];
        random_configuration(q);
        random_vector(v, N, 1.0);
        random_vector(a, N, 1.0);
        for (int i = 0; i < drivers; ++i) random_vector(f[i], 3, 1.0);
        set_drivers(d, drivers, f, 0.0);

        double phi0[N], J[N * N], phi_t[N], gamma[N];
        mbs_evaluate(d, q, v, phi0, J, phi_t, gamma);

        /* Jacobian columns by central differences. */
        const double h = 1e-6;
        for (int c = 0; c < N; ++c) {
            double qp[N], qm[N], fp[N], fm[N];
            memcpy(qp, q, sizeof q);
            memcpy(qm, q, sizeof q);
            qp[c] += h;
            qm[c] -= h;
            mbs_evaluate(d, qp, NULL, fp, NULL, NULL, NULL);
            mbs_evaluate(d, qm, NULL, fm, NULL, NULL, NULL);
            for (int r = 0; r < N; ++r) {
                const double fd = (fp[r] - fm[r]) / (2 * h);
                TEST_ASSERT_DOUBLE_WITHIN(1e-7 * (1 + fabs(fd)), fd, J[r * N + c]);
            }
        }

        /* Along the path: dPhi/dt = Phi_q v + Phi_t and d2Phi/dt2 = Phi_q a - gamma. */
        const double ht = 1e-4;
        double path_p[N], path_m[N], fp[N], fm[N];
        for (int i = 0; i < N; ++i) {
            path_p[i] = q[i] + ht * v[i] + 0.5 * ht * ht * a[i];
            path_m[i] = q[i] - ht * v[i] + 0.5 * ht * ht * a[i];
        }
        set_drivers(d, drivers, f, ht);
        mbs_evaluate(d, path_p, NULL, fp, NULL, NULL, NULL);
        set_drivers(d, drivers, f, -ht);
        mbs_evaluate(d, path_m, NULL, fm, NULL, NULL, NULL);
        for (int r = 0; r < N; ++r) {
            double Jv = 0, Ja = 0;
            for (int c = 0; c < N; ++c) Jv += J[r * N + c] * v[c], Ja += J[r * N + c] * a[c];
            const double d1 = (fp[r] - fm[r]) / (2 * ht);
            const double d2 = (fp[r] - 2 * phi0[r] + fm[r]) / (ht * ht);
            TEST_ASSERT_DOUBLE_WITHIN(1e-7 * (1 + fabs(d1)), d1, Jv + phi_t[r]);
            TEST_ASSERT_DOUBLE_WITHIN(2e-5 * (1 + fabs(d2)), d2, Ja - gamma[r]);
        }
    }
    mbs_data_free(d);
    mbs_model_free(m);
}

static void test_spherical(void) { check_kind(SPHERICAL); }
static void test_cardan(void) { check_kind(CARDAN); }
static void test_cylindrical(void) { check_kind(CYLINDRICAL); }
static void test_revolute(void) { check_kind(REVOLUTE); }
static void test_prismatic(void) { check_kind(PRISMATIC); }
static void test_weld(void) { check_kind(WELD); }
static void test_distance_driver(void) { check_kind(DISTANCE); }
static void test_angle_driver(void) { check_kind(ANGLE); }
static void test_pose_driver(void) { check_kind(POSE); }
static void test_fixed_body(void) { check_kind(FIXED); }

/* A model whose equation count does not match its coordinates is refused with a message. */
static void test_non_square_refused(void) {
    mbs_model *m = mbs_model_create();
    double I[3] = {1, 1, 1}, q[7] = {0, 0, 0, 1, 0, 0, 0};
    mbs_add_body(m, "free", 1.0, I, q);
    char msg[MBS_MESSAGE_SIZE];
    TEST_ASSERT_EQUAL(MBS_ERR_PARAMETER, mbs_model_finalize(m, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL(strstr(msg, "1 constraint equations for 7 coordinates"));
    TEST_ASSERT_EQUAL(MBS_ERR_ARGUMENT, mbs_add_spherical(m, 0, q, 3, q));
    mbs_model_free(m);
}

/* Bad input is refused with a status and a message naming the variable and its value. */
static void test_bad_input_named(void) {
    mbs_model *m = mbs_model_create();
    double I[3] = {1, 1, 1}, q[7] = {0, 0, 0, 1, 0, 0, 0}, zero[3] = {0, 0, 0};
    TEST_ASSERT_EQUAL(MBS_ERR_PARAMETER, mbs_add_body(m, "bad", -2.0, I, q));
    TEST_ASSERT_NOT_NULL(strstr(mbs_model_message(m), "mass of body bad = -2"));
    double q_bad[7] = {0, 0, 0, 2, 0, 0, 0};
    TEST_ASSERT_EQUAL(MBS_ERR_ARGUMENT, mbs_add_body(m, "p", 1.0, I, q_bad));
    TEST_ASSERT_NOT_NULL(strstr(mbs_model_message(m), "norm^2 4"));
    const int a = mbs_add_body(m, "a", 1.0, I, q), b = mbs_add_body(m, "b", 1.0, I, q);
    TEST_ASSERT_EQUAL(MBS_ERR_ARGUMENT, mbs_add_cardan(m, a, zero, zero, b, zero, zero));
    TEST_ASSERT_NOT_NULL(strstr(mbs_model_message(m), "s_i = (0, 0, 0)"));
    TEST_ASSERT_EQUAL(MBS_ERR_ARGUMENT, mbs_add_coordinate_driver(m, a, 9, NULL));
    TEST_ASSERT_NOT_NULL(strstr(mbs_model_message(m), "coordinate = 9"));
    TEST_ASSERT_EQUAL(MBS_ERR_ARGUMENT, mbs_add_distance_driver(m, 42, NULL));
    TEST_ASSERT_NOT_NULL(strstr(mbs_model_message(m), "joint = 42"));
    mbs_fix_body(m, a);
    mbs_add_weld(m, a, zero, b, zero);
    char msg[MBS_MESSAGE_SIZE];
    TEST_ASSERT_EQUAL(MBS_OK, mbs_model_finalize(m, msg, sizeof msg));
    mbs_data *d = mbs_data_create(m, MBS_LINEAR_AUTOMATIC);
    TEST_ASSERT_EQUAL(MBS_ERR_ARGUMENT, mbs_set_driver(d, 0, 1, 0, 0));
    TEST_ASSERT_NOT_NULL(strstr(mbs_data_message(d), "driver = 0"));
    mbs_options o;
    mbs_options_default(&o);
    TEST_ASSERT_EQUAL(MBS_ERR_ARGUMENT, mbs_step(d, NAN, &o));
    TEST_ASSERT_NOT_NULL(strstr(mbs_data_message(d), "t = nan"));
    TEST_ASSERT_EQUAL(MBS_OK, mbs_step(d, 0, &o)); /* the weld holds b on a */
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 1.0, mbs_q(d)[7 + 3]);
    mbs_data_free(d);
    mbs_model_free(m);
}

/* A multiplier that overflows (Euler-parameter rates of 1e200 square to infinity in the inertial
 * forces) is refused with a status naming lambda, never returned with MBS_OK. */
static void test_overflowing_multipliers_refused(void) {
    mbs_model *m = mbs_model_create();
    double I[3] = {1, 1, 1}, q[7] = {0, 0, 0, 1, 0, 0, 0};
    const int b = mbs_add_body(m, "b", 1.0, I, q);
    int slot = -1;
    TEST_ASSERT_TRUE(mbs_add_pose_driver(m, b, &slot) >= 0);
    char msg[MBS_MESSAGE_SIZE];
    TEST_ASSERT_EQUAL_MESSAGE(MBS_OK, mbs_model_finalize(m, msg, sizeof msg), msg);
    mbs_data *d = mbs_data_create(m, MBS_LINEAR_AUTOMATIC);
    for (int k = 0; k < 7; ++k)
        TEST_ASSERT_EQUAL(MBS_OK, mbs_set_driver(d, slot + k, q[k], k >= 3 ? 1e200 : 0.0, 0.0));
    mbs_options o;
    mbs_options_default(&o);
    TEST_ASSERT_NOT_EQUAL(MBS_OK, mbs_step(d, 0, &o));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(mbs_data_message(d), "lambda"), mbs_data_message(d));
    mbs_data_free(d);
    mbs_model_free(m);
}

int main(void) {
    srand(12345);
    UNITY_BEGIN();
    RUN_TEST(test_spherical);
    RUN_TEST(test_cardan);
    RUN_TEST(test_cylindrical);
    RUN_TEST(test_revolute);
    RUN_TEST(test_prismatic);
    RUN_TEST(test_weld);
    RUN_TEST(test_distance_driver);
    RUN_TEST(test_angle_driver);
    RUN_TEST(test_pose_driver);
    RUN_TEST(test_fixed_body);
    RUN_TEST(test_non_square_refused);
    RUN_TEST(test_bad_input_named);
    RUN_TEST(test_overflowing_multipliers_refused);
    return UNITY_END();
}
