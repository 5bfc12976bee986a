/* The real-time guard (realtime_guard.h): lock interposition and a seccomp user-notification
 * supervisor. */
#define _GNU_SOURCE
#include "realtime_guard.h"

#include <dlfcn.h>
#include <errno.h>
#include <linux/audit.h>
#include <linux/filter.h>
#include <linux/seccomp.h>
#include <poll.h>
#include <pthread.h>
#include <semaphore.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <unistd.h>

volatile int realtime_counting = 0;
static volatile long lock_calls = 0;

/* ---- locks: every entry point counted while counting, then the C library's own ---- */

#define INTERPOSE(ret, name, params, args)                        \
    ret name params {                                             \
        static ret(*real) params = NULL;                          \
        if (!real) real = (ret(*) params)dlsym(RTLD_NEXT, #name); \
        if (realtime_counting) ++lock_calls;                      \
        return real args;                                         \
    }
INTERPOSE(int, pthread_mutex_lock, (pthread_mutex_t * m), (m))
INTERPOSE(int, pthread_mutex_trylock, (pthread_mutex_t * m), (m))
INTERPOSE(int, pthread_rwlock_rdlock, (pthread_rwlock_t * l), (l))
INTERPOSE(int, pthread_rwlock_wrlock, (pthread_rwlock_t * l), (l))
INTERPOSE(int, pthread_spin_lock, (pthread_spinlock_t * l), (l))
INTERPOSE(int, sem_wait, (sem_t * s), (s))

/* Resolves the C library's functions before any counting (dlsym may allocate). */
static void resolve_locks(void) {
    pthread_mutex_t m = PTHREAD_MUTEX_INITIALIZER;
    pthread_mutex_lock(&m);
    pthread_mutex_unlock(&m);
    if (pthread_mutex_trylock(&m) == 0) pthread_mutex_unlock(&m);
    pthread_rwlock_t l = PTHREAD_RWLOCK_INITIALIZER;
    pthread_rwlock_rdlock(&l);
    pthread_rwlock_unlock(&l);
    pthread_rwlock_wrlock(&l);
    pthread_rwlock_unlock(&l);
    pthread_spinlock_t s;
    pthread_spin_init(&s, 0);
    pthread_spin_lock(&s);
    pthread_spin_unlock(&s);
    sem_t sem;
    sem_init(&sem, 0, 1);
    sem_wait(&sem);
    sem_destroy(&sem);
}

/* ---- system calls: the guarded thread's filter and the supervisor ---- */

typedef struct guarded {
    void (*body)(void *);
    void *arg;
    volatile int listener; /* the filter's notification fd (-1 until set, -2 on failure) */
    volatile int done;
    int error; /* errno of a failed filter installation */
} guarded;

static void *guarded_thread(void *p) {
    guarded *g = (guarded *)p;
    /* every system call of this thread (x86-64 or not) goes to the supervisor */
    struct sock_filter code[] = {BPF_STMT(BPF_RET | BPF_K, SECCOMP_RET_USER_NOTIF)};
    struct sock_fprog prog = {sizeof code / sizeof code[0], code};
    int fd = -1;
    if (prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) == 0)
        fd = (int)syscall(SYS_seccomp, SECCOMP_SET_MODE_FILTER, SECCOMP_FILTER_FLAG_NEW_LISTENER,
                          &prog);
    if (fd < 0) {
        g->error = errno;
        __atomic_store_n(&g->listener, -2, __ATOMIC_SEQ_CST);
        return NULL;
    }
    __atomic_store_n(&g->listener, fd, __ATOMIC_SEQ_CST);
    g->body(g->arg);
    __atomic_store_n(&g->done, 1, __ATOMIC_SEQ_CST);
    return NULL;
}

int realtime_guard_run(void (*body)(void *), void *arg, realtime_counts *counts, char *message,
                       size_t size) {
    resolve_locks();
    memset(counts, 0, sizeof *counts);
    counts->first_syscall = -1;
    guarded g = {body, arg, -1, 0, 0};
    /* read before the thread starts: once its filter is in place the body may lock before this
     * thread runs again (CI saw 0 locks counted for the body's one when read later) */
    const long locks_before = lock_calls;
    pthread_t thread;
    if (pthread_create(&thread, NULL, guarded_thread, &g) != 0) {
        snprintf(message, size, "cannot start the guarded thread");
        return -1;
    }
    int fd;
    while ((fd = __atomic_load_n(&g.listener, __ATOMIC_SEQ_CST)) == -1) sched_yield();
    if (fd == -2) {
        pthread_join(thread, NULL);
        snprintf(message, size,
                 "seccomp user notification is not available here (%s): the "
                 "system-call check needs Linux >= 5.5 and seccomp allowed",
                 strerror(g.error));
        return -1;
    }
    /* answer every notification (let the call proceed) until no thread uses the filter any more
     * (the listener hangs up, Linux >= 5.8; else 10 s of silence after the body) */
    int silent = 0;
    for (;;) {
        struct pollfd pfd = {fd, POLLIN, 0};
        const int ready = poll(&pfd, 1, 200);
        if (ready < 0 && errno == EINTR) continue;
        if (ready < 0) break;
        if (ready == 0) {
            if (__atomic_load_n(&g.done, __ATOMIC_SEQ_CST) && ++silent >= 50) break;
            continue;
        }
        if (!(pfd.revents & POLLIN)) break; /* hang-up: the guarded thread has exited */
        silent = 0;
        struct seccomp_notif request;
        memset(&request, 0, sizeof request);
        if (ioctl(fd, SECCOMP_IOCTL_NOTIF_RECV, &request) != 0) continue;
        if (realtime_counting) {
            if (counts->syscalls++ == 0) counts->first_syscall = request.data.nr;
        }
        struct seccomp_notif_resp response;
        memset(&response, 0, sizeof response);
        response.id = request.id;
        response.flags = SECCOMP_USER_NOTIF_FLAG_CONTINUE;
        ioctl(fd, SECCOMP_IOCTL_NOTIF_SEND, &response);
    }
    pthread_join(thread, NULL);
    close(fd);
    counts->locks = lock_calls - locks_before;
    return 0;
}
