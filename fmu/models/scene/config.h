/*
 * The scene player's identity and sizes (StewartScene.fmu): a pose trajectory as
 * scripts/scenes.py defines it, value = mean + amplitude sin(omega t + phase) per component,
 * with its exact first and second derivatives, for masters that cannot feed a trajectory
 * themselves (libcosim). No state: the outputs are a function of time.
 */
#ifndef STEWART_FMU_CONFIG_H
#define STEWART_FMU_CONFIG_H

#define FMU_MODEL_IDENTIFIER "StewartScene"
#define FMU_GUID "{e1c83b56-7d2a-4f90-b4e5-91a6f0c2d378}"
#define FMU_NVR 301
#define FMU_MODEL_DESCRIPTION_TEXT                                                             \
    "Stewart platform scene player: pose, pose rates and accelerations of a sum of one "        \
    "sinusoid per component (scenes/*.json), exact at every communication point"
#define FMU_DEFAULT_EXPERIMENT "startTime=\"0\" stopTime=\"12\" stepSize=\"0.001\""
#define FMU_CAN_INTERPOLATE_INPUTS 0

typedef struct model_values {
    int none;
} model_values;

typedef struct model_resources {
    int none;
} model_resources;

#endif
