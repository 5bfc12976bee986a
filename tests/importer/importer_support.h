/*
 * What the C importer (importer.c) and the benchmark master (fmu_bench.c) share: the FMI 2
 * functions looked up in a dlopen'ed binary, a monotonic clock and a median.
 */
#ifndef STEWART_IMPORTER_SUPPORT_H
#define STEWART_IMPORTER_SUPPORT_H

#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "fmi2Functions.h"

/* dlsym, or exit(2) naming the missing symbol: an importer without it cannot go on. */
static inline void *importer_symbol(void *lib, const char *name) {
    void *f = dlsym(lib, name);
    if (!f) {
        fprintf(stderr, "%s not found: %s\n", name, dlerror());
        exit(2);
    }
    return f;
}

/* The FMI 2 co-simulation calls the importers make. */
typedef struct {
    fmi2InstantiateTYPE *instantiate;
    fmi2FreeInstanceTYPE *free_instance;
    fmi2SetupExperimentTYPE *setup;
    fmi2EnterInitializationModeTYPE *enter;
    fmi2ExitInitializationModeTYPE *exit_init;
    fmi2SetIntegerTYPE *set_int;
    fmi2SetRealTYPE *set_real;
    fmi2GetRealTYPE *get_real;
    fmi2GetIntegerTYPE *get_int;
    fmi2DoStepTYPE *do_step;
    fmi2TerminateTYPE *terminate;
} fmi2_api;

static inline fmi2_api fmi2_api_load(void *lib) {
    fmi2_api f;
    f.instantiate = (fmi2InstantiateTYPE *)importer_symbol(lib, "fmi2Instantiate");
    f.free_instance = (fmi2FreeInstanceTYPE *)importer_symbol(lib, "fmi2FreeInstance");
    f.setup = (fmi2SetupExperimentTYPE *)importer_symbol(lib, "fmi2SetupExperiment");
    f.enter =
        (fmi2EnterInitializationModeTYPE *)importer_symbol(lib, "fmi2EnterInitializationMode");
    f.exit_init =
        (fmi2ExitInitializationModeTYPE *)importer_symbol(lib, "fmi2ExitInitializationMode");
    f.set_int = (fmi2SetIntegerTYPE *)importer_symbol(lib, "fmi2SetInteger");
    f.set_real = (fmi2SetRealTYPE *)importer_symbol(lib, "fmi2SetReal");
    f.get_real = (fmi2GetRealTYPE *)importer_symbol(lib, "fmi2GetReal");
    f.get_int = (fmi2GetIntegerTYPE *)importer_symbol(lib, "fmi2GetInteger");
    f.do_step = (fmi2DoStepTYPE *)importer_symbol(lib, "fmi2DoStep");
    f.terminate = (fmi2TerminateTYPE *)importer_symbol(lib, "fmi2Terminate");
    return f;
}

static inline double now_us(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e6 + ts.tv_nsec * 1e-3;
}

static inline int importer_cmp_double(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Sorts v in place. */
static inline double median(double *v, size_t n) {
    qsort(v, n, sizeof *v, importer_cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

#endif
