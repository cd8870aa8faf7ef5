/* memory_limit.c: how much more memory this process can have, for the
 * check before the largest allocation of a run (the numeric factorization)
 * and for the threads' budget at start-up (blas_start.c).
 *
 * The smallest of: the address space left under RLIMIT_AS (ulimit -v, a
 * batch system's limit) once what the process has mapped (VmSize,
 * /proc/self/statm) is taken off; what its cgroup may still charge, for
 * the process's own cgroup and each one above it (a batch system's or a
 * container's memory limit): cgroup v2 memory.max - memory.current, cgroup
 * v1 (the memory controller) memory.limit_in_bytes - memory.usage_in_bytes,
 * each plus inactive_file of memory.stat; and what the machine can still
 * give (MemAvailable + SwapFree of /proc/meminfo).  -1 when none is known.
 *
 * Test hooks, not meant for users: CONTACT2D_CGROUP_ROOT, when set, is read
 * as the mount point of the cgroup hierarchies (v2, and v1's memory
 * controller) instead of those /proc/self/mountinfo names, and
 * CONTACT2D_CGROUP_FILE instead of /proc/self/cgroup: a folder of fake
 * memory.max or memory.limit_in_bytes files (tests/robust/memory_limits). */
#define _DEFAULT_SOURCE
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "memory_limit.h"

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

/* Whether the comma-separated list `list` holds `item`. */
static int listed(const char *list, const char *item)
{
    size_t n = strlen(item);
    while (list != NULL && *list != '\0')
    {
        if (strncmp(list, item, n) == 0 && (list[n] == ',' || list[n] == '\0')) return 1;
        list = strchr(list, ',');
        if (list != NULL) list++;
    }
    return 0;
}

/* A cgroup hierarchy's mount point and the cgroup path it shows as its root
 * (ROOT of mountinfo: a container's own cgroup when the host's hierarchy is
 * bound into it).  v2: the cgroup2 line; v1: the cgroup line whose super
 * options hold "memory".  CONTACT2D_CGROUP_ROOT replaces the mount point
 * (root "/").  0 when there is none. */
static int cgroup_mount(int v1, char *mnt, char *root, size_t size)
{
    const char *hook = getenv("CONTACT2D_CGROUP_ROOT");
    char line[4096], fstype[64], options[1024], m[PATH_MAX], r[PATH_MAX];
    int found = 0;
    FILE *f;
    if (hook != NULL && hook[0] != '\0')
    {
        strcpy(root, "/");
        return snprintf(mnt, size, "%s", hook) < (int) size;
    }
    f = fopen("/proc/self/mountinfo", "r");
    if (f == NULL) return 0;
    while (!found && fgets(line, sizeof line, f) != NULL)
    {
        /* ID PARENT MAJ:MIN ROOT MOUNTPOINT OPTIONS [TAGS] - FSTYPE SOURCE SUPER */
        const char *dash = strstr(line, " - ");
        options[0] = '\0';
        if (dash == NULL || sscanf(dash + 3, "%63s %*s %1023s", fstype, options) < 1) continue;
        if (strcmp(fstype, v1 ? "cgroup" : "cgroup2") != 0 || (v1 && !listed(options, "memory"))) continue;
        if (sscanf(line, "%*s %*s %*s %4095s %4095s", r, m) == 2 && strlen(m) < size && strlen(r) < size)
        {
            strcpy(mnt, m);
            strcpy(root, r);
            found = 1;
        }
    }
    fclose(f);
    return found;
}

/* This process's cgroup path in the v2 hierarchy (the "0::" line of
 * /proc/self/cgroup) or, v1, in the memory controller's ("N:...memory...:");
 * CONTACT2D_CGROUP_FILE replaces /proc/self/cgroup.  0 when absent. */
static int cgroup_path(int v1, char *rel, size_t size)
{
    const char *hook = getenv("CONTACT2D_CGROUP_FILE");
    char line[4096];
    int found = 0;
    FILE *f = fopen(hook != NULL && hook[0] != '\0' ? hook : "/proc/self/cgroup", "r");
    if (f == NULL) return 0;
    while (!found && fgets(line, sizeof line, f) != NULL)
    {
        char *controllers = strchr(line, ':'), *path;
        if (controllers == NULL) continue;
        controllers++;
        path = strchr(controllers, ':');
        if (path == NULL) continue;
        *path++ = '\0';
        path[strcspn(path, "\n")] = '\0';
        if (v1 ? !listed(controllers, "memory") : strncmp(line, "0:", 2) != 0 || controllers[0] != '\0') continue;
        if (strlen(path) < size)
        {
            strcpy(rel, path);
            found = 1;
        }
    }
    fclose(f);
    return found;
}

/* What the cgroups of this process may still charge in one hierarchy, the
 * smallest over its own cgroup and those above it (as far as the mount
 * shows them); -1 when no limit is found.  v2: memory.max -
 * memory.current; v1: memory.limit_in_bytes - memory.usage_in_bytes (no
 * limit is a number near 2^63); each plus the inactive page cache of
 * memory.stat, which the kernel drops before it refuses. */
static int64_t cgroup_left(int v1)
{
    char mnt[PATH_MAX], root[PATH_MAX], rel[PATH_MAX], dir[PATH_MAX];
    const char *limit_file = v1 ? "memory.limit_in_bytes" : "memory.max";
    const char *usage_file = v1 ? "memory.usage_in_bytes" : "memory.current";
    int64_t left = -1;
    size_t n;

    if (!cgroup_mount(v1, mnt, root, sizeof root) || !cgroup_path(v1, rel, sizeof rel)) return -1;
    n = strlen(root);
    if (strcmp(root, "/") != 0 && strncmp(rel, root, n) == 0 && (rel[n] == '/' || rel[n] == '\0'))
        memmove(rel, rel + n, strlen(rel + n) + 1);   /* the mount shows the hierarchy from root down */
    if (strcmp(rel, "/") == 0) rel[0] = '\0';
    for (;;)
    {
        char *slash;
        if (snprintf(dir, sizeof dir, "%s%s", mnt, rel) < (int) sizeof dir)
        {
            int64_t max = cgroup_number(dir, limit_file, NULL), current = cgroup_number(dir, usage_file, NULL);
            if (max >= 0 && max < INT64_C(1) << 62 && current >= 0)
            {
                int64_t inactive = cgroup_number(dir, "memory.stat", "inactive_file");
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
    int64_t left = c2d_address_space_left(), group;
    int v1;
    FILE *f;

    for (v1 = 0; v1 <= 1; v1++)                        /* a hybrid system may limit in either */
    {
        group = cgroup_left(v1);
        if (group >= 0 && (left < 0 || group < left)) left = group;
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
