/* Full (14-body) level against independent references: the closed-form leg lengths, the
 * massless-leg level when the legs weigh nothing, the power balance of the 13 moving bodies,
 * the thesis' pose-driver formulation, and Euler-parameter normalisation over a long run. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "platform_fixture.h"
#include "stewart/stewart_full.h"
#include "thesis_forces.h"
#include "test_support.h"
#include "unity.h"

static stewart_pose manoeuvre(int which, double t) {
    return which == 6 ? combined_pose(t) : thesis_pose(which, t);
}

static void test_lengths_match_closed_form(void) {
    const int which[5] = {2, 3, 4, 5, 6};
    for (int w = 0; w < 5; ++w)
        for (int i = 0; i <= 120; ++i) {
            stewart_pose pose = manoeuvre(which[w], 0.1 * i);
            stewart_inverse_output out = solve_ok(data, STEWART_FULL, &pose);
            for (int k = 0; k < 6; ++k)
                TEST_ASSERT_DOUBLE_WITHIN(1e-11, closed_form_length(&params, &pose, k),
                                          out.lengths.length[k]);
            TEST_ASSERT_TRUE(out.residual <= 1e-12);
            TEST_ASSERT_TRUE(out.iterations <= 2);
        }
}

static void expect_relative(double expected, double actual, double rel) {
    TEST_ASSERT_DOUBLE_WITHIN(rel * (1.0 + fabs(expected)), expected, actual);
}

/* w = 2 E(p) y for the Euler parameters p and y = p_dot (angular velocity) or p_ddot (its rate:
 * E(p_dot) p_dot = 0), and A(p) u, written out here independently of the core. */
static void world_rate(const double *p, const double *y, double w[3]) {
    w[0] = 2 * (-p[1] * y[0] + p[0] * y[1] - p[3] * y[2] + p[2] * y[3]);
    w[1] = 2 * (-p[2] * y[0] + p[3] * y[1] + p[0] * y[2] - p[1] * y[3]);
    w[2] = 2 * (-p[3] * y[0] - p[2] * y[1] + p[1] * y[2] + p[0] * y[3]);
}
static void cross(const double a[3], const double b[3], double c[3]) {
    c[0] = a[1] * b[2] - a[2] * b[1], c[1] = a[2] * b[0] - a[0] * b[2],
    c[2] = a[0] * b[1] - a[1] * b[0];
}
/* Position, velocity and acceleration of the point u (body frame) of body b. */
static void body_point(const double *q, const double *v, const double *a, int b, const double u[3],
                       double x[3], double xd[3], double xdd[3]) {
    const double *r = q + MBS_BODY_R(b), *p = q + MBS_BODY_P(b);
    const double e0 = p[0], e1 = p[1], e2 = p[2], e3 = p[3];
    const double A[3][3] = {
        {e0 * e0 + e1 * e1 - e2 * e2 - e3 * e3, 2 * (e1 * e2 - e0 * e3), 2 * (e1 * e3 + e0 * e2)},
        {2 * (e1 * e2 + e0 * e3), e0 * e0 - e1 * e1 + e2 * e2 - e3 * e3, 2 * (e2 * e3 - e0 * e1)},
        {2 * (e1 * e3 - e0 * e2), 2 * (e2 * e3 + e0 * e1), e0 * e0 - e1 * e1 - e2 * e2 + e3 * e3}};
    double s[3], w[3], alpha[3], ws[3], wws[3], as[3];
    for (int i = 0; i < 3; ++i) s[i] = A[i][0] * u[0] + A[i][1] * u[1] + A[i][2] * u[2];
    world_rate(p, v + MBS_BODY_P(b), w);
    world_rate(p, a + MBS_BODY_P(b), alpha);
    cross(w, s, ws);
    cross(w, ws, wws);
    cross(alpha, s, as);
    for (int i = 0; i < 3; ++i) {
        x[i] = r[i] + s[i];
        xd[i] = v[MBS_BODY_R(b) + i] + ws[i];
        xdd[i] = a[MBS_BODY_R(b) + i] + as[i] + wws[i];
    }
}

/* The lengths, rates and accelerations the full level reports are those of its solved bodies:
 * the distance between each leg's two Cardan centres (cylinder body 1 + k, its point
 * (0, 0, -cylinder_com); piston body 7 + k, (0, 0, piston_com)), read from the core's state. */
static void test_lengths_are_the_solved_bodies(void) {
    const mbs_data *mech = stewart_inverse_mechanism(data);
    const double L0 = stewart_model_length_unit(model);
    for (int i = 0; i <= 120; i += 5) {
        stewart_pose pose = combined_pose(0.1 * i);
        stewart_inverse_output out = solve_ok(data, STEWART_FULL, &pose);
        const double *q = mbs_q(mech), *v = mbs_q_dot(mech), *a = mbs_q_ddot(mech);
        for (int k = 0; k < 6; ++k) {
            const double uc[3] = {0, 0, -params.cylinder_com / L0},
                         up[3] = {0, 0, params.piston_com / L0};
            double xc[3], vc[3], ac[3], xp[3], vp[3], ap[3], d[3], dd[3], ddd[3];
            body_point(q, v, a, 1 + k, uc, xc, vc, ac);
            body_point(q, v, a, 7 + k, up, xp, vp, ap);
            for (int c = 0; c < 3; ++c)
                d[c] = xp[c] - xc[c], dd[c] = vp[c] - vc[c], ddd[c] = ap[c] - ac[c];
            const double L = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            const double L_dot = (d[0] * dd[0] + d[1] * dd[1] + d[2] * dd[2]) / L;
            const double L_ddot = (dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2] + d[0] * ddd[0] +
                                   d[1] * ddd[1] + d[2] * ddd[2] - L_dot * L_dot) /
                                  L;
            expect_relative(L * L0, out.lengths.length[k], 1e-12);
            expect_relative(L_dot * L0, out.lengths.length_rate[k], 1e-12);
            expect_relative(L_ddot * L0, out.lengths.length_accel[k], 1e-12);
        }
    }
}

static void compare_with_massless(void) {
    for (int w = 2; w <= 6; ++w)
        for (int i = 0; i <= 120; i += 3) {
            stewart_pose pose = manoeuvre(w, 0.1 * i);
            stewart_inverse_output full = solve_ok(data, STEWART_FULL, &pose);
            stewart_inverse_output mass = solve_ok(data, STEWART_MASSLESS, &pose);
            for (int k = 0; k < 6; ++k) {
                expect_relative(mass.force[k], full.force[k], 1e-9);
                expect_relative(mass.lengths.length_rate[k], full.lengths.length_rate[k], 1e-9);
                expect_relative(mass.lengths.length_accel[k], full.lengths.length_accel[k], 1e-9);
            }
            for (int i3 = 0; i3 < 3; ++i3) {
                expect_relative(mass.base_force[i3], full.base_force[i3], 1e-9);
                expect_relative(mass.base_torque[i3], full.base_torque[i3], 1e-9);
            }
            TEST_ASSERT_EQUAL_DOUBLE(mass.condition, full.condition);
        }
}

/* Weightless legs: the full model must reduce to the massless-leg level. */
static void test_weightless_legs_equal_massless_level(void) {
    params.cylinder_mass = params.piston_mass = 0;
    for (int i = 0; i < 3; ++i) params.cylinder_inertia[i] = params.piston_inertia[i] = 0;
    rebuild_platform();
    compare_with_massless();
}

/* The same with an off-centre payload whose inertia is not diagonal in the plate frame. */
static void test_weightless_legs_with_offset_payload(void) {
    params.cylinder_mass = params.piston_mass = 0;
    for (int i = 0; i < 3; ++i) params.cylinder_inertia[i] = params.piston_inertia[i] = 0;
    params.payload_mass = 40;
    params.payload_com[0] = 0.1, params.payload_com[1] = -0.05, params.payload_com[2] = 0.2;
    params.payload_inertia[0] = 1.0, params.payload_inertia[1] = 1.5,
    params.payload_inertia[2] = 2.0;
    rebuild_platform();
    compare_with_massless();
}

/* Kinetic + potential energy of the 13 moving bodies, from their coordinates. */
static double energy(const double *q, const double *v) {
    double e = 0;
    for (int b = 1; b <= 13; ++b) {
        const double *r = q + MBS_BODY_R(b), *p = q + MBS_BODY_P(b), *rd = v + MBS_BODY_R(b),
                     *pd = v + MBS_BODY_P(b);
        double m;
        const double *J;
        if (b <= 6) m = params.cylinder_mass, J = params.cylinder_inertia;
        else if (b <= 12) m = params.piston_mass, J = params.piston_inertia;
        else m = params.platform_mass, J = params.platform_inertia;
        /* body angular velocity w' = 2 G p_dot, G = [-e, e0 I - skew(e)] */
        const double w[3] = {2 * (-p[1] * pd[0] + p[0] * pd[1] + p[3] * pd[2] - p[2] * pd[3]),
                             2 * (-p[2] * pd[0] - p[3] * pd[1] + p[0] * pd[2] + p[1] * pd[3]),
                             2 * (-p[3] * pd[0] + p[2] * pd[1] - p[1] * pd[2] + p[0] * pd[3])};
        e += 0.5 * m * (rd[0] * rd[0] + rd[1] * rd[1] + rd[2] * rd[2]);
        e += 0.5 * (J[0] * w[0] * w[0] + J[1] * w[1] * w[1] + J[2] * w[2] * w[2]);
        e += m * 9.81 * r[2];
    }
    return e;
}

static double energy_at(double t, int which) {
    stewart_pose pose = manoeuvre(which, t);
    solve_ok(data, STEWART_FULL, &pose);
    const mbs_data *md = stewart_inverse_mechanism(data);
    return energy(mbs_q(md), mbs_q_dot(md));
}

/* sum F_k L_dot_k = dE/dt along the four thesis manoeuvres (and a combined one). */
static void test_power_balance(void) {
    for (int w = 2; w <= 6; ++w)
        for (int i = 1; i <= 120; i += 7) {
            const double t = 0.1 * i, h = 1e-5;
            const double dE = (energy_at(t + h, w) - energy_at(t - h, w)) / (2 * h);
            stewart_pose pose = manoeuvre(w, t);
            stewart_inverse_output out = solve_ok(data, STEWART_FULL, &pose);
            double power = 0, scale = 0;
            for (int k = 0; k < 6; ++k) {
                power += out.force[k] * out.lengths.length_rate[k];
                scale += fabs(out.force[k] * out.lengths.length_rate[k]);
            }
            TEST_ASSERT_DOUBLE_WITHIN(1e-7 * (1 + scale), dE, power);
        }
}

/* The thesis' way (pose drivers + virtual power) against the actuator-length multipliers. */
static void test_thesis_formulation_agrees(void) {
    params.payload_mass = 25;
    params.payload_com[0] = -0.05, params.payload_com[2] = 0.1;
    params.payload_inertia[0] = 0.5, params.payload_inertia[1] = 0.7,
    params.payload_inertia[2] = 0.9;
    rebuild_platform();
    for (int w = 2; w <= 6; ++w)
        for (int i = 0; i <= 120; i += 8) {
            stewart_pose pose = manoeuvre(w, 0.1 * i);
            stewart_inverse_output out = solve_ok(data, STEWART_FULL, &pose);
            double thesis[6];
            char msg[STEWART_MESSAGE_SIZE];
            TEST_ASSERT_EQUAL_MESSAGE(
                STEWART_OK, stewart_thesis_forces(&params, &pose, thesis, msg, sizeof msg), msg);
            for (int k = 0; k < 6; ++k) expect_relative(out.force[k], thesis[k], 1e-9);
        }
}

/* The core's block solver factors each leg block in its planned pivot order (one order for the
 * six legs, so that they factor side by side in vector lanes); partial pivoting is its fallback
 * for a block that order refuses (a multiplier over 1e3), and it repairs even a garbled block: a
 * wrong body row in the scatter gave right forces at 2.4 times the instructions. One instance
 * (solve_ok solves on a fresh copy each time, whose count would be lost), every 10 ms for 12 s:
 * along the thesis manoeuvres 3 fallbacks in all (the third's; 0 with each leg's own order, which
 * the lanes cannot share), along the combined one 5 (21 with each leg's own order): a planned
 * pivot passing through zero as a leg turns, a structural limit of a fixed order, not a fault.
 * Bounds with a little room: at most 5 and 10 of 1201 steps. With the scatter broken, every step
 * falls back. */
static long fallbacks_along(int which) {
    const stewart_inverse_options o = test_options(STEWART_FULL);
    char msg[STEWART_MESSAGE_SIZE];
    stewart_inverse *inverse = stewart_inverse_create(model, &o, msg, sizeof msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(inverse, msg);
    for (int i = 0; i <= 1200; ++i) {
        stewart_inverse_input in;
        in.pose = manoeuvre(which, 0.01 * i);
        stewart_inverse_output out;
        TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_inverse_solve(inverse, &in, &out),
                                      stewart_inverse_message(inverse));
        TEST_ASSERT_EQUAL_INT(0, out.iterations);
    }
    const long fallbacks = mbs_linear_fallbacks(stewart_inverse_mechanism(inverse));
    stewart_inverse_free(inverse);
    return fallbacks;
}

static void test_normal_path_rarely_falls_back(void) {
    long thesis = 0;
    for (int w = 2; w <= 5; ++w) thesis += fallbacks_along(w);
    TEST_ASSERT_TRUE_MESSAGE(thesis <= 5, "the thesis manoeuvres fell back more than 5 times");
    const long combined = fallbacks_along(6);
    TEST_ASSERT_TRUE_MESSAGE(combined <= 10, "the combined manoeuvre fell back more than 10 times");
}

/* |det| of the test's own leg Jacobian (rows n_k and (P_k - p) x n_k / radius, from the closed
 * form of the pose) over the product of its row norms: 0 for a singular matrix, 1 for an
 * orthogonal one. Gaussian elimination with partial pivoting. */
static double jacobian_det_ratio(const stewart_pose *pose) {
    double R[3][3], J[6][6], scale = 1;
    pose_rotation(pose, R);
    for (int k = 0; k < 6; ++k) {
        const double b[3] = {params.platform_radius * cos(params.platform_angle[k]),
                             params.platform_radius * sin(params.platform_angle[k]), 0};
        const double a[3] = {params.base_radius * cos(params.base_angle[k]),
                             params.base_radius * sin(params.base_angle[k]), 0};
        double arm[3], n[3];
        for (int i = 0; i < 3; ++i) arm[i] = R[i][0] * b[0] + R[i][1] * b[1] + R[i][2] * b[2];
        for (int i = 0; i < 3; ++i)
            n[i] = (pose->q[i] + arm[i] - a[i]) / closed_form_length(&params, pose, k);
        J[k][0] = n[0], J[k][1] = n[1], J[k][2] = n[2];
        J[k][3] = (arm[1] * n[2] - arm[2] * n[1]) / params.platform_radius;
        J[k][4] = (arm[2] * n[0] - arm[0] * n[2]) / params.platform_radius;
        J[k][5] = (arm[0] * n[1] - arm[1] * n[0]) / params.platform_radius;
        double norm = 0;
        for (int j = 0; j < 6; ++j) norm += J[k][j] * J[k][j];
        scale *= sqrt(norm);
    }
    double det = 1;
    for (int c = 0; c < 6; ++c) {
        int p = c;
        for (int r = c + 1; r < 6; ++r)
            if (fabs(J[r][c]) > fabs(J[p][c])) p = r;
        if (p != c)
            for (int j = 0; j < 6; ++j) {
                const double t = J[c][j];
                J[c][j] = J[p][j], J[p][j] = t;
            }
        det *= J[c][c];
        if (J[c][c] == 0) break;
        for (int r = c + 1; r < 6; ++r) {
            const double f = J[r][c] / J[c][c];
            for (int j = c; j < 6; ++j) J[r][j] -= f * J[c][j];
        }
    }
    return fabs(det) / scale;
}

/* Yaw = pi/2 exactly: the leg Jacobian is singular (checked here from the geometry alone), so the
 * thesis' way must refuse the pose as stewart_inverse_solve does (it returned forces of 4.7e18 N),
 * leaving force untouched; the same platform a little off that yaw still answers. */
static void test_thesis_forces_refuse_a_singular_pose(void) {
    stewart_pose pose = {{0, 0, 0.5, 0, 0, M_PI / 2}, {0}, {0}};
    TEST_ASSERT_TRUE(jacobian_det_ratio(&pose) < 1e-14);
    stewart_inverse_options o = test_options(STEWART_FULL);
    stewart_inverse_output out;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_SINGULAR, solve_as(data, &o, &pose, &out));

    double force[6];
    for (int k = 0; k < 6; ++k) force[k] = 1000.0 + k;
    char msg[STEWART_MESSAGE_SIZE] = "";
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_SINGULAR,
                          stewart_thesis_forces(&params, &pose, force, msg, sizeof msg));
    for (int k = 0; k < 6; ++k) TEST_ASSERT_EQUAL_DOUBLE(1000.0 + k, force[k]);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "condition number"), msg);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "singular_condition 1e+10"), msg);
    TEST_ASSERT_EQUAL_STRING(stewart_inverse_message(data), msg);

    /* 0.1 rad away the Jacobian is regular and both ways give the same forces. */
    pose.q[5] = M_PI / 2 - 0.1;
    TEST_ASSERT_TRUE(jacobian_det_ratio(&pose) > 1e-3);
    out = solve_ok(data, STEWART_FULL, &pose);
    TEST_ASSERT_EQUAL_MESSAGE(STEWART_OK,
                              stewart_thesis_forces(&params, &pose, force, msg, sizeof msg), msg);
    for (int k = 0; k < 6; ++k) expect_relative(out.force[k], force[k], 1e-9);
}

/* Forces whose exact value exceeds DBL_MAX: refused, never a NaN or infinite force. Near the
 * yaw singularity (condition 4.5e6) with z_ddot = 1e298 the forces are about 4e305 N; they are
 * linear in z_ddot (gravity is negligible), so at 1e302 they would be 1e4 times that, beyond
 * DBL_MAX (the thesis' way returned NaN there). */
static void test_thesis_forces_never_overflow(void) {
    stewart_pose pose = {{0, 0, 0.5, 0, 0, M_PI / 2 - 1e-6}, {0}, {0, 0, 1e298, 0, 0, 0}};
    double force[6];
    char msg[STEWART_MESSAGE_SIZE] = "";
    TEST_ASSERT_EQUAL_MESSAGE(STEWART_OK,
                              stewart_thesis_forces(&params, &pose, force, msg, sizeof msg), msg);
    double largest = 0;
    for (int k = 0; k < 6; ++k) largest = fmax(largest, fabs(force[k]));
    TEST_ASSERT_TRUE(largest > 1e305 && largest < 1e306);
    TEST_ASSERT_TRUE(largest * 1e4 > DBL_MAX);

    pose.q_ddot[2] = 1e302;
    for (int k = 0; k < 6; ++k) force[k] = k + 1.0;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT,
                          stewart_thesis_forces(&params, &pose, force, msg, sizeof msg));
    for (int k = 0; k < 6; ++k) TEST_ASSERT_EQUAL_DOUBLE(k + 1.0, force[k]);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(msg, "not finite"), msg);
}

/* Inputs so large that the solve overflows are out of range (an argument error, as at the
 * massless level), not a singular Jacobian: at home Phi_q is far from singular (condition 11). */
static void test_huge_accelerations_are_out_of_range(void) {
    stewart_pose pose = {{0, 0, 0.5, 0, 0, 0}, {0}, {0, 0, 1e307, 0, 0, 0}};
    stewart_inverse_options o;
    stewart_inverse_options_default(&o);
    stewart_inverse_output out;
    for (int fidelity = STEWART_MASSLESS; fidelity <= STEWART_FULL; ++fidelity) {
        o.fidelity = fidelity;
        TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, solve_as(data, &o, &pose, &out));
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(stewart_inverse_message(data), "out of range"),
                                     stewart_inverse_message(data));
    }
    pose.q_ddot[2] = 1.0; /* and the next ordinary pose is solved */
    solve_ok(data, STEWART_FULL, &pose);
}

/* Heavier legs carry more than the massless level, and the platform at rest loads them. */
static void test_massive_legs_at_rest(void) {
    stewart_pose home = {{0, 0, 0.5, 0, 0, 0}, {0}, {0}};
    stewart_inverse_output full = solve_ok(data, STEWART_FULL, &home);
    const double total = params.platform_mass + 6 * (params.cylinder_mass + params.piston_mass);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9 * total * 9.81, -total * 9.81, full.base_force[2]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 0.0, full.base_force[0]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 0.0, full.base_torque[2]);
    for (int k = 0; k < 6; ++k) TEST_ASSERT_TRUE(full.force[k] > 0);
}

/* |p|^2 - 1 stays within 1e-12 for every body over 1e5 steps of the yaw manoeuvre. */
static void test_normalisation_long_run(void) {
    double worst = 0;
    for (int i = 0; i < 100000; ++i) {
        stewart_pose pose = thesis_pose(5, 1.2e-4 * i);
        solve_ok(data, STEWART_FULL, &pose);
        const double *q = mbs_q(stewart_inverse_mechanism(data));
        for (int b = 0; b < 14; ++b) {
            const double *p = q + MBS_BODY_P(b);
            const double e = fabs(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + p[3] * p[3] - 1);
            if (e > worst) worst = e;
        }
    }
    TEST_ASSERT_TRUE(worst <= 1e-12);
}

/* A copy is a rollback point: solving on after restoring it repeats the same outputs. */
static void test_copy_is_rollback(void) {
    stewart_inverse *saved = test_inverse(model);
    stewart_pose a = combined_pose(0.3), b = combined_pose(0.7);
    solve_ok(data, STEWART_FULL, &a);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_inverse_copy(saved, data));
    stewart_inverse_output first = solve_ok(data, STEWART_FULL, &b);
    stewart_pose c = combined_pose(2.0);
    solve_ok(data, STEWART_FULL, &c);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_inverse_copy(data, saved));
    stewart_inverse_output again = solve_ok(data, STEWART_FULL, &b);
    TEST_ASSERT_EQUAL_MEMORY(&first, &again, sizeof first);
    stewart_inverse_reset(data);
    stewart_inverse_output fresh = solve_ok(data, STEWART_FULL, &b);
    for (int k = 0; k < 6; ++k) TEST_ASSERT_DOUBLE_WITHIN(1e-9, first.force[k], fresh.force[k]);
    stewart_inverse_free(saved);
}

/* q_dot and q_ddot of all 98 coordinates against central differences of q(t) along the
 * combined manoeuvre (each neighbour solved on a copy, so Euler-parameter signs stay put). */
static void test_rates_against_finite_differences(void) {
    stewart_inverse *side = test_inverse(model);
    double q0[98], qp[98], qm[98], v[98], a[98];
    const double steps[2] = {1e-4, 1e-3}; /* first, second difference (Newton noise ~1e-12) */
    for (int i = 0; i <= 120; i += 11)
        for (int which = 0; which < 2; ++which) {
            const double t = 0.1 * i, h = steps[which];
            stewart_pose pose = combined_pose(t), pp = combined_pose(t + h),
                         pm = combined_pose(t - h);
            solve_ok(data, STEWART_FULL, &pose);
            const mbs_data *md = stewart_inverse_mechanism(data);
            memcpy(q0, mbs_q(md), sizeof q0);
            memcpy(v, mbs_q_dot(md), sizeof v);
            memcpy(a, mbs_q_ddot(md), sizeof a);
            TEST_ASSERT_EQUAL(STEWART_OK, stewart_inverse_copy(side, data));
            solve_ok(side, STEWART_FULL, &pp);
            memcpy(qp, mbs_q(stewart_inverse_mechanism(side)), sizeof qp);
            TEST_ASSERT_EQUAL(STEWART_OK, stewart_inverse_copy(side, data));
            solve_ok(side, STEWART_FULL, &pm);
            memcpy(qm, mbs_q(stewart_inverse_mechanism(side)), sizeof qm);
            for (int k = 0; k < 98; ++k) {
                if (which == 0) TEST_ASSERT_DOUBLE_WITHIN(1e-7, (qp[k] - qm[k]) / (2 * h), v[k]);
                else TEST_ASSERT_DOUBLE_WITHIN(1e-5, (qp[k] - 2 * q0[k] + qm[k]) / (h * h), a[k]);
            }
        }
    stewart_inverse_free(side);
}

/* The velocities and accelerations of every body that the full level gives the core in closed
 * form (the core then skips its velocity and acceleration solves) against the core's own solves
 * of Phi_q q_dot = -Phi_t and Phi_q q_ddot = gamma: a copy of the solved state (same coordinates,
 * same drivers) stepped again by mbs_step. */
static void test_closed_form_motion_equals_solved(void) {
    mbs_data *mech = mbs_data_create(stewart_model_mechanism(model), MBS_LINEAR_AUTOMATIC);
    TEST_ASSERT_NOT_NULL(mech);
    mbs_options mo;
    mbs_options_default(&mo);
    mo.use_predictor = 0;
    const int n = mbs_coordinate_count(stewart_model_mechanism(model));
    for (int i = 0; i <= 120; i += 7) {
        stewart_pose pose = combined_pose(0.1 * i);
        const stewart_inverse_output out = solve_ok(data, STEWART_FULL, &pose);
        const mbs_data *md = stewart_inverse_mechanism(data);
        TEST_ASSERT_EQUAL_INT(0, out.iterations);
        TEST_ASSERT_EQUAL_INT(MBS_OK, mbs_data_copy(mech, md));
        TEST_ASSERT_EQUAL_INT_MESSAGE(MBS_OK, mbs_step(mech, 0.1 * i, &mo), mbs_data_message(mech));
        TEST_ASSERT_EQUAL_INT(0, mbs_iterations(mech));
        for (int c = 0; c < n; ++c) {
            const double v = mbs_q_dot(mech)[c], a = mbs_q_ddot(mech)[c];
            TEST_ASSERT_DOUBLE_WITHIN(1e-12 * (1 + fabs(v)), v, mbs_q_dot(md)[c]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-11 * (1 + fabs(a)), a, mbs_q_ddot(md)[c]);
        }
    }
    mbs_data_free(mech);
}

/* Two models and three data blocks side by side, interleaved: each gives what it gives alone
 * (no shared state). */
static void test_instances_side_by_side(void) {
    stewart_params heavy = params;
    heavy.payload_mass = 60;
    heavy.piston_mass = 0.5;
    stewart_model *other = test_model(&heavy);
    stewart_inverse *a = test_inverse(model), *b = test_inverse(other), *c = test_inverse(model);
    stewart_inverse_output alone_a[20], alone_b[20];
    for (int i = 0; i < 20; ++i) {
        stewart_pose pose = combined_pose(0.05 * i);
        alone_a[i] = solve_ok(data, STEWART_FULL, &pose);
    }
    stewart_inverse_reset(data);
    for (int i = 0; i < 20; ++i) {
        stewart_pose pose = combined_pose(0.05 * i);
        alone_b[i] = solve_ok(b, STEWART_FULL, &pose);
    }
    stewart_inverse_reset(b);
    for (int i = 0; i < 20; ++i) {
        stewart_pose pose = combined_pose(0.05 * i), away = thesis_pose(3, 0.3 * i);
        stewart_inverse_output oa = solve_ok(a, STEWART_FULL, &pose);
        solve_ok(c, STEWART_FULL, &away);
        stewart_inverse_output ob = solve_ok(b, STEWART_FULL, &pose);
        TEST_ASSERT_EQUAL_MEMORY(&alone_a[i], &oa, sizeof oa);
        TEST_ASSERT_EQUAL_MEMORY(&alone_b[i], &ob, sizeof ob);
        TEST_ASSERT_TRUE(ob.force[0] > oa.force[0]); /* the payload weighs */
    }
    stewart_inverse_free(a);
    stewart_inverse_free(b);
    stewart_inverse_free(c);
    stewart_model_free(other);
}

/* KINSOL from a poor guess (the home configuration) to a far pose, on the platform's mechanism:
 * exact and modified Newton, block and dense linear solvers land on the same solution. */
static void test_newton_from_home(void) {
    const mbs_model *mech = stewart_model_mechanism(model);
    stewart_pose target = {{0.03, -0.02, 0.53, 0.12, -0.08, 0.15}, {0}, {0}};
    double L[6];
    for (int k = 0; k < 6; ++k) L[k] = closed_form_length(&params, &target, k);
    const mbs_linear_solver kinds[3] = {MBS_LINEAR_AUTOMATIC, MBS_LINEAR_DENSE,
                                        MBS_LINEAR_KINSOL_DENSE};
    double lambda0[98];
    for (int kind = 0; kind < 3; ++kind)
        for (int modified = 0; modified <= 1; ++modified) {
            mbs_data *d = mbs_data_create(mech, kinds[kind]);
            TEST_ASSERT_NOT_NULL(d);
            for (int k = 0; k < 6; ++k) mbs_set_driver(d, k, L[k], 0, 0);
            mbs_options o;
            mbs_options_default(&o);
            o.modified_newton = modified;
            o.max_iterations = 50;
            TEST_ASSERT_EQUAL_MESSAGE(MBS_OK, mbs_step(d, 0, &o), mbs_data_message(d));
            TEST_ASSERT_TRUE(mbs_iterations(d) >= 3);
            TEST_ASSERT_TRUE(mbs_residual(d) <= 1e-12);
            const double *q = mbs_q(d);
            /* The platform (body 13, centre of mass at the plate centre here) reaches the pose. */
            for (int i = 0; i < 3; ++i)
                TEST_ASSERT_DOUBLE_WITHIN(1e-10, target.q[i], q[MBS_BODY_R(13) + i]);
            if (kind == 0 && modified == 0) memcpy(lambda0, mbs_lambda(d), sizeof lambda0);
            else
                for (int i = 0; i < 98; ++i) expect_relative(lambda0[i], mbs_lambda(d)[i], 1e-9);
            mbs_data_free(d);
        }
}

/* The same Newton iteration capped short of convergence: every capped step is reported as not
 * converged (never as a solution), and the residuals it stops at fall quadratically, as exact
 * Newton's must near a regular solution (r_k+1 <= r_k^2 here, r_k in metres). */
static void test_newton_capped_is_not_converged(void) {
    const mbs_model *mech = stewart_model_mechanism(model);
    stewart_pose target = {{0.03, -0.02, 0.53, 0.12, -0.08, 0.15}, {0}, {0}};
    double previous = INFINITY;
    for (int cap = 1; cap <= 4; ++cap) {
        mbs_data *d = mbs_data_create(mech, MBS_LINEAR_AUTOMATIC);
        TEST_ASSERT_NOT_NULL(d);
        for (int k = 0; k < 6; ++k)
            mbs_set_driver(d, k, closed_form_length(&params, &target, k), 0, 0);
        mbs_options o;
        mbs_options_default(&o);
        o.max_iterations = cap;
        const mbs_status s = mbs_step(d, 0, &o);
        const double r = mbs_residual(d);
        TEST_ASSERT_EQUAL_INT(cap, mbs_iterations(d));
        if (cap < 4) {
            TEST_ASSERT_EQUAL_INT_MESSAGE(MBS_ERR_NOT_CONVERGED, s, mbs_data_message(d));
            TEST_ASSERT_TRUE(r > o.tolerance);
            TEST_ASSERT_NOT_NULL_MESSAGE(strstr(mbs_data_message(d), "not converged"),
                                         mbs_data_message(d));
        } else {
            TEST_ASSERT_EQUAL_INT_MESSAGE(MBS_OK, s, mbs_data_message(d));
            TEST_ASSERT_TRUE(r <= o.tolerance);
        }
        TEST_ASSERT_TRUE(r < 0.1 && r <= previous * previous);
        previous = r;
        mbs_data_free(d);
    }
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_lengths_match_closed_form);
    RUN_TEST(test_lengths_are_the_solved_bodies);
    RUN_TEST(test_weightless_legs_equal_massless_level);
    RUN_TEST(test_weightless_legs_with_offset_payload);
    RUN_TEST(test_power_balance);
    RUN_TEST(test_thesis_formulation_agrees);
    RUN_TEST(test_normal_path_rarely_falls_back);
    RUN_TEST(test_thesis_forces_refuse_a_singular_pose);
    RUN_TEST(test_thesis_forces_never_overflow);
    RUN_TEST(test_huge_accelerations_are_out_of_range);
    RUN_TEST(test_massive_legs_at_rest);
    RUN_TEST(test_copy_is_rollback);
    RUN_TEST(test_rates_against_finite_differences);
    RUN_TEST(test_closed_form_motion_equals_solved);
    RUN_TEST(test_instances_side_by_side);
    RUN_TEST(test_newton_from_home);
    RUN_TEST(test_newton_capped_is_not_converged);
    RUN_TEST(test_normalisation_long_run);
    return UNITY_END();
}
