/* The scene player (config.h): each pose component mean + amplitude sin(omega t + phase) and its
 * derivatives at the instance's time, or the trajectory file's (trajectory.h); a step moves the
 * outputs to t + h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bindings.h"
#include "logging.h"
#include "model_interface.h"
#include "model_without_saved_state.h"
#include "trajectory.h"

void model_start_values(fmu_values *v) {
    fmu_start_values(v);
    v->real[VR_z_mean] = 0.5; /* at rest at home */
}

char *model_string(fmu_values *v, unsigned vr) {
    (void)vr; /* trajectory_file, the one String parameter */
    return v->model.trajectory_file;
}

/* The trajectory file's rows into the resources, unless they hold that file's already; with a
 * file, no amplitude (the sinusoids are not played). */
static fmu_status load_trajectory(fmu_instance *inst) {
    const char *path = inst->v.model.trajectory_file;
    if (!*path) return FMU_OK;
    for (int i = 0; i < 6; ++i)
        if (inst->v.real[VR_x_amplitude + 4 * i] != 0.0) {
            fmu_log(inst, FMU_ERROR, LOG_ERROR,
                    "%s = %g and trajectory_file \"%s\" are both "
                    "given: the player plays the file or the sinusoids; set the amplitudes to 0 "
                    "or trajectory_file to \"\"",
                    fmu_variable_by_vr(VR_x_amplitude + 4 * i)->name,
                    inst->v.real[VR_x_amplitude + 4 * i], path);
            return FMU_ERROR;
        }
    if (inst->res.rows && !strcmp(inst->res.path, path)) return FMU_OK;
    model_free(inst);
    double *rows = NULL;
    size_t n = 0;
    if (trajectory_read(inst, path, &rows, &n) != FMU_OK) return FMU_ERROR;
    inst->res.rows = rows;
    inst->res.n = n;
    strcpy(inst->res.path, path);
    return FMU_OK;
}

fmu_status model_apply_parameters(fmu_instance *inst) {
#define FMU_OPTION_REAL(vr, id, name, field, unit, desc)                                       \
    if (!isfinite(inst->v.real[vr])) {                                                         \
        fmu_log(inst, FMU_ERROR, LOG_ERROR, "invalid parameter " name " = %g: must be finite", \
                inst->v.real[vr]);                                                             \
        return FMU_ERROR;                                                                      \
    }
#include "variables.def"
    return load_trajectory(inst);
}

static void write_outputs(fmu_values *v, double out[3][6]) {
    for (int i = 0; i < 6; ++i) {
        v->real[VR_x + i] = out[0][i];
        v->real[VR_x_dot + i] = out[1][i];
        v->real[VR_x_ddot + i] = out[2][i];
    }
    v->outputs_current = 1;
}

/* The trajectory file's outputs at time t: Discard before its first row, and past its last when
 * it does not end at rest (a held pose would jump its rate), the last values kept. */
static fmu_status evaluate_trajectory(fmu_instance *inst, double t) {
    const double *rows = inst->res.rows, *last = rows + (inst->res.n - 1) * TRAJECTORY_COLUMNS;
    double out[3][6];
    switch (trajectory_at(rows, inst->res.n, t, out)) {
        case TRAJECTORY_ON: write_outputs(&inst->v, out); return FMU_OK;
        case TRAJECTORY_BEFORE:
            fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                    "t = %.17g is before the first row of "
                    "trajectory_file \"%s\" (t = %.17g); outputs keep their last values",
                    t, inst->res.path, rows[0]);
            return FMU_DISCARD;
        case TRAJECTORY_PAST: break;
    }
    fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
            "t = %.17g is past the last row of trajectory_file "
            "\"%s\" (t = %.17g), which does not end at rest (x_dot %g, y_dot %g, z_dot %g, "
            "roll_dot %g, pitch_dot %g, yaw_dot %g, and the accelerations): holding its pose would "
            "jump the rates; end the file at rest or stop at its last row; outputs keep their "
            "last values",
            t, inst->res.path, last[0], last[7], last[8], last[9], last[10], last[11], last[12]);
    return FMU_DISCARD;
}

/* The outputs at time t, written only if all are finite: else Discard naming the component (finite
 * parameters can still overflow, e.g. omega = 1e308), the last values kept. */
static fmu_status evaluate(fmu_instance *inst, double t) {
    if (inst->v.model.trajectory_file[0]) return evaluate_trajectory(inst, t);
    fmu_values *v = &inst->v;
    double out[3][6];
    for (int i = 0; i < 6; ++i) {
        const double *p = &v->real[VR_x_mean + 4 * i]; /* mean, amplitude, omega, phase */
        const double a = p[1], w = p[2], angle = w * t + p[3];
        out[0][i] = p[0] + a * sin(angle);
        out[1][i] = a * w * cos(angle);
        out[2][i] = -a * w * w * sin(angle);
        for (int d = 0; d < 3; ++d)
            if (!isfinite(out[d][i])) {
                fmu_log(inst, FMU_DISCARD, LOG_DISCARD,
                        "t = %.17g: %s of the scene is not finite (mean %g, amplitude %g, omega "
                        "%g, phase %g); outputs keep their last values",
                        t, fmu_variable_by_vr(VR_x + 6 * d + i)->name, p[0], p[1], p[2], p[3]);
                return FMU_DISCARD;
            }
    }
    write_outputs(v, out);
    return FMU_OK;
}

/* A reset forgets the file's rows: the next initialisation reads the file again (it may have
 * been written anew under the same name). */
void model_reset(fmu_instance *inst) { model_free(inst); }

void model_free(fmu_instance *inst) {
    free(inst->res.rows);
    inst->res.rows = NULL;
    inst->res.n = 0;
    inst->res.path[0] = '\0';
}

fmu_status model_start(fmu_instance *inst) {
    (void)inst;
    return FMU_OK;
}

fmu_status model_refresh_outputs(fmu_instance *inst) { return evaluate(inst, inst->v.time); }

fmu_status model_do_step(fmu_instance *inst, double t, double h) { return evaluate(inst, t + h); }

const char *model_check_state(fmu_instance *inst, const fmu_values *v, const unsigned char *in,
                              size_t size, char *why, size_t why_size) {
    (void)inst;
    (void)in;
    (void)why;
    (void)why_size;
    if (size != 0) return "the scene player has no saved resources";
    if (!memchr(v->model.trajectory_file, '\0', sizeof v->model.trajectory_file))
        return "trajectory_file is not a terminated string";
#define FMU_OUTPUT(vr, id, name, unit, field, desc) \
    if (!isfinite(v->real[vr])) return "output " name " is not finite";
#define FMU_OPTION_REAL(vr, id, name, field, unit, desc) \
    if (!isfinite(v->real[vr])) return "parameter " name " is not finite";
#include "variables.def"
    return NULL;
}
