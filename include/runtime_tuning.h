/* runtime_tuning.h: the process-wide settings of a run (src/sys/runtime_tuning.c),
 * made once at start-up, and the BLAS thread count a loop of factors side by
 * side sets for itself.
 *
 * Only documented interfaces: glibc's mallopt and malloc_trim, OpenBLAS's
 * openblas_get_num_threads and openblas_set_num_threads (weak references:
 * with another BLAS nothing is done). */
#ifndef CONTACT2D_RUNTIME_TUNING_H
#define CONTACT2D_RUNTIME_TUNING_H

/* Once, before any parallel region: at most two glibc malloc arenas and
 * OpenBLAS's thread count set to nthreads (nthreads >= 1). */
void c2d_runtime_start(int nthreads);

/* Set OpenBLAS's thread count to n (n <= 0: leave it) and return the count
 * it had; 0 and nothing done when the BLAS is not OpenBLAS. */
int c2d_blas_threads(int n);

/* Give the free pages of every malloc arena back to the system. */
void c2d_malloc_trim(void);
#endif /* CONTACT2D_RUNTIME_TUNING_H */
