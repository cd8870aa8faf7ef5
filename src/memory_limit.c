/* memory_limit.c: how much more memory this process can have, for the
 * check before the largest allocation of a run (the numeric factorization)
 * and for the threads' budget at start-up (blas_start.c).
 *
 * The smallest of: the address space left under RLIMIT_AS (ulimit -v, a
 * batch system's limit) once what the process has mapped (VmSize,
 * /proc/self/statm) is taken off; what its cgroup (v2) may still charge,
 * memory.max - memory.current + inactive_file of memory.stat, for the
 * process's own cgroup and each one above it (a batch system's or a
 * container's memory limit); and what the machine can still give
 * (MemAvailable + SwapFree of /proc/meminfo).  -1 when none is known.
 *
 * Test hook: CONTACT2D_CGROUP_ROOT, when set, is read as the cgroup v2
 * mount point instead of the one /proc/self/mountinfo names (a folder of
 * fake memory.max files: tests/robust/oom).  Not meant for users. */
#define _DEFAULT_SOURCE
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "cholmod_shim.h"

/* bytes of the `key: N kB` line of /proc/meminfo, -1 when absent */
static int64_t meminfo_bytes(FILE *f, const char *key)
{
    char line[256], name[64];
    long long kb;
    rewind(f);
    while (fgets(line, sizeof line, f) != NULL)
        if (sscanf(line, "%63[^:]: %lld", name, &kb) == 2 && strcmp(name, key) == 0) return (int64_t) kb * 1024;
    return -1;
}

int64_t c2d_address_space_left(void)
{
    struct rlimit rl;
    long pages = 0;
    int64_t left;
    FILE *f;

    if (getrlimit(RLIMIT_AS, &rl) != 0 || rl.rlim_cur == RLIM_INFINITY) return -1;
    f = fopen("/proc/self/statm", "r");
    if (f != NULL)
    {
        if (fscanf(f, "%ld", &pages) != 1) pages = 0;
        fclose(f);
    }
    left = (int64_t) rl.rlim_cur - (int64_t) pages * (int64_t) sysconf(_SC_PAGESIZE);
    return left < 0 ? 0 : left;
}

/* The first number of file dir/name ("max" or absent: -1); with key, the
 * number on the line `key N` of that file. */
static int64_t cgroup_number(const char *dir, const char *name, const char *key)
{
    char path[PATH_MAX], line[256], word[64];
    long long v = -1, x;
    FILE *f;
    if (snprintf(path, sizeof path, "%s/%s", dir, name) >= (int) sizeof path) return -1;
    f = fopen(path, "r");
    if (f == NULL) return -1;
    while (fgets(line, sizeof line, f) != NULL)
    {
        if (key == NULL)
        {
            if (sscanf(line, "%lld", &x) == 1) v = x;   /* "max" leaves -1 */
            break;
        }
        if (sscanf(line, "%63s %lld", word, &x) == 2 && strcmp(word, key) == 0)
        {
            v = x;
            break;
        }
    }
    fclose(f);
    return v;
}

/* The cgroup v2 mount point (CONTACT2D_CGROUP_ROOT, else the cgroup2 line
 * of /proc/self/mountinfo) into root; 0 when there is none. */
static int cgroup_root(char *root, size_t size)
{
    const char *hook = getenv("CONTACT2D_CGROUP_ROOT");
    char line[4096], mnt[PATH_MAX], fstype[64];
    int found = 0;
    FILE *f;
    if (hook != NULL && hook[0] != '\0')
        return snprintf(root, size, "%s", hook) < (int) size;
    f = fopen("/proc/self/mountinfo", "r");
    if (f == NULL) return 0;
    while (!found && fgets(line, sizeof line, f) != NULL)
    {
        /* ID PARENT MAJ:MIN ROOT MOUNTPOINT OPTIONS [TAGS] - FSTYPE SOURCE SUPER */
        const char *dash = strstr(line, " - ");
        if (dash == NULL || sscanf(dash + 3, "%63s", fstype) != 1 || strcmp(fstype, "cgroup2") != 0) continue;
        if (sscanf(line, "%*s %*s %*s %*s %4095s", mnt) == 1 && strlen(mnt) < size)
        {
            strcpy(root, mnt);
            found = 1;
        }
    }
    fclose(f);
    return found;
}

/* What the cgroups of this process may still charge, the smallest over its
 * own cgroup and those above it; -1 when no cgroup v2 limit is found. */
static int64_t cgroup_left(void)
{
    char root[PATH_MAX], line[4096], rel[PATH_MAX], dir[PATH_MAX];
    int64_t left = -1;
    FILE *f;

    if (!cgroup_root(root, sizeof root)) return -1;
    f = fopen("/proc/self/cgroup", "r");
    if (f == NULL) return -1;
    rel[0] = '\0';
    while (fgets(line, sizeof line, f) != NULL)
        if (strncmp(line, "0::", 3) == 0)               /* the v2 hierarchy's line */
        {
            line[strcspn(line, "\n")] = '\0';
            if (strlen(line + 3) < sizeof rel) strcpy(rel, line + 3);
            break;
        }
    fclose(f);
    for (;;)
    {
        char *slash;
        if (snprintf(dir, sizeof dir, "%s%s", root, rel) < (int) sizeof dir)
        {
            int64_t max = cgroup_number(dir, "memory.max", NULL), current = cgroup_number(dir, "memory.current", NULL);
            if (max >= 0 && current >= 0)
            {
                int64_t inactive = cgroup_number(dir, "memory.stat", "inactive_file");   /* page cache it can drop */
                int64_t here = max - current + (inactive > 0 ? inactive : 0);
                if (here < 0) here = 0;
                if (left < 0 || here < left) left = here;
            }
        }
        slash = strrchr(rel, '/');                     /* then the cgroup above: "/a/b" -> "/a" -> "" */
        if (rel[0] == '\0' || slash == NULL) break;
        *slash = '\0';
    }
    return left;
}

int64_t c2d_memory_available(void)
{
    int64_t left = c2d_address_space_left(), group = cgroup_left();
    FILE *f;

    if (group >= 0 && (left < 0 || group < left)) left = group;
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
