/*
 * What latency.c and latency_work.c share: the monotonic clock in ns, and quantiles of sorted
 * values.
 */
#ifndef STEWART_LATENCY_CLOCK_H
#define STEWART_LATENCY_CLOCK_H

#include <time.h>

/* The monotonic clock in ns (a vDSO read, no system call). */
static inline double now_ns(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e9 + ts.tv_nsec;
}

/* qsort's comparison of two doubles, ascending. */
static inline int by_value(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The p-quantile of n sorted values: the smallest value with at least p n values at or below. */
static inline double quantile(const double *sorted, long n, double p) {
    long k = (long)(p * n + 0.999999) - 1;
    if (k < 0) k = 0;
    if (k >= n) k = n - 1;
    return sorted[k];
}

#endif
