/* blas_start.c: OpenBLAS's threads and work buffers under an address-space
 * limit (ulimit -v).
 *
 * OpenBLAS (0.3.21, pthreads) maps a work buffer of 128 MB for each thread
 * that runs a BLAS 3 call, at the first such call, and retries the mapping
 * without end when it fails: under a limit the run would hang at its first
 * factorization.  It starts its worker threads when the thread count is set
 * and ends the process (exit(3)) when one cannot be created.  So, once, at
 * start-up and only under a limit, before the run allocates anything large:
 *   - not even one buffer fits: the caller ends the run with the
 *     out-of-memory diagnosis (nothing has been read or written yet);
 *   - each thread beyond the first costs a buffer and two stacks (an OpenMP
 *     thread and an OpenBLAS worker); the further threads may take at most
 *     half of what is left once the first buffer is counted, and the thread
 *     count is lowered to what fits (the caller says so in the run log);
 *   - a BLAS 3 call on that many threads then maps every buffer while the
 *     room is there.  OpenBLAS keeps its buffers mapped for the life of the
 *     process and reuses them, so no later call maps one.
 * Without a limit nothing is done here: the machine's memory is the
 * factorization's check (memory_limit.c).
 *
 * OpenBLAS also starts its workers when it is loaded, before main, as many
 * as OPENBLAS_NUM_THREADS or OMP_NUM_THREADS say (else one per core), and
 * each maps its buffer at once: under a limit one of them may be left
 * retrying for ever, and the run hangs when OpenBLAS joins it.  No thread
 * can be stopped from outside, so under a limit a program loaded with more
 * than one BLAS thread executes itself again (same arguments, same
 * environment but OPENBLAS_NUM_THREADS=1) before doing anything else;
 * start-up then sets the count as above.  The thread count of the run is
 * -j or OMP_NUM_THREADS either way (threads.f90). */
#define _GNU_SOURCE
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

#include "blas_start.h"
#include "memory_limit.h"

extern void openblas_set_num_threads(int) __attribute__((weak));
extern int openblas_get_num_threads(void) __attribute__((weak));
extern void dgemm_(const char *ta, const char *tb, const int *m, const int *n, const int *k, const double *alpha,
                   const double *a, const int *lda, const double *b, const int *ldb, const double *beta, double *c,
                   const int *ldc);

/* OpenBLAS's buffer as mapped (strace: 134,217,728 bytes, then up to
 * 135,266,304 when it retries with room for alignment). */
static const int64_t blas_buffer = 135266304;
/* glibc's second malloc arena reserves 64 MB of address space (two arenas
 * at most: threads.f90). */
static const int64_t malloc_arena = (int64_t) 64 << 20;
/* Beyond the buffer, what the first buffer's malloc and the run's start
 * may still take (found by a sweep of limits in 0.5 MB steps: a limit that
 * left the buffer and less than this hung in OpenBLAS). */
static const int64_t probe_margin = (int64_t) 4 << 20;

static int64_t thread_stack(void)
{
    pthread_attr_t attr;
    size_t size = 8u << 20;
    if (pthread_getattr_default_np(&attr) == 0)
    {
        (void) pthread_attr_getstacksize(&attr, &size);
        pthread_attr_destroy(&attr);
    }
    return (int64_t) size;
}

int c2d_blas_start(int n, int64_t *left, int64_t *per_thread, int64_t *first)
{
    int fit, m = 256;
    double *a;

    *left = c2d_address_space_left();
    *per_thread = blas_buffer + 2 * thread_stack();
    *first = blas_buffer + probe_margin;
    if (*left < 0 || openblas_set_num_threads == NULL) return n;
    /* the product's matrices first, so that the probe below sees the room
     * that is left for the buffer once they are there */
    a = calloc((size_t) 3 * (size_t) m * (size_t) m, sizeof *a);
    if (a == NULL) return 0;
    {   /* room for the first buffer as OpenBLAS will map it, and a margin:
         * malloc asks for the buffer plus its header and page rounding, and
         * one that cannot be had leaves OpenBLAS retrying without end */
        size_t size = (size_t) (blas_buffer + probe_margin);
        void *p = mmap(NULL, size, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
        if (p == MAP_FAILED)
        {
            free(a);
            return 0;
        }
        (void) munmap(p, size);
    }
    fit = 1;
    if (n > 1 && *left - blas_buffer - malloc_arena > 0)
        fit = 1 + (int) (((*left - blas_buffer - malloc_arena) / 2) / *per_thread);
    if (fit < n) n = fit;
    openblas_set_num_threads(n);
    /* C = A B on 256 x 256: large enough for OpenBLAS to use its buffers and
     * every thread, a few milliseconds */
    {
        const double one = 1.0, zero = 0.0;
        dgemm_("N", "N", &m, &m, &m, &one, a, &m, a + m * m, &m, &zero, a + 2 * m * m, &m);
    }
    free(a);
    return n;
}

/* How long an idle OpenBLAS worker spins before it sleeps, as the exponent
 * of a cycle count (OPENBLAS_THREAD_TIMEOUT, read once when OpenBLAS loads;
 * its default, 28, is about 0.1 s).  A worker spinning through the phases
 * that use OpenMP and no BLAS (the meshes, the assembly, the stresses) takes
 * a core from them; 2^20 cycles, a fraction of a millisecond, outlasts the
 * gaps between the BLAS calls of one factorization (doc/performance.md,
 * "OpenBLAS's idle workers"). */
static const char *const idle_spin = "20";

/* Run by the C library after the libraries' constructors (OpenBLAS's has
 * started its workers) and before main; glibc passes main's arguments.
 * What OpenBLAS reads when it loads can only be given to it by executing
 * the program again, once, with the environment set: one thread under a
 * limit (see above), and the idle spin unless the user set one. */
__attribute__((constructor)) static void restart_with_blas_settings(int argc, char **argv, char **envp)
{
    struct rlimit rl;
    int limited, spin;
    (void) argc;
    (void) envp;
    if (argv == NULL || openblas_get_num_threads == NULL || openblas_get_num_threads() <= 1) return;
    limited = getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY;
    spin = getenv("OPENBLAS_THREAD_TIMEOUT") == NULL;
    if (!limited && !spin) return;
    if (limited && setenv("OPENBLAS_NUM_THREADS", "1", 1) != 0) return;
    if (spin && setenv("OPENBLAS_THREAD_TIMEOUT", idle_spin, 1) != 0) return;
    (void) execv("/proc/self/exe", argv);   /* on failure: go on as loaded */
}
