/* runtime_tuning.c: the process-wide settings of a run (see
 * include/runtime_tuning.h), each through a documented interface.
 *
 * Why these settings: the bodies of a scene are ordered and factorized side
 * by side on the OpenMP threads, each with a BLAS of one thread; glibc gives
 * every thread that allocates an arena of its own whose freed pages stay
 * resident, and OpenBLAS reads its thread count from the environment when it
 * loads, not from the program's `-j N` (doc/performance.md, "Bodies
 * factorized side by side"). */
#include <malloc.h>

#include "runtime_tuning.h"

/* OpenBLAS's own thread count, when the BLAS is OpenBLAS: documented in its
 * cblas.h, declared here by weak reference so that with another BLAS both
 * are NULL and nothing is done. */
extern int openblas_get_num_threads(void) __attribute__((weak));
extern void openblas_set_num_threads(int) __attribute__((weak));

/* At most two malloc arenas (glibc's default is 8 per core): each further
 * arena keeps freed pages resident, while a single arena serializes the two
 * threads' allocations (two was measured on two cores: doc/performance.md). */
void c2d_runtime_start(int nthreads)
{
    (void) mallopt(M_ARENA_MAX, 2);
    (void) c2d_blas_threads(nthreads);
}

int c2d_blas_threads(int n)
{
    int old;
    if (openblas_get_num_threads == NULL || openblas_set_num_threads == NULL) return 0;
    old = openblas_get_num_threads();
    if (n > 0 && n != old) openblas_set_num_threads(n);
    return old;
}

void c2d_malloc_trim(void)
{
    (void) malloc_trim(0);
}
