/* blas_start.h: OpenBLAS's threads and work buffers under an address-space
 * limit (src/sys/blas_start.c), once at start-up (threads.f90). */
#ifndef CONTACT2D_BLAS_START_H
#define CONTACT2D_BLAS_START_H
#include <stdint.h>

/* The thread count to use (<= n), its buffers mapped; n and nothing done
 * without a limit or without OpenBLAS; 0 when not even one buffer fits.
 * *left: the address space left (-1: no limit), *per_thread: the cost of a
 * further thread, *first: of the first buffer. */
int c2d_blas_start(int n, int64_t *left, int64_t *per_thread, int64_t *first);
#endif /* CONTACT2D_BLAS_START_H */
