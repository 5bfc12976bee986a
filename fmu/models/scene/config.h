/*
 * The scene player's identity and sizes (StewartScene.fmu): a pose trajectory for masters that
 * cannot feed one themselves (libcosim, SSP masters), with its exact first and second
 * derivatives. Either the scene's sinusoids (trajectory_file empty), value = mean + amplitude
 * sin(omega t + phase) per component, or a trajectory file (trajectory.h: t, the pose, its rates
 * and accelerations per row) played by quintic Hermite interpolation. No state: the outputs are a
 * function of time (and of the file, read once at initialisation into the resources).
 */
#ifndef STEWART_FMU_CONFIG_H
#define STEWART_FMU_CONFIG_H

#define FMU_MODEL_IDENTIFIER "StewartScene"
#define FMU_GUID "{093d0d08-9403-4ce0-a0e6-2d2b7c5c7852}"
#define FMU_NVR 301
#define FMU_MODEL_DESCRIPTION_TEXT                                                         \
    "Stewart platform scene player: pose, pose rates and accelerations of a sum of one "   \
    "sinusoid per component (scenes/*.json), exact at every communication point, or of a " \
    "trajectory file (a planned move) interpolated by quintic Hermite"
#define FMU_DEFAULT_EXPERIMENT "startTime=\"0\" stopTime=\"12\" stepSize=\"0.001\""
#define FMU_CAN_INTERPOLATE_INPUTS 0

/* One String parameter, trajectory_file: in the plain values, so that a state holds it. */
#define FMU_STRING_PARAMETERS 1
#define FMU_STRING_SIZE 4096

typedef struct model_values {
    char trajectory_file[FMU_STRING_SIZE]; /* path of the trajectory file; "" plays the sinusoids */
} model_values;

/* The trajectory file's samples (trajectory.h), read at initialisation; `path` is the file they
 * were read from ("" none), so that a restored state with the same path reuses them. */
typedef struct model_resources {
    char path[FMU_STRING_SIZE];
    double *rows; /* n rows of 19: t, pose, rates, accelerations */
    size_t n;
} model_resources;

#endif
