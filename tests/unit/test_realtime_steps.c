/* No step allocates, takes a lock or makes a system call: every workload of the latency benchmark
 * (studies/bench/latency_steps.h: the inverse full solve, forward tracking, the plant step at both
 * fidelities and its derivatives, each FMU's doStep and the Model Exchange unit's derivatives)
 * runs 1,000 calls in a thread under the real-time guard (realtime_guard.h: locks interposed,
 * system calls seen through a seccomp filter) with malloc interposed (allocation_counter.c); the
 * untimed preparations between the calls are not counted. The guard checks itself first: a call
 * that allocates, locks and makes a system call is seen as such. */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "allocation_counter.h"
#include "latency_steps.h"
#include "realtime_guard.h"
#include "unity.h"

void setUp(void) {}
void tearDown(void) {}

enum { CALLS = 1000 };

typedef struct job {
    latency_step *step;
    long allocations, failures;
} job;

/* CALLS calls of the workload, each counted alone. */
static void run_calls(void *p) {
    job *j = (job *)p;
    for (long n = 0; n < CALLS; ++n) {
        latency_step_prepare(j->step, n);
        const long before = allocations;
        realtime_counting = 1;
        j->failures += latency_step_run(j->step, n) != 0;
        realtime_counting = 0;
        j->allocations += allocations - before;
    }
}

/* A call that does all three, once. */
static void misbehave(void *p) {
    job *j = (job *)p;
    static pthread_mutex_t m = PTHREAD_MUTEX_INITIALIZER;
    void *volatile first = malloc(64); /* a thread's first allocation maps its arena */
    free(first);
    const long before = allocations;
    realtime_counting = 1;
    void *volatile block = malloc(64);
    pthread_mutex_lock(&m);
    pthread_mutex_unlock(&m);
    (void)getppid();
    realtime_counting = 0;
    j->allocations = allocations - before;
    free(block);
}

static void test_the_guard_sees_an_allocation_a_lock_and_a_system_call(void) {
    job j = {NULL, 0, 0};
    realtime_counts counts;
    char message[256];
    TEST_ASSERT_EQUAL_MESSAGE(0,
                              realtime_guard_run(misbehave, &j, &counts, message, sizeof message),
                              message);
    TEST_ASSERT_EQUAL(1, j.allocations);
    TEST_ASSERT_EQUAL(1, counts.locks);
    TEST_ASSERT_EQUAL(1, counts.syscalls);
}

static void test_no_step_allocates_locks_or_makes_a_system_call(void) {
    for (int w = 0; w < latency_step_count(); ++w) {
        char message[512] = "";
        latency_step *s = latency_step_create(w, FMU_DIR, message, sizeof message);
        TEST_ASSERT_NOT_NULL_MESSAGE(s, message);
        job j = {s, 0, 0};
        realtime_counts counts;
        TEST_ASSERT_EQUAL_MESSAGE(
            0, realtime_guard_run(run_calls, &j, &counts, message, sizeof message), message);
        latency_step_free(s);
        snprintf(message, sizeof message,
                 "%s: %ld failed calls, %ld allocations, %ld locks, "
                 "%ld system calls (the first: number %d)",
                 latency_step_name(w), j.failures, j.allocations, counts.locks, counts.syscalls,
                 counts.first_syscall);
        printf("%s\n", message);
        TEST_ASSERT_EQUAL_MESSAGE(0, j.failures, message);
        TEST_ASSERT_EQUAL_MESSAGE(0, j.allocations, message);
        TEST_ASSERT_EQUAL_MESSAGE(0, counts.locks, message);
        TEST_ASSERT_EQUAL_MESSAGE(0, counts.syscalls, message);
    }
}

int main(void) {
    UNITY_BEGIN();
    RUN_TEST(test_the_guard_sees_an_allocation_a_lock_and_a_system_call);
    RUN_TEST(test_no_step_allocates_locks_or_makes_a_system_call);
    return UNITY_END();
}
