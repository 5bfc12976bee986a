/* What the controller's model.c shares with derivatives.c: its mode and each leg's cascade. */
#ifndef STEWART_CONTROLLER_H
#define STEWART_CONTROLLER_H

#include "cascade.h"
#include "instance.h"

enum { LEGS = 6 };

/* 1 with output = 1 (motor currents), 0 with output = 0 (forces). */
int controller_current_mode(const fmu_values *v);
/* Leg k's drive (0-based) and the gains, from the parameters in v. */
void controller_drive(const fmu_values *v, int k, cascade_drive *d, cascade_gains *g);
/* Leg k's five inputs from v, in cascade.h's order. */
void controller_leg_inputs(const fmu_values *v, int k, double in[CASCADE_INPUTS]);

#endif
