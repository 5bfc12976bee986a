/*
 * A second model on the FMU runtime, for its tests only: y' = gain * u with u held over each
 * step (so y(t + h) = y(t) + gain * u * h exactly), a state the FMU state must carry, and none
 * of the inverse model's variables. It shows that a model is a folder plus one stewart_fmu line.
 */
#ifndef INTEGRATOR_CONFIG_H
#define INTEGRATOR_CONFIG_H

#define FMU_MODEL_IDENTIFIER "RuntimeIntegrator"
#define FMU_GUID "{8e3c1f52-6a0d-4b7e-9c21-0f4d5a6b7c80}"
#define FMU_NVR 8
#define FMU_MODEL_DESCRIPTION_TEXT "Integrator y' = gain u (a test model of the FMU runtime)"
#define FMU_DEFAULT_EXPERIMENT "startTime=\"0\" stopTime=\"1\" stepSize=\"0.1\""
#define FMU_CAN_INTERPOLATE_INPUTS 0

/* The state y and the number of accepted steps: plain values, copied by FMU states. */
typedef struct model_values {
    double y;
    int steps;
} model_values;

/* No resources. */
typedef struct model_resources {
    int none;
} model_resources;

#endif
