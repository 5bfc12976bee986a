/* Counts heap allocations: linking allocation_counter.c into a test interposes malloc and
 * friends (glibc) for the whole executable. */
#ifndef STEWART_ALLOCATION_COUNTER_H
#define STEWART_ALLOCATION_COUNTER_H

/* Allocations since the program started. */
extern volatile long allocations;

#endif
