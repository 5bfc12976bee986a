/* One plant FMU instance behind either FMI layer for the C tests (test_plant_fmu*.c), linked
 * statically with StewartPlant_model and its FMI 2 and FMI 3 layers. */
#ifndef STEWART_TEST_PLANT_FMU_UNIT_H
#define STEWART_TEST_PLANT_FMU_UNIT_H

#include <stddef.h>
#include <stdint.h>

#include "fmi2Functions.h"
#include "fmi3Functions.h"
#include "variables.h"

#define STEP 1e-3

/* The last message logged by an instance (each instance its own: the environment pointer). */
typedef struct log_sink {
    char last[1024];
    int count;
} log_sink;

/* One plant instance behind either FMI layer (the statuses have the same numbers in both). */
typedef struct unit {
    int v3;
    void *c;
    log_sink log;
    fmi2CallbackFunctions cb2;
} unit;

/* The outputs: the Reals 100..129 and 142 (in that order), the Integers 130..141 (status and
 * the statistics). */
#define N_REALS 31
#define N_INTS 12
typedef struct snapshot {
    double real[N_REALS];
    int32_t integer[N_INTS];
} snapshot;

/* Instantiates (logging on), sets the fidelity, the forces and n Real parameters, and initialises
 * at t0; 0 if a call failed (no Unity assertion: threads call it too). */
int unit_open_at(unit *u, int v3, int fidelity, const double force[6], double t0, size_t n,
                 const unsigned *vr, const double *value);
/* unit_open_at at t = 0 with the default parameters. */
int unit_open(unit *u, int v3, int fidelity, const double force[6]);
/* unit_open, failing the test with the unit's last message. */
void unit_start(unit *u, int v3, int fidelity, const double force[6]);
/* Terminates and frees the instance. */
void unit_free(unit *u);
/* SetReal of the six forces; the FMI status. */
int set_forces(unit *u, const double force[6]);
/* FMI 2 only: order-1 derivatives of the six forces for the next step. */
int set_force_rates(unit *u, const double rate[6]);
/* DoStep; *last gets the unit's last successful time (NaN if it cannot be read). */
int do_step_status(unit *u, double t, double h, double *last);
/* do_step_status, asserting that the last successful time could be read. */
int do_step(unit *u, double t, double h, double *last);
/* Reads the outputs; 0 if a call failed (no Unity assertion: threads call it too). */
int read_outputs(unit *u, snapshot *s);
/* read_outputs, asserting that it succeeds and that every Real is finite. */
snapshot outputs(unit *u);
/* Asserts that two snapshots are the same bit for bit. */
void assert_same_bits(const snapshot *a, const snapshot *b, const char *what);
/* The inverse side's forces for the pose at rest at home (stewart_inverse_solve). */
void static_forces(int fidelity, double force[6]);

#endif
