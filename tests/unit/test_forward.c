/* Forward kinematics against the inverse side's closed form (lengths, rates and accelerations
 * from the pose written out in test_support.c and by stewart_inverse_solve), the mirror pose (same
 * lengths, computed here), the 14-body mechanism driven by the lengths, and bad input. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "platform_fixture.h"
#include "stewart/stewart_forward.h"
#include "stewart/stewart_full.h"
#include "test_support.h"
#include "unity.h"

static unsigned long long rng_state = 12345;
static double uniform(double lo, double hi) {
    rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * (double)(rng_state >> 11) / 9007199254740992.0;
}

/* Every leg leaves its base point upward and reaches its platform point from below the platform
 * (the legs' Cardans work in those half-spaces), written out from the pose. */
static int legs_on_the_joint_sides(const stewart_pose *p) {
    double R[3][3];
    pose_rotation(p, R);
    for (int k = 0; k < 6; ++k) {
        const double b[2] = {params.platform_radius * cos(params.platform_angle[k]),
                             params.platform_radius * sin(params.platform_angle[k])};
        const double a[2] = {params.base_radius * cos(params.base_angle[k]),
                             params.base_radius * sin(params.base_angle[k])};
        double leg[3], along_normal = 0;
        for (int i = 0; i < 3; ++i) {
            leg[i] = p->q[i] + R[i][0] * b[0] + R[i][1] * b[1] - (i < 2 ? a[i] : 0);
            along_normal += leg[i] * R[i][2];
        }
        if (!(leg[2] > 0 && along_normal > 0)) return 0;
    }
    return 1;
}

/* A random pose of the stroke workspace (every length in [stroke_min, stroke_max], the legs on
 * their joints' sides, condition below warn_condition), with random rates and accelerations; its
 * lengths from the closed form. */
static stewart_pose workspace_pose(stewart_inverse_output *legs) {
    for (;;) {
        stewart_pose p = {{0}, {0}, {0}};
        const double box[6] = {0.15, 0.15, 0.15, 0.35, 0.35, 0.45};
        for (int i = 0; i < 6; ++i) {
            p.q[i] = uniform(-box[i], box[i]) + (i == 2 ? 0.5 : 0);
            p.q_dot[i] = uniform(-1, 1);
            p.q_ddot[i] = uniform(-10, 10);
        }
        int inside = 1;
        for (int k = 0; k < 6; ++k) {
            const double L = closed_form_length(&params, &p, k);
            inside = inside && L >= params.stroke_min[k] && L <= params.stroke_max[k];
        }
        if (!inside || !legs_on_the_joint_sides(&p)) continue;
        *legs = solve_ok(data, STEWART_MASSLESS, &p);
        if (legs->condition < 1e3) return p;
    }
}

static stewart_forward_options default_options(void) {
    stewart_forward_options o;
    stewart_forward_options_default(&o);
    return o;
}

static double max_abs_diff(const double *a, const double *b, int n) {
    double worst = 0;
    for (int i = 0; i < n; ++i) worst = fmax(worst, fabs(a[i] - b[i]));
    return worst;
}
static double max_abs(const double *a, int n) {
    double worst = 0;
    for (int i = 0; i < n; ++i) worst = fmax(worst, fabs(a[i]));
    return worst;
}

/* The pose, rates and accelerations of `r` against `truth`: 1e-12 m and rad, 1e-9 relative (to
 * the largest component, at least 1e-6: a derivative that is zero is matched to 1e-15). */
static void check_round_trip(const stewart_forward_output *r, const stewart_pose *truth,
                             int derivatives) {
    char text[200];
    snprintf(text, sizeof text, "pose error %.3g", max_abs_diff(r->pose.q, truth->q, 6));
    TEST_ASSERT_TRUE_MESSAGE(max_abs_diff(r->pose.q, truth->q, 6) <= 1e-12, text);
    if (!derivatives) return;
    snprintf(text, sizeof text, "rate error %.3g of %.3g",
             max_abs_diff(r->pose.q_dot, truth->q_dot, 6), max_abs(truth->q_dot, 6));
    TEST_ASSERT_TRUE_MESSAGE(max_abs_diff(r->pose.q_dot, truth->q_dot, 6) <=
                                 1e-9 * fmax(max_abs(truth->q_dot, 6), 1e-6),
                             text);
    snprintf(text, sizeof text, "acceleration error %.3g of %.3g",
             max_abs_diff(r->pose.q_ddot, truth->q_ddot, 6), max_abs(truth->q_ddot, 6));
    TEST_ASSERT_TRUE_MESSAGE(max_abs_diff(r->pose.q_ddot, truth->q_ddot, 6) <=
                                 1e-9 * fmax(max_abs(truth->q_ddot, 6), 1e-6),
                             text);
}

/* stewart_forward_solve on the fixture's solver with the inputs as arrays (rates, accels and
 * guess NULL for none). */
static stewart_status forward_arrays(double t, const double *L, const double *rates,
                                     const double *accels, const double *guess,
                                     stewart_forward_output *r) {
    stewart_forward_input in;
    memset(&in, 0, sizeof in);
    in.time = t;
    memcpy(in.lengths.length, L, sizeof in.lengths.length);
    if (rates) memcpy(in.lengths.length_rate, rates, sizeof in.lengths.length_rate);
    if (accels) memcpy(in.lengths.length_accel, accels, sizeof in.lengths.length_accel);
    in.derivatives = accels ? 2 : rates ? 1 : 0;
    in.use_guess = guess != NULL;
    if (guess) memcpy(in.guess, guess, sizeof in.guess);
    return stewart_forward_solve(forward_solver, &in, r);
}

static stewart_status forward(const stewart_inverse_output *legs, double t, int derivatives,
                              const double *guess, stewart_forward_output *r) {
    return forward_arrays(t, legs->lengths.length, derivatives ? legs->lengths.length_rate : NULL,
                          derivatives ? legs->lengths.length_accel : NULL, guess, r);
}

/* A pose drawn in the workspace (its legs' lengths, rates and accelerations in legs), solved
 * cold from home with its rates into r, which must succeed; returns the pose. */
static stewart_pose cold_start_from_home(stewart_inverse_output *legs, stewart_forward_output *r) {
    const stewart_pose truth = workspace_pose(legs);
    stewart_forward_reset(forward_solver);
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, forward(legs, 0, 1, NULL, r),
                                  stewart_forward_message(forward_solver));
    return truth;
}

static void test_cold_starts_over_the_workspace_find_the_pose(void) {
    int worst_iterations = 0;
    for (int i = 0; i < 2000; ++i) {
        stewart_inverse_output legs;
        stewart_forward_output r;
        const stewart_pose truth = cold_start_from_home(&legs, &r);
        TEST_ASSERT_EQUAL_INT(STEWART_START_HOME, r.start);
        TEST_ASSERT_EQUAL_INT(0, r.branch);
        TEST_ASSERT_EQUAL_INT(0, r.warnings);
        TEST_ASSERT_TRUE(r.residual <= 1e-12);
        check_round_trip(&r, &truth, 1);
        if (r.iterations > worst_iterations) worst_iterations = r.iterations;
    }
    printf("2000 cold starts from home: at most %d iterations\n", worst_iterations);
}

/* Any geometry the parameters describe: another 6-6 platform (radii, angles, home height),
 * cold starts from home over its stroke workspace and the mirror pose. */
static void test_another_geometry_round_trips(void) {
    static const double beta_deg[6] = {10, 110, 130, 230, 250, 350};
    static const double tau_deg[6] = {50, 70, 170, 190, 290, 310};
    params.base_radius = 0.7;
    params.platform_radius = 0.35;
    params.home_height = 0.55;
    for (int k = 0; k < 6; ++k) {
        params.base_angle[k] = beta_deg[k] * M_PI / 180;
        params.platform_angle[k] = tau_deg[k] * M_PI / 180;
    }
    for (int k = 0; k < 6; ++k) params.stroke_min[k] = 0.45, params.stroke_max[k] = 0.85;
    rebuild_platform();
    for (int i = 0; i < 500; ++i) {
        stewart_inverse_output legs;
        stewart_forward_output r;
        const stewart_pose truth = cold_start_from_home(&legs, &r);
        check_round_trip(&r, &truth, 1);
        double guess[6];
        for (int j = 0; j < 6; ++j) guess[j] = (j >= 2 && j < 5 ? -1 : 1) * truth.q[j];
        TEST_ASSERT_EQUAL_INT(STEWART_ERR_OTHER_BRANCH, forward(&legs, 0, 0, guess, &r));
        TEST_ASSERT_TRUE(r.branch & STEWART_BRANCH_BELOW_BASE);
    }
}

/* Tracking a manoeuvre at 1 kHz: every sample's pose, rates and accelerations; with the rates
 * given (Taylor predictor) and without them (secant predictor, pose only). */
static void track(stewart_pose (*manoeuvre)(int, double), int component, int derivatives) {
    stewart_forward_reset(forward_solver);
    int worst_iterations = 0;
    for (int i = 0; i <= 3000; ++i) {
        const double t = 1e-3 * i;
        const stewart_pose truth = manoeuvre(component, t);
        const stewart_inverse_output legs = solve_ok(data, STEWART_KINEMATIC, &truth);
        stewart_forward_output r;
        TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, forward(&legs, t, derivatives, NULL, &r),
                                      stewart_forward_message(forward_solver));
        /* Without rates the predictor needs two poses: the second sample starts from the first. */
        TEST_ASSERT_EQUAL_INT(i == 0                 ? STEWART_START_HOME
                              : derivatives || i > 1 ? STEWART_START_PREDICTOR
                                                     : STEWART_START_LAST,
                              r.start);
        check_round_trip(&r, &truth, derivatives);
        if (i > 0 && r.iterations > worst_iterations) worst_iterations = r.iterations;
    }
    printf("tracking component %d (derivatives %d): at most %d iterations per sample\n", component,
           derivatives, worst_iterations);
}

static stewart_pose combined(int component, double t) {
    (void)component;
    return combined_pose(t);
}

static void test_tracking_the_combined_cue(void) {
    track(combined, 0, 1);
    track(combined, 0, 0);
}

static void test_tracking_the_thesis_manoeuvres(void) {
    for (int c = 2; c < 6; ++c) track(thesis_pose, c, 1);
}

static void test_mirror_pose_is_another_branch_never_returned_from_home(void) {
    for (int i = 0; i < 200; ++i) {
        stewart_inverse_output legs;
        const stewart_pose truth = workspace_pose(&legs);
        /* The pose mirrored through the base plane: S R S with S = diag(1, 1, -1) keeps Rz and
         * reverses Ry and Rx, so (x, y, -z, -roll, -pitch, yaw). */
        stewart_pose mirror = truth;
        for (int j = 2; j < 5; ++j) mirror.q[j] = -truth.q[j];
        for (int k = 0; k < 6; ++k)
            TEST_ASSERT_DOUBLE_WITHIN(1e-14, legs.lengths.length[k],
                                      closed_form_length(&params, &mirror, k));
        double guess[6];
        for (int j = 0; j < 6; ++j) guess[j] = mirror.q[j] + uniform(-0.02, 0.02);
        stewart_forward_output r;
        TEST_ASSERT_EQUAL_INT(STEWART_ERR_OTHER_BRANCH, forward(&legs, 0, 0, guess, &r));
        TEST_ASSERT_TRUE(r.branch & STEWART_BRANCH_BELOW_BASE);
        TEST_ASSERT_TRUE(r.warnings & STEWART_WARN_OTHER_BRANCH);
        TEST_ASSERT_TRUE(max_abs_diff(r.pose.q, mirror.q, 6) <= 1e-12);
        TEST_ASSERT_NOT_NULL(strstr(stewart_forward_message(forward_solver), "below the base"));
        stewart_forward_reset(forward_solver);
        TEST_ASSERT_EQUAL_INT(STEWART_OK, forward(&legs, 0, 0, NULL, &r));
        TEST_ASSERT_TRUE(r.pose.q[2] > 0);
        check_round_trip(&r, &truth, 0);
    }
}

/* Tracking: lengths whose pose lies farther from the last pose than the stroke allows in one
 * sample are reported as a jump, not taken; the history stays, a cold start takes them. */
static void test_a_jump_larger_than_the_stroke_is_reported(void) {
    stewart_pose near = {{0, 0, 0.5, 0, 0, 0}, {0}, {0}};
    stewart_pose far = {{0.15, -0.1, 0.45, 0.1, 0, 0.3}, {0}, {0}};
    const stewart_inverse_output near_legs = solve_ok(data, STEWART_KINEMATIC, &near);
    const stewart_inverse_output far_legs = solve_ok(data, STEWART_KINEMATIC, &far);
    stewart_forward_reset(forward_solver);
    stewart_forward_output r;
    TEST_ASSERT_EQUAL_INT(STEWART_OK, forward(&near_legs, 0, 0, NULL, &r));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_OTHER_BRANCH, forward(&far_legs, 1e-3, 0, NULL, &r));
    TEST_ASSERT_EQUAL_INT(STEWART_BRANCH_JUMP, r.branch);
    TEST_ASSERT_TRUE(r.jump > params.stroke_max[0] - params.stroke_min[0]);
    check_round_trip(&r, &far, 0); /* the pose found is shown, for inspection */
    TEST_ASSERT_EQUAL_INT(STEWART_OK, forward(&near_legs, 2e-3, 0, NULL, &r));
    TEST_ASSERT_EQUAL_INT(STEWART_START_LAST, r.start); /* still tracking from `near` */
    stewart_forward_reset(forward_solver);
    TEST_ASSERT_EQUAL_INT(STEWART_OK, forward(&far_legs, 3e-3, 0, NULL, &r));
    check_round_trip(&r, &far, 0);
}

/* The thesis geometry is singular at yaw = 90 deg: warning on the way, error there, and the
 * next good measurement tracks again. */
static void test_singular_pose_fails_and_the_next_measurement_recovers(void) {
    stewart_forward_reset(forward_solver);
    int warned = 0;
    stewart_forward_output r;
    const int samples = 93;
    for (int i = 0; i <= samples; ++i) {
        /* 0, 1, .., 89 deg, then 90 - 10^-1 .. 90 - 10^-3 deg, then 90 deg */
        const double deg = i < 90 ? i : i < samples ? 90 - pow(10, 89 - i) : 90;
        stewart_pose p = {{0, 0, 0.5, 0, 0, deg * M_PI / 180}, {0}, {0}};
        const stewart_inverse_output legs = solve_ok(data, STEWART_KINEMATIC, &p);
        memset(&r, 0x5a, sizeof r);
        const stewart_forward_output untouched = r;
        const stewart_status s = forward(&legs, i, 0, NULL, &r);
        if (i < samples) {
            TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, s, stewart_forward_message(forward_solver));
            if (r.condition < 1e3) check_round_trip(&r, &p, 0); /* else error ~ condition eps */
            if (r.condition > 1e3) {
                TEST_ASSERT_TRUE(r.warnings & STEWART_WARN_NEAR_SINGULAR);
                ++warned;
            }
        } else {
            TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_ERR_SINGULAR, s,
                                          stewart_forward_message(forward_solver));
            TEST_ASSERT_NOT_NULL(strstr(stewart_forward_message(forward_solver), "condition"));
            TEST_ASSERT_EQUAL_MEMORY(&untouched, &r, sizeof r);
        }
    }
    TEST_ASSERT_TRUE(warned > 0);
    stewart_pose back = {{0, 0, 0.5, 0, 0, 85 * M_PI / 180}, {0}, {0}};
    const stewart_inverse_output legs = solve_ok(data, STEWART_KINEMATIC, &back);
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, forward(&legs, samples + 1, 0, NULL, &r),
                                  stewart_forward_message(forward_solver));
    check_round_trip(&r, &back, 0);
}

static void test_lengths_no_pose_has_are_an_error_naming_the_leg(void) {
    stewart_pose home = {{0, 0, 0.5, 0, 0, 0}, {0}, {0}};
    stewart_inverse_output legs = solve_ok(data, STEWART_KINEMATIC, &home);
    for (int leg = 0; leg < 6; ++leg) {
        stewart_inverse_output bad = legs;
        bad.lengths.length[leg] = 3.0;
        stewart_forward_output r;
        memset(&r, 0x5a, sizeof r);
        const stewart_forward_output untouched = r;
        stewart_forward_reset(forward_solver);
        TEST_ASSERT_EQUAL_INT(STEWART_ERR_UNREACHABLE, forward(&bad, 0, 0, NULL, &r));
        char expected[16];
        snprintf(expected, sizeof expected, "leg %d", leg + 1);
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(stewart_forward_message(forward_solver), expected),
                                     stewart_forward_message(forward_solver));
        TEST_ASSERT_EQUAL_MEMORY(&untouched, &r, sizeof r);
    }
    stewart_forward_output r;
    /* All six at 0.2 m: legs 1 and 2 join base points 2 r sin 15 deg = 0.259 m apart to platform
     * points 2 r sin 45 deg = 0.707 m apart, so together they need at least 0.448 m. */
    stewart_inverse_output short_legs = legs;
    for (int k = 0; k < 6; ++k) short_legs.lengths.length[k] = 0.2;
    stewart_forward_reset(forward_solver);
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_UNREACHABLE, forward(&short_legs, 0, 0, NULL, &r));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(stewart_forward_message(forward_solver), "legs 1 and 2"),
                                 stewart_forward_message(forward_solver));
    /* All six equal and huge: a pose far up has them, but nothing is returned as NaN. */
    stewart_inverse_output far = legs;
    for (int k = 0; k < 6; ++k) far.lengths.length[k] = 1e140;
    stewart_forward_reset(forward_solver);
    const stewart_status s = forward(&far, 0, 0, NULL, &r);
    TEST_ASSERT_TRUE(s == STEWART_OK || s == STEWART_ERR_NOT_CONVERGED);
    if (s == STEWART_OK) TEST_ASSERT_TRUE(isfinite(r.pose.q[2]));
}

static void test_lengths_outside_the_stroke_are_solved_with_the_warning(void) {
    stewart_pose high = {{0.02, -0.01, 0.8, 0.05, 0, 0.1}, {0}, {0}};
    const stewart_inverse_output legs = solve_ok(data, STEWART_KINEMATIC, &high);
    TEST_ASSERT_TRUE(legs.lengths.length[0] > params.stroke_max[0]);
    stewart_forward_output r;
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, forward(&legs, 0, 0, NULL, &r),
                                  stewart_forward_message(forward_solver));
    TEST_ASSERT_TRUE(r.warnings & STEWART_WARN_STROKE);
    check_round_trip(&r, &high, 0);
}

static void test_bad_input_is_named_and_the_block_stays_usable(void) {
    stewart_pose home = {{0, 0, 0.5, 0, 0, 0}, {0}, {0}};
    stewart_inverse_output legs = solve_ok(data, STEWART_KINEMATIC, &home);
    stewart_forward_options o = default_options();
    stewart_forward_output r;
    double bad[6];
    memcpy(bad, legs.lengths.length, sizeof bad);
    bad[2] = NAN;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, forward_arrays(0, bad, NULL, NULL, NULL, &r));
    TEST_ASSERT_NOT_NULL(strstr(stewart_forward_message(forward_solver), "L3"));
    bad[2] = -0.5;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, forward_arrays(0, bad, NULL, NULL, NULL, &r));
    TEST_ASSERT_NOT_NULL(strstr(stewart_forward_message(forward_solver), "L3"));
    double rates[6] = {0, INFINITY, 0, 0, 0, 0};
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT,
                          forward_arrays(0, legs.lengths.length, rates, NULL, NULL, &r));
    TEST_ASSERT_NOT_NULL(strstr(stewart_forward_message(forward_solver), "L_dot2"));
    stewart_forward_input in = {0, legs.lengths, 3, 0, {0}};
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_forward_solve(forward_solver, &in, &r));
    TEST_ASSERT_NOT_NULL(strstr(stewart_forward_message(forward_solver), "derivatives is 3"));
    double guess[6] = {0, 0, 0.5, NAN, 0, 0};
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT,
                          forward_arrays(0, legs.lengths.length, NULL, NULL, guess, &r));
    TEST_ASSERT_NOT_NULL(strstr(stewart_forward_message(forward_solver), "roll"));
    char msg[STEWART_MESSAGE_SIZE];
    o.tolerance = 1e-17;
    TEST_ASSERT_NULL(stewart_forward_create(model, &o, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL(strstr(msg, "tolerance"));
    TEST_ASSERT_NULL(stewart_forward_create(NULL, &o, msg, sizeof msg));
    TEST_ASSERT_NOT_NULL(strstr(msg, "model is NULL"));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_forward_solve(forward_solver, NULL, &r));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_forward_solve(forward_solver, &in, NULL));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_forward_solve(NULL, &in, &r));
    TEST_ASSERT_EQUAL_INT(STEWART_OK, forward_arrays(0, legs.lengths.length, NULL, NULL, NULL, &r));
    TEST_ASSERT_EQUAL_STRING("", stewart_forward_message(forward_solver));
    check_round_trip(&r, &home, 0);
}

/* The 14-body mechanism driven by the same lengths (KINSOL on its constraint equations) places
 * every body where the full level's closed-form placement of the forward pose puts it. */
static void test_forward_pose_agrees_with_the_length_driven_mechanism(void) {
    mbs_data *mech = mbs_data_create(stewart_model_mechanism(model), MBS_LINEAR_AUTOMATIC);
    TEST_ASSERT_NOT_NULL(mech);
    mbs_options mo;
    mbs_options_default(&mo);
    stewart_forward_reset(forward_solver);
    double worst_position = 0, worst_rotation = 0;
    for (int i = 0; i <= 2000; ++i) {
        const double t = 1e-3 * i;
        const stewart_pose pose = combined_pose(t);
        const stewart_inverse_output legs = solve_ok(data, STEWART_KINEMATIC, &pose);
        for (int k = 0; k < 6; ++k)
            mbs_set_driver(mech, k, legs.lengths.length[k], legs.lengths.length_rate[k],
                           legs.lengths.length_accel[k]);
        TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, mbs_step(mech, t, &mo), mbs_data_message(mech));
        stewart_forward_output r;
        TEST_ASSERT_EQUAL_INT(STEWART_OK, forward(&legs, t, 1, NULL, &r));
        if (i % 100 != 0) continue;
        solve_ok(data, STEWART_FULL, &r.pose);
        const double *q = mbs_q(mech), *ref = mbs_q(stewart_inverse_mechanism(data));
        for (int b = 1; b < 14; ++b) {
            const double *e = q + 7 * b + 3, *e_ref = ref + 7 * b + 3;
            worst_position = fmax(worst_position, max_abs_diff(q + 7 * b, ref + 7 * b, 3));
            const double dot =
                e[0] * e_ref[0] + e[1] * e_ref[1] + e[2] * e_ref[2] + e[3] * e_ref[3];
            for (int c = 0; c < 4; ++c)
                worst_rotation = fmax(worst_rotation, fabs(e[c] - (dot < 0 ? -1 : 1) * e_ref[c]));
        }
    }
    printf("forward pose vs the length-driven 14-body mechanism: body positions within %.3g m, "
           "Euler parameters within %.3g\n",
           worst_position, worst_rotation);
    mbs_data_free(mech);
    TEST_ASSERT_TRUE(worst_position <= 1e-11);
    TEST_ASSERT_TRUE(worst_rotation <= 1e-12);
}

/* Rollback of the tracking history: after saving (bytes) and copying it, three more measurements
 * are solved; loaded back (or copied back), the same three measurements give bit for bit the same
 * poses, starts and iterations. Without the rollback they do not (the history moved on), and bytes
 * that are not a history are refused by name with the solver unchanged. */
static void test_rollback_restores_the_tracking_history(void) {
    stewart_inverse_output legs[9];
    for (int j = 0; j < 9; ++j) {
        const stewart_pose p = combined_pose(0.01 * j);
        legs[j] = solve_ok(data, STEWART_KINEMATIC, &p);
    }
    stewart_forward_output r;
    for (int j = 0; j < 6; ++j)
        TEST_ASSERT_EQUAL_INT(STEWART_OK, forward(&legs[j], 0.01 * j, 1, NULL, &r));
    unsigned char bytes[1024];
    const size_t size = stewart_forward_state_size(forward_solver);
    TEST_ASSERT_TRUE(size > 0 && size <= sizeof bytes);
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_forward_save(forward_solver, bytes, size));
    stewart_forward_options o = default_options();
    stewart_forward *copy = stewart_forward_create(model, &o, NULL, 0);
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_forward_copy(copy, forward_solver));
    stewart_forward_output first[3], again[3], from_copy[3];
    for (int j = 0; j < 3; ++j)
        TEST_ASSERT_EQUAL_INT(STEWART_OK,
                              forward(&legs[6 + j], 0.01 * (6 + j), 1, NULL, &first[j]));
    TEST_ASSERT_EQUAL_INT(STEWART_START_PREDICTOR, first[0].start);
    /* without a rollback the same measurement is solved from another history */
    stewart_forward_output moved_on;
    TEST_ASSERT_EQUAL_INT(STEWART_OK, forward(&legs[6], 0.06, 1, NULL, &moved_on));
    TEST_ASSERT_NOT_EQUAL(0, memcmp(&moved_on, &first[0], sizeof moved_on));
    /* refused bytes: a wrong version, a flag that is not 0 or 1, a value that is not finite */
    unsigned char bad[1024];
    memcpy(bad, bytes, size);
    bad[4] ^= 1;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_forward_load(forward_solver, bad, size));
    TEST_ASSERT_NOT_NULL(strstr(stewart_forward_message(forward_solver), "version"));
    memcpy(bad, bytes, size);
    bad[3 * sizeof(unsigned)] = 2;
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_forward_load(forward_solver, bad, size));
    TEST_ASSERT_NOT_NULL(strstr(stewart_forward_message(forward_solver), "flag 0 is 2"));
    memcpy(bad, bytes, size);
    bad[3 * sizeof(unsigned) + 5] = 9; /* the leg Jacobian's first pivot, out of range */
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_forward_load(forward_solver, bad, size));
    TEST_ASSERT_NOT_NULL(strstr(stewart_forward_message(forward_solver), "factors"));
    memcpy(bad, bytes, size);
    const double nan = NAN;
    memcpy(bad + size - sizeof nan, &nan, sizeof nan);
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_forward_load(forward_solver, bad, size));
    TEST_ASSERT_NOT_NULL(strstr(stewart_forward_message(forward_solver), "finite"));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT,
                          stewart_forward_load(forward_solver, bytes, size - 1));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT,
                          stewart_forward_save(forward_solver, bad, size - 1));
    TEST_ASSERT_NOT_NULL(strstr(stewart_forward_message(forward_solver), "the state needs"));
    /* loaded back: the three solves again, bit for bit */
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_forward_load(forward_solver, bytes, size));
    for (int j = 0; j < 3; ++j)
        TEST_ASSERT_EQUAL_INT(STEWART_OK,
                              forward(&legs[6 + j], 0.01 * (6 + j), 1, NULL, &again[j]));
    TEST_ASSERT_EQUAL_MEMORY(first, again, sizeof first);
    /* and from the copy */
    stewart_forward *kept = forward_solver;
    forward_solver = copy;
    for (int j = 0; j < 3; ++j)
        TEST_ASSERT_EQUAL_INT(STEWART_OK,
                              forward(&legs[6 + j], 0.01 * (6 + j), 1, NULL, &from_copy[j]));
    forward_solver = kept;
    TEST_ASSERT_EQUAL_MEMORY(first, from_copy, sizeof first);
    stewart_forward_free(copy);
}

/* Tracking at 1 kHz takes one chord step on the last pose's factored Jacobian: the answer is
 * exact Newton's. A second solver solves every sample by exact Newton from a guess (the last
 * pose); poses, rates and accelerations agree, and both are the closed-form truth. */
static void test_chord_step_gives_exact_newtons_answer(void) {
    stewart_forward_options o = default_options();
    stewart_forward *exact = stewart_forward_create(model, &o, NULL, 0);
    TEST_ASSERT_NOT_NULL(exact);
    stewart_forward *kept = forward_solver;
    stewart_forward_reset(forward_solver);
    double last[6] = {0};
    double worst[3] = {0, 0, 0};
    for (int j = 0; j < 300; ++j) {
        const stewart_pose truth = combined_pose(1e-3 * j);
        const stewart_inverse_output legs = solve_ok(data, STEWART_KINEMATIC, &truth);
        stewart_forward_output tracked, newton;
        forward_solver = kept;
        TEST_ASSERT_EQUAL_INT(STEWART_OK, forward(&legs, 1e-3 * j, 1, NULL, &tracked));
        if (j >= 2) {
            TEST_ASSERT_EQUAL_INT(STEWART_START_PREDICTOR, tracked.start);
            TEST_ASSERT_EQUAL_INT(1, tracked.iterations);
        }
        if (j > 0) {
            forward_solver = exact;
            stewart_forward_reset(exact);
            TEST_ASSERT_EQUAL_INT(STEWART_OK, forward(&legs, 1e-3 * j, 1, last, &newton));
            const double *a[3] = {tracked.pose.q, tracked.pose.q_dot, tracked.pose.q_ddot};
            const double *b[3] = {newton.pose.q, newton.pose.q_dot, newton.pose.q_ddot};
            const double *t[3] = {truth.q, truth.q_dot, truth.q_ddot};
            for (int g = 0; g < 3; ++g)
                for (int i = 0; i < 6; ++i) {
                    worst[g] = fmax(worst[g], fabs(a[g][i] - b[g][i]));
                    TEST_ASSERT_TRUE(fabs(a[g][i] - t[g][i]) <= (g == 0 ? 1e-12 : 1e-9));
                }
        }
        memcpy(last, tracked.pose.q, sizeof last);
    }
    forward_solver = kept;
    stewart_forward_free(exact);
    printf("chord vs exact Newton: pose %.3g, rates %.3g, accelerations %.3g\n", worst[0], worst[1],
           worst[2]);
    TEST_ASSERT_TRUE(worst[0] <= 1e-14);
    TEST_ASSERT_TRUE(worst[1] <= 1e-11);
    TEST_ASSERT_TRUE(worst[2] <= 1e-10);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_cold_starts_over_the_workspace_find_the_pose);
    RUN_TEST(test_another_geometry_round_trips);
    RUN_TEST(test_tracking_the_combined_cue);
    RUN_TEST(test_tracking_the_thesis_manoeuvres);
    RUN_TEST(test_mirror_pose_is_another_branch_never_returned_from_home);
    RUN_TEST(test_a_jump_larger_than_the_stroke_is_reported);
    RUN_TEST(test_singular_pose_fails_and_the_next_measurement_recovers);
    RUN_TEST(test_lengths_no_pose_has_are_an_error_naming_the_leg);
    RUN_TEST(test_lengths_outside_the_stroke_are_solved_with_the_warning);
    RUN_TEST(test_bad_input_is_named_and_the_block_stays_usable);
    RUN_TEST(test_forward_pose_agrees_with_the_length_driven_mechanism);
    RUN_TEST(test_rollback_restores_the_tracking_history);
    RUN_TEST(test_chord_step_gives_exact_newtons_answer);
    return UNITY_END();
}
