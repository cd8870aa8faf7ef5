/* process_runner: start a program with an argument vector and a time limit
 * (see include/process_runner.h).
 *
 * Two processes per run:
 *
 *   contact2d
 *     watchdog     its own process group, a child subreaper
 *                  (PR_SET_CHILD_SUBREAPER), ignores INT/TERM/HUP/QUIT
 *       program    its own process group, PR_SET_PDEATHSIG = SIGKILL
 *
 * The watchdog starts the program, waits for it and reports how it ended on
 * a pipe; it also holds the read end of a second pipe (the control pipe)
 * whose only write end contact2d keeps.  End of file there means contact2d
 * is gone (killed, even by SIGKILL) or wants the program stopped (time limit,
 * signal, exit).  Either way, and when the program ends by itself, the
 * watchdog kills the program's group and then every process still below it:
 * as a subreaper it becomes the parent of whatever the program leaves
 * orphaned (a double fork into a new session, bubblewrap's process inside
 * the sandbox when bubblewrap's outer process dies first), so it finds them
 * in its list of children (/proc/self/task/PID/children) and kills them,
 * generation by generation, until it has no child left.  Only then does it
 * report and exit.  So no process the program started outlives the run,
 * whatever group or session it moved to and whatever signals it ignores.
 *
 * Why not the death signal and the group alone (the earlier design):
 * bubblewrap's inner process moves to a new session (--new-session) and
 * sets its own death signal only after the namespaces are made; when the
 * outer bubblewrap died first (contact2d killed at start-up under load),
 * the inner one and gmsh ran on with PPID 1 (tests/robust/orphans reproduces
 * it without load).  And a watchdog in contact2d's own group died with it
 * when the whole group was killed.
 *
 * fork/exec rather than posix_spawn: the program's process must set
 * PR_SET_PDEATHSIG (it dies with the watchdog, should that be killed) and
 * posix_spawn has no attribute for it.  After fork both children call only
 * async-signal-safe functions (contact2d may run OpenMP threads).
 *
 * Test hook: CONTACT2D_TEST_STOP_AT=spawn|watchdog|exec stops (SIGSTOP) the
 * process at that point of a start: contact2d just after forking the
 * watchdog, the watchdog before forking the program, the program's process
 * before exec (tests/robust/orphans kills contact2d there). */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "cpu_seconds.h"
#include "process_runner.h"

/* the running program's watchdog, read by the signal handler
 * (c2d_kill_running): the write end of its control pipe (-1 when none runs)
 * and its pid */
static int running_control = -1;
static pid_t running_watchdog = 0;

/* what the watchdog (or the program's process, when exec fails) reports */
struct report {
    int how;                                /* C2D_RUN_EXITED, _SIGNALED or _NOT_STARTED */
    int status;                             /* exit status, signal or errno */
};

/* the points of a start where CONTACT2D_TEST_STOP_AT stops a process */
enum { STOP_NONE, STOP_SPAWN, STOP_WATCHDOG, STOP_EXEC };

/* Seconds on the monotonic clock. */
static double now_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int c2d_find_program(const char *name, char *path, int len)
{
    const char *dirs = getenv("PATH");
    struct stat st;
    size_t n = strlen(name);
    if (strchr(name, '/') != NULL) {
        char *real = realpath(name, NULL);
        int found = real != NULL && strlen(real) < (size_t)len && stat(real, &st) == 0 && S_ISREG(st.st_mode) &&
                    access(real, X_OK) == 0;
        if (found) strcpy(path, real);
        free(real);
        return found ? 0 : 1;
    }
    if (dirs == NULL || *dirs == '\0') dirs = "/usr/local/bin:/usr/bin:/bin";
    while (*dirs != '\0') {
        const char *end = strchr(dirs, ':');
        size_t d = end ? (size_t)(end - dirs) : strlen(dirs);
        if (d > 0 && d + 1 + n < (size_t)len) {       /* an empty entry would be ".": skipped */
            memcpy(path, dirs, d);
            path[d] = '/';
            memcpy(path + d + 1, name, n + 1);
            if (stat(path, &st) == 0 && S_ISREG(st.st_mode) && access(path, X_OK) == 0) {
                char *real = realpath(path, NULL);      /* the sandbox binds its real location */
                if (real != NULL && strlen(real) < (size_t)len) strcpy(path, real);
                free(real);
                return path[0] == '/' ? 0 : 1;
            }
        }
        dirs += d;
        if (*dirs == ':') dirs++;
    }
    return 1;
}

/* Set the disposition of the signals a user or a batch system sends. */
static void set_job_signals(void (*disposition)(int))
{
    static const int job_signals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE};
    struct sigaction sa;
    size_t i;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = disposition;
    sigemptyset(&sa.sa_mask);
    for (i = 0; i < sizeof job_signals / sizeof job_signals[0]; i++) sigaction(job_signals[i], &sa, NULL);
}

/* The program's process: own group, dies with the watchdog, signals as a
 * fresh process has them, stdin /dev/null, stdout and stderr to log (kept
 * as they are when log < 0); a server's stdin and stdout are the pipes in
 * and out instead (each -1 when none); reports exec's errno on the
 * close-on-exec report pipe. */
static void start_program(char **argv, int log, int in, int out, int report, pid_t watchdog, int stop)
{
    int null = in >= 0 ? in : open("/dev/null", O_RDONLY | O_CLOEXEC);
    struct report r = {C2D_RUN_NOT_STARTED, 0};
    sigset_t none;
    setpgid(0, 0);
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != watchdog) _exit(127);          /* the watchdog died before prctl */
    set_job_signals(SIG_DFL);
    signal(SIGCHLD, SIG_DFL);
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, NULL);
    if (null < 0 || dup2(null, 0) < 0 || (log >= 0 && (dup2(log, 1) < 0 || dup2(log, 2) < 0)) ||
        (out >= 0 && dup2(out, 1) < 0)) {
        r.status = errno;
    } else {
        if (stop == STOP_EXEC) raise(SIGSTOP);
        execv(argv[0], argv);
        r.status = errno;
    }
    if (write(report, &r, sizeof r) < 0) _exit(127);
    _exit(127);
}

/* Send SIGKILL to every child of this process listed in
 * /proc/self/task/PID/children (this process has one thread); returns how
 * many were listed, -1 when the list cannot be read. */
static int kill_children(void)
{
    char path[64] = "/proc/self/task/", digits[24], buf[512];
    pid_t self = getpid(), pid = 0;
    int fd, nd = 0, n = 0, pending = 0;
    size_t at = strlen(path);
    ssize_t got, i;
    do {
        digits[nd++] = (char)('0' + self % 10);
        self /= 10;
    } while (self > 0);
    while (nd > 0) path[at++] = digits[--nd];
    memcpy(path + at, "/children", sizeof "/children");
    fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return -1;
    while ((got = read(fd, buf, sizeof buf)) > 0) {    /* "pid pid ... ", a pid may span two reads */
        for (i = 0; i < got; i++) {
            if (buf[i] >= '0' && buf[i] <= '9') {
                pid = 10 * pid + (buf[i] - '0');
                pending = 1;
            } else if (pending) {
                kill(pid, SIGKILL);                 /* an unreaped child: its pid cannot be reused */
                n++;
                pid = 0;
                pending = 0;
            }
        }
    }
    if (pending) {
        kill(pid, SIGKILL);
        n++;
    }
    close(fd);
    return n;
}

/* Kill the program's group (while its process is unreaped, so the group id
 * is still its own), then every process below this one, until none is
 * left, each reaped.  Bounded (a process stuck in the kernel): after 10 s
 * the rest is left to the death signals. */
static void end_everything(pid_t program)
{
    struct timespec nap = {0, 1000000};
    double give_up = now_seconds() + 10.0;
    kill(-program, SIGKILL);
    for (;;) {
        pid_t r;
        int listed = kill_children();
        while ((r = waitpid(-1, NULL, WNOHANG)) > 0) continue;
        if (r < 0 && errno == ECHILD) return;       /* nothing left below */
        if (listed < 0 || now_seconds() > give_up) return;
        nanosleep(&nap, NULL);
        if (nap.tv_nsec < 10000000) nap.tv_nsec *= 2;
    }
}

/* Close every descriptor from 3 up but the n in keep (-1 entries ignored):
 * the watchdog outlives contact2d for a moment and must hold nothing of
 * its (pipes, files, the output folder's lock).  close_range(2), Linux 5.9;
 * before it, the descriptors stay open (all are close-on-exec for the
 * program). */
static void close_others(int *keep, int n)
{
    unsigned int from = 3;
    int i, j;
    for (i = 0; i < n; i++)                         /* sort: n is 5 */
        for (j = i + 1; j < n; j++)
            if (keep[j] < keep[i]) {
                int t = keep[i];
                keep[i] = keep[j];
                keep[j] = t;
            }
    for (i = 0; i < n; i++) {
        if (keep[i] < (int)from) continue;
        if ((unsigned int)keep[i] > from) syscall(SYS_close_range, from, (unsigned int)keep[i] - 1, 0);
        from = (unsigned int)keep[i] + 1;
    }
    syscall(SYS_close_range, from, ~0U, 0);
}

/* The watchdog (module header): never returns. */
static void run_watchdog(char **argv, int log, int in, int out, int control, int report, int stop)
{
    struct report r = {C2D_RUN_NOT_STARTED, 0};
    pid_t program, self = getpid();
    int pidfd;
    siginfo_t info;

    setpgid(0, 0);
    set_job_signals(SIG_IGN);                       /* contact2d's handlers are not ours to run */
    signal(SIGCHLD, SIG_DFL);                       /* SIG_IGN would reap the program unasked */
    prctl(PR_SET_CHILD_SUBREAPER, 1);
    {
        int keep[5];
        keep[0] = log;
        keep[1] = control;
        keep[2] = report;
        keep[3] = in;
        keep[4] = out;
        close_others(keep, 5);
    }
    if (stop == STOP_WATCHDOG) raise(SIGSTOP);
    program = fork();
    if (program == 0) start_program(argv, log, in, out, report, self, stop);
    if (program < 0) {
        r.status = errno;
        if (write(report, &r, sizeof r) < 0) _exit(1);
        _exit(0);
    }
    setpgid(program, program);                      /* both sides: no race with kill(-program) */
    if (log >= 0) close(log);
    if (in >= 0) close(in);                         /* the program's own now: its end is contact2d's */
    if (out >= 0) close(out);
    pidfd = (int)syscall(SYS_pidfd_open, program, 0);
    for (;;) {
        struct pollfd fds[2];
        int nfds = 1;
        fds[0].fd = control;
        fds[0].events = POLLIN;
        if (pidfd >= 0) {
            fds[1].fd = pidfd;
            fds[1].events = POLLIN;
            nfds = 2;
        }
        /* without a pidfd (Linux < 5.3) the program's end is polled every 10 ms */
        if (poll(fds, (nfds_t)nfds, pidfd >= 0 ? -1 : 10) > 0 && (fds[0].revents != 0)) {
            end_everything(program);                /* contact2d is gone or stops the run */
            _exit(0);
        }
        memset(&info, 0, sizeof info);
        if (waitid(P_PID, (id_t)program, &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == program) break;
    }
    if (info.si_code == CLD_EXITED) {
        r.how = C2D_RUN_EXITED;
    } else {
        r.how = C2D_RUN_SIGNALED;
    }
    r.status = info.si_status;
    end_everything(program);                        /* what it left running, before the report */
    if (write(report, &r, sizeof r) < 0) _exit(1);
    _exit(0);
}

/* The run is over: the watchdog is told (end of file on its control pipe),
 * ends what is left and is reaped; its wait status to *wstatus (left as it
 * is when the watchdog was reaped already, by the signal handler).
 * Async-signal-safe. */
static void end_run(int *wstatus)
{
    int control = __atomic_exchange_n(&running_control, -1, __ATOMIC_SEQ_CST);
    pid_t watchdog = __atomic_load_n(&running_watchdog, __ATOMIC_SEQ_CST);
    if (control < 0) return;
    close(control);
    while (waitpid(watchdog, wstatus, 0) < 0 && errno == EINTR) continue;
}

/* Read the watchdog's report within `timeout` seconds: 1 and *r set, 0 at
 * the time limit, -1 when the pipe ended without one. */
static int read_report(int fd, double timeout, struct report *r)
{
    double end = now_seconds() + timeout;
    for (;;) {
        struct pollfd pfd;
        double left = end - now_seconds();
        ssize_t got;
        if (left <= 0.0) return 0;
        pfd.fd = fd;
        pfd.events = POLLIN;
        if (poll(&pfd, 1, left > 1000.0 ? 1000000 : (int)(1000.0 * left) + 1) <= 0) continue;
        got = read(fd, r, sizeof *r);               /* a record is written at once: PIPE_BUF */
        if (got == (ssize_t)sizeof *r) return 1;
        if (got < 0 && errno == EINTR) continue;
        return -1;
    }
}

/* Start args' program under a watchdog (module header): the log opened
 * (O_EXCL), the control and report pipes made, the watchdog forked and
 * recorded as the running one.  in and out: a server's stdin and stdout
 * (the program's ends of its pipes, closed here), -1 for /dev/null and the
 * log.  0 and *report set (the report pipe's read end), or 1 with *status
 * an errno. */
static int start_watched(const char *args, int nargs, const char *log_path, int in, int out, int *report_fd,
                         int *status)
{
    char **argv = calloc((size_t)nargs + 1, sizeof *argv);
    const char *p = args, *hook = getenv("CONTACT2D_TEST_STOP_AT");
    int log = -1, control[2] = {-1, -1}, report[2] = {-1, -1}, i, stop = STOP_NONE;
    pid_t watchdog;

    *status = ENOMEM;
    if (argv != NULL) {
        for (i = 0; i < nargs; i++) {               /* the packed strings, in place */
            argv[i] = (char *)p;
            p += strlen(p) + 1;
        }
        if (hook != NULL) {
            if (strcmp(hook, "spawn") == 0) stop = STOP_SPAWN;
            if (strcmp(hook, "watchdog") == 0) stop = STOP_WATCHDOG;
            if (strcmp(hook, "exec") == 0) stop = STOP_EXEC;
        }
        if (log_path[0] != '\0') log = open(log_path, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
        if ((log < 0 && log_path[0] != '\0') || pipe2(control, O_CLOEXEC) != 0 || pipe2(report, O_CLOEXEC) != 0) {
            *status = errno;
            argv = (free(argv), NULL);
        }
    }
    if (argv == NULL) {
        int fds[7] = {log, control[0], control[1], report[0], report[1], in, out};
        for (i = 0; i < 7; i++)
            if (fds[i] >= 0) close(fds[i]);
        return 1;
    }
    watchdog = fork();
    if (watchdog == 0) {
        close(control[1]);                          /* contact2d's alone: its end is the signal */
        close(report[0]);
        run_watchdog(argv, log, in, out, control[0], report[1], stop);
    }
    *status = errno;
    close(control[0]);
    close(report[1]);
    if (log >= 0) close(log);
    if (in >= 0) close(in);
    if (out >= 0) close(out);
    free(argv);
    if (watchdog < 0) {
        close(control[1]);
        close(report[0]);
        return 1;
    }
    setpgid(watchdog, watchdog);                    /* both sides, as for the program */
    __atomic_store_n(&running_watchdog, watchdog, __ATOMIC_SEQ_CST);
    __atomic_store_n(&running_control, control[1], __ATOMIC_SEQ_CST);
    if (stop == STOP_SPAWN) raise(SIGSTOP);
    *report_fd = report[0];
    return 0;
}

/* the running server (c2d_server_start): its stdin's write end, its
 * stdout's read end, the watchdog's report pipe, its CPU seconds so far
 * (its last reply's) */
static int server_in = -1, server_out = -1, server_report = -1;
static double server_cpu = 0.0;

int c2d_run_program(const char *args, int nargs, const char *log_path, double timeout, int *how, int *status)
{
    int report, got, wstatus = 0;
    struct report r;

    c2d_server_stop();                              /* one watched program at a time */
    *how = C2D_RUN_NOT_STARTED;
    if (start_watched(args, nargs, log_path, -1, -1, &report, status) != 0) return 0;
    got = read_report(report, timeout, &r);
    close(report);
    end_run(&wstatus);
    if (got == 1) {
        *how = r.how;
        *status = r.status;
    } else if (got == 0) {
        *how = C2D_RUN_TIMEOUT;
        *status = 0;
    } else if (WIFSIGNALED(wstatus)) {              /* no report: the watchdog was killed */
        *how = C2D_RUN_SIGNALED;
        *status = WTERMSIG(wstatus);
    } else {
        *status = ECHILD;
    }
    return 0;
}

int c2d_server_start(const char *args, int nargs, const char *log_path, int *status)
{
    int to[2], from[2];
    c2d_server_stop();
    if (pipe2(to, O_CLOEXEC) != 0) {
        *status = errno;
        return 1;
    }
    if (pipe2(from, O_CLOEXEC) != 0) {
        *status = errno;
        close(to[0]);
        close(to[1]);
        return 1;
    }
    if (start_watched(args, nargs, log_path, to[0], from[1], &server_report, status) != 0) {
        close(to[1]);
        close(from[0]);
        return 1;
    }
    server_in = to[1];
    server_out = from[0];
    server_cpu = 0.0;
    return 0;
}

int c2d_server_running(void)
{
    return server_in >= 0;
}

/* Write len bytes to the pipe fd, which a partial write may need; 0 when
 * all went, 1 when the reader is gone.  SIGPIPE, whose default action would
 * end contact2d, is blocked in this thread meanwhile, and one it raised is
 * taken (sigtimedwait) before the mask is restored. */
static int write_unsignaled(int fd, const char *bytes, int len)
{
    sigset_t pipe_only, old;
    struct timespec none = {0, 0};
    int at = 0, broken = 0;
    sigemptyset(&pipe_only);
    sigaddset(&pipe_only, SIGPIPE);
    pthread_sigmask(SIG_BLOCK, &pipe_only, &old);
    while (at < len) {
        ssize_t put = write(fd, bytes + at, (size_t)(len - at));
        if (put < 0 && errno == EINTR) continue;
        if (put <= 0) {
            broken = 1;
            if (errno == EPIPE) sigtimedwait(&pipe_only, NULL, &none);
            break;
        }
        at += (int)put;
    }
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    return broken;
}

int c2d_server_call(const char *request, int len, double timeout, int *how, int *status)
{
    char line[128];
    size_t have = 0;
    double end = now_seconds() + timeout;

    if (server_in < 0) return 2;
    if (write_unsignaled(server_in, request, len) != 0) return 2;
    for (;;) {
        struct pollfd fds[2];
        double left = end - now_seconds();
        ssize_t got;
        char *nl;
        if (left <= 0.0) return 1;
        fds[0].fd = server_out;
        fds[0].events = POLLIN;
        fds[1].fd = server_report;                  /* readable: the server ended */
        fds[1].events = POLLIN;
        if (poll(fds, 2, left > 1000.0 ? 1000000 : (int)(1000.0 * left) + 1) <= 0) continue;
        if (fds[0].revents == 0) return 2;
        got = read(server_out, line + have, sizeof line - 1 - have);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) return 2;
        have += (size_t)got;
        line[have] = '\0';
        nl = strchr(line, '\n');
        if (nl != NULL) {
            double cpu;
            if (sscanf(line, "%d %d %lf", how, status, &cpu) != 3) return 2;
            server_cpu = cpu;
            return 0;
        }
        if (have == sizeof line - 1) return 2;
    }
}

void c2d_server_stop(void)
{
    if (server_in < 0) return;
    close(server_in);                               /* end of file: the server's loop ends */
    end_run(NULL);                                  /* the watchdog ends the rest; reaped */
    close(server_out);
    close(server_report);
    server_in = server_out = server_report = -1;
    server_cpu = 0.0;                               /* reaped: in RUSAGE_CHILDREN now */
}

void c2d_kill_running(void)
{
    int saved = errno;
    end_run(NULL);
    errno = saved;
}

double c2d_cpu_seconds(void)
{
    return c2d_own_and_reaped_seconds() + server_cpu;   /* a running server's, not reaped yet */
}
