/*
 * The leg controller's identity and sizes (StewartController.fmu). output = 0: feed-forward plus
 * PD on the six actuator lengths, F = F_ff + kp (L_ref - L) + kd (L_dot_ref - L_dot), no state.
 * output = 1: a position -> speed -> current cascade per leg (cascade.h), whose speed loop's
 * integral is the unit's state.
 */
#ifndef STEWART_FMU_CONFIG_H
#define STEWART_FMU_CONFIG_H

#define FMU_MODEL_IDENTIFIER "StewartController"
#define FMU_GUID "{4a9d2e71-c05b-4f3a-9e18-6b7c2d5f8a13}"
#define FMU_NVR 301
#define FMU_MODEL_DESCRIPTION_TEXT                                                              \
    "Stewart platform leg controller: F = F_ff + kp (L_ref - L) + kd (L_dot_ref - L_dot) per "  \
    "leg (output = 0), or the motor currents of a position, speed and current cascade "         \
    "(output = 1); the reference and feed-forward from the inverse unit, L and L_dot from the " \
    "plant"
#define FMU_DEFAULT_EXPERIMENT "startTime=\"0\" stopTime=\"1\" stepSize=\"0.001\""
#define FMU_CAN_INTERPOLATE_INPUTS 0

/* Directional derivatives: the gains, or the cascade's slopes (derivatives.c). */
#define FMU_PROVIDES_DIRECTIONAL_DERIVATIVE 1
/* The model structure: F[k] depends on leg k's five inputs only (the inputs come in blocks of
 * six, one per leg); status checks every input. */
#define FMU_OUTPUT_DEPENDS_ON(out, in) \
    ((out) >= VR_F_1 && (out) <= VR_F_6 ? ((in) - VR_L_ref_1) % 6 == (out) - VR_F_1 : 1)

/* Plain values: the cascade's state and what the outputs' last evaluation returned. */
typedef struct model_values {
    double speed_integral[6]; /* output = 1: each leg's integral of its speed error [rad] */
    int solve_status;
} model_values;

/* No resources. */
typedef struct model_resources {
    int none;
} model_resources;

#endif
