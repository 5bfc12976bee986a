/*
 * What checking a deserialised plant FMU state costs (fmi2DeSerializeFMUstate of a valid state
 * after initialisation): a state with the unit's own parameters (checked on the unit's model) and
 * one whose base radius differs (a model of its parameters is built for the check). Prints the
 * median wall time per call of each; for instruction counts run it under
 * valgrind --tool=callgrind --toggle-collect=fmi2DeSerializeFMUstate and divide by the calls
 * printed (KIND own or other measures only that kind).
 * usage: bench_plant_fmu_states [CALLS=200 per kind] [KIND=both]
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "plant_fmu_unit.h"

/* plant_fmu_unit.c's helpers are built on Unity, which wants these. */
void setUp(void) {}
void tearDown(void) {}

/* Opens a unit with the platform moving and base_radius = radius, steps it 10 times and
 * serialises its state into bytes; the size, 0 if a call failed. */
static size_t open_with_state(unit *u, double radius, unsigned char *bytes, size_t capacity) {
    double force[6], last;
    static_forces(2, force);
    for (int k = 0; k < 6; ++k) force[k] *= 1.01;
    const unsigned vr[2] = {VR_base_radius, VR_x_dot0};
    const double value[2] = {radius, 0.01};
    if (!unit_open_at(u, 0, 2, force, 0.0, 2, vr, value)) return 0;
    for (int i = 0; i < 10; ++i)
        if (do_step_status(u, i * STEP, STEP, &last) != fmi2OK) return 0;
    fmi2FMUstate s = NULL;
    size_t n = 0;
    const int ok = fmi2GetFMUstate(u->c, &s) == fmi2OK &&
                   fmi2SerializedFMUstateSize(u->c, s, &n) == fmi2OK && n <= capacity &&
                   fmi2SerializeFMUstate(u->c, s, (fmi2Byte *)bytes, n) == fmi2OK;
    fmi2FreeFMUstate(u->c, &s);
    return ok ? n : 0;
}

static int by_value(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median seconds per fmi2DeSerializeFMUstate of bytes into u over calls calls; -1 on a refusal. */
static double median_deserialise(unit *u, const unsigned char *bytes, size_t n, int calls) {
    double *seconds = malloc(sizeof(double) * (size_t)calls);
    if (!seconds) return -1;
    fmi2FMUstate s = NULL;
    for (int i = 0; i < calls; ++i) {
        struct timespec t0, t1;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        const fmi2Status status = fmi2DeSerializeFMUstate(u->c, (const fmi2Byte *)bytes, n, &s);
        clock_gettime(CLOCK_MONOTONIC, &t1);
        if (status != fmi2OK) {
            fprintf(stderr, "refused: %s\n", u->log.last);
            free(seconds);
            return -1;
        }
        seconds[i] = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    }
    fmi2FreeFMUstate(u->c, &s);
    qsort(seconds, (size_t)calls, sizeof *seconds, by_value);
    const double median = seconds[calls / 2];
    free(seconds);
    return median;
}

int main(int argc, char **argv) {
    const int calls = argc > 1 ? atoi(argv[1]) : 200;
    if (calls < 1) {
        fprintf(stderr, "CALLS = %s must be a positive integer\n", argv[1]);
        return 2;
    }
    static unsigned char own_bytes[1 << 16], other_bytes[1 << 16];
    unit u, other;
    const size_t n = open_with_state(&u, 0.5, own_bytes, sizeof own_bytes);
    const size_t n_other = open_with_state(&other, 0.52, other_bytes, sizeof other_bytes);
    if (!n || !n_other) {
        fprintf(stderr, "setting up failed: %s\n", !n ? u.log.last : other.log.last);
        return 1;
    }
    const char *kind = argc > 2 ? argv[2] : "both";
    const int both = !strcmp(kind, "both");
    if (!both && strcmp(kind, "own") && strcmp(kind, "other")) {
        fprintf(stderr, "KIND = %s must be own, other or both\n", kind);
        return 2;
    }
    const double own =
        both || !strcmp(kind, "own") ? median_deserialise(&u, own_bytes, n, calls) : 0;
    const double foreign =
        both || !strcmp(kind, "other") ? median_deserialise(&u, other_bytes, n_other, calls) : 0;
    unit_free(&u);
    unit_free(&other);
    if (own < 0 || foreign < 0) return 1;
    printf("fmi2DeSerializeFMUstate, %d calls of each kind measured, median per call:\n", calls);
    printf("  the unit's own parameters:               %8.1f us\n", 1e6 * own);
    printf("  other parameters (base_radius 0.52 m):   %8.1f us\n", 1e6 * foreign);
    if (both) printf("  ratio other / own: %.1f\n", foreign / own);
    return 0;
}
