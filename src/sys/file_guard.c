/* file_guard: private folder, output temporaries, safe inputs, folders and
 * the output folder's lock (see include/file_guard.h).
 *
 * What the exit and signal cleanup removes is recorded here, in storage the
 * handler reads without allocating: the private folder's path and the
 * temporaries' paths (each allocated before it is published), in tables of
 * slots chained as a run needs more (a load history has two files per step),
 * each table published whole and never freed, so that the handler can walk
 * them at any moment. */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include "file_guard.h"
#include "process_runner.h"

#define TABLE_SLOTS 64
#define MAX_DEPTH 32                        /* folders gmsh may have made inside the private folder */

static char private_path[PATH_MAX];         /* "" until made */
struct temporary_table {                    /* the run's output temporaries not yet committed */
    char *slot[TABLE_SLOTS];                /* a path, or NULL */
    struct temporary_table *next;           /* the next table, NULL until one is needed */
};
static struct temporary_table temporaries;
static int cleanup_installed = 0;
static int deferring = 0;                   /* > 0: a commit, or a temporary being made and recorded,
                                               is under way: signals wait for its end (a depth: the
                                               commit makes temporaries) */
static int dying = 0;                       /* a signal's cleanup has begun */
static int pending_signal = 0;              /* the signal that arrived while deferring */
static const int guarded_signals[] = {SIGINT, SIGTERM, SIGHUP};

/* Remove name (a folder's entries first) relative to folder fd `at`; only
 * async-signal-safe calls (no opendir/nftw: they allocate). */
static void remove_tree(int at, const char *name, int depth)
{
    char buf[4096];
    int fd, again = 1;
    long n, off;
    if (unlinkat(at, name, 0) == 0 || (errno != EISDIR && errno != EPERM)) return;
    fd = openat(at, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) return;
    while (again && depth < MAX_DEPTH) {    /* entries removed while listed: list again until empty */
        again = 0;
        lseek(fd, 0, SEEK_SET);
        while ((n = (long)getdents64(fd, buf, sizeof buf)) > 0) {
            for (off = 0; off < n;) {
                struct dirent64 *e = (struct dirent64 *)(buf + off);
                off += e->d_reclen;
                if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
                remove_tree(fd, e->d_name, depth + 1);
                again = 1;
            }
        }
    }
    close(fd);
    unlinkat(at, name, AT_REMOVEDIR);
}

/* Everything the run made and has not committed: the gmsh group, the
 * temporaries, the private folder.  Async-signal-safe when may_free is 0. */
static void clean_up(int may_free)
{
    int i;
    struct temporary_table *table;
    c2d_kill_running();
    for (table = &temporaries; table != NULL; table = __atomic_load_n(&table->next, __ATOMIC_SEQ_CST)) {
        for (i = 0; i < TABLE_SLOTS; i++) {
            char *t = __atomic_exchange_n(&table->slot[i], NULL, __ATOMIC_SEQ_CST);
            if (t != NULL) {
                unlink(t);
                if (may_free) free(t);      /* a signal handler may not call free */
            }
        }
    }
    if (private_path[0] != '\0') {
        remove_tree(AT_FDCWD, private_path, 0);
        private_path[0] = '\0';
    }
}

static void die_of(int sig)
{
    int saved = errno;
    clean_up(0);
    signal(sig, SIG_DFL);
    raise(sig);                             /* the default action: the status says which signal */
    errno = saved;
}

static void on_signal(int sig)
{
    /* the pending signal before `dying`: whoever sees dying without a pending
     * signal knows a cleanup runs that ends the process (begin_deferral) */
    if (__atomic_load_n(&deferring, __ATOMIC_SEQ_CST) > 0) {
        __atomic_store_n(&pending_signal, sig, __ATOMIC_SEQ_CST);
        __atomic_store_n(&dying, 1, __ATOMIC_SEQ_CST);
        return;
    }
    __atomic_store_n(&dying, 1, __ATOMIC_SEQ_CST);
    die_of(sig);
}

/* From here to end_deferral a signal waits (on_signal records it); when a
 * signal's cleanup already runs, wait for it to end the process. */
static void begin_deferral(void)
{
    __atomic_add_fetch(&deferring, 1, __ATOMIC_SEQ_CST);
    if (__atomic_load_n(&dying, __ATOMIC_SEQ_CST) && __atomic_load_n(&pending_signal, __ATOMIC_SEQ_CST) == 0) {
        __atomic_sub_fetch(&deferring, 1, __ATOMIC_SEQ_CST);
        for (;;) pause();
    }
}

/* The end of the outermost deferral acts on a signal that came meanwhile. */
static void end_deferral(void)
{
    int sig;
    if (__atomic_sub_fetch(&deferring, 1, __ATOMIC_SEQ_CST) > 0) return;
    sig = __atomic_exchange_n(&pending_signal, 0, __ATOMIC_SEQ_CST);
    if (sig != 0) die_of(sig);
}

static void on_exit_cleanup(void)
{
    clean_up(1);
}

static void install_cleanup(void)
{
    struct sigaction sa, old;
    size_t i;
    if (cleanup_installed) return;
    cleanup_installed = 1;
    atexit(on_exit_cleanup);
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigfillset(&sa.sa_mask);
    for (i = 0; i < sizeof guarded_signals / sizeof guarded_signals[0]; i++) {
        if (sigaction(guarded_signals[i], NULL, &old) == 0 && old.sa_handler == SIG_IGN) continue;   /* nohup */
        sigaction(guarded_signals[i], &sa, NULL);
    }
}

static int kind_of(const struct stat *st)
{
    if (S_ISREG(st->st_mode)) return C2D_REGULAR;
    if (S_ISFIFO(st->st_mode)) return C2D_FIFO;
    if (S_ISCHR(st->st_mode) || S_ISBLK(st->st_mode)) return C2D_DEVICE;
    if (S_ISDIR(st->st_mode)) return C2D_FOLDER;
    return C2D_SOCKET;
}

int c2d_file_kind(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) return (errno == ENOENT || errno == ENOTDIR) ? C2D_MISSING : C2D_UNREADABLE;
    return kind_of(&st);
}

int c2d_open_input(const char *path, int *fd)
{
    struct stat st;
    int kind = c2d_file_kind(path);
    *fd = -1;
    if (kind != C2D_REGULAR) return kind;
    *fd = open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (*fd < 0) return (errno == ENOENT) ? C2D_MISSING : C2D_UNREADABLE;
    if (fstat(*fd, &st) != 0 || !S_ISREG(st.st_mode)) {     /* swapped since the stat */
        kind = fstat(*fd, &st) == 0 ? kind_of(&st) : C2D_UNREADABLE;
        close(*fd);
        *fd = -1;
        return kind;
    }
    return C2D_REGULAR;
}

int c2d_close(int fd)
{
    return close(fd) == 0 ? 0 : errno;
}

int c2d_make_folders(const char *path)
{
    size_t n = strlen(path), i;
    char *p;
    struct stat st;
    int status = 0;
    if (n == 0) return ENOENT;
    p = malloc(n + 1);
    if (p == NULL) return ENOMEM;
    memcpy(p, path, n + 1);
    for (i = 1; i <= n && status == 0; i++) {       /* each prefix ending at a '/' or at the end */
        if (i < n && p[i] != '/') continue;
        if (p[i - 1] == '/') continue;               /* "a//b" */
        p[i] = '\0';
        if (mkdir(p, 0777) != 0) {
            if (errno != EEXIST) status = errno;
            else if (stat(p, &st) != 0) status = errno;
            else if (!S_ISDIR(st.st_mode)) status = ENOTDIR;
        }
        if (i < n) p[i] = '/';
    }
    free(p);
    return status;
}

int c2d_private_folder(char *path, int len)
{
    const char *base = getenv("TMPDIR");
    char tmpl[PATH_MAX];
    size_t n;
    if (private_path[0] == '\0') {
        if (base == NULL || base[0] == '\0' || strlen(base) + 20 >= sizeof tmpl) base = "/tmp";
        strcpy(tmpl, base);
        strcat(tmpl, "/contact2d-XXXXXX");
        install_cleanup();
        if (mkdtemp(tmpl) == NULL) return -errno;
        memcpy(private_path, tmpl, strlen(tmpl) + 1);
    }
    n = strlen(private_path);
    if ((int)n >= len) return -ENAMETOOLONG;
    memcpy(path, private_path, n + 1);
    return (int)n;
}

/* 0666 & ~umask, read once (umask can only be read by setting it) */
static mode_t file_mode(void)
{
    static mode_t mode = 0;
    static int known = 0;
    if (!known) {
        mode_t mask = umask(077);
        umask(mask);
        mode = 0666 & ~mask;
        known = 1;
    }
    return mode;
}

/* An empty slot of the temporaries' tables, a new table chained when all
 * are full; NULL when no memory is left for one. */
static char **free_slot(void)
{
    struct temporary_table *table = &temporaries, *more;
    int i;
    for (;;) {
        for (i = 0; i < TABLE_SLOTS; i++) {
            if (__atomic_load_n(&table->slot[i], __ATOMIC_SEQ_CST) == NULL) return &table->slot[i];
        }
        more = __atomic_load_n(&table->next, __ATOMIC_SEQ_CST);
        if (more == NULL) {
            more = calloc(1, sizeof *more);             /* every slot NULL before the handler can see it */
            if (more == NULL) return NULL;
            __atomic_store_n(&table->next, more, __ATOMIC_SEQ_CST);
        }
        table = more;
    }
}

int c2d_create_temporary(const char *dir, const char *name, char *path, int len, int *fd)
{
    size_t n = strlen(dir) + strlen(name) + 10;
    char *t;
    char **slot = free_slot();
    *fd = -1;
    if ((int)n >= len) return ENAMETOOLONG;
    install_cleanup();
    if (slot == NULL) return ENOMEM;
    t = malloc(n);
    if (t == NULL) return ENOMEM;
    strcpy(t, dir);
    strcat(t, "/.");
    strcat(t, name);
    strcat(t, "~XXXXXX");
    begin_deferral();                               /* a signal between the file and its record waits */
    *fd = mkostemp(t, O_CLOEXEC);                   /* O_CREAT|O_EXCL: a link at the name is not followed */
    if (*fd < 0) {
        int e = errno;
        free(t);
        end_deferral();
        return e;
    }
    if (fchmod(*fd, file_mode()) != 0) {            /* mkostemp makes 0600: give the mode of a plain file */
        int e = errno;
        close(*fd);
        unlink(t);
        free(t);
        *fd = -1;
        end_deferral();
        return e;
    }
    strcpy(path, t);
    __atomic_store_n(slot, t, __ATOMIC_SEQ_CST);
    end_deferral();
    return 0;
}

void c2d_forget_temporary(const char *path)
{
    int i;
    struct temporary_table *table;
    for (table = &temporaries; table != NULL; table = __atomic_load_n(&table->next, __ATOMIC_SEQ_CST)) {
        for (i = 0; i < TABLE_SLOTS; i++) {
            char *t = __atomic_load_n(&table->slot[i], __ATOMIC_SEQ_CST);
            if (t != NULL && strcmp(t, path) == 0) {
                if (__atomic_compare_exchange_n(&table->slot[i], &t, NULL, 0, __ATOMIC_SEQ_CST, __ATOMIC_SEQ_CST))
                    free(t);
                return;
            }
        }
    }
}

int c2d_lock_folder(const char *dir)
{
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return -errno;
    while (flock(fd, LOCK_EX) != 0) {
        if (errno != EINTR) {
            int e = errno;
            close(fd);
            return -e;
        }
    }
    begin_deferral();                               /* a signal's cleanup runs: commit nothing */
    return fd;
}

void c2d_unlock_folder(int fd)
{
    flock(fd, LOCK_UN);
    close(fd);
    end_deferral();
}

int c2d_file_stamp(const char *path, long long *size, long long *mtime_ns)
{
    struct stat st;
    if (stat(path, &st) != 0) return errno;
    *size = (long long)st.st_size;
    *mtime_ns = (long long)st.st_mtim.tv_sec * 1000000000LL + (long long)st.st_mtim.tv_nsec;
    return 0;
}

int c2d_real_path(const char *path, char *real, int len)
{
    char *r = realpath(path, NULL);
    if (r == NULL) return errno;
    if ((int)strlen(r) >= len) {
        free(r);
        return ENAMETOOLONG;
    }
    strcpy(real, r);
    free(r);
    return 0;
}
