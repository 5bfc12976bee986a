/*
 * The machine's interruptions, counted (latency.c): a loop that does nothing but read the clock
 * records every gap between two reads longer than a threshold, over a fixed time. A gap is time
 * the loop did not run: an interrupt, the hypervisor, another task. From their sizes and rate
 * follows the p99.99 that a call of a given length would have on this machine if its own work
 * never varied (its "noise floor"; an estimate, which takes the gaps as independent of the call).
 */
#ifndef STEWART_LATENCY_CENSUS_H
#define STEWART_LATENCY_CENSUS_H

#include <stdio.h>
#include <stdlib.h>

#include "latency_clock.h"

enum { census_capacity = 1 << 20 };

/* The gaps seen over `seconds` seconds, longest first. */
typedef struct {
    double seconds;   /* how long the loop ran [s] */
    double threshold; /* the shortest gap recorded [ns] */
    long count;       /* gaps recorded */
    long missed;      /* gaps beyond the capacity, not recorded */
    double *gap;      /* [count] longest first [ns] */
} census;

/* qsort's comparison of two doubles, descending. */
static inline int by_value_descending(const void *a, const void *b) { return by_value(b, a); }

/* Spins for `seconds` reading the clock and records the gaps above `threshold` ns; 0 on failure. */
static inline int census_take(census *c, double seconds, double threshold) {
    c->seconds = seconds;
    c->threshold = threshold;
    c->count = c->missed = 0;
    c->gap = (double *)malloc(sizeof(double) * census_capacity);
    if (!c->gap) return 0;
    const double start = now_ns(), end = start + seconds * 1e9;
    double previous = start;
    for (;;) {
        const double t = now_ns();
        const double gap = t - previous;
        previous = t;
        if (gap > threshold) {
            if (c->count < census_capacity) c->gap[c->count++] = gap;
            else ++c->missed;
        }
        if (t > end) break;
    }
    qsort(c->gap, (size_t)c->count, sizeof *c->gap, by_value_descending);
    return 1;
}

/* Gaps per second longer than `ns`. */
static inline double census_rate_above(const census *c, double ns) {
    long k = 0;
    while (k < c->count && c->gap[k] > ns) ++k;
    return k / c->seconds;
}

/*
 * The extra time [ns] that the machine alone puts on the p-quantile of a call lasting `duration`
 * ns: the longest gap x such that calls meet a gap of at least x more often than 1 - p of the
 * time (gaps of at least x arrive at rate r(x); a call meets one with probability r(x) duration).
 * -1 when even the shortest recorded gaps are too rare: the extra is then below the threshold.
 */
static inline double census_extra(const census *c, double duration, double p) {
    const double needed = (1.0 - p) * c->seconds * 1e9 / duration; /* gaps at least this many */
    const long k = (long)(needed + 0.999999);
    if (k < 1) return c->count > 0 ? c->gap[0] : -1;
    return k <= c->count ? c->gap[k - 1] : -1;
}

/* Prints (and writes to out) the gaps' rate above a few sizes, one table row. */
static inline void census_print(const census *c, const char *when, FILE *out) {
    static const double sizes_us[] = {1, 2, 5, 10, 20, 50, 100, 1000};
    char row[512];
    int used = snprintf(row, sizeof row, "| %s | %.0f |", when, c->seconds);
    for (size_t i = 0; i < sizeof sizes_us / sizeof *sizes_us && used < (int)sizeof row; ++i)
        used += snprintf(row + used, sizeof row - (size_t)used, " %.1f |",
                         census_rate_above(c, sizes_us[i] * 1e3));
    if (used < (int)sizeof row)
        snprintf(row + used, sizeof row - (size_t)used, " %.1f |%s\n",
                 c->count ? c->gap[0] * 1e-3 : 0.0, c->missed ? " (capacity exceeded)" : "");
    fputs(row, out);
    fputs(row, stdout);
}

/* The census table's header. */
static inline void census_header(FILE *out) {
    const char *h = "| census | seconds | gaps/s > 1 us | > 2 us | > 5 us | > 10 us | > 20 us | "
                    "> 50 us | > 100 us | > 1 ms | longest [us] |\n"
                    "|---|---|---|---|---|---|---|---|---|---|---|\n";
    fputs(h, out);
    fputs(h, stdout);
}

#endif
