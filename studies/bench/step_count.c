// Instructions a program runs inside one function, counted by single-stepping it with ptrace:
// for kernels valgrind cannot run (AVX-512: its CPUID hides it, so the avx512vl kernel is not
// chosen under callgrind, and it could not run it). Slow (a
// few µs per instruction): use small batches. Prints the instructions in all and in the function.
// Run through studies/bench/step_count.sh (the function's address range from nm, the program
// without address randomisation).
#include <stdio.h>
#include <stdlib.h>
#include <sys/ptrace.h>
#include <sys/user.h>
#include <sys/wait.h>
#include <unistd.h>

int main(int argc, char **argv) {
    if (argc < 4) {
        fprintf(stderr, "usage: step_count LOW HIGH PROGRAM ARGS... (addresses in hex)\n");
        return 2;
    }
    const unsigned long low = strtoul(argv[1], 0, 16), high = strtoul(argv[2], 0, 16);
    const pid_t pid = fork();
    if (pid == 0) {
        ptrace(PTRACE_TRACEME, 0, 0, 0);
        execv(argv[3], argv + 3);
        _exit(127);
    }
    int status;
    waitpid(pid, &status, 0);
    unsigned long total = 0, inside = 0;
    while (!WIFEXITED(status) && !WIFSIGNALED(status)) {
        struct user_regs_struct regs;
        ptrace(PTRACE_GETREGS, pid, 0, &regs);
        ++total;
        inside += regs.rip >= low && regs.rip < high;
        ptrace(PTRACE_SINGLESTEP, pid, 0, 0);
        waitpid(pid, &status, 0);
    }
    printf("%lu %lu\n", total, inside);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}
