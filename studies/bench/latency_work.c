/*
 * Where the plant step's slow calls come from (issue 21/22): the latency workloads' calls
 * (studies/bench/latency_steps.h) one by one, each timed and with the integrator's counters of
 * the call (internal steps, right-hand sides, rejected steps), then the calls grouped by their
 * number of right-hand sides: how many, their median time, how many of them come right after a
 * rewind to rest (call number a multiple of 200) or within 5 calls of one, and how many follow a
 * call that took more than one internal step. Also the
 * quantiles of the right-hand sides per call: the work's own tail, free of the machine's noise.
 *
 * usage: latency-work FMU_DIR [N [WORKLOAD...]]   (default N 200000, workloads 4 and 5)
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "latency_clock.h"
#include "latency_steps.h"

enum { kMaxRhs = 512, kRewind = 200 };

/* One workload: its table of calls by right-hand sides per call. 0, or 1 if it failed. */
static int report(int w, const char *fmu_dir, long n, double *time, double *rhs, long *steps,
                  long *count) {
    char message[512] = "";
    latency_step *s = latency_step_create(w, fmu_dir, message, sizeof message);
    if (!s) {
        fprintf(stderr, "latency-work: %s: %s\n", latency_step_name(w), message);
        return 1;
    }
    long steps_total = 0, rejected_total = 0, failed = 0;
    for (long i = 0; i < n; ++i) {
        latency_step_prepare(s, i);
        const double t0 = now_ns();
        failed += latency_step_run(s, i) != 0;
        time[i] = now_ns() - t0;
        long work[3] = {0, 0, 0};
        if (!latency_step_work(s, work)) {
            fprintf(stderr, "latency-work: %s has no integrator counters\n", latency_step_name(w));
            latency_step_free(s);
            return 1;
        }
        rhs[i] = (double)work[1];
        steps[i] = work[0];
        steps_total += work[0];
        rejected_total += work[2];
    }
    latency_step_free(s);
    printf("## %s: %ld calls, %ld failed; %.3f internal steps, %.4f rejected steps per call\n\n",
           latency_step_name(w), n, failed, (double)steps_total / n, (double)rejected_total / n);
    printf(
        "| RHS per call | calls | share | median time [us] | right after a rewind | "
        "within 5 calls after one | after a call of > 1 step |\n|---|---|---|---|---|---|---|\n");
    /* per class: the calls, then their times gathered for the median */
    for (int r = 0; r < kMaxRhs; ++r) count[r] = 0;
    for (long i = 0; i < n; ++i) count[(int)rhs[i] < kMaxRhs ? (int)rhs[i] : kMaxRhs - 1]++;
    double *class_time = malloc(sizeof(double) * (size_t)n);
    for (int r = 0; r < kMaxRhs && class_time; ++r) {
        if (!count[r]) continue;
        long m = 0, at_rewind = 0, near_rewind = 0, after_multi = 0;
        for (long i = 0; i < n; ++i) {
            const int ri = (int)rhs[i] < kMaxRhs ? (int)rhs[i] : kMaxRhs - 1;
            if (ri != r) continue;
            class_time[m++] = time[i];
            /* the workload's call number is i + its warm-up (100), a multiple of 200 rewinds */
            const long since = (i + 100) % kRewind;
            at_rewind += since == 0;
            near_rewind += since < 5;
            after_multi += i > 0 && steps[i - 1] > 1;
        }
        qsort(class_time, (size_t)m, sizeof *class_time, by_value);
        printf("| %d | %ld | %.4f %% | %.3f | %ld | %ld | %ld |\n", r, m, 100.0 * m / n,
               quantile(class_time, m, 0.5) * 1e-3, at_rewind, near_rewind, after_multi);
    }
    free(class_time);
    qsort(rhs, (size_t)n, sizeof *rhs, by_value);
    printf("\nRHS per call: p50 %.0f, p99 %.0f, p99.9 %.0f, p99.99 %.0f, max %.0f\n\n",
           quantile(rhs, n, 0.5), quantile(rhs, n, 0.99), quantile(rhs, n, 0.999),
           quantile(rhs, n, 0.9999), rhs[n - 1]);
    return 0;
}

int main(int argc, char **argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: latency-work FMU_DIR [N [WORKLOAD...]]\n");
        return 2;
    }
    const long n = argc > 2 ? atol(argv[2]) : 200000;
    double *time = malloc(sizeof(double) * (size_t)(n > 0 ? n : 1));
    double *rhs = malloc(sizeof(double) * (size_t)(n > 0 ? n : 1));
    long *steps = malloc(sizeof(long) * (size_t)(n > 0 ? n : 1));
    long *count = malloc(sizeof(long) * kMaxRhs);
    if (!time || !rhs || !steps || !count || n < 1) {
        fprintf(stderr, "latency-work: cannot allocate %ld values\n", n);
        return 2;
    }
    int status = 0;
    if (argc > 3)
        for (int a = 3; a < argc; ++a)
            status |= report(atoi(argv[a]), argv[1], n, time, rhs, steps, count);
    else
        for (int w = 4; w <= 5; ++w) status |= report(w, argv[1], n, time, rhs, steps, count);
    free(time);
    free(rhs);
    free(steps);
    free(count);
    return status;
}
