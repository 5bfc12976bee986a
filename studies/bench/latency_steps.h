/*
 * The calls whose latency studies/bench/latency.c measures and whose freedom from allocation,
 * locks and system calls tests/unit/test_realtime_steps.c checks: one workload per call, each
 * with an untimed preparation (inputs for call n, a periodic rewind that keeps an open-loop
 * plant near home) and the call itself. FMU calls go through the FMI 2 binaries (dlopen), found
 * in the build's fmu/ directory.
 */
#ifndef STEWART_LATENCY_STEPS_H
#define STEWART_LATENCY_STEPS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct latency_step latency_step;

/* The number of workloads (0: the empty call, the machine's own noise). */
int latency_step_count(void);
/* The name of workload i, e.g. "inverse full solve". */
const char *latency_step_name(int i);
/* Workload i, built and warmed up (allocation allowed here); fmu_dir is the build's fmu/
 * directory (build/fmu). NULL with a message if it cannot be built. */
latency_step *latency_step_create(int i, const char *fmu_dir, char *message, size_t size);
/* The untimed part of call n: its inputs, and every 200 calls the rewind to the start. */
void latency_step_prepare(latency_step *s, long n);
/* The measured call n: 0 if it succeeded, else nonzero. Allocates nothing, takes no lock, makes
 * no system call (what the test checks). */
int latency_step_run(latency_step *s, long n);
/* The integrator's work in workload s's last call: internal steps, right-hand-side evaluations,
 * rejected steps (error test failures) into work[3]; 0 for a workload with no integrator. */
int latency_step_work(const latency_step *s, long work[3]);
/* Frees the workload (NULL is ignored). */
void latency_step_free(latency_step *s);

#ifdef __cplusplus
}
#endif

#endif
