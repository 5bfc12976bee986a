/*
 * A small FMI importer without Python: loads the StewartPlatform shared objects with dlopen, runs
 * the FMI 2.0 and FMI 3.0 co-simulation call sequences on a combined thesis-like manoeuvre, checks
 * that both give the same finite outputs with status OK, and prints the median time per doStep
 * (and per full communication step: set inputs, doStep, get outputs), in microseconds.
 *
 * It also counts heap allocations (malloc, calloc, realloc interposed below, glibc) while the
 * steps run: a step must not allocate. And it sets every Integer parameter and input with a
 * declared min and max (the unit's own variable table, from which its model description is
 * written) just outside its range, which both versions must refuse with an Error naming it, the
 * value kept, and at both ends, which they must take.
 *
 * usage: fmu_importer FMI2.so FMI3.so [OUT.txt] [STEPS]
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "importer_support.h"
#include "fmi3Functions.h"
#include "variables.h"

#define GUID FMU_GUID
#define N_OUT \
    98 /* Real outputs: 32, the 18 limit outputs (limit_margin, range_min, range_max) and
                     the 48 drive outputs (motor_angle .. motor_power, 8 of six legs) */

/* Every Real output, in table order (L[1..6] first), from the FMU's own variable table. */
static void real_outputs(unsigned vr[N_OUT]) {
    int n = 0;
    for (size_t i = 0; i < fmu_n_variables; ++i)
        if (fmu_variables[i].causality == FMU_OUTPUT_VAR && fmu_variables[i].type == FMU_REAL) {
            if (n == N_OUT) {
                fprintf(stderr, "importer: more than %d Real outputs\n", N_OUT);
                exit(2);
            }
            vr[n++] = fmu_variables[i].vr;
        }
    if (n != N_OUT) {
        fprintf(stderr, "importer: %d Real outputs, expected %d\n", n, N_OUT);
        exit(2);
    }
}

/* ---- allocation counter: the executable's definitions interpose on the FMU's calls (glibc).
 * Not under AddressSanitizer, which intercepts the allocator itself. */
#if defined(__SANITIZE_ADDRESS__)
#define COUNT_ALLOCATIONS 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define COUNT_ALLOCATIONS 0
#endif
#endif
#ifndef COUNT_ALLOCATIONS
#define COUNT_ALLOCATIONS 1
#endif
static long allocations = 0;
static int counting = 0;
#if COUNT_ALLOCATIONS
extern void *__libc_malloc(size_t);
extern void *__libc_calloc(size_t, size_t);
extern void *__libc_realloc(void *, size_t);
void *malloc(size_t n) {
    allocations += counting;
    return __libc_malloc(n);
}
void *calloc(size_t n, size_t size) {
    allocations += counting;
    return __libc_calloc(n, size);
}
void *realloc(void *p, size_t n) {
    allocations += counting;
    return __libc_realloc(p, n);
}
#endif

static int failures = 0;
#define CHECK(cond, ...)                                       \
    do {                                                       \
        if (!(cond) && ++failures <= 10) {                     \
            fprintf(stderr, "importer: FAILED: " __VA_ARGS__); \
            fputc('\n', stderr);                               \
        }                                                      \
    } while (0)

/* Combined manoeuvre: heave, roll, pitch and yaw at once (half the thesis amplitudes, so that
 * the legs stay inside the stroke; 5 rad/s). */
static void pose_at(double t, double q[18]) {
    const double w = 5.0, a = 0.02, b = 3.14159265358979323846 / 36;
    const double s = sin(w * t), c = cos(w * t);
    memset(q, 0, 18 * sizeof(double));
    q[2] = 0.5 + a * s;
    q[8] = a * w * c;
    q[14] = -a * w * w * s;
    for (int i = 3; i < 6; ++i) {
        q[i] = b * s;
        q[i + 6] = b * w * c;
        q[i + 12] = -b * w * w * s;
    }
}

typedef struct {
    double step_us;  /* median doStep */
    double cycle_us; /* median set + doStep + get */
    int ran;         /* 0: fidelity unsupported in this build */
} timing;

/* ------------------------------------------------------------------ FMI 2 */

static void logger2(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                    fmi2String category, fmi2String message, ...) {
    (void)env;
    if (status != fmi2OK)
        fprintf(stderr, "  [fmi2 %s %d %s] %s\n", name, status, category, message);
}

static timing run_fmi2(void *lib, int fidelity, int derivatives, int steps, double *outputs) {
    const fmi2_api f = fmi2_api_load(lib);

    timing tm = {0, 0, 0};
    const fmi2CallbackFunctions cb = {logger2, calloc, free, NULL, NULL};
    fmi2Component c =
        f.instantiate("importer", fmi2CoSimulation, GUID, "", &cb, fmi2False, fmi2False);
    CHECK(c != NULL, "fmi2Instantiate");
    if (!c) return tm;
    const fmi2ValueReference pvr[2] = {VR_fidelity, VR_derivatives};
    const fmi2Integer pval[2] = {fidelity, derivatives};
    fmi2ValueReference in_vr[18], out_vr[N_OUT];
    for (int i = 0; i < 18; ++i) in_vr[i] = VR_x + i;
    real_outputs(out_vr);
    double q[18];
    pose_at(0.0, q);
    CHECK(f.set_int(c, pvr, 2, pval) == fmi2OK, "fmi2SetInteger");
    CHECK(f.set_real(c, in_vr, 18, q) == fmi2OK, "fmi2SetReal");
    CHECK(f.setup(c, fmi2False, 0, 0.0, fmi2False, 0) == fmi2OK, "fmi2SetupExperiment");
    CHECK(f.enter(c) == fmi2OK, "fmi2EnterInitializationMode");
    if (f.exit_init(c) != fmi2OK) { /* fidelity not available */
        f.free_instance(c);
        return tm;
    }
    tm.ran = 1;
    double *t_step = malloc(steps * sizeof(double)), *t_cycle = malloc(steps * sizeof(double));
    const double h = 1e-3;
    const fmi2ValueReference status_vr = VR_status;
    for (int j = 0; j < steps; ++j) {
        const double t = j * h;
        pose_at(t, q);
        counting = 1;
        const double t0 = now_us();
        fmi2Status s = f.set_real(c, in_vr, derivatives ? 18 : 6, q);
        const double t1 = now_us();
        s |= f.do_step(c, t, h, fmi2True);
        const double t2 = now_us();
        s |= f.get_real(c, out_vr, N_OUT, outputs + (size_t)j * N_OUT);
        const double t3 = now_us();
        counting = 0;
        CHECK(s == fmi2OK, "fmi2 set/doStep/get status %d at t = %g", s, t);
        t_step[j] = t2 - t1;
        t_cycle[j] = t3 - t0;
        fmi2Integer st = -1;
        f.get_int(c, &status_vr, 1, &st);
        CHECK(st == 0, "fmi2 status %d at t = %g", st, t);
    }
    tm.step_us = median(t_step, steps);
    tm.cycle_us = median(t_cycle, steps);
    free(t_step);
    free(t_cycle);
    CHECK(f.terminate(c) == fmi2OK, "fmi2Terminate");
    f.free_instance(c);
    return tm;
}

/* ------------------------------------------------------------------ FMI 3 */

static void logger3(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category,
                    fmi3String message) {
    (void)env;
    if (status != fmi3OK) fprintf(stderr, "  [fmi3 %d %s] %s\n", status, category, message);
}

static timing run_fmi3(void *lib, int fidelity, int derivatives, int steps, double *outputs) {
    fmi3InstantiateCoSimulationTYPE *instantiate =
        importer_symbol(lib, "fmi3InstantiateCoSimulation");
    fmi3FreeInstanceTYPE *free_instance = importer_symbol(lib, "fmi3FreeInstance");
    fmi3EnterInitializationModeTYPE *enter = importer_symbol(lib, "fmi3EnterInitializationMode");
    fmi3ExitInitializationModeTYPE *exit_init = importer_symbol(lib, "fmi3ExitInitializationMode");
    fmi3SetInt32TYPE *set_int = importer_symbol(lib, "fmi3SetInt32");
    fmi3SetFloat64TYPE *set_real = importer_symbol(lib, "fmi3SetFloat64");
    fmi3GetFloat64TYPE *get_real = importer_symbol(lib, "fmi3GetFloat64");
    fmi3GetInt32TYPE *get_int = importer_symbol(lib, "fmi3GetInt32");
    fmi3DoStepTYPE *do_step = importer_symbol(lib, "fmi3DoStep");
    fmi3TerminateTYPE *terminate = importer_symbol(lib, "fmi3Terminate");

    timing tm = {0, 0, 0};
    fmi3Instance c = instantiate("importer", GUID, "", fmi3False, fmi3False, fmi3False, fmi3False,
                                 NULL, 0, NULL, logger3, NULL);
    CHECK(c != NULL, "fmi3InstantiateCoSimulation");
    if (!c) return tm;
    const fmi3ValueReference pvr[2] = {VR_fidelity, VR_derivatives};
    const fmi3Int32 pval[2] = {fidelity, derivatives};
    fmi3ValueReference in_vr[18], out_vr[N_OUT];
    for (int i = 0; i < 18; ++i) in_vr[i] = VR_x + i;
    real_outputs(out_vr);
    const int n_out = N_OUT;
    double q[18];
    pose_at(0.0, q);
    CHECK(set_int(c, pvr, 2, pval, 2) == fmi3OK, "fmi3SetInt32");
    CHECK(set_real(c, in_vr, 18, q, 18) == fmi3OK, "fmi3SetFloat64");
    CHECK(enter(c, fmi3False, 0, 0.0, fmi3False, 0) == fmi3OK, "fmi3EnterInitializationMode");
    if (exit_init(c) != fmi3OK) {
        free_instance(c);
        return tm;
    }
    tm.ran = 1;
    double *t_step = malloc(steps * sizeof(double)), *t_cycle = malloc(steps * sizeof(double));
    const double h = 1e-3;
    const fmi3ValueReference status_vr = VR_status;
    fmi3Boolean event, term, early;
    fmi3Float64 last;
    for (int j = 0; j < steps; ++j) {
        const double t = j * h;
        pose_at(t, q);
        const double t0 = now_us();
        counting = 1;
        fmi3Status s = set_real(c, in_vr, derivatives ? 18 : 6, q, derivatives ? 18 : 6);
        const double t1 = now_us();
        s |= do_step(c, t, h, fmi3True, &event, &term, &early, &last);
        const double t2 = now_us();
        s |= get_real(c, out_vr, n_out, outputs + (size_t)j * N_OUT, n_out);
        const double t3 = now_us();
        counting = 0;
        CHECK(s == fmi3OK, "fmi3 set/doStep/get status %d at t = %g", s, t);
        t_step[j] = t2 - t1;
        t_cycle[j] = t3 - t0;
        fmi3Int32 st = -1;
        get_int(c, &status_vr, 1, &st, 1);
        CHECK(st == 0, "fmi3 status %d at t = %g", st, t);
    }
    tm.step_us = median(t_step, steps);
    tm.cycle_us = median(t_cycle, steps);
    free(t_step);
    free(t_cycle);
    CHECK(terminate(c) == fmi3OK, "fmi3Terminate");
    free_instance(c);
    return tm;
}

/* ------------------------------------------------------------------ declared ranges */

/* The last message a ranges instance logged (its environment is this buffer). */
static void remember2(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                      fmi2String category, fmi2String message, ...) {
    (void)name;
    (void)status;
    (void)category;
    snprintf((char *)env, 512, "%s", message);
}

static void remember3(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category,
                      fmi3String message) {
    (void)status;
    (void)category;
    snprintf((char *)env, 512, "%s", message);
}

/* The calls of the ranges check, of one FMI version (v3 0: fmi2*, 1: fmi3*). */
typedef struct {
    int v3;
    fmi2_api f2;
    fmi3InstantiateCoSimulationTYPE *instantiate3;
    fmi3EnterInitializationModeTYPE *enter3;
    fmi3SetInt32TYPE *set3;
    fmi3GetInt32TYPE *get3;
    fmi3FreeInstanceTYPE *free3;
} range_api;

static range_api range_api_load(void *lib, int v3) {
    range_api a;
    memset(&a, 0, sizeof a);
    a.v3 = v3;
    if (!v3) {
        a.f2 = fmi2_api_load(lib);
        return a;
    }
    a.instantiate3 = importer_symbol(lib, "fmi3InstantiateCoSimulation");
    a.enter3 = importer_symbol(lib, "fmi3EnterInitializationMode");
    a.set3 = importer_symbol(lib, "fmi3SetInt32");
    a.get3 = importer_symbol(lib, "fmi3GetInt32");
    a.free3 = importer_symbol(lib, "fmi3FreeInstance");
    return a;
}

static int32_t range_get(const range_api *a, void *c, unsigned vr) {
    int32_t x = 0;
    if (a->v3) a->get3(c, &vr, 1, &x, 1);
    else a->f2.get_int(c, &vr, 1, &x);
    return x;
}

/* One set of value x of var: Error with a message naming var, x and the range if x is outside
 * the declared range, else OK; the value read back is x if taken, else what it was. */
static void check_one_set(const range_api *a, void *c, const fmu_variable *var, int32_t x,
                          const char *message) {
    const unsigned vr = var->vr;
    const int32_t before = range_get(a, c, vr);
    const int status = a->v3 ? (int)a->set3(c, &vr, 1, &x, 1) : (int)a->f2.set_int(c, &vr, 1, &x);
    const int32_t after = range_get(a, c, vr);
    const int inside = x >= var->min && x <= var->max;
    char words[256];
    snprintf(words, sizeof words, "%s = %d is outside its declared range [%ld, %ld]", var->name,
             (int)x, var->min, var->max);
    const int v = a->v3 ? 3 : 2;
    CHECK(status == (inside ? 0 : 3), "fmi%d set %s = %d: status %d", v, var->name, (int)x, status);
    CHECK(after == (inside ? x : before), "fmi%d %s reads %d after a set of %d", v, var->name,
          (int)after, (int)x);
    CHECK(inside || strstr(message, words), "fmi%d: no message '%s' (last: %s)", v, words, message);
}

/* An instance in initialisation mode (where parameters are set and read) logging into message. */
static void *range_instance(const range_api *a, char *message, fmi2CallbackFunctions *cb) {
    if (a->v3) {
        void *c = a->instantiate3("ranges", GUID, "", fmi3False, fmi3True, fmi3False, fmi3False,
                                  NULL, 0, message, remember3, NULL);
        if (c && a->enter3(c, fmi3False, 0, 0.0, fmi3False, 0) != fmi3OK) c = NULL;
        return c;
    }
    *cb = (fmi2CallbackFunctions){remember2, calloc, free, NULL, message};
    void *c = a->f2.instantiate("ranges", fmi2CoSimulation, GUID, "", cb, fmi2False, fmi2True);
    if (c &&
        (a->f2.setup(c, fmi2False, 0, 0.0, fmi2False, 0) != fmi2OK || a->f2.enter(c) != fmi2OK))
        c = NULL;
    return c;
}

/* Every Integer parameter and input with a declared range, just outside it and at its ends; the
 * number of such variables. */
static int check_declared_ranges(void *lib, int v3) {
    const range_api a = range_api_load(lib, v3);
    char message[512] = "";
    fmi2CallbackFunctions cb;
    void *c = range_instance(&a, message, &cb);
    CHECK(c != NULL, "fmi%d instance in initialisation mode for the ranges: %s", v3 ? 3 : 2,
          message);
    if (!c) return 0;
    int checked = 0;
    for (size_t i = 0; i < fmu_n_variables; ++i) {
        const fmu_variable *var = &fmu_variables[i];
        if (!var->has_range || var->type != FMU_INTEGER ||
            (var->causality != FMU_PARAMETER_VAR && var->causality != FMU_INPUT_VAR))
            continue;
        if (var->min > INT32_MIN) check_one_set(&a, c, var, (int32_t)(var->min - 1), message);
        if (var->max < INT32_MAX) check_one_set(&a, c, var, (int32_t)(var->max + 1), message);
        check_one_set(&a, c, var, (int32_t)var->min, message);
        check_one_set(&a, c, var, (int32_t)var->max, message);
        ++checked;
    }
    if (v3) a.free3(c);
    else a.f2.free_instance(c);
    return checked;
}

int main(int argc, char **argv) {
    if (argc < 3) {
        fprintf(stderr, "usage: fmu_importer FMI2.so FMI3.so [OUT.txt] [STEPS]\n");
        return 2;
    }
    const int steps = argc > 4 ? atoi(argv[4]) : 20000;
    void *lib2 = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (!lib2) {
        fprintf(stderr, "importer: %s\n", dlerror());
        return 2;
    }
    void *lib3 = dlopen(argv[2], RTLD_NOW | RTLD_LOCAL);
    if (!lib3) {
        fprintf(stderr, "importer: %s\n", dlerror());
        return 2;
    }
    FILE *out = argc > 3 ? fopen(argv[3], "w") : NULL;
    if (argc > 3 && !out) {
        fprintf(stderr, "importer: cannot write %s\n", argv[3]);
        return 2;
    }

    const int ranged = check_declared_ranges(lib2, 0);
    CHECK(ranged > 0 && check_declared_ranges(lib3, 1) == ranged,
          "the declared ranges: %d Integer variables with one", ranged);
    printf("declared ranges: %d Integer parameters and inputs, FMI 2 and 3\n", ranged);

    static const char *const level[3] = {"kinematic", "massless", "full"};
    double *o2 = calloc((size_t)steps * N_OUT, sizeof(double));
    double *o3 = calloc((size_t)steps * N_OUT, sizeof(double));
    printf("%-6s %-10s %-12s %10s %10s   (median microseconds, %d steps of 1 ms)\n", "fmi",
           "fidelity", "derivatives", "doStep", "cycle", steps);
    for (int fid = 0; fid <= 2; ++fid)
        for (int der = 0; der <= 1; ++der) {
            const timing a = run_fmi2(lib2, fid, der, steps, o2);
            const timing b = run_fmi3(lib3, fid, der, steps, o3);
            CHECK(a.ran == b.ran, "fidelity %d available in one FMI version only", fid);
            const char *src = der ? "inputs" : "fd";
            if (!a.ran) {
                printf("%-6s %-10s %-12s %10s %10s\n", "2+3", level[fid], src, "n/a", "n/a");
                if (out)
                    fprintf(out,
                            "fmi2 fidelity=%s derivatives=%s unsupported\n"
                            "fmi3 fidelity=%s derivatives=%s unsupported\n",
                            level[fid], src, level[fid], src);
                continue;
            }
            /* same outputs from both versions, bit for bit, all finite; lengths near 0.56 m */
            unsigned vr[N_OUT];
            real_outputs(vr);
            for (int j = 0; j < steps; ++j) {
                const double *r2 = o2 + (size_t)j * N_OUT, *r3 = o3 + (size_t)j * N_OUT;
                for (int i = 0; i < N_OUT; ++i) {
                    CHECK(isfinite(r2[i]), "non-finite output %u", vr[i]);
                    CHECK(r2[i] == r3[i], "FMI 2 and FMI 3 differ: vr %u step %d: %.17g vs %.17g",
                          vr[i], j, r2[i], r3[i]);
                }
                for (int k = 0; k < 6; ++k)
                    CHECK(r2[k] > 0.45 && r2[k] < 0.65, "L[%d] = %g at step %d", k + 1, r2[k], j);
            }
            printf("%-6s %-10s %-12s %10.3f %10.3f\n", "2", level[fid], src, a.step_us, a.cycle_us);
            printf("%-6s %-10s %-12s %10.3f %10.3f\n", "3", level[fid], src, b.step_us, b.cycle_us);
            if (out)
                fprintf(out,
                        "fmi2 fidelity=%s derivatives=%s doStep_us=%.3f cycle_us=%.3f\n"
                        "fmi3 fidelity=%s derivatives=%s doStep_us=%.3f cycle_us=%.3f\n",
                        level[fid], src, a.step_us, a.cycle_us, level[fid], src, b.step_us,
                        b.cycle_us);
        }
#if COUNT_ALLOCATIONS
    CHECK(allocations == 0, "%ld heap allocations during the steps", allocations);
    printf("heap allocations during the steps: %ld\n", allocations);
    { /* the counter works: instantiation does allocate */
        const fmi2_api f = fmi2_api_load(lib2);
        const fmi2CallbackFunctions cb = {logger2, calloc, free, NULL, NULL};
        counting = 1;
        fmi2Component c =
            f.instantiate("probe", fmi2CoSimulation, GUID, "", &cb, fmi2False, fmi2False);
        counting = 0;
        CHECK(c != NULL && allocations > 0, "the allocation counter does not see the FMU's calls");
        f.free_instance(c);
    }
#else
    (void)counting;
    (void)allocations;
    printf("heap allocations during the steps: not counted under AddressSanitizer\n");
#endif
    free(o2);
    free(o3);
    if (out) fclose(out);
    dlclose(lib2);
    dlclose(lib3);
    if (failures) {
        fprintf(stderr, "importer: %d check(s) failed\n", failures);
        return 1;
    }
    return 0;
}
