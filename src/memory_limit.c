/* memory_limit.c: how much more memory this process can have, for the
 * check before the largest allocation of a run (the numeric factorization).
 *
 * The smaller of: the address space left under RLIMIT_AS (ulimit -v, a batch
 * system's limit) once what the process has mapped (VmSize,
 * /proc/self/statm) is taken off, and what the machine can still give
 * (MemAvailable + SwapFree of /proc/meminfo).  -1 when neither is known. */
#define _DEFAULT_SOURCE
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "memory_limit.h"

/* bytes of the /proc/meminfo line `key: N kB`, -1 when absent */
static int64_t meminfo_bytes(FILE *f, const char *key)
{
    char line[256], name[64];
    long long kb;
    rewind(f);
    while (fgets(line, sizeof line, f) != NULL)
        if (sscanf(line, "%63[^:]: %lld", name, &kb) == 2 && strcmp(name, key) == 0) return (int64_t) kb * 1024;
    return -1;
}

int64_t c2d_memory_available(void)
{
    int64_t left = -1;
    struct rlimit rl;
    FILE *f;

    if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY)
    {
        long pages = 0;
        f = fopen("/proc/self/statm", "r");
        if (f != NULL)
        {
            if (fscanf(f, "%ld", &pages) != 1) pages = 0;
            fclose(f);
        }
        left = (int64_t) rl.rlim_cur - (int64_t) pages * (int64_t) sysconf(_SC_PAGESIZE);
        if (left < 0) left = 0;
    }
    f = fopen("/proc/meminfo", "r");
    if (f != NULL)
    {
        int64_t avail = meminfo_bytes(f, "MemAvailable"), swap = meminfo_bytes(f, "SwapFree");
        fclose(f);
        if (avail >= 0)
        {
            if (swap > 0) avail += swap;
            if (left < 0 || avail < left) left = avail;
        }
    }
    return left;
}
