/*
 * A second Model Exchange master (beside fmpy's CVODE): dlopens StewartPlantME's FMI 2 or FMI 3
 * binary and integrates its states with the classical fixed-step Runge-Kutta method, the forces
 * held over each step (before t_switch one set, after it another), as the co-simulation plant
 * holds them. Prints one CSV line per step: t, x .. yaw, x_dot .. yaw_dot, L[1..6], L_dot[1..6].
 * tests/python/test_plant_me_fmu.py compares it with StewartPlant.
 *
 * usage: me_rk4 2|3 BINARY.so FIDELITY H T_END T_SWITCH F_BEFORE[6] F_AFTER[6] X0[12]
 *   X0: the start parameters x0 .. yaw0, x_dot0 .. yaw_dot0
 */
#include <dlfcn.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "fmi3Functions.h"
#include "variables.h" /* StewartPlantME's value references */

enum { N = 12 };

static void *lib;

/* dlsym, or exit(2) naming the missing symbol. */
static void *symbol(const char *name) {
    void *f = dlsym(lib, name);
    if (!f) {
        fprintf(stderr, "%s not found: %s\n", name, dlerror());
        exit(2);
    }
    return f;
}

/* Exits naming the call unless its status is OK (or Warning). */
static void check(int status, const char *call) {
    if (status > 1) {
        fprintf(stderr, "me_rk4: %s returned status %d\n", call, status);
        exit(1);
    }
}

static void log_fmi2(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                     fmi2String category, fmi2String message, ...) {
    (void)env;
    (void)name;
    (void)status;
    fprintf(stderr, "[%s] %s\n", category, message);
}

static void log_fmi3(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category,
                     fmi3String message) {
    (void)env;
    (void)status;
    fprintf(stderr, "[%s] %s\n", category, message);
}

/* The calls of either version, each returning its status as an int. */
typedef struct master {
    int version;
    void *c;
    int (*set_real)(void *, const unsigned *, size_t, const double *);
    int (*get_real)(void *, const unsigned *, size_t, double *);
    int (*set_time)(void *, double);
    int (*set_states)(void *, const double *, size_t);
    int (*get_states)(void *, double *, size_t);
    int (*derivatives)(void *, double *, size_t);
} master;

#define API2(name) ((fmi2##name##TYPE *)symbol("fmi2" #name))
#define API3(name) ((fmi3##name##TYPE *)symbol("fmi3" #name))

static int set_real2(void *c, const unsigned *vr, size_t n, const double *v) {
    return API2(SetReal)(c, vr, n, v);
}
static int get_real2(void *c, const unsigned *vr, size_t n, double *v) {
    return API2(GetReal)(c, vr, n, v);
}
static int set_time2(void *c, double t) { return API2(SetTime)(c, t); }
static int set_states2(void *c, const double *x, size_t n) {
    return API2(SetContinuousStates)(c, x, n);
}
static int get_states2(void *c, double *x, size_t n) { return API2(GetContinuousStates)(c, x, n); }
static int derivatives2(void *c, double *dx, size_t n) { return API2(GetDerivatives)(c, dx, n); }

static int set_real3(void *c, const unsigned *vr, size_t n, const double *v) {
    return API3(SetFloat64)(c, vr, n, v, n);
}
static int get_real3(void *c, const unsigned *vr, size_t n, double *v) {
    return API3(GetFloat64)(c, vr, n, v, n);
}
static int set_time3(void *c, double t) { return API3(SetTime)(c, t); }
static int set_states3(void *c, const double *x, size_t n) {
    return API3(SetContinuousStates)(c, x, n);
}
static int get_states3(void *c, double *x, size_t n) { return API3(GetContinuousStates)(c, x, n); }
static int derivatives3(void *c, double *dx, size_t n) {
    return API3(GetContinuousStateDerivatives)(c, dx, n);
}

/* Instantiated, parameters set, initialised, through event mode into continuous-time mode. */
static master start(int version, int fidelity, const double x0[N]) {
    master m = {version,   NULL,        set_real2,   get_real2,
                set_time2, set_states2, get_states2, derivatives2};
    static fmi2CallbackFunctions callbacks = {log_fmi2, calloc, free, NULL, NULL};
    if (version == 3) {
        m.set_real = set_real3;
        m.get_real = get_real3;
        m.set_time = set_time3;
        m.set_states = set_states3;
        m.get_states = get_states3;
        m.derivatives = derivatives3;
        m.c = API3(InstantiateModelExchange)("rk4", FMU_GUID, NULL, fmi3False, fmi3False, NULL,
                                             log_fmi3);
    } else {
        m.c = API2(Instantiate)("rk4", fmi2ModelExchange, FMU_GUID, NULL, &callbacks, fmi2False,
                                fmi2False);
    }
    if (!m.c) {
        fprintf(stderr, "me_rk4: instantiation failed\n");
        exit(1);
    }
    if (version == 3) {
        check(API3(EnterInitializationMode)(m.c, fmi3False, 0, 0.0, fmi3False, 0), "enter init");
        const fmi3ValueReference vr = VR_fidelity;
        const fmi3Int32 value = fidelity;
        check(API3(SetInt32)(m.c, &vr, 1, &value, 1), "set fidelity");
    } else {
        check(API2(SetupExperiment)(m.c, fmi2False, 0, 0.0, fmi2False, 0), "setup");
        check(API2(EnterInitializationMode)(m.c), "enter init");
        const fmi2ValueReference vr = VR_fidelity;
        const fmi2Integer value = fidelity;
        check(API2(SetInteger)(m.c, &vr, 1, &value), "set fidelity");
    }
    unsigned start_vr[N];
    for (int i = 0; i < N; ++i) start_vr[i] = VR_x0 + i;
    check(m.set_real(m.c, start_vr, N, x0), "set start state");
    if (version == 3) {
        check(API3(ExitInitializationMode)(m.c), "exit init");
        fmi3Boolean more = fmi3True, flag;
        fmi3Float64 next;
        while (more)
            check(API3(UpdateDiscreteStates)(m.c, &more, &flag, &flag, &flag, &flag, &next),
                  "update discrete states");
        check(API3(EnterContinuousTimeMode)(m.c), "enter continuous time");
    } else {
        check(API2(ExitInitializationMode)(m.c), "exit init");
        fmi2EventInfo info = {fmi2True, 0, 0, 0, 0, 0};
        while (info.newDiscreteStatesNeeded)
            check(API2(NewDiscreteStates)(m.c, &info), "new discrete states");
        check(API2(EnterContinuousTimeMode)(m.c), "enter continuous time");
    }
    return m;
}

/* dx at (t, x). */
static void rhs(const master *m, double t, const double x[N], double dx[N]) {
    check(m->set_time(m->c, t), "set time");
    check(m->set_states(m->c, x, N), "set states");
    check(m->derivatives(m->c, dx, N), "get derivatives");
}

/* The CSV line at the current state: t and the pose, rates, lengths and length rates. */
static void print_outputs(const master *m, double t) {
    unsigned vr[24];
    double value[24];
    for (int i = 0; i < 24; ++i) vr[i] = VR_x + i; /* x .. L_dot[6]: 100..123 */
    check(m->get_real(m->c, vr, 24, value), "get outputs");
    printf("%.17g", t);
    for (int i = 0; i < 24; ++i) printf(",%.17g", value[i]);
    printf("\n");
}

int main(int argc, char **argv) {
    if (argc != 7 + 12 + N) {
        fprintf(stderr, "usage: me_rk4 2|3 BINARY.so FIDELITY H T_END T_SWITCH F_BEFORE[6] "
                        "F_AFTER[6] X0[12]\n");
        return 2;
    }
    const int version = atoi(argv[1]);
    lib = dlopen(argv[2], RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        fprintf(stderr, "me_rk4: %s\n", dlerror());
        return 2;
    }
    const int fidelity = atoi(argv[3]);
    const double h = atof(argv[4]), t_end = atof(argv[5]), t_switch = atof(argv[6]);
    double before[6], after[6], x[N];
    for (int k = 0; k < 6; ++k) {
        before[k] = atof(argv[7 + k]);
        after[k] = atof(argv[13 + k]);
    }
    for (int i = 0; i < N; ++i) x[i] = atof(argv[19 + i]);
    master m = start(version, fidelity, x);
    check(m.get_states(m.c, x, N), "get states");
    unsigned force_vr[6];
    for (int k = 0; k < 6; ++k) force_vr[k] = VR_F_1 + k;

    print_outputs(&m, 0.0);
    const long steps = (long)(t_end / h + 0.5);
    for (long n = 0; n < steps; ++n) {
        const double t = n * h;
        /* forces held over the step, the value at its start */
        check(m.set_real(m.c, force_vr, 6, t < t_switch - 1e-12 ? before : after), "set F");
        double k1[N], k2[N], k3[N], k4[N], y[N];
        rhs(&m, t, x, k1);
        for (int i = 0; i < N; ++i) y[i] = x[i] + 0.5 * h * k1[i];
        rhs(&m, t + 0.5 * h, y, k2);
        for (int i = 0; i < N; ++i) y[i] = x[i] + 0.5 * h * k2[i];
        rhs(&m, t + 0.5 * h, y, k3);
        for (int i = 0; i < N; ++i) y[i] = x[i] + h * k3[i];
        rhs(&m, t + h, y, k4);
        for (int i = 0; i < N; ++i) x[i] += h / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
        const double t_next = (n + 1) * h;
        check(m.set_time(m.c, t_next), "set time");
        check(m.set_states(m.c, x, N), "set states");
        if (version == 3) {
            fmi3Boolean event, terminate;
            check(API3(CompletedIntegratorStep)(m.c, fmi3True, &event, &terminate),
                  "completed step");
        } else {
            fmi2Boolean event, terminate;
            check(API2(CompletedIntegratorStep)(m.c, fmi2True, &event, &terminate),
                  "completed step");
        }
        print_outputs(&m, t_next);
    }
    if (version == 3) {
        check(API3(Terminate)(m.c), "terminate");
        API3(FreeInstance)(m.c);
    } else {
        check(API2(Terminate)(m.c), "terminate");
        API2(FreeInstance)(m.c);
    }
    dlclose(lib);
    return 0;
}
