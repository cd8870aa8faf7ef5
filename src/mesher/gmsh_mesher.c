/* contact2d-mesher: gmsh's batch program, started once and run many times.
 *
 * Starting the gmsh program costs about 0.12 s of CPU before it reads a
 * line: the dynamic linker binds libgmsh and the ninety libraries it
 * needs (OpenCASCADE, FLTK, MED, ...).  A run meshes a .geo per body, and
 * ADAPT again at every step, so a two-body ADAPT run paid that four to six
 * times, more than its solves.  This program pays it once: it is linked
 * with libgmsh, reads requests on stdin and, for each, forks a child that
 * runs libgmsh's own batch entry point, GmshMainBatch(argc, argv), with the
 * request's argument vector: what the gmsh program's main() calls when
 * given -2.  The child starts from the state this process has before
 * anything is meshed, so every request is a fresh gmsh run: options, the
 * parser's variables and the models of one .geo never reach the next, and
 * the mesh is byte for byte the one the gmsh program writes.
 *
 * The child's stdout and stderr go to the request's log (created, must
 * not exist); its stdin is /dev/null.  It has a process group of its own,
 * killed once it has ended (whatever it left), and dies at the request's
 * time limit (SIGALRM's default action) or with this process.
 *
 * Protocol (pipes; contact2d's src/sys/process_runner.c is the other end).
 *   request: NUL-terminated strings: N, TIMEOUT (s), LOG, then N arguments
 *            (argv[0] first).  End of file on stdin ends this program.
 *   reply:   one line "HOW STATUS CPU\n": HOW 0 exited (STATUS its exit
 *            status), 1 killed by signal STATUS, 2 time limit, 3 not started
 *            (STATUS an errno); CPU the seconds (user + system) this program
 *            and every child it has reaped have used so far.
 * Requests and replies use read(2) and write(2) alone: a child must find
 * no stdio buffer of this process's to flush at its exit.
 *
 * The mangled name below is libgmsh's exported C++ symbol for
 *   int GmshMainBatch(int argc, char **argv);
 * (Gmsh.h, not among the headers Debian's libgmsh-dev installs). */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cpu_seconds.h"

extern int gmsh_main_batch(int argc, char **argv) __asm__("_Z13GmshMainBatchiPPc");

enum { HOW_EXITED = 0, HOW_SIGNALED = 1, HOW_TIMEOUT = 2, HOW_NOT_STARTED = 3 };

/* the request being read: a growing buffer of NUL-terminated strings */
static char *buf = NULL;
static size_t have = 0, cap = 0;

/* Read until buf holds `want` complete strings (from its start); 1 when it
 * does, 0 at end of file or on an error. */
static int read_strings(int want)
{
    for (;;) {
        size_t i;
        int n = 0;
        ssize_t got;
        for (i = 0; i < have; i++)
            if (buf[i] == '\0' && ++n == want) return 1;
        if (have == cap) {
            size_t ncap = cap == 0 ? 4096 : 2 * cap;
            char *nbuf = realloc(buf, ncap);
            if (nbuf == NULL) return 0;
            buf = nbuf;
            cap = ncap;
        }
        got = read(0, buf + have, cap - have);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) return 0;
        have += (size_t)got;
    }
}

/* The i-th string of buf (0-based). */
static char *string_at(int i)
{
    char *p = buf;
    while (i-- > 0) p += strlen(p) + 1;
    return p;
}

static int reply(int how, int status)
{
    char line[96];
    int n = snprintf(line, sizeof line, "%d %d %.6f\n", how, status, c2d_own_and_reaped_seconds());
    return write(1, line, (size_t)n) == n ? 0 : 1;
}

/* The child: a fresh gmsh run on argv; never returns. */
static void run_gmsh(int argc, char **argv, const char *log_path, unsigned int timeout, pid_t parent)
{
    int null, log;
    setpgid(0, 0);
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(127);
    null = open("/dev/null", O_RDONLY);
    log = open(log_path, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW, 0600);
    if (null < 0 || log < 0 || dup2(null, 0) < 0 || dup2(log, 1) < 0 || dup2(log, 2) < 0) _exit(126);
    syscall(SYS_close_range, 3U, ~0U, 0);
    signal(SIGPIPE, SIG_DFL);
    alarm(timeout);
    exit(gmsh_main_batch(argc, argv));
}

int main(void)
{
    pid_t self = getpid();
    signal(SIGPIPE, SIG_IGN);                   /* contact2d gone: write fails, the loop ends */
    for (;;) {
        int n, how, status, wstatus;
        unsigned int timeout;
        char **argv, *log_path;
        double seconds;
        pid_t child;
        struct rusage ru;

        have = 0;
        if (!read_strings(3)) return 0;
        n = atoi(string_at(0));
        seconds = atof(string_at(1));
        if (n < 1 || n > 100000 || !(seconds > 0.0)) return 1;
        timeout = seconds > 1e6 ? 1000000U : (unsigned int)seconds + 1U;
        if (!read_strings(3 + n)) return 0;
        log_path = string_at(2);
        argv = calloc((size_t)n + 1, sizeof *argv);
        if (argv == NULL) {
            if (reply(HOW_NOT_STARTED, ENOMEM)) return 1;
            continue;
        }
        argv[0] = string_at(3);
        for (int i = 1; i < n; i++) argv[i] = argv[i - 1] + strlen(argv[i - 1]) + 1;
        child = fork();
        if (child == 0) run_gmsh(n, argv, log_path, timeout, self);
        free(argv);
        if (child < 0) {
            if (reply(HOW_NOT_STARTED, errno)) return 1;
            continue;
        }
        setpgid(child, child);
        while (wait4(child, &wstatus, 0, &ru) < 0 && errno == EINTR) continue;
        kill(-child, SIGKILL);                  /* whatever it left in its group */
        while (waitpid(-1, NULL, WNOHANG) > 0) continue;
        if (WIFEXITED(wstatus)) {
            how = HOW_EXITED;
            status = WEXITSTATUS(wstatus);
        } else if (WIFSIGNALED(wstatus) && WTERMSIG(wstatus) == SIGALRM) {
            how = HOW_TIMEOUT;
            status = 0;
        } else {
            how = HOW_SIGNALED;
            status = WIFSIGNALED(wstatus) ? WTERMSIG(wstatus) : 0;
        }
        if (reply(how, status)) return 1;
    }
}
