/*
 * Runs one configuration of the FMI 2.0 (or, with --fmi 3, 3.0) FMU over a sinusoidal scene
 * without Python, the way a
 * co-simulation master does (set the pose at t, doStep(t, h), read the outputs, which belong to
 * t + h), and prints the median microseconds per doStep and the mean Newton iterations. With
 * --out it also writes t + h and every output after each step (the leg outputs, newton_iterations,
 * status, condition, residual, the base wrench), for accuracy studies (studies/speed_accuracy.py)
 * and bit-for-bit comparisons of two builds.
 *
 * usage: fmu_bench FMU.so [--fmi 2|3] [--fidelity F] [--derivatives D] [--step H] [--duration T]
 *                  [--tolerance TOL] [--modified-newton M] [--max-iterations N]
 *                  [--pose 24 comma-separated numbers: mean,amplitude,omega,phase for x..yaw]
 *                  [--set NAME=VALUE ...] [--out OUT.csv]
 * --set gives any parameter of the FMU by its name (e.g. --set cylinder_mass=20).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi3Functions.h"
#include "importer_support.h"
#include "variables.h"

typedef struct {
    double mean[6], amplitude[6], omega[6], phase[6];
} scene;

static void pose_at(const scene *s, double t, double q[18]) {
    for (int i = 0; i < 6; ++i) {
        const double arg = s->omega[i] * t + s->phase[i], a = s->amplitude[i], w = s->omega[i];
        q[i] = s->mean[i] + a * sin(arg);
        q[6 + i] = a * w * cos(arg);
        q[12 + i] = -a * w * w * sin(arg);
    }
}

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                   fmi2String category, fmi2String message, ...) {
    (void)env;
    if (status > fmi2Warning) fprintf(stderr, "[%s %d %s] %s\n", name, status, category, message);
}

static void logger3(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category,
                    fmi3String message) {
    (void)env;
    if (status > fmi3Warning) fprintf(stderr, "[%d %s] %s\n", status, category, message);
}

/* The FMI 3 co-simulation calls the benchmark makes. */
typedef struct {
    fmi3InstantiateCoSimulationTYPE *instantiate;
    fmi3FreeInstanceTYPE *free_instance;
    fmi3EnterInitializationModeTYPE *enter;
    fmi3ExitInitializationModeTYPE *exit_init;
    fmi3SetInt32TYPE *set_int;
    fmi3SetFloat64TYPE *set_real;
    fmi3GetFloat64TYPE *get_real;
    fmi3GetInt32TYPE *get_int;
    fmi3DoStepTYPE *do_step;
} fmi3_api;

/* One instance of either version: each call below goes to the version's function (statuses are
 * numbered alike in both). */
typedef struct {
    int v3;
    fmi2_api f2;
    fmi3_api f3;
    void *c;
} unit;

static int unit_load(unit *u, void *lib, int version) {
    u->v3 = version == 3;
    if (!u->v3) {
        u->f2 = fmi2_api_load(lib);
        static const fmi2CallbackFunctions cb = {logger, calloc, free, NULL, NULL};
        u->c =
            u->f2.instantiate("bench", fmi2CoSimulation, FMU_GUID, "", &cb, fmi2False, fmi2False);
        return u->c != NULL;
    }
    u->f3.instantiate =
        (fmi3InstantiateCoSimulationTYPE *)importer_symbol(lib, "fmi3InstantiateCoSimulation");
    u->f3.free_instance = (fmi3FreeInstanceTYPE *)importer_symbol(lib, "fmi3FreeInstance");
    u->f3.enter =
        (fmi3EnterInitializationModeTYPE *)importer_symbol(lib, "fmi3EnterInitializationMode");
    u->f3.exit_init =
        (fmi3ExitInitializationModeTYPE *)importer_symbol(lib, "fmi3ExitInitializationMode");
    u->f3.set_int = (fmi3SetInt32TYPE *)importer_symbol(lib, "fmi3SetInt32");
    u->f3.set_real = (fmi3SetFloat64TYPE *)importer_symbol(lib, "fmi3SetFloat64");
    u->f3.get_real = (fmi3GetFloat64TYPE *)importer_symbol(lib, "fmi3GetFloat64");
    u->f3.get_int = (fmi3GetInt32TYPE *)importer_symbol(lib, "fmi3GetInt32");
    u->f3.do_step = (fmi3DoStepTYPE *)importer_symbol(lib, "fmi3DoStep");
    u->c = u->f3.instantiate("bench", FMU_GUID, "", fmi3False, fmi3False, fmi3False, fmi3False,
                             NULL, 0, NULL, logger3, NULL);
    return u->c != NULL;
}

static int set_reals(const unit *u, const unsigned *vr, size_t n, const double *x) {
    return u->v3 ? u->f3.set_real(u->c, vr, n, x, n) : u->f2.set_real(u->c, vr, n, x);
}

static int set_ints(const unit *u, const unsigned *vr, size_t n, const int *x) {
    return u->v3 ? u->f3.set_int(u->c, vr, n, x, n) : u->f2.set_int(u->c, vr, n, x);
}

static int get_reals(const unit *u, const unsigned *vr, size_t n, double *x) {
    return u->v3 ? u->f3.get_real(u->c, vr, n, x, n) : u->f2.get_real(u->c, vr, n, x);
}

static int get_ints(const unit *u, const unsigned *vr, size_t n, int *x) {
    return u->v3 ? u->f3.get_int(u->c, vr, n, x, n) : u->f2.get_int(u->c, vr, n, x);
}

/* Initialisation at t = 0 (statuses OK or Warning pass). */
static int initialise(const unit *u) {
    if (u->v3)
        return u->f3.enter(u->c, fmi3False, 0, 0.0, fmi3False, 0) == fmi3OK &&
               u->f3.exit_init(u->c) <= fmi3Warning;
    return u->f2.setup(u->c, fmi2False, 0, 0, fmi2False, 0) == fmi2OK &&
           u->f2.enter(u->c) == fmi2OK && u->f2.exit_init(u->c) <= fmi2Warning;
}

static int do_step(const unit *u, double t, double h) {
    if (!u->v3) return u->f2.do_step(u->c, t, h, fmi2True);
    fmi3Boolean event, terminate, early;
    fmi3Float64 last;
    return u->f3.do_step(u->c, t, h, fmi3True, &event, &terminate, &early, &last);
}

static void unit_free(const unit *u) {
    if (u->v3) u->f3.free_instance(u->c);
    else u->f2.free_instance(u->c);
}

int main(int argc, char **argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: fmu_bench FMI2.so [options] (see the source)\n");
        return 2;
    }
    int fidelity = 2, derivatives = 1, modified = 0, max_iterations = 20, version = 2;
    double h = 1e-3, duration = 12.0, tolerance = 1e-12;
    const char *out_path = NULL;
    const char *sets[64];
    int n_sets = 0;
    scene sc = {{0, 0, 0.5, 0, 0, 0}, {0}, {0}, {0}};
    for (int i = 2; i + 1 < argc; i += 2) {
        const char *k = argv[i], *v = argv[i + 1];
        if (!strcmp(k, "--fmi")) version = atoi(v);
        else if (!strcmp(k, "--fidelity")) fidelity = atoi(v);
        else if (!strcmp(k, "--derivatives")) derivatives = atoi(v);
        else if (!strcmp(k, "--step")) h = atof(v);
        else if (!strcmp(k, "--duration")) duration = atof(v);
        else if (!strcmp(k, "--tolerance")) tolerance = atof(v);
        else if (!strcmp(k, "--modified-newton")) modified = atoi(v);
        else if (!strcmp(k, "--max-iterations")) max_iterations = atoi(v);
        else if (!strcmp(k, "--out")) out_path = v;
        else if (!strcmp(k, "--set") && n_sets < 64) sets[n_sets++] = v;
        else if (!strcmp(k, "--pose")) {
            double *dst[4] = {sc.mean, sc.amplitude, sc.omega, sc.phase};
            char *p = (char *)v;
            for (int j = 0; j < 24; ++j) {
                dst[j % 4][j / 4] = strtod(p, &p);
                if (*p == ',') ++p;
            }
        } else {
            fprintf(stderr, "fmu_bench: unknown option %s\n", k);
            return 2;
        }
    }

    void *lib = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        fprintf(stderr, "fmu_bench: %s\n", dlerror());
        return 2;
    }
    unit u;
    if (!unit_load(&u, lib, version)) return 1;
    const fmi2ValueReference ivr[4] = {VR_fidelity, VR_derivatives, VR_modified_newton,
                                       VR_max_iterations};
    const fmi2Integer ival[4] = {fidelity, derivatives, modified, max_iterations};
    const fmi2ValueReference tol_vr = VR_tolerance;
    fmi2ValueReference in_vr[18], out_vr[24];
    const fmi2ValueReference first_in[3] = {VR_x, VR_x_dot, VR_x_ddot};
    for (int i = 0; i < 18; ++i) in_vr[i] = first_in[i / 6] + i % 6;
    const fmi2ValueReference first_out[4] = {VR_L_1, VR_L_dot_1, VR_L_ddot_1, VR_F_1};
    for (int i = 0; i < 24; ++i) out_vr[i] = first_out[i / 6] + i % 6;
    const fmi2ValueReference int_out[2] = {VR_newton_iterations, VR_status};
    /* with --out also the rest of the Real outputs (read only then: the timed loop stays) */
    const fmi2ValueReference more_vr[8] = {VR_condition,     VR_residual,     VR_base_force_1,
                                           VR_base_force_2,  VR_base_force_3, VR_base_torque_1,
                                           VR_base_torque_2, VR_base_torque_3};

    for (int i = 0; i < n_sets; ++i) {
        const char *eq = strchr(sets[i], '=');
        const fmu_variable *var = NULL;
        for (size_t j = 0; eq && j < fmu_n_variables; ++j)
            if (strlen(fmu_variables[j].name) == (size_t)(eq - sets[i]) &&
                !strncmp(fmu_variables[j].name, sets[i], eq - sets[i]))
                var = &fmu_variables[j];
        if (!var) {
            fprintf(stderr, "fmu_bench: --set %s: no such variable\n", sets[i]);
            return 2;
        }
        const fmi2ValueReference vr = var->vr;
        const double value = atof(eq + 1);
        const fmi2Integer int_value = (fmi2Integer)value;
        if ((var->type == FMU_REAL ? set_reals(&u, &vr, 1, &value)
                                   : set_ints(&u, &vr, 1, &int_value)) != fmi2OK) {
            fprintf(stderr, "fmu_bench: --set %s refused\n", sets[i]);
            return 2;
        }
    }
    double q[18];
    pose_at(&sc, 0.0, q);
    int ok = set_ints(&u, ivr, 4, ival) == fmi2OK &&
             set_reals(&u, &tol_vr, 1, &tolerance) == fmi2OK &&
             set_reals(&u, in_vr, 18, q) == fmi2OK && initialise(&u);
    if (!ok) {
        fprintf(stderr, "fmu_bench: initialisation failed\n");
        unit_free(&u);
        return 1;
    }
    FILE *out = out_path ? fopen(out_path, "w") : NULL;
    if (out) {
        fprintf(out, "t");
        const char *g[4] = {"L", "L_dot", "L_ddot", "F"};
        for (int i = 0; i < 24; ++i) fprintf(out, ",%s%d", g[i / 6], i % 6 + 1);
        fprintf(out, ",newton_iterations,status,condition,residual,base_force1,base_force2,"
                     "base_force3,base_torque1,base_torque2,base_torque3\n");
    }
    const long steps = lround(duration / h);
    double *t_step = malloc(steps * sizeof(double));
    double y[24];
    long iterations = 0, failed = 0;
    for (long j = 0; j < steps; ++j) {
        const double t = j * h;
        pose_at(&sc, t, q);
        set_reals(&u, in_vr, derivatives ? 18 : 6, q);
        const double t0 = now_us();
        const int s = do_step(&u, t, h);
        t_step[j] = now_us() - t0;
        failed += s > fmi2Warning;
        get_reals(&u, out_vr, 24, y);
        fmi2Integer iv[2];
        get_ints(&u, int_out, 2, iv);
        iterations += iv[0];
        if (out) {
            fprintf(out, "%.17g", (j + 1) * h);
            for (int i = 0; i < 24; ++i) fprintf(out, ",%.17g", y[i]);
            double more[8];
            get_reals(&u, more_vr, 8, more);
            fprintf(out, ",%d,%d", iv[0], iv[1]);
            for (int i = 0; i < 8; ++i) fprintf(out, ",%.17g", more[i]);
            fprintf(out, "\n");
        }
    }
    qsort(t_step, steps, sizeof *t_step, importer_cmp_double);
    printf("doStep_us_median=%.4f doStep_us_p90=%.4f iterations_mean=%.4f steps=%ld failed=%ld\n",
           t_step[steps / 2], t_step[steps * 9 / 10], (double)iterations / steps, steps, failed);
    free(t_step);
    if (out) fclose(out);
    unit_free(&u);
    dlclose(lib);
    return failed ? 1 : 0;
}
