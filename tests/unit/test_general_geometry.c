/* General 6-6 geometry (issue 19, docs/geometry.md): random platforms with joints at any height
 * and random Cardan arms, checked against references written here: the lengths against the
 * closed form; forward kinematics' round trip; the 14-body model's forces against the massless
 * level as the leg masses go to zero and against the principle of virtual work evaluated with
 * finite differences of every body's motion; the plant's round trip. The thesis platform as 36
 * coordinates against the default circles; bad geometries refused by name.
 *
 * Counts (CI time): 10^4 geometries for lengths and forward kinematics, 200 for the 14-body
 * checks, 4 for the plant round trip. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "stewart/stewart.h"
#include "stewart/stewart_forward.h"
#include "stewart/stewart_plant.h"
#include "stewart/stewart_table.h"
#include "test_support.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

static uint64_t rng = 0x9e3779b97f4a7c15ull;

static double uniform(double lo, double hi) {
    return lo + (hi - lo) * ((double)(test_random(&rng) >> 11) * 0x1.0p-53);
}

typedef double vec3[3];

static void cross(const double a[3], const double b[3], double out[3]) {
    const double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                         a[0] * b[1] - a[1] * b[0]};
    memcpy(out, c, sizeof c);
}
static double dot(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static double norm(const double a[3]) { return sqrt(dot(a, a)); }

/* R v for R row-major [3][3]. */
static void rotate(double R[3][3], const double v[3], double out[3]) {
    for (int i = 0; i < 3; ++i) out[i] = R[i][0] * v[0] + R[i][1] * v[1] + R[i][2] * v[2];
}

/* A unit vector at least 30 degrees from the unit vector n. */
static void random_arm(const double n[3], double out[3]) {
    for (;;) {
        double u[3] = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)}, c[3];
        const double l = norm(u);
        if (l < 0.2 || l > 1) continue;
        for (int i = 0; i < 3; ++i) u[i] /= l;
        cross(u, n, c);
        if (norm(c) < 0.5) continue;
        memcpy(out, u, sizeof u);
        return;
    }
}

/* A random general platform: three pairs of base joints and three of platform joints (pair
 * spread and radii random, every joint at its own height and a few degrees off its place), the
 * legs crossing as in the thesis; random Cardan arms; heavy legs with unequal transverse
 * inertias (so that each leg body's spin, set by its Cardan arms, shows in the forces); a
 * platform centre of mass off its origin. Rejected and drawn again if its leg Jacobian's
 * condition at home exceeds 50. */
static void random_platform(stewart_params *p) {
    for (;;) {
        stewart_params_default(p);
        p->geometry = 1;
        const double rb = uniform(0.3, 0.7), rp = uniform(0.2, 0.6), h = uniform(0.4, 0.8);
        const double db = uniform(5, 25) * M_PI / 180, dp = uniform(5, 25) * M_PI / 180;
        const double offset = uniform(-M_PI, M_PI);
        for (int i = 0; i < 3; ++i) {
            const double centre = offset + i * 2 * M_PI / 3;
            /* leg 2i: base joint at centre + db to the platform joint at centre + 60 - dp;
             * leg 2i+1: base joint at centre + 120 - db to centre + 60 + dp */
            const double base_angle[2] = {centre + db, centre + 2 * M_PI / 3 - db};
            const double plate_angle[2] = {centre + M_PI / 3 - dp, centre + M_PI / 3 + dp};
            for (int j = 0; j < 2; ++j) {
                const int k = 2 * i + j;
                const double ab = base_angle[j] + uniform(-0.05, 0.05);
                const double ap = plate_angle[j] + uniform(-0.05, 0.05);
                const double r1 = rb * uniform(0.9, 1.1), r2 = rp * uniform(0.9, 1.1);
                p->base_joint[3 * k] = r1 * cos(ab), p->base_joint[3 * k + 1] = r1 * sin(ab);
                p->base_joint[3 * k + 2] = uniform(-0.08, 0.08);
                p->platform_joint[3 * k] = r2 * cos(ap),
                                      p->platform_joint[3 * k + 1] = r2 * sin(ap);
                p->platform_joint[3 * k + 2] = uniform(-0.08, 0.08);
            }
        }
        p->home_height = h;
        for (int k = 0; k < 6; ++k) {
            double n[3];
            for (int i = 0; i < 3; ++i)
                n[i] = p->platform_joint[3 * k + i] + (i == 2 ? h : 0) - p->base_joint[3 * k + i];
            const double l = norm(n);
            for (int i = 0; i < 3; ++i) n[i] /= l;
            random_arm(n, p->base_cardan_axis + 3 * k);
            random_arm(n, p->platform_cardan_axis + 3 * k);
            p->stroke_min[k] = 0.01, p->stroke_max[k] = 10;
        }
        p->cylinder_mass = uniform(0.5, 3), p->piston_mass = uniform(0.5, 3);
        p->cylinder_com = uniform(0.05, 0.3), p->piston_com = uniform(0.05, 0.3);
        const double Ic[3] = {uniform(0.02, 0.05), uniform(0.005, 0.01), uniform(0.02, 0.03)};
        const double Ip[3] = {uniform(0.005, 0.01), uniform(0.02, 0.05), uniform(0.02, 0.03)};
        memcpy(p->cylinder_inertia, Ic, sizeof Ic);
        memcpy(p->piston_inertia, Ip, sizeof Ip);
        for (int i = 0; i < 3; ++i) p->platform_com[i] = uniform(-0.05, 0.05);
        /* the triangle inequalities may fail for the leg inertias above: draw again */
        char msg[STEWART_MESSAGE_SIZE];
        if (stewart_params_check(p, msg, sizeof msg) != STEWART_OK) continue;
        stewart_model *m = test_model(p);
        stewart_inverse *d = test_inverse(m);
        stewart_pose home = {{0, 0, h, 0, 0, 0}, {0}, {0}};
        stewart_inverse_output out;
        stewart_inverse_options o = test_options(STEWART_MASSLESS);
        const stewart_status s = solve_as(d, &o, &home, &out);
        stewart_inverse_free(d);
        stewart_model_free(m);
        if (s == STEWART_OK && out.condition < 50) return;
    }
}

/* A random pose near home, with random rates and accelerations. */
static stewart_pose random_pose(const stewart_params *p) {
    stewart_pose pose;
    for (int i = 0; i < 6; ++i) {
        pose.q[i] = i < 3 ? uniform(-0.04, 0.04) : uniform(-0.12, 0.12);
        pose.q_dot[i] = uniform(-1, 1);
        pose.q_ddot[i] = uniform(-3, 3);
    }
    pose.q[2] += p->home_height;
    return pose;
}

/* The pose at time t along q + t q_dot + t^2/2 q_ddot (rates and accelerations unused). */
static stewart_pose pose_at(const stewart_pose *p, double t) {
    stewart_pose out = *p;
    for (int i = 0; i < 6; ++i) out.q[i] = p->q[i] + t * p->q_dot[i] + 0.5 * t * t * p->q_ddot[i];
    return out;
}

/* ---------------------------------------------------------------- every body, written out */

/* A body's centre of mass and axes (columns) at a pose: 0 the platform, 1..6 the cylinders,
 * 7..12 the pistons (docs/model.md: leg bodies' z along the leg, x = s x n / |s x n| with s the
 * fixed arm of their Cardan). */
enum { BODIES = 13 };
static void body_at(const stewart_params *p, const stewart_pose *pose, int body, double r[3],
                    double A[3][3]) {
    double R[3][3];
    pose_rotation(pose, R);
    if (body == 0) {
        double c[3];
        rotate(R, p->platform_com, c);
        for (int i = 0; i < 3; ++i) r[i] = pose->q[i] + c[i];
        memcpy(A, R, sizeof R);
        return;
    }
    const int k = (body - 1) % 6;
    const int piston = body > 6;
    double b[3], P[3], n[3], s[3], x[3], y[3];
    rotate(R, p->platform_joint + 3 * k, b);
    for (int i = 0; i < 3; ++i) P[i] = pose->q[i] + b[i], n[i] = P[i] - p->base_joint[3 * k + i];
    const double L = norm(n);
    for (int i = 0; i < 3; ++i) n[i] /= L;
    if (piston) rotate(R, p->platform_cardan_axis + 3 * k, s);
    else memcpy(s, p->base_cardan_axis + 3 * k, sizeof s);
    cross(s, n, x);
    const double lx = norm(x);
    for (int i = 0; i < 3; ++i) x[i] /= lx;
    cross(n, x, y);
    for (int i = 0; i < 3; ++i) {
        r[i] = piston ? P[i] - p->piston_com * n[i]
                      : p->base_joint[3 * k + i] + p->cylinder_com * n[i];
        A[i][0] = x[i], A[i][1] = y[i], A[i][2] = n[i];
    }
}

static void body_mass(const stewart_params *p, int body, double *m, double I[3]) {
    if (body == 0) {
        *m = p->platform_mass;
        memcpy(I, p->platform_inertia, 3 * sizeof(double));
    } else if (body <= 6) {
        *m = p->cylinder_mass;
        memcpy(I, p->cylinder_inertia, 3 * sizeof(double));
    } else {
        *m = p->piston_mass;
        memcpy(I, p->piston_inertia, 3 * sizeof(double));
    }
}

/* vee((A1 - A0) A^T) / dt: the angular velocity of a frame from two nearby samples about A. */
static void angular_rate(double A1[3][3], double A0[3][3], double A[3][3], double dt, double w[3]) {
    double M[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            M[i][j] = 0;
            for (int c = 0; c < 3; ++c) M[i][j] += (A1[i][c] - A0[i][c]) * A[j][c];
        }
    w[0] = 0.5 * (M[2][1] - M[1][2]) / dt;
    w[1] = 0.5 * (M[0][2] - M[2][0]) / dt;
    w[2] = 0.5 * (M[1][0] - M[0][1]) / dt;
}

/* A body's angular velocity at time t along the pose's trajectory (central differences). */
static void body_omega(const stewart_params *p, const stewart_pose *pose, int body, double t,
                       double w[3]) {
    const double dt = 1e-5;
    double r[3], A[3][3], A1[3][3], A0[3][3];
    stewart_pose q = pose_at(pose, t), q1 = pose_at(pose, t + dt), q0 = pose_at(pose, t - dt);
    body_at(p, &q, body, r, A);
    body_at(p, &q1, body, r, A1);
    body_at(p, &q0, body, r, A0);
    angular_rate(A1, A0, A, 2 * dt, w);
}

/* The generalized force of the bodies' inertia and weight along pose coordinate i:
 * sum over bodies of m (a - g).dr/dq_i + (I alpha + w x I w).dtheta/dq_i, every derivative by
 * finite differences; with_legs 0 counts the platform alone (massless legs). */
static double inertia_and_weight(const stewart_params *p, const stewart_pose *pose, int i,
                                 int with_legs) {
    const double h = 1e-4, e = 1e-6;
    double total = 0;
    for (int body = 0; body < (with_legs ? BODIES : 1); ++body) {
        double m, I[3], r[3], r1[3], r0[3], A[3][3], A1[3][3], A0[3][3];
        body_mass(p, body, &m, I);
        stewart_pose q = pose_at(pose, 0), qa = pose_at(pose, h), qb = pose_at(pose, -h);
        body_at(p, &q, body, r, A);
        body_at(p, &qa, body, r1, A1);
        body_at(p, &qb, body, r0, A0);
        double a[3], w[3], w1[3], w0[3], alpha[3];
        for (int c = 0; c < 3; ++c) a[c] = (r1[c] - 2 * r[c] + r0[c]) / (h * h) - p->gravity[c];
        body_omega(p, pose, body, 0, w);
        body_omega(p, pose, body, h, w1);
        body_omega(p, pose, body, -h, w0);
        for (int c = 0; c < 3; ++c) alpha[c] = (w1[c] - w0[c]) / (2 * h);
        /* world inertia A diag(I) A^T applied to alpha and w */
        double Ia[3] = {0}, Iw[3] = {0}, torque[3], gyro[3];
        for (int c = 0; c < 3; ++c) {
            double la = 0, lw = 0;
            for (int j = 0; j < 3; ++j) la += A[j][c] * alpha[j], lw += A[j][c] * w[j];
            for (int j = 0; j < 3; ++j) Ia[j] += A[j][c] * I[c] * la, Iw[j] += A[j][c] * I[c] * lw;
        }
        cross(w, Iw, gyro);
        for (int c = 0; c < 3; ++c) torque[c] = Ia[c] + gyro[c];
        /* dr/dq_i and dtheta/dq_i at the pose */
        stewart_pose qp = q, qm = q;
        qp.q[i] += e, qm.q[i] -= e;
        double rp[3], rm[3], Ap[3][3], Am[3][3], dtheta[3];
        body_at(p, &qp, body, rp, Ap);
        body_at(p, &qm, body, rm, Am);
        angular_rate(Ap, Am, A, 2 * e, dtheta);
        for (int c = 0; c < 3; ++c)
            total += m * a[c] * (rp[c] - rm[c]) / (2 * e) + torque[c] * dtheta[c];
    }
    return total;
}

/* sum_k F_k dL_k/dq_i, dL_k/dq_i by central differences of the closed form. */
static double actuator_work(const stewart_params *p, const stewart_pose *pose, const double F[6],
                            int i) {
    const double e = 1e-6;
    stewart_pose qp = *pose, qm = *pose;
    qp.q[i] += e, qm.q[i] -= e;
    double total = 0;
    for (int k = 0; k < 6; ++k)
        total += F[k] * (closed_form_length(p, &qp, k) - closed_form_length(p, &qm, k)) / (2 * e);
    return total;
}

/* ---------------------------------------------------------------- the checks */

static stewart_inverse_output solve_at(stewart_inverse *d, stewart_fidelity f, double tolerance,
                                       const stewart_pose *pose) {
    stewart_inverse_options o = test_options(f);
    o.tolerance = tolerance;
    stewart_inverse_output out;
    const stewart_status s = solve_as(d, &o, pose, &out);
    if (s != STEWART_OK) TEST_FAIL_MESSAGE(stewart_inverse_message(d));
    return out;
}

/* Lengths, rates and accelerations against the closed form (rates and accelerations by
 * differences of it along the pose's trajectory), and forward kinematics back to the pose from
 * home (working assembly mode), on 10^4 random geometries. */
static void test_lengths_and_forward_round_trip(void) {
    double worst_length = 0, worst_rate = 0, worst_accel = 0, worst_position = 0, worst_angle = 0;
    for (int g = 0; g < 10000; ++g) {
        stewart_params p;
        random_platform(&p);
        stewart_model *m = test_model(&p);
        stewart_inverse *d = test_inverse(m);
        const stewart_pose pose = random_pose(&p);
        const stewart_inverse_output out = solve_at(d, STEWART_KINEMATIC, 1e-12, &pose);
        /* steps for the first and second differences: truncation and rounding balanced */
        const double h1 = 1e-5, h2 = 2e-4;
        const stewart_pose ahead1 = pose_at(&pose, h1), behind1 = pose_at(&pose, -h1);
        const stewart_pose ahead2 = pose_at(&pose, h2), behind2 = pose_at(&pose, -h2);
        for (int k = 0; k < 6; ++k) {
            const double L = closed_form_length(&p, &pose, k);
            const double rate =
                (closed_form_length(&p, &ahead1, k) - closed_form_length(&p, &behind1, k)) /
                (2 * h1);
            const double accel =
                (closed_form_length(&p, &ahead2, k) - 2 * L + closed_form_length(&p, &behind2, k)) /
                (h2 * h2);
            worst_length = fmax(worst_length, fabs(out.lengths.length[k] - L));
            worst_rate = fmax(worst_rate, fabs(out.lengths.length_rate[k] - rate));
            worst_accel = fmax(worst_accel, fabs(out.lengths.length_accel[k] - accel));
        }
        stewart_forward_options fo;
        stewart_forward_options_default(&fo);
        fo.tolerance = 1e-15;
        char msg[STEWART_MESSAGE_SIZE];
        stewart_forward *f = stewart_forward_create(m, &fo, msg, sizeof msg);
        if (!f) TEST_FAIL_MESSAGE(msg);
        stewart_forward_input in;
        memset(&in, 0, sizeof in);
        memcpy(in.lengths.length, out.lengths.length, sizeof in.lengths.length);
        stewart_forward_output back;
        if (stewart_forward_solve(f, &in, &back) != STEWART_OK)
            TEST_FAIL_MESSAGE(stewart_forward_message(f));
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, back.branch, "the pose is on the working assembly mode");
        for (int i = 0; i < 3; ++i)
            worst_position = fmax(worst_position, fabs(back.pose.q[i] - pose.q[i]));
        for (int i = 3; i < 6; ++i)
            worst_angle = fmax(worst_angle, fabs(back.pose.q[i] - pose.q[i]));
        stewart_forward_free(f);
        stewart_inverse_free(d);
        stewart_model_free(m);
    }
    printf("10^4 geometries: length %.3g m, rate %.3g m/s, accel %.3g m/s2 from the closed form; "
           "forward round trip %.3g m, %.3g rad\n",
           worst_length, worst_rate, worst_accel, worst_position, worst_angle);
    TEST_ASSERT_TRUE(worst_length <= 1e-14);
    TEST_ASSERT_TRUE(worst_rate <= 1e-8); /* the differences' own error */
    TEST_ASSERT_TRUE(worst_accel <= 1e-5);
    TEST_ASSERT_TRUE(worst_position <= 1e-12);
    TEST_ASSERT_TRUE(worst_angle <= 1e-12);
}

/* The 14-body model's forces, and the massless level's, satisfy virtual work against every
 * body's inertia and weight computed here; and the 14-body forces tend to the massless ones as
 * the leg bodies' masses and inertias shrink (linearly: 1000 times smaller legs, about 1000
 * times closer). 200 geometries. */
static void test_forces_by_virtual_work_and_massless_limit(void) {
    double worst_full = 0, worst_massless = 0, worst_ratio = 0;
    for (int g = 0; g < 200; ++g) {
        stewart_params p;
        random_platform(&p);
        const stewart_pose pose = random_pose(&p);
        stewart_model *m = test_model(&p);
        stewart_inverse *d = test_inverse(m);
        const stewart_inverse_output full = solve_at(d, STEWART_FULL, 1e-14, &pose);
        const stewart_inverse_output massless = solve_at(d, STEWART_MASSLESS, 1e-14, &pose);
        double scale = 1;
        for (int k = 0; k < 6; ++k) scale = fmax(scale, fabs(full.force[k]));
        for (int i = 0; i < 6; ++i) {
            const double full_error =
                actuator_work(&p, &pose, full.force, i) - inertia_and_weight(&p, &pose, i, 1);
            const double massless_error =
                actuator_work(&p, &pose, massless.force, i) - inertia_and_weight(&p, &pose, i, 0);
            worst_full = fmax(worst_full, fabs(full_error) / scale);
            worst_massless = fmax(worst_massless, fabs(massless_error) / scale);
        }
        stewart_inverse_free(d);
        stewart_model_free(m);

        double difference[2];
        for (int step = 0; step < 2; ++step) {
            stewart_params light = p;
            const double factor = step == 0 ? 1e-3 : 1e-6;
            light.cylinder_mass *= factor, light.piston_mass *= factor;
            for (int i = 0; i < 3; ++i)
                light.cylinder_inertia[i] *= factor, light.piston_inertia[i] *= factor;
            stewart_model *lm = test_model(&light);
            stewart_inverse *ld = test_inverse(lm);
            const stewart_inverse_output a = solve_at(ld, STEWART_FULL, 1e-14, &pose);
            const stewart_inverse_output b = solve_at(ld, STEWART_MASSLESS, 1e-14, &pose);
            difference[step] = 0;
            for (int k = 0; k < 6; ++k)
                difference[step] = fmax(difference[step], fabs(a.force[k] - b.force[k]));
            stewart_inverse_free(ld);
            stewart_model_free(lm);
        }
        TEST_ASSERT_TRUE(difference[1] <= 1e-6 * scale);
        worst_ratio = fmax(worst_ratio, difference[1] / difference[0]);
    }
    printf("200 geometries: virtual work residual / max|F|: full %.3g, massless %.3g; "
           "legs 1e-6 vs 1e-3 of their mass: force difference ratio %.3g\n",
           worst_full, worst_massless, worst_ratio);
    TEST_ASSERT_TRUE(worst_full <= 1e-6);
    TEST_ASSERT_TRUE(worst_massless <= 1e-6);
    TEST_ASSERT_TRUE(worst_ratio <= 2e-3);
}

/* The plant driven by the 14-body model's forces along a smooth trajectory follows it (4
 * geometries, 0.1 s each). */
static void test_plant_round_trip(void) {
    double worst = 0;
    for (int g = 0; g < 4; ++g) {
        stewart_params p;
        random_platform(&p);
        const stewart_pose centre = random_pose(&p);
        stewart_model *m = test_model(&p);
        stewart_inverse *d = test_inverse(m);
        stewart_plant_options po;
        stewart_plant_options_default(&po);
        po.fidelity = STEWART_FULL;
        po.relative_tolerance = 1e-12, po.absolute_tolerance = 1e-14;
        po.max_internal_steps = 100000;
        char msg[STEWART_MESSAGE_SIZE];
        stewart_plant *plant = stewart_plant_create(m, &po, msg, sizeof msg);
        if (!plant) TEST_FAIL_MESSAGE(msg);
        /* q(t) = centre.q + A sin(w t) per component */
        double amplitude[6], w[6];
        for (int i = 0; i < 6; ++i) amplitude[i] = i < 3 ? 0.01 : 0.03, w[i] = uniform(2, 6);
        stewart_pose at[1];
        const double h = 1e-4, fd = 1e-6;
        double F0[6], R0[6];
        for (int step = 0; step <= 1000; ++step) {
            const double t = step * h;
            double F[3][6];
            for (int s = 0; s < 3; ++s) {
                const double ts = t + (s - 1) * fd;
                at[0] = centre;
                for (int i = 0; i < 6; ++i) {
                    at[0].q[i] = centre.q[i] + amplitude[i] * sin(w[i] * ts);
                    at[0].q_dot[i] = amplitude[i] * w[i] * cos(w[i] * ts);
                    at[0].q_ddot[i] = -amplitude[i] * w[i] * w[i] * sin(w[i] * ts);
                }
                const stewart_inverse_output out = solve_at(d, STEWART_FULL, 1e-14, &at[0]);
                memcpy(F[s], out.force, sizeof F[s]);
            }
            double R[6];
            for (int k = 0; k < 6; ++k) R[k] = (F[2][k] - F[0][k]) / (2 * fd);
            if (step == 0) {
                double q0[6], v0[6];
                for (int i = 0; i < 6; ++i) q0[i] = centre.q[i], v0[i] = amplitude[i] * w[i];
                TEST_ASSERT_EQUAL(STEWART_OK, stewart_plant_set_state(plant, 0, q0, v0));
            } else {
                stewart_plant_input in;
                memset(&in, 0, sizeof in);
                in.h = h, in.derivatives = 1;
                memcpy(in.force_start, F0, sizeof F0), memcpy(in.force_end, F[1], sizeof F0);
                memcpy(in.force_rate_start, R0, sizeof R0), memcpy(in.force_rate_end, R, sizeof R);
                stewart_plant_output out;
                if (stewart_plant_step(plant, &in, &out) != STEWART_OK)
                    TEST_FAIL_MESSAGE(stewart_plant_message(plant));
                for (int i = 0; i < 6; ++i)
                    worst = fmax(worst, fabs(out.pose.q[i] -
                                             (centre.q[i] + amplitude[i] * sin(w[i] * t))));
            }
            memcpy(F0, F[1], sizeof F0), memcpy(R0, R, sizeof R0);
        }
        stewart_plant_free(plant);
        stewart_inverse_free(d);
        stewart_model_free(m);
    }
    printf("plant round trip, 4 geometries x 0.1 s: largest pose error %.3g\n", worst);
    TEST_ASSERT_TRUE(worst <= 1e-7);
}

/* The thesis platform given as its 36 coordinates (geometry 1, the table's default joints)
 * against the default circles: the same joints bit for bit, so lengths, massless forces and
 * forward kinematics bit for bit; the Cardan arms come from each joint's azimuth instead of the
 * angle, so the 14-body forces agree to rounding (1e-12 relative). */
static void test_thesis_as_coordinates(void) {
    stewart_params circles, joints;
    stewart_params_default(&circles);
    stewart_params_default(&joints);
    joints.geometry = 1;
    stewart_model *mc = test_model(&circles), *mj = test_model(&joints);
    stewart_inverse *dc = test_inverse(mc), *dj = test_inverse(mj);
    for (int n = 0; n < 50; ++n) {
        const stewart_pose pose = combined_pose(0.1 * n);
        for (int f = STEWART_KINEMATIC; f <= STEWART_MASSLESS; ++f) {
            const stewart_inverse_output a = solve_at(dc, (stewart_fidelity)f, 1e-12, &pose);
            const stewart_inverse_output b = solve_at(dj, (stewart_fidelity)f, 1e-12, &pose);
            TEST_ASSERT_EQUAL_MEMORY(&a, &b, sizeof a);
        }
        const stewart_inverse_output a = solve_at(dc, STEWART_FULL, 1e-12, &pose);
        const stewart_inverse_output b = solve_at(dj, STEWART_FULL, 1e-12, &pose);
        for (int k = 0; k < 6; ++k) {
            TEST_ASSERT_EQUAL_DOUBLE(a.lengths.length[k], b.lengths.length[k]);
            TEST_ASSERT_TRUE(fabs(a.force[k] - b.force[k]) <= 1e-12 * fabs(a.force[k]));
        }
    }
    stewart_forward *fc = test_forward(mc);
    stewart_forward *fj = test_forward(mj);
    for (int n = 0; n < 50; ++n) {
        const stewart_pose pose = combined_pose(0.1 * n);
        const stewart_inverse_output legs = solve_at(dc, STEWART_KINEMATIC, 1e-12, &pose);
        stewart_forward_input in;
        memset(&in, 0, sizeof in);
        in.time = 0.1 * n;
        in.lengths = legs.lengths;
        stewart_forward_output a, b;
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_forward_solve(fc, &in, &a));
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_forward_solve(fj, &in, &b));
        TEST_ASSERT_EQUAL_MEMORY(&a, &b, sizeof a);
    }
    stewart_forward_free(fc), stewart_forward_free(fj);
    stewart_inverse_free(dc), stewart_inverse_free(dj);
    stewart_model_free(mc), stewart_model_free(mj);
}

/* A hanging platform (its joints 0.5 m below the base's at home: every leg falls) is on its
 * working assembly mode at home; its mirror image above the base, the same lengths, is not: the
 * legs leave both Cardans on the other side than at home. */
static void test_a_hanging_platform_has_its_own_working_mode(void) {
    stewart_params p;
    stewart_params_default(&p);
    p.geometry = 1;
    for (int k = 0; k < 6; ++k) p.platform_joint[3 * k + 2] = -1.0;
    stewart_model *m = test_model(&p);
    stewart_inverse *d = test_inverse(m);
    stewart_forward_options fo;
    stewart_forward_options_default(&fo);
    char msg[STEWART_MESSAGE_SIZE];
    stewart_forward *f = stewart_forward_create(m, &fo, msg, sizeof msg);
    if (!f) TEST_FAIL_MESSAGE(msg);
    const stewart_pose home = {{0, 0, 0.5, 0, 0, 0}, {0}, {0}};
    const stewart_inverse_output legs = solve_at(d, STEWART_KINEMATIC, 1e-12, &home);
    stewart_forward_input in;
    memset(&in, 0, sizeof in);
    in.lengths = legs.lengths;
    stewart_forward_output out;
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_forward_solve(f, &in, &out));
    TEST_ASSERT_EQUAL_INT(0, out.branch);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 0.5, out.pose.q[2]);
    in.use_guess = 1;
    in.guess[2] = 1.5; /* the platform points mirrored to z = +0.5 */
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_OTHER_BRANCH, stewart_forward_solve(f, &in, &out));
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, 1.5, out.pose.q[2]);
    TEST_ASSERT_EQUAL_INT(STEWART_BRANCH_BELOW_BASE | STEWART_BRANCH_PLATFORM_CARDAN,
                          out.branch &
                              (STEWART_BRANCH_BELOW_BASE | STEWART_BRANCH_PLATFORM_CARDAN));
    stewart_forward_free(f);
    stewart_inverse_free(d);
    stewart_model_free(m);
}

/* Every check of a general geometry refuses by the field's name. */
static void expect_refused(const stewart_params *p, const char *words) {
    char msg[STEWART_MESSAGE_SIZE];
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_PARAMETER, stewart_params_check(p, msg, sizeof msg));
    TEST_ASSERT_NULL(stewart_model_create(p, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, words), msg);
}

static void test_bad_geometries_are_refused_by_name(void) {
    stewart_params p;
    stewart_params_default(&p), p.geometry = 0.5, expect_refused(&p, "geometry = 0.5");
    stewart_params_default(&p), p.geometry = 2, expect_refused(&p, "geometry = 2");
    /* a Cardan axis neither zero nor unit */
    stewart_params_default(&p), p.base_cardan_axis[3] = 0.5,
                                expect_refused(&p, "base_cardan_axis[4..6]");
    stewart_params_default(&p), p.geometry = 1, p.platform_cardan_axis[17] = 0.9;
    expect_refused(&p, "platform_cardan_axis[16..18]");
    /* a Cardan axis along its leg at home */
    stewart_params_default(&p);
    double leg[3];
    for (int i = 0; i < 3; ++i)
        leg[i] = p.platform_joint[3 + i] + (i == 2 ? p.home_height : 0) - p.base_joint[3 + i];
    for (int i = 0; i < 3; ++i) p.base_cardan_axis[3 + i] = leg[i] / norm(leg);
    p.geometry = 1, expect_refused(&p, "base_cardan_axis[4..6]");
    /* one leg twice (both ends coincide) */
    stewart_params_default(&p), p.geometry = 1;
    memcpy(p.base_joint + 6, p.base_joint + 3, 3 * sizeof(double));
    memcpy(p.platform_joint + 6, p.platform_joint + 3, 3 * sizeof(double));
    expect_refused(&p, "legs 2 and 3 are one leg");
    stewart_params_default(&p), p.base_angle[4] = p.base_angle[3],
                                p.platform_angle[4] = p.platform_angle[3];
    expect_refused(&p, "base_angle[4] and base_angle[5]");
    /* a joint on the z axis with the default (tangent) arm */
    stewart_params_default(&p), p.geometry = 1, p.platform_joint[0] = p.platform_joint[1] = 0;
    expect_refused(&p, "platform_joint[1..3]");
    /* a leg of zero length at home */
    stewart_params_default(&p), p.geometry = 1;
    for (int i = 0; i < 3; ++i)
        p.platform_joint[i] = p.base_joint[i] - (i == 2 ? p.home_height : 0);
    expect_refused(&p, "leg 1 has length 0");
    /* per-leg strokes, and a non-finite joint coordinate */
    stewart_params_default(&p), p.stroke_min[5] = 0.8, expect_refused(&p, "stroke_min[6]");
    stewart_params_default(&p), p.base_joint[7] = NAN, expect_refused(&p, "base_joint[8]");
    /* two legs sharing a base joint (genhexkins' default) are a valid platform */
    stewart_params_default(&p), p.geometry = 1;
    memcpy(p.base_joint + 3, p.base_joint, 3 * sizeof(double));
    char msg[STEWART_MESSAGE_SIZE];
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_params_check(&p, msg, sizeof msg), msg);
}

/* A bare per-leg name fills the six legs (the spelling of before issue 19). */
static void test_bare_stroke_names_fill_every_leg(void) {
    stewart_params p;
    stewart_params_default(&p);
    char msg[STEWART_MESSAGE_SIZE];
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_params_set(&p, "stroke_max", 0.9, msg, sizeof msg));
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_params_set(&p, "stroke_min[3]", 0.3, msg, sizeof msg));
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_params_set(&p, "base_joint[18]", 0.25, msg, sizeof msg));
    for (int k = 0; k < 6; ++k) TEST_ASSERT_EQUAL_DOUBLE(0.9, p.stroke_max[k]);
    TEST_ASSERT_EQUAL_DOUBLE(0.3, p.stroke_min[2]);
    TEST_ASSERT_EQUAL_DOUBLE(0.4, p.stroke_min[3]);
    TEST_ASSERT_EQUAL_DOUBLE(0.25, p.base_joint[17]);
    /* other arrays keep needing their element */
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT,
                      stewart_params_set(&p, "base_joint", 0.1, msg, sizeof msg));
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT,
                      stewart_params_set(&p, "base_joint[19]", 0.1, msg, sizeof msg));
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT,
                      stewart_params_set(&p, "base_joint[01]", 0.1, msg, sizeof msg));
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_bad_geometries_are_refused_by_name);
    RUN_TEST(test_bare_stroke_names_fill_every_leg);
    RUN_TEST(test_thesis_as_coordinates);
    RUN_TEST(test_a_hanging_platform_has_its_own_working_mode);
    RUN_TEST(test_forces_by_virtual_work_and_massless_limit);
    RUN_TEST(test_plant_round_trip);
    RUN_TEST(test_lengths_and_forward_round_trip);
    return UNITY_END();
}
