/* Linearisation (stewart_linearize.h) against references independent of its code:
 * - the plant's state rate against the inverse solver (the 14-body model at full fidelity): at the
 *   inverse forces of a pose with rates and accelerations, the plant's q_ddot is that pose's;
 * - A, B, C, D and the inverse side's Jacobian against central finite differences of the
 *   nonlinear functions (the plant's state rate and outputs; the inverse solver's lengths and
 *   forces), at random operating points of both fidelities and near the workspace edge;
 * - dL/dq and dL_dot/dq_dot against the leg Jacobian written out here;
 * - the life cycle: save, load, copy, bad input; no allocation in a call. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "allocation_counter.h"
#include "linearize_support.h"
#include "platform_fixture.h"
#include "stewart/stewart_linearize.h"
#include "test_support.h"
#include "unity.h"

static const double kStepState = LINEARIZE_STEP_STATE;
static const double kStepForce = LINEARIZE_STEP_FORCE;
static const double kRelative = 1e-7;

static double uniform(uint64_t *rng, double a, double b) {
    return a + (b - a) * (double)(test_random(rng) >> 11) / 9007199254740992.0;
}

/* A random pose of the workspace (legs within their stroke) with random rates and accelerations. */
static stewart_pose random_pose(uint64_t *rng) {
    stewart_pose p;
    const double q_half[6] = {0.08, 0.08, 0.05, 0.12, 0.12, 0.2};
    for (int i = 0; i < 6; ++i) {
        p.q[i] = uniform(rng, -q_half[i], q_half[i]);
        p.q_dot[i] = uniform(rng, -0.5, 0.5);
        p.q_ddot[i] = uniform(rng, -2, 2);
    }
    p.q[2] += params.home_height;
    return p;
}

static int within_stroke(const stewart_pose *p) {
    for (int k = 0; k < 6; ++k) {
        const double L = closed_form_length(&params, p, k);
        if (L < params.stroke_min[k] || L > params.stroke_max[k]) return 0;
    }
    return 1;
}

/* A pose at 99.9 % of the way from home to the stroke limit along a random direction. */
static stewart_pose edge_pose(uint64_t *rng) {
    stewart_pose p = random_pose(rng), home = p;
    double direction[6];
    for (int i = 0; i < 6; ++i) direction[i] = p.q[i] - (i == 2 ? params.home_height : 0);
    for (int i = 0; i < 6; ++i) home.q[i] = i == 2 ? params.home_height : 0;
    double inside = 0, outside = 1;
    for (;;) { /* grow until a leg leaves its stroke */
        for (int i = 0; i < 6; ++i) p.q[i] = home.q[i] + outside * direction[i];
        if (!within_stroke(&p)) break;
        inside = outside;
        outside *= 2;
    }
    for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (inside + outside);
        for (int i = 0; i < 6; ++i) p.q[i] = home.q[i] + mid * direction[i];
        if (within_stroke(&p)) inside = mid;
        else outside = mid;
    }
    for (int i = 0; i < 6; ++i) p.q[i] = home.q[i] + 0.999 * inside * direction[i];
    return p;
}

static stewart_linearize_output plant_ok(stewart_linearize *l, const stewart_linearize_input *in) {
    stewart_linearize_output out;
    const stewart_status s = stewart_linearize_plant(l, in, &out);
    TEST_ASSERT_EQUAL_MESSAGE(STEWART_OK, s, stewart_linearize_message(l));
    return out;
}

/* The forces of the inverse solver at the plant's fidelity (inverse fidelity numbers match). */
static void inverse_forces(int fidelity, const stewart_pose *pose, double force[6]) {
    stewart_pose p = *pose;
    const stewart_inverse_output out = solve_ok(data, fidelity, &p);
    memcpy(force, out.force, sizeof out.force);
}

/* A, B, C, D at one point against central differences of state_rate and output. */
static double check_plant_point(stewart_linearize *l, const stewart_linearize_input *in) {
    const stewart_linearize_output exact = plant_ok(l, in);
    /* blocks: A (q_ddot wrt q, wrt q_dot), B (q_ddot wrt F), C (L wrt q, L_dot wrt q, wrt q_dot),
     * D (outputs wrt F); A and C's constant rows are checked entry by entry too. */
    block_error blocks[8] = {{0, 0}};
    double rate_scale = 0, output_scale = 0;
    for (int i = 0; i < 12; ++i) rate_scale = fmax(rate_scale, fabs(exact.state_rate[i]));
    for (int i = 0; i < 24; ++i) output_scale = fmax(output_scale, fabs(exact.output[i]));
    for (int j = 0; j < 18; ++j) {
        stewart_linearize_input plus = *in, minus = *in;
        double h;
        if (j < 6) {
            h = kStepState;
            plus.pose.q[j] += h;
            minus.pose.q[j] -= h;
        } else if (j < 12) {
            h = kStepState;
            plus.pose.q_dot[j - 6] += h;
            minus.pose.q_dot[j - 6] -= h;
        } else {
            h = kStepForce;
            plus.force[j - 12] += h;
            minus.force[j - 12] -= h;
        }
        const stewart_linearize_output a = plant_ok(l, &plus), b = plant_ok(l, &minus);
        for (int i = 0; i < 12; ++i) {
            const double difference = (a.state_rate[i] - b.state_rate[i]) / (2 * h);
            const double analytic = j < 12 ? exact.A[i][j] : exact.B[i][j - 12];
            block_add(&blocks[i < 6 ? 7 : j < 6 ? 0 : j < 12 ? 1 : 2], analytic, difference);
        }
        for (int i = 0; i < 24; ++i) {
            const double difference = (a.output[i] - b.output[i]) / (2 * h);
            const double analytic = j < 12 ? exact.C[i][j] : exact.D[i][j - 12];
            int b_index = 7;
            if (i >= 12 && j < 12) b_index = i < 18 ? 3 : j < 6 ? 4 : 5;
            if (j >= 12) b_index = 6;
            block_add(&blocks[b_index], analytic, difference);
        }
    }
    /* blocks 0-2 of the state rate, by column unit (q, q_dot, F); 3-5 of the outputs */
    const double h_of[6] = {kStepState, kStepState, kStepForce, kStepState, kStepState, kStepState};
    double worst = 0;
    for (int b = 0; b < 6; ++b) {
        const double r = block_relative(blocks[b], b < 3 ? rate_scale : output_scale, h_of[b]);
        if (r > worst) worst = r;
    }
    /* The identity and zero rows are exact: their differences are 0 or 1 to rounding. */
    TEST_ASSERT_LESS_THAN_DOUBLE(1e-9, blocks[7].error);
    TEST_ASSERT_EQUAL_DOUBLE(0.0, blocks[6].scale); /* D = 0 */
    return worst;
}

static void plant_against_differences(int fidelity, int edge) {
    stewart_linearize *l = linearize_make(fidelity);
    uint64_t rng = 0x5eed1234u + (uint64_t)(fidelity * 7 + edge);
    double worst = 0;
    for (int n = 0; n < 12; ++n) {
        stewart_linearize_input in;
        in.pose = edge ? edge_pose(&rng) : random_pose(&rng);
        inverse_forces(fidelity, &in.pose, in.force);
        for (int k = 0; k < 6; ++k) in.force[k] *= uniform(&rng, 0.8, 1.2);
        const double e = check_plant_point(l, &in);
        if (e > worst) worst = e;
    }
    printf("fidelity %d%s: A, B, C against central differences, worst block error %.2e\n", fidelity,
           edge ? " near the stroke limits" : "", worst);
    TEST_ASSERT_LESS_THAN_DOUBLE(kRelative, worst);
    stewart_linearize_free(l);
}

static void test_plant_massless_against_differences(void) {
    plant_against_differences(STEWART_MASSLESS, 0);
}
static void test_plant_full_against_differences(void) {
    plant_against_differences(STEWART_FULL, 0);
}
static void test_plant_massless_near_edge(void) { plant_against_differences(STEWART_MASSLESS, 1); }
static void test_plant_full_near_edge(void) { plant_against_differences(STEWART_FULL, 1); }

/* The plant's state rate at the inverse forces of a pose is that pose's acceleration (the inverse
 * solver at full fidelity is the 14-body model: another formulation of the same physics). */
static void rate_matches_inverse(int fidelity) {
    stewart_linearize *l = linearize_make(fidelity);
    uint64_t rng = 99 + (uint64_t)fidelity;
    double worst = 0;
    for (int n = 0; n < 20; ++n) {
        stewart_linearize_input in;
        in.pose = random_pose(&rng);
        inverse_forces(fidelity, &in.pose, in.force);
        const stewart_linearize_output out = plant_ok(l, &in);
        for (int i = 0; i < 6; ++i) {
            TEST_ASSERT_EQUAL_DOUBLE(in.pose.q_dot[i], out.state_rate[i]);
            const double e = fabs(out.state_rate[6 + i] - in.pose.q_ddot[i]);
            if (e > worst) worst = e;
        }
        for (int k = 0; k < 6; ++k)
            TEST_ASSERT_DOUBLE_WITHIN(1e-12, closed_form_length(&params, &in.pose, k),
                                      out.output[12 + k]);
    }
    printf("fidelity %d: plant q_ddot at the inverse forces, worst error %.2e (of 2)\n", fidelity,
           worst);
    TEST_ASSERT_LESS_THAN_DOUBLE(1e-8, worst);
    stewart_linearize_free(l);
}
static void test_rate_matches_inverse_massless(void) { rate_matches_inverse(STEWART_MASSLESS); }
static void test_rate_matches_inverse_full(void) { rate_matches_inverse(STEWART_FULL); }

/* The inverse side's Jacobian against central differences of the inverse solver's lengths,
 * forces and base wrench (the 14-body model at full fidelity), and its values against that
 * solver's. */
static void inverse_against_differences(int fidelity, int edge) {
    stewart_linearize *l = linearize_make(fidelity);
    uint64_t rng = 777 + (uint64_t)(fidelity * 3 + edge);
    double worst = 0, worst_value = 0;
    for (int n = 0; n < 8; ++n) {
        stewart_pose pose = edge ? edge_pose(&rng) : random_pose(&rng);
        stewart_linearize_inverse_output exact;
        TEST_ASSERT_EQUAL_MESSAGE(STEWART_OK, stewart_linearize_inverse(l, &pose, &exact),
                                  stewart_linearize_message(l));
        stewart_pose p = pose;
        const stewart_inverse_output reference = solve_ok(data, fidelity, &p);
        double force_scale = 0;
        for (int k = 0; k < 6; ++k) {
            if (fabs(reference.force[k]) > force_scale) force_scale = fabs(reference.force[k]);
            const double e = fabs(exact.force[k] - reference.force[k]);
            if (e > worst_value) worst_value = e;
            TEST_ASSERT_DOUBLE_WITHIN(1e-12, reference.lengths.length[k], exact.lengths.length[k]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-12, reference.lengths.length_rate[k],
                                      exact.lengths.length_rate[k]);
            TEST_ASSERT_DOUBLE_WITHIN(1e-11, reference.lengths.length_accel[k],
                                      exact.lengths.length_accel[k]);
        }
        worst_value /= force_scale;
        for (int i = 0; i < 3; ++i) {
            const double e = fmax(fabs(exact.base_force[i] - reference.base_force[i]),
                                  fabs(exact.base_torque[i] - reference.base_torque[i]));
            if (e / force_scale > worst_value) worst_value = e / force_scale;
        }
        const double e = inverse_jacobian_error(&exact, &pose, fidelity);
        if (e > worst) worst = e;
    }
    printf("inverse fidelity %d%s: Jacobian against central differences of the inverse solver, "
           "worst block error %.2e; forces and base wrench against the solver's %.2e\n",
           fidelity, edge ? " near the stroke limits" : "", worst, worst_value);
    TEST_ASSERT_LESS_THAN_DOUBLE(kRelative, worst);
    TEST_ASSERT_LESS_THAN_DOUBLE(1e-9, worst_value);
    stewart_linearize_free(l);
}
static void test_inverse_massless_against_differences(void) {
    inverse_against_differences(STEWART_MASSLESS, 0);
}
static void test_inverse_full_against_differences(void) {
    inverse_against_differences(STEWART_FULL, 0);
}
static void test_inverse_full_near_edge(void) { inverse_against_differences(STEWART_FULL, 1); }

/* dL/dq written out: dL_k/dp = n_k, dL_k/d(angles) = ((R b_k) x n_k) . E columns, with
 * E = [Rz Ry e_x, Rz e_y, e_z]; and dL_dot/dq_dot is the same matrix. */
static void test_leg_jacobian_written_out(void) {
    stewart_linearize *l = linearize_make(STEWART_FULL);
    uint64_t rng = 4242;
    for (int n = 0; n < 5; ++n) {
        stewart_pose pose = random_pose(&rng);
        stewart_linearize_inverse_output out;
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_linearize_inverse(l, &pose, &out));
        double R[3][3];
        pose_rotation(&pose, R);
        const double cp = cos(pose.q[4]), sp = sin(pose.q[4]), cy = cos(pose.q[5]),
                     sy = sin(pose.q[5]);
        const double E[3][3] = {{cy * cp, -sy, 0}, {sy * cp, cy, 0}, {-sp, 0, 1}};
        for (int k = 0; k < 6; ++k) {
            const double ba = params.base_angle[k], pa = params.platform_angle[k];
            const double a[3] = {params.base_radius * cos(ba), params.base_radius * sin(ba), 0};
            const double b[3] = {params.platform_radius * cos(pa), params.platform_radius * sin(pa),
                                 0};
            double arm[3], d[3], L = 0;
            for (int i = 0; i < 3; ++i) {
                arm[i] = R[i][0] * b[0] + R[i][1] * b[1] + R[i][2] * b[2];
                d[i] = pose.q[i] + arm[i] - a[i];
                L += d[i] * d[i];
            }
            L = sqrt(L);
            const double nn[3] = {d[0] / L, d[1] / L, d[2] / L};
            const double m[3] = {arm[1] * nn[2] - arm[2] * nn[1], arm[2] * nn[0] - arm[0] * nn[2],
                                 arm[0] * nn[1] - arm[1] * nn[0]};
            double row[6];
            for (int i = 0; i < 3; ++i) row[i] = nn[i];
            for (int j = 0; j < 3; ++j)
                row[3 + j] = m[0] * E[0][j] + m[1] * E[1][j] + m[2] * E[2][j];
            for (int j = 0; j < 6; ++j) {
                TEST_ASSERT_DOUBLE_WITHIN(1e-13, row[j], out.jacobian[k][j]);
                TEST_ASSERT_DOUBLE_WITHIN(1e-13, row[j], out.jacobian[6 + k][6 + j]);
                TEST_ASSERT_DOUBLE_WITHIN(1e-13, row[j], out.jacobian[12 + k][12 + j]);
            }
        }
    }
    stewart_linearize_free(l);
}

static void test_life_cycle_and_bad_input(void) {
    char message[STEWART_MESSAGE_SIZE];
    stewart_linearize_options o;
    stewart_linearize_options_default(&o);
    TEST_ASSERT_EQUAL(STEWART_FULL, o.fidelity);
    o.fidelity = 0;
    TEST_ASSERT_NULL(stewart_linearize_create(model, &o, message, sizeof message));
    TEST_ASSERT_NOT_NULL(strstr(message, "fidelity = 0"));
    TEST_ASSERT_NULL(stewart_linearize_create(NULL, &o, message, sizeof message));

    stewart_linearize *full = linearize_make(STEWART_FULL),
                      *massless = linearize_make(STEWART_MASSLESS);
    uint64_t rng = 1;
    stewart_linearize_input in;
    in.pose = random_pose(&rng);
    inverse_forces(STEWART_FULL, &in.pose, in.force);
    const stewart_linearize_output reference = plant_ok(full, &in);

    /* save the full one, load it into the massless one: the same numbers */
    unsigned char bytes[64];
    TEST_ASSERT_TRUE(stewart_linearize_state_size(full) <= sizeof bytes);
    TEST_ASSERT_EQUAL(STEWART_OK, stewart_linearize_save(full, bytes, sizeof bytes));
    TEST_ASSERT_EQUAL(STEWART_OK,
                      stewart_linearize_load(massless, bytes, stewart_linearize_state_size(full)));
    stewart_linearize_output again = plant_ok(massless, &in);
    TEST_ASSERT_EQUAL_MEMORY(&reference, &again, sizeof again);
    bytes[0] ^= 1;
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT,
                      stewart_linearize_load(massless, bytes, stewart_linearize_state_size(full)));
    TEST_ASSERT_NOT_NULL(strstr(stewart_linearize_message(massless), "not a linearisation"));
    again = plant_ok(massless, &in); /* unchanged, still usable */
    TEST_ASSERT_EQUAL_MEMORY(&reference, &again, sizeof again);

    /* bad inputs: a message naming the value, the output untouched, the object usable */
    stewart_linearize_output untouched;
    memset(&untouched, 0x5a, sizeof untouched);
    stewart_linearize_input bad = in;
    bad.force[2] = NAN;
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT, stewart_linearize_plant(full, &bad, &untouched));
    TEST_ASSERT_NOT_NULL(strstr(stewart_linearize_message(full), "force[3]"));
    TEST_ASSERT_EQUAL_HEX8(0x5a, ((unsigned char *)&untouched)[100]);
    bad = in;
    bad.pose.q[4] = M_PI / 2;
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT, stewart_linearize_plant(full, &bad, &untouched));
    TEST_ASSERT_NOT_NULL(strstr(stewart_linearize_message(full), "pitch"));
    bad = in;
    bad.pose.q_dot[0] = INFINITY;
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT, stewart_linearize_plant(full, &bad, &untouched));
    bad = in;
    bad.pose.q_dot[3] = 1e300;
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT, stewart_linearize_plant(full, &bad, &untouched));
    TEST_ASSERT_NOT_NULL(strstr(stewart_linearize_message(full), "overflows"));
    /* a zero-length leg: the platform point on its base point */
    bad = in;
    for (int i = 0; i < 6; ++i) bad.pose.q[i] = 0;
    bad.pose.q[0] = params.base_radius * cos(params.base_angle[0]) -
                    params.platform_radius * cos(params.platform_angle[0]);
    bad.pose.q[1] = params.base_radius * sin(params.base_angle[0]) -
                    params.platform_radius * sin(params.platform_angle[0]);
    TEST_ASSERT_EQUAL(STEWART_ERR_UNREACHABLE, stewart_linearize_plant(massless, &bad, &untouched));
    TEST_ASSERT_EQUAL_HEX8(0x5a, ((unsigned char *)&untouched)[100]);
    again = plant_ok(full, &in);
    TEST_ASSERT_EQUAL_MEMORY(&reference, &again, sizeof again);
    TEST_ASSERT_EQUAL_STRING("", stewart_linearize_message(full));
    stewart_pose bad_pose = in.pose;
    bad_pose.q_ddot[5] = NAN;
    stewart_linearize_inverse_output inverse;
    TEST_ASSERT_EQUAL(STEWART_ERR_ARGUMENT, stewart_linearize_inverse(full, &bad_pose, &inverse));
    TEST_ASSERT_NOT_NULL(strstr(stewart_linearize_message(full), "q_ddot[5]"));

    TEST_ASSERT_EQUAL(STEWART_OK, stewart_linearize_copy(massless, full));
    stewart_linearize_reset(massless);
    TEST_ASSERT_EQUAL_STRING("", stewart_linearize_message(massless));
    stewart_linearize_free(full);
    stewart_linearize_free(massless);
    stewart_linearize_free(NULL);
}

/* The sensors' length_offset shifts the lengths, not their derivatives (tool and user frames:
 * test_linearize_frames.c). */
static void test_length_offset(void) {
    uint64_t rng = 77;
    stewart_linearize_input in;
    in.pose = random_pose(&rng);
    inverse_forces(STEWART_FULL, &in.pose, in.force);
    params.length_offset[2] = 0.01;
    rebuild_platform();
    stewart_linearize *l = linearize_make(STEWART_FULL);
    const stewart_linearize_output out = plant_ok(l, &in);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, closed_form_length(&params, &in.pose, 2) - 0.01,
                              out.output[14]);
    TEST_ASSERT_DOUBLE_WITHIN(1e-12, closed_form_length(&params, &in.pose, 1), out.output[13]);
    stewart_linearize_free(l);
}

/* No heap allocation in either call (allocation_counter.c interposes malloc and friends). */
static void test_no_allocation(void) {
    stewart_linearize *l = linearize_make(STEWART_FULL);
    uint64_t rng = 31;
    stewart_linearize_input in;
    in.pose = random_pose(&rng);
    inverse_forces(STEWART_FULL, &in.pose, in.force);
    stewart_linearize_output out;
    stewart_linearize_inverse_output inverse;
    const long before = allocations;
    for (int n = 0; n < 10; ++n) {
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_linearize_plant(l, &in, &out));
        TEST_ASSERT_EQUAL(STEWART_OK, stewart_linearize_inverse(l, &in.pose, &inverse));
    }
    TEST_ASSERT_EQUAL(0, allocations - before);
    stewart_linearize_free(l);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_rate_matches_inverse_massless);
    RUN_TEST(test_rate_matches_inverse_full);
    RUN_TEST(test_plant_massless_against_differences);
    RUN_TEST(test_plant_full_against_differences);
    RUN_TEST(test_plant_massless_near_edge);
    RUN_TEST(test_plant_full_near_edge);
    RUN_TEST(test_inverse_massless_against_differences);
    RUN_TEST(test_inverse_full_against_differences);
    RUN_TEST(test_inverse_full_near_edge);
    RUN_TEST(test_leg_jacobian_written_out);
    RUN_TEST(test_life_cycle_and_bad_input);
    RUN_TEST(test_length_offset);
    RUN_TEST(test_no_allocation);
    return UNITY_END();
}
