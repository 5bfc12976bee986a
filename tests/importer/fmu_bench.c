/*
 * Runs one configuration of the FMI 2.0 FMU over a sinusoidal scene without Python, the way a
 * co-simulation master does (set the pose at t, doStep(t, h), read the outputs, which belong to
 * t + h), and prints the median microseconds per doStep and the mean Newton iterations. With
 * --out it also writes t + h and every leg output after each step, for accuracy studies
 * (studies/speed_accuracy.py).
 *
 * usage: fmu_bench FMI2.so [--fidelity F] [--derivatives D] [--step H] [--duration T]
 *                  [--tolerance TOL] [--modified-newton M] [--max-iterations N]
 *                  [--pose 24 comma-separated numbers: mean,amplitude,omega,phase for x..yaw]
 *                  [--set NAME=VALUE ...] [--out OUT.csv]
 * --set gives any parameter of the FMU by its name (e.g. --set cylinder_mass=20).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

int main(int argc, char **argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: fmu_bench FMI2.so [options] (see the source)\n");
        return 2;
    }
    int fidelity = 2, derivatives = 1, modified = 0, max_iterations = 20;
    double h = 1e-3, duration = 12.0, tolerance = 1e-12;
    const char *out_path = NULL;
    const char *sets[64];
    int n_sets = 0;
    scene sc = {{0, 0, 0.5, 0, 0, 0}, {0}, {0}, {0}};
    for (int i = 2; i + 1 < argc; i += 2) {
        const char *k = argv[i], *v = argv[i + 1];
        if (!strcmp(k, "--fidelity")) fidelity = atoi(v);
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
    if (!lib) { fprintf(stderr, "fmu_bench: %s\n", dlerror()); return 2; }
    const fmi2_api f = fmi2_api_load(lib);

    const fmi2CallbackFunctions cb = {logger, calloc, free, NULL, NULL};
    fmi2Component c = f.instantiate("bench", fmi2CoSimulation, FMU_GUID, "", &cb, fmi2False, fmi2False);
    if (!c) return 1;
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
        if ((var->type == FMU_REAL ? f.set_real(c, &vr, 1, &value) : f.set_int(c, &vr, 1, &int_value)) != fmi2OK) {
            fprintf(stderr, "fmu_bench: --set %s refused\n", sets[i]);
            return 2;
        }
    }
    double q[18];
    pose_at(&sc, 0.0, q);
    int ok = f.set_int(c, ivr, 4, ival) == fmi2OK && f.set_real(c, &tol_vr, 1, &tolerance) == fmi2OK &&
             f.set_real(c, in_vr, 18, q) == fmi2OK && f.setup(c, fmi2False, 0, 0, fmi2False, 0) == fmi2OK &&
             f.enter(c) == fmi2OK && f.exit_init(c) <= fmi2Warning;
    if (!ok) {
        fprintf(stderr, "fmu_bench: initialisation failed\n");
        f.free_instance(c);
        return 1;
    }
    FILE *out = out_path ? fopen(out_path, "w") : NULL;
    if (out) {
        fprintf(out, "t");
        const char *g[4] = {"L", "L_dot", "L_ddot", "F"};
        for (int i = 0; i < 24; ++i) fprintf(out, ",%s%d", g[i / 6], i % 6 + 1);
        fprintf(out, ",newton_iterations,status\n");
    }
    const long steps = lround(duration / h);
    double *t_step = malloc(steps * sizeof(double));
    double y[24];
    long iterations = 0, failed = 0;
    for (long j = 0; j < steps; ++j) {
        const double t = j * h;
        pose_at(&sc, t, q);
        f.set_real(c, in_vr, derivatives ? 18 : 6, q);
        const double t0 = now_us();
        const fmi2Status s = f.do_step(c, t, h, fmi2True);
        t_step[j] = now_us() - t0;
        failed += s > fmi2Warning;
        f.get_real(c, out_vr, 24, y);
        fmi2Integer iv[2];
        f.get_int(c, int_out, 2, iv);
        iterations += iv[0];
        if (out) {
            fprintf(out, "%.17g", (j + 1) * h);
            for (int i = 0; i < 24; ++i) fprintf(out, ",%.17g", y[i]);
            fprintf(out, ",%d,%d\n", iv[0], iv[1]);
        }
    }
    qsort(t_step, steps, sizeof *t_step, importer_cmp_double);
    printf("doStep_us_median=%.4f doStep_us_p90=%.4f iterations_mean=%.4f steps=%ld failed=%ld\n",
           t_step[steps / 2], t_step[steps * 9 / 10], (double)iterations / steps, steps, failed);
    free(t_step);
    if (out) fclose(out);
    f.free_instance(c);
    dlclose(lib);
    return failed ? 1 : 0;
}
