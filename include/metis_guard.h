/* metis_guard.h: a METIS call that runs out of memory returns, it does not
 * end the process.
 *
 * Debian's METIS 5.1 (GKlib's gk_malloc) prints "***Memory allocation failed
 * for ..." and raises SIGABRT when an allocation fails; its own signal trap
 * does not reach the ordering routines CHOLMOD and the shim call, so the
 * process died with a core and a backtrace.  C2D_METIS_CALL runs one METIS
 * call (or a CHOLMOD call that orders with METIS) with a SIGABRT handler
 * that jumps back to the call site on this thread: `call` runs, and when
 * METIS aborts inside it, `on_abort` runs instead (the caller reports
 * CHOLMOD_OUT_OF_MEMORY; the process then ends with the diagnosis, and
 * whatever METIS had allocated is not reused).  An abort anywhere else, or on
 * another thread outside such a call, goes to the handler there was before.
 * The call sits between c2d_metis_begin and c2d_metis_end (metis_random.c).
 */
#ifndef CONTACT2D_METIS_GUARD_H
#define CONTACT2D_METIS_GUARD_H
#include <setjmp.h>
#include "metis_random.h"

/* env: the landing point of this thread's METIS call; NULL when it ended. */
void c2d_metis_guard(sigjmp_buf *env);

#define C2D_METIS_CALL(call, on_abort)                  \
    do                                                  \
    {                                                   \
        sigjmp_buf c2d_landing_;                        \
        c2d_metis_begin();                              \
        if (sigsetjmp(c2d_landing_, 1) == 0)            \
        {                                               \
            c2d_metis_guard(&c2d_landing_);             \
            call;                                       \
        }                                               \
        else                                            \
        {                                               \
            on_abort;                                   \
        }                                               \
        c2d_metis_guard(NULL);                          \
        c2d_metis_end();                                \
    } while (0)

#endif /* CONTACT2D_METIS_GUARD_H */
