/* metis_guard.c: the SIGABRT handler of C2D_METIS_CALL (include/metis_guard.h).
 *
 * Installed once, the first time a METIS call is guarded; the handler it
 * replaces (gfortran's backtrace, or the default) is kept and still takes
 * every abort that does not come from inside a guarded call on the same
 * thread. */
#define _POSIX_C_SOURCE 200809L
#include <pthread.h>
#include <setjmp.h>
#include <signal.h>
#include <string.h>

#include "metis_guard.h"

static __thread sigjmp_buf *landing;   /* this thread's guarded call, or NULL */
static struct sigaction previous;      /* the handler before ours */
static pthread_once_t installed = PTHREAD_ONCE_INIT;

static void on_abort(int sig)
{
    sigjmp_buf *to = landing;
    if (to != NULL)
    {
        landing = NULL;
        siglongjmp(*to, 1);
    }
    /* not METIS's: as if we were not there */
    sigaction(SIGABRT, &previous, NULL);
    raise(sig);
}

static void install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_abort;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGABRT, &sa, &previous);
}

void c2d_metis_guard(sigjmp_buf *env)
{
    if (env != NULL) pthread_once(&installed, install);
    landing = env;
}
