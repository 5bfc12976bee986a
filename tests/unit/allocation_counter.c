#include "allocation_counter.h"

#include <stddef.h>

extern void *__libc_malloc(size_t);
extern void *__libc_calloc(size_t, size_t);
extern void *__libc_realloc(void *, size_t);
extern void *__libc_memalign(size_t, size_t);
extern void __libc_free(void *);

volatile long allocations = 0;

void *malloc(size_t n) {
    ++allocations;
    return __libc_malloc(n);
}
void *calloc(size_t n, size_t s) {
    ++allocations;
    return __libc_calloc(n, s);
}
void *realloc(void *p, size_t n) {
    ++allocations;
    return __libc_realloc(p, n);
}
void *memalign(size_t a, size_t n) {
    ++allocations;
    return __libc_memalign(a, n);
}
int posix_memalign(void **out, size_t a, size_t n) {
    ++allocations;
    *out = __libc_memalign(a, n);
    return *out ? 0 : 12;
}
void *aligned_alloc(size_t a, size_t n) {
    ++allocations;
    return __libc_memalign(a, n);
}
void free(void *p) { __libc_free(p); }
