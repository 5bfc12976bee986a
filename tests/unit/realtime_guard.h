/*
 * The real-time guard of tests/unit/test_realtime_steps.c: counts, while `realtime_counting` is
 * set, the lock calls (pthread mutexes, read-write
 * locks, spin locks, semaphores: interposed here for the whole executable, shared objects it
 * dlopens included) and the system calls (every one, seen through a seccomp filter that hands
 * each system call of the guarded thread to a supervising thread, which counts it and lets it
 * proceed: SECCOMP_RET_USER_NOTIF, Linux 5.5 or later; no ptrace, no root, no strace needed).
 */
#ifndef STEWART_REALTIME_GUARD_H
#define STEWART_REALTIME_GUARD_H

#include <stddef.h>

/* Set it around the calls under test (in the guarded thread). */
extern volatile int realtime_counting;

typedef struct realtime_counts {
    long locks, syscalls;
    int first_syscall; /* number of the first system call counted, -1 if none */
} realtime_counts;

/* Runs body(arg) in a new thread whose every system call the calling thread sees; counts what
 * happens while realtime_counting is set. 0, or -1 with a message if the guard cannot be set up
 * (no seccomp user notification in this kernel or container). */
int realtime_guard_run(void (*body)(void *), void *arg, realtime_counts *counts, char *message,
                       size_t size);

#endif
