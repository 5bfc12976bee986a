/* One plant FMU instance behind either FMI layer for the C tests (test_plant_fmu*.c): open,
 * step, read the outputs, log the last message; the inverse side's static forces. */
#include "plant_fmu_unit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_support.h"
#include "unity.h"

static void logger2(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                    fmi2String category, fmi2String message, ...) {
    (void)name, (void)status, (void)category;
    log_sink *sink = env;
    if (!sink) return;
    snprintf(sink->last, sizeof sink->last, "%s", message);
    sink->count++;
}

static void logger3(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category,
                    fmi3String message) {
    logger2(env, "", (fmi2Status)status, category, message);
}


/* Instantiates (logging on), sets the fidelity, the forces and n Real parameters, and initialises
 * at t0; 0 if a call failed (no Unity assertion: threads call it too). */
int unit_open_at(unit *u, int v3, int fidelity, const double force[6], double t0, size_t n,
                 const unsigned *vr, const double *value) {
    memset(u, 0, sizeof *u);
    u->v3 = v3;
    u->cb2 = (fmi2CallbackFunctions){logger2, calloc, free, NULL, &u->log};
    const unsigned fidelity_vr = VR_fidelity,
                   force_vr[6] = {VR_F_1, VR_F_2, VR_F_3, VR_F_4, VR_F_5, VR_F_6};
    const int32_t fidelity_value = fidelity;
    if (v3) {
        u->c = fmi3InstantiateCoSimulation("plant", FMU_GUID, "", fmi3False, fmi3True, fmi3False,
                                           fmi3False, NULL, 0, &u->log, logger3, NULL);
        return u->c && fmi3SetInt32(u->c, &fidelity_vr, 1, &fidelity_value, 1) == fmi3OK &&
               fmi3SetFloat64(u->c, force_vr, 6, force, 6) == fmi3OK &&
               (n == 0 || fmi3SetFloat64(u->c, vr, n, value, n) == fmi3OK) &&
               fmi3EnterInitializationMode(u->c, fmi3False, 0, t0, fmi3False, 0) == fmi3OK &&
               fmi3ExitInitializationMode(u->c) == fmi3OK;
    }
    u->c = fmi2Instantiate("plant", fmi2CoSimulation, FMU_GUID, "", &u->cb2, fmi2False, fmi2True);
    return u->c && fmi2SetInteger(u->c, &fidelity_vr, 1, &fidelity_value) == fmi2OK &&
           fmi2SetReal(u->c, force_vr, 6, force) == fmi2OK &&
           (n == 0 || fmi2SetReal(u->c, vr, n, value) == fmi2OK) &&
           fmi2SetupExperiment(u->c, fmi2False, 0, t0, fmi2False, 0) == fmi2OK &&
           fmi2EnterInitializationMode(u->c) == fmi2OK &&
           fmi2ExitInitializationMode(u->c) == fmi2OK;
}

/* unit_open_at at t = 0 with the default parameters. */
int unit_open(unit *u, int v3, int fidelity, const double force[6]) {
    return unit_open_at(u, v3, fidelity, force, 0.0, 0, NULL, NULL);
}

/* unit_open, failing the test with the unit's last message. */
void unit_start(unit *u, int v3, int fidelity, const double force[6]) {
    TEST_ASSERT_TRUE_MESSAGE(unit_open(u, v3, fidelity, force), u->log.last);
}

void unit_free(unit *u) {
    if (u->v3) {
        fmi3Terminate(u->c);
        fmi3FreeInstance(u->c);
    } else {
        fmi2Terminate(u->c);
        fmi2FreeInstance(u->c);
    }
}

int set_forces(unit *u, const double force[6]) {
    const unsigned vr[6] = {VR_F_1, VR_F_2, VR_F_3, VR_F_4, VR_F_5, VR_F_6};
    return u->v3 ? (int)fmi3SetFloat64(u->c, vr, 6, force, 6)
                 : (int)fmi2SetReal(u->c, vr, 6, force);
}

/* FMI 2 only: order-1 derivatives of the six forces for the next step. */
int set_force_rates(unit *u, const double rate[6]) {
    const fmi2ValueReference vr[6] = {VR_F_1, VR_F_2, VR_F_3, VR_F_4, VR_F_5, VR_F_6};
    const fmi2Integer order[6] = {1, 1, 1, 1, 1, 1};
    return (int)fmi2SetRealInputDerivatives(u->c, vr, 6, order, rate);
}

/* DoStep; *last gets the unit's last successful time (NaN if it cannot be read). */
int do_step_status(unit *u, double t, double h, double *last) {
    if (u->v3) {
        fmi3Boolean event, terminate, early;
        return (int)fmi3DoStep(u->c, t, h, fmi3True, &event, &terminate, &early, last);
    }
    const int s = (int)fmi2DoStep(u->c, t, h, fmi2True);
    if (fmi2GetRealStatus(u->c, fmi2LastSuccessfulTime, last) != fmi2OK) *last = NAN;
    return s;
}

/* do_step_status, asserting that the last successful time could be read. */
int do_step(unit *u, double t, double h, double *last) {
    const int s = do_step_status(u, t, h, last);
    TEST_ASSERT_FALSE(isnan(*last));
    return s;
}


/* Reads the outputs; 0 if a call failed (no Unity assertion: threads call it too). */
int read_outputs(unit *u, snapshot *s) {
    unsigned real_vr[N_REALS], int_vr[N_INTS];
    for (int i = 0; i < N_REALS; ++i) real_vr[i] = i < 30 ? VR_x + i : VR_last_step_size;
    for (int i = 0; i < N_INTS; ++i) int_vr[i] = VR_status + i;
    memset(s, 0, sizeof *s);
    if (u->v3)
        return fmi3GetFloat64(u->c, real_vr, N_REALS, s->real, N_REALS) == fmi3OK &&
               fmi3GetInt32(u->c, int_vr, N_INTS, s->integer, N_INTS) == fmi3OK;
    return fmi2GetReal(u->c, real_vr, N_REALS, s->real) == fmi2OK &&
           fmi2GetInteger(u->c, int_vr, N_INTS, s->integer) == fmi2OK;
}

/* read_outputs, asserting that it succeeds and that every Real is finite. */
snapshot outputs(unit *u) {
    snapshot s;
    TEST_ASSERT_TRUE_MESSAGE(read_outputs(u, &s), u->log.last);
    for (int i = 0; i < N_REALS; ++i) TEST_ASSERT_TRUE(isfinite(s.real[i]));
    return s;
}

void assert_same_bits(const snapshot *a, const snapshot *b, const char *what) {
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(a, b, sizeof *a, what);
}

/* The inverse side's forces for the pose at rest at home (stewart_inverse_solve). */
void static_forces(int fidelity, double force[6]) {
    stewart_params params;
    stewart_params_default(&params);
    stewart_model *model = test_model(&params);
    stewart_inverse *data = test_inverse(model);
    const stewart_pose home = {{0, 0, params.home_height, 0, 0, 0}, {0}, {0}};
    const stewart_inverse_output out = solve_ok(data, (stewart_fidelity)fidelity, &home);
    memcpy(force, out.force, 6 * sizeof(double));
    stewart_inverse_free(data);
    stewart_model_free(model);
}
