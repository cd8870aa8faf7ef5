/* cpu_seconds: the CPU seconds (user + system) a process has used, with
 * those of the children it has reaped: what contact2d (process_runner.c)
 * and contact2d-mesher (src/mesher/gmsh_mesher.c) count as a run's cost. */
#ifndef CONTACT2D_CPU_SECONDS_H
#define CONTACT2D_CPU_SECONDS_H

#include <sys/resource.h>

static inline double c2d_own_and_reaped_seconds(void)
{
    static const int who[2] = {RUSAGE_SELF, RUSAGE_CHILDREN};
    double t = 0.0;
    for (int i = 0; i < 2; i++) {
        struct rusage r;
        if (getrusage(who[i], &r) == 0)
            t += r.ru_utime.tv_sec + 1e-6 * r.ru_utime.tv_usec + r.ru_stime.tv_sec + 1e-6 * r.ru_stime.tv_usec;
    }
    return t;
}

#endif
