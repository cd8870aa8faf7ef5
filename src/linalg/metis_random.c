/* metis_random.c: METIS's random numbers, one sequence per thread.
 *
 * METIS's coarsening, initial bisections and refinement visit vertices in
 * random orders.  Debian's METIS 5.1 draws them through three GKlib entry
 * points built on libc's one generator for the whole process:
 *     gk_randinit(seed)   srand(seed)           (at the start of each METIS call)
 *     gk_randint32()      rand()
 *     gk_randint64()      rand() << 32 | rand()
 * Two orderings on two threads (the bodies of a scene, side by side) then
 * reseed and draw from one sequence, interleaved as the threads happen to
 * run, and the ordering, nnz(L) and the last digits of the solution change
 * from run to run.
 *
 * The program defines the three entry points itself.  libmetis calls them
 * through its procedure linkage table, so these definitions are the ones it
 * runs; each keeps glibc's generator (the same additive feedback generator,
 * through initstate_r / random_r) in thread-local storage.  A thread draws
 * exactly the sequence srand/rand would give it alone: an ordering is the
 * same on one thread or two, side by side with another or not.
 *
 * Should a build of METIS bind these calls internally, the definitions are
 * never called: c2d_metis_begin/c2d_metis_end find that out once (an
 * ordering of a 4-cycle must call gk_randinit) and then let one METIS call
 * run at a time.  Results stay the same either way; only the concurrency is
 * lost. */
#define _DEFAULT_SOURCE
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "metis.h"
#include "metis_random.h"

void gk_randinit(uint64_t seed);
uint32_t gk_randint32(void);
uint64_t gk_randint64(void);

static __thread struct random_data generator;
static __thread char generator_table[128];  /* 128 bytes: TYPE_3, as rand()'s own */
static __thread int seeded;
static __thread long reseeds;               /* gk_randinit calls on this thread */

void gk_randinit(uint64_t seed)
{
    memset(&generator, 0, sizeof generator);
    initstate_r((unsigned int) seed, generator_table, sizeof generator_table, &generator);
    seeded = 1;
    reseeds++;
}

/* rand(): never seeded means seed 1 */
static uint32_t next31(void)
{
    int32_t r;
    if (!seeded) gk_randinit(1);
    random_r(&generator, &r);
    return (uint32_t) r;
}

uint32_t gk_randint32(void)
{
    return next31();
}

uint64_t gk_randint64(void)
{
    uint64_t hi = next31();
    return (hi << 32) | (uint64_t) next31();
}

static pthread_once_t probe_once = PTHREAD_ONCE_INIT;
static pthread_mutex_t one_at_a_time = PTHREAD_MUTEX_INITIALIZER;
static int per_thread = 0;

/* Does an ordering reach gk_randinit above?  (A 4-cycle, no weights.) */
static void probe(void)
{
    idx_t nv = 4, xadj[5] = {0, 2, 4, 6, 8}, adj[8] = {1, 3, 0, 2, 1, 3, 0, 2};
    idx_t perm[4], iperm[4];
    long before = reseeds;
    if (METIS_NodeND(&nv, xadj, adj, NULL, NULL, perm, iperm) == METIS_OK) per_thread = reseeds > before;
}

int c2d_metis_per_thread(void)
{
    pthread_once(&probe_once, probe);
    return per_thread;
}

void c2d_metis_begin(void)
{
    if (!c2d_metis_per_thread()) pthread_mutex_lock(&one_at_a_time);
}

void c2d_metis_end(void)
{
    if (!per_thread) pthread_mutex_unlock(&one_at_a_time);
}
