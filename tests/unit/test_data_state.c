/* A data block saved to bytes and loaded into another one holds the same state and continues
 * exactly as the original; bytes that are not a state are refused and change nothing. */
#include <stdlib.h>
#include <string.h>

#include "platform_fixture.h"
#include "test_support.h"
#include "unity.h"

static void run(stewart_data *d, double t0, int n, stewart_output *last) {
    for (int i = 0; i < n; ++i) {
        stewart_pose p = combined_pose(t0 + 1e-3 * i);
        *last = solve_ok(model, d, STEWART_FULL, &p);
    }
}

static void test_saved_state_resumes_bit_for_bit(void) {
    stewart_output a, b;
    run(data, 0.0, 50, &a);
    const size_t size = stewart_data_state_size(data);
    TEST_ASSERT_TRUE(size > 0);
    unsigned char *bytes = malloc(size);
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_data_save(data, bytes, size));

    stewart_data *other = stewart_data_create(model);
    run(other, 3.0, 7, &b); /* some other history, to be overwritten */
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_data_load(other, bytes, size));
    /* the loaded block holds exactly the saved state (its own history is gone) */
    unsigned char *again = malloc(size);
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_data_save(other, again, size));
    TEST_ASSERT_EQUAL_MEMORY(bytes, again, size);
    free(again);
    run(data, 0.05, 30, &a);
    run(other, 0.05, 30, &b);
    TEST_ASSERT_EQUAL_MEMORY(&a, &b, sizeof a);
    stewart_data_free(other);
    free(bytes);
}

static void test_bytes_that_are_not_a_state_are_refused(void) {
    stewart_output before, after;
    run(data, 0.0, 5, &before);
    const size_t size = stewart_data_state_size(data);
    unsigned char *bytes = malloc(size + 8);
    TEST_ASSERT_EQUAL_INT(STEWART_OK, stewart_data_save(data, bytes, size));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_data_save(data, bytes, size - 1));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_data_load(data, bytes, size - 1));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_data_load(data, bytes, size + 8));
    unsigned char saved = bytes[0];
    bytes[0] ^= 0xff; /* the tag */
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_data_load(data, bytes, size));
    bytes[0] = saved;
    memset(bytes + size - 8, 0xff, 8); /* a NaN among the values */
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_data_load(data, bytes, size));
    TEST_ASSERT_EQUAL_INT(STEWART_ERR_ARGUMENT, stewart_data_load(data, NULL, size));
    /* refused loads changed nothing: the run goes on as if they had not happened */
    stewart_data *reference = stewart_data_create(model);
    stewart_data_copy(reference, data);
    run(data, 0.005, 5, &before);
    run(reference, 0.005, 5, &after);
    TEST_ASSERT_EQUAL_MEMORY(&before, &after, sizeof before);
    stewart_data_free(reference);
    free(bytes);
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_saved_state_resumes_bit_for_bit);
    RUN_TEST(test_bytes_that_are_not_a_state_are_refused);
    return UNITY_END();
}
