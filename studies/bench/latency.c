/*
 * Worst-case latency of the calls a 1 kHz controller makes (studies/bench/latency_steps.h): each
 * workload's call timed one by one with the monotonic clock over N calls (default 10^6), then
 * p50, p99, p99.9, p99.99 and the maximum, and the ratio p99.99 / p50. Workload 0, the empty
 * call, is the machine's own noise (the loop, the clock, an indirect call). The machine's load
 * (/proc/loadavg) before and after each workload goes with its numbers. Before the workloads and
 * after them, a census of the machine's interruptions (latency_census.h, LATENCY_CENSUS_SECONDS each,
 * default 10) gives each row its noise floor: the p99.99 a call of that row's median would have
 * here if its own work never varied. Prints the tables and writes them to OUT.
 *
 * usage: latency FMU_DIR OUT [N [WORKLOAD...]]   (FMU_DIR: the build's fmu/ directory)
 *        environment: LATENCY_CENSUS_SECONDS (default 10)
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "latency_census.h"
#include "latency_clock.h"
#include "latency_steps.h"

/* The 1-minute load average, or -1. */
static double load_average(void) {
    FILE *f = fopen("/proc/loadavg", "r");
    double load = -1;
    if (f) {
        if (fscanf(f, "%lf", &load) != 1) load = -1;
        fclose(f);
    }
    return load;
}

int main(int argc, char **argv) {
    if (argc < 3) {
        fprintf(stderr, "usage: latency FMU_DIR OUT [N [WORKLOAD...]]\n");
        return 2;
    }
    const long n = argc > 3 ? atol(argv[3]) : 1000000;
    double *latency = malloc(sizeof(double) * (size_t)(n > 0 ? n : 1));
    FILE *out = fopen(argv[2], "w");
    if (!latency || !out || n < 1) {
        fprintf(stderr, "latency: cannot allocate %ld values or write %s\n", n, argv[2]);
        return 2;
    }
    const char *census_seconds = getenv("LATENCY_CENSUS_SECONDS");
    const double seconds = census_seconds ? atof(census_seconds) : 10.0;
    census before, after;
    if (!(seconds > 0 && seconds <= 600)) {
        fprintf(stderr, "latency: LATENCY_CENSUS_SECONDS = %s must be in (0, 600]\n",
                census_seconds);
        return 2;
    }
    if (!census_take(&before, seconds, 500.0)) {
        fprintf(stderr, "latency: cannot allocate the census's %d gaps\n", census_capacity);
        return 2;
    }
    fputs("The machine's interruptions (gaps in a loop that only reads the clock):\n\n", out);
    census_header(out);
    census_print(&before, "before the rows", out);
    const char *header = "| call | p50 [us] | p99 [us] | p99.9 [us] | p99.99 [us] | max [us] | "
                         "p99.99/p50 | machine floor p99.99 [us] | failed | load before/after |\n"
                         "|---|---|---|---|---|---|---|---|---|---|\n";
    fprintf(out, "\ncalls per row: %ld\n\n%s", n, header);
    printf("\ncalls per row: %ld\n\n%s", n, header);
    const int count = latency_step_count();
    for (int w = 0; w < count; ++w) {
        if (argc > 4) { /* only the workloads named by number */
            int wanted = 0;
            for (int a = 4; a < argc; ++a) wanted |= atoi(argv[a]) == w;
            if (!wanted) continue;
        }
        char message[512] = "";
        latency_step *s = latency_step_create(w, argv[1], message, sizeof message);
        if (!s) {
            fprintf(stderr, "latency: %s: %s\n", latency_step_name(w), message);
            return 1;
        }
        const double load_before = load_average();
        long failed = 0;
        for (long i = 0; i < n; ++i) {
            latency_step_prepare(s, i);
            const double t0 = now_ns();
            failed += latency_step_run(s, i) != 0;
            latency[i] = now_ns() - t0;
        }
        const double load_after = load_average();
        latency_step_free(s);
        qsort(latency, (size_t)n, sizeof *latency, by_value);
        const double p50 = quantile(latency, n, 0.5), p99 = quantile(latency, n, 0.99);
        const double p999 = quantile(latency, n, 0.999), p9999 = quantile(latency, n, 0.9999);
        const double max = latency[n - 1];
        const double extra = census_extra(&before, p50, 0.9999);
        char noise_floor[32]; /* below the census's threshold when its gaps are too rare */
        snprintf(noise_floor, sizeof noise_floor, "%s%.1f", extra < 0 ? "< " : "",
                 (p50 + (extra < 0 ? before.threshold : extra)) * 1e-3);
        char row[512];
        snprintf(row, sizeof row,
                 "| %s | %.3f | %.3f | %.3f | %.3f | %.1f | %.1f | %s | %ld | %.2f / %.2f |\n",
                 latency_step_name(w), p50 * 1e-3, p99 * 1e-3, p999 * 1e-3, p9999 * 1e-3,
                 max * 1e-3, p9999 / p50, noise_floor, failed, load_before, load_after);
        fputs(row, out);
        fputs(row, stdout);
        fflush(out);
        fflush(stdout);
    }
    if (census_take(&after, seconds, 500.0)) {
        fputs("\n", out);
        census_header(out);
        census_print(&before, "before the rows", out);
        census_print(&after, "after the rows", out);
        free(after.gap);
    }
    free(before.gap);
    fclose(out);
    free(latency);
    return 0;
}
