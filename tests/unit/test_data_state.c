/* A data block saved to bytes and loaded into another one holds the same state and continues
 * exactly as the original; bytes that are not a state, or a state that does not fit the model
 * (issue 15 item 2), are refused and change nothing; a data block is used only with its model
 * (item 3). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "stewart/stewart_full.h"

#include "platform_fixture.h"
#include "test_support.h"
#include "unity.h"

static void run(stewart_inverse *d, double t0, int n, stewart_inverse_output *last) {
    for (int i = 0; i < n; ++i) {
        stewart_pose p = combined_pose(t0 + 1e-3 * i);
        *last = solve_ok(d, STEWART_FULL, &p);
    }
}

static void test_saved_state_resumes_bit_for_bit(void) {
    stewart_inverse_output a, b;
    run(data, 0.0, 50, &a);
    const size_t size = stewart_inverse_state_size(data);
    TEST_ASSERT_TRUE(size > 0);
    unsigned char *bytes = malloc(size);
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_inverse_save(data, bytes, size));

    stewart_inverse *other = test_inverse(model);
    run(other, 3.0, 7, &b); /* some other history, to be overwritten */
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_inverse_load(other, bytes, size));
    /* the loaded block holds exactly the saved state (its own history is gone) */
    unsigned char *again = malloc(size);
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_inverse_save(other, again, size));
    TEST_ASSERT_EQUAL_MEMORY(bytes, again, size);
    free(again);
    run(data, 0.05, 30, &a);
    run(other, 0.05, 30, &b);
    TEST_ASSERT_EQUAL_MEMORY(&a, &b, sizeof a);
    stewart_inverse_free(other);
    free(bytes);
}

static void test_bytes_that_are_not_a_state_are_refused(void) {
    stewart_inverse_output before, after;
    run(data, 0.0, 5, &before);
    const size_t size = stewart_inverse_state_size(data);
    unsigned char *bytes = malloc(size + 8);
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_inverse_save(data, bytes, size));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_inverse_save(data, bytes, size - 1));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(stewart_inverse_message(data), "the state needs"),
                                 stewart_inverse_message(data));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_inverse_load(data, bytes, size - 1));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_inverse_load(data, bytes, size + 8));
    unsigned char saved = bytes[0];
    bytes[0] ^= 0xff; /* the tag */
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_inverse_load(data, bytes, size));
    bytes[0] = saved;
    memset(bytes + size - 8, 0xff, 8); /* a NaN among the values */
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_inverse_load(data, bytes, size));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_inverse_load(data, NULL, size));
    /* refused loads changed nothing: the run goes on as if they had not happened */
    stewart_inverse *reference = test_inverse(model);
    stewart_inverse_copy(reference, data);
    run(data, 0.005, 5, &before);
    run(reference, 0.005, 5, &after);
    TEST_ASSERT_EQUAL_MEMORY(&before, &after, sizeof before);
    stewart_inverse_free(reference);
    free(bytes);
}

/* Where the saved bytes hold the coordinates q (found by content, not by layout): right after
 * the save, while the data block still holds them. */
static size_t q_at;
static size_t q_offset(const unsigned char *bytes, size_t size) {
    const mbs_data *mech = stewart_inverse_mechanism(data);
    const size_t n = (size_t)mbs_coordinate_count(stewart_model_mechanism(model)) * sizeof(double);
    for (size_t at = 0; at + n <= size; at += 4)
        if (memcmp(bytes + at, mbs_q(mech), n) == 0) return at;
    TEST_FAIL_MESSAGE("q not found in the saved state");
    return 0;
}

/* Changes the double at q[coordinate] in a saved state; the load must refuse it with a message
 * and leave the data block as it was (it then solves on exactly as a copy taken before). */
static void expect_refused(const unsigned char *saved, size_t size, int coordinate, double value,
                           const char *mention) {
    unsigned char *bytes = malloc(size);
    memcpy(bytes, saved, size);
    memcpy(bytes + q_at + coordinate * sizeof(double), &value, sizeof value);
    stewart_inverse *reference = test_inverse(model);
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_inverse_copy(reference, data));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_inverse_load(data, bytes, size));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(stewart_inverse_message(data), mention),
                                 stewart_inverse_message(data));
    stewart_inverse_output a, b;
    run(data, 0.06, 20, &a);
    run(reference, 0.06, 20, &b);
    TEST_ASSERT_EQUAL_MEMORY(&b, &a, sizeof a);
    stewart_inverse_free(reference);
    free(bytes);
}

static void test_states_that_do_not_fit_the_model_are_refused(void) {
    stewart_inverse_output out;
    run(data, 0.0, 50, &out);
    const size_t size = stewart_inverse_state_size(data);
    unsigned char *bytes = malloc(size);
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_inverse_save(data, bytes, size));
    q_at = q_offset(bytes, size);
    /* the probe's corruptions: a base (fixed body 0) Euler parameter */
    const double base_values[4] = {0.0, -1.0, 1e3, 1e300};
    for (int i = 0; i < 4; ++i)
        for (int c = 3; c < 7; ++c)
            if (base_values[i] != (c == 3 ? 1.0 : 0.0))
                expect_refused(bytes, size, c, base_values[i], "fixed");
    expect_refused(bytes, size, 0, 1e-3, "fixed"); /* the base moved */
    /* the platform's (body 13) Euler parameters off the unit sphere */
    expect_refused(bytes, size, MBS_BODY_P(13), 0.0, "Euler parameters");
    expect_refused(bytes, size, MBS_BODY_P(13) + 2, 1e3, "Euler parameters");
    /* a solved state whose bodies no longer meet at their joints */
    double z;
    memcpy(&z, bytes + q_at + (MBS_BODY_R(13) + 2) * sizeof z, sizeof z);
    expect_refused(bytes, size, MBS_BODY_R(13) + 2, z + 1e-6, "residual");
    /* the state as saved still loads */
    TEST_ASSERT_EQUAL_INT_MESSAGE(STEWART_OK, stewart_inverse_load(data, bytes, size),
                                  stewart_inverse_message(data));
    free(bytes);
}

/* A solver's state copied into a solver of another model (same shape, base_radius 0.6): refused,
 * by name, and both solvers go on. */
static void test_data_of_another_model_is_refused(void) {
    stewart_params other_params = params;
    other_params.base_radius = 0.6;
    stewart_model *other = test_model(&other_params);
    stewart_inverse *elsewhere = test_inverse(other);
    stewart_pose home = {{0, 0, 0.5, 0, 0, 0}, {0}, {0}};
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_inverse_copy(data, elsewhere));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(stewart_inverse_message(data), "different models"),
                                 stewart_inverse_message(data));
    for (int f = STEWART_KINEMATIC; f <= STEWART_FULL; ++f) {
        solve_ok(data, (stewart_fidelity)f, &home);
        solve_ok(elsewhere, (stewart_fidelity)f, &home);
    }
    stewart_inverse_free(elsewhere);
    stewart_model_free(other);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_saved_state_resumes_bit_for_bit);
    RUN_TEST(test_bytes_that_are_not_a_state_are_refused);
    RUN_TEST(test_states_that_do_not_fit_the_model_are_refused);
    RUN_TEST(test_data_of_another_model_is_refused);
    return UNITY_END();
}
