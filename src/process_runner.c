/* process_runner: start a program with an argument vector and a time limit
 * (see include/process_runner.h).
 *
 * fork/exec rather than posix_spawn: the child must set PR_SET_PDEATHSIG, so
 * that it dies with contact2d even when contact2d is killed by SIGKILL, and
 * posix_spawn has no attribute for it.  Between fork and exec the child calls
 * only async-signal-safe functions (the parent may run OpenMP threads).
 *
 * The death signal alone is not enough: bubblewrap's outer process, started
 * as root, was seen to outlive a contact2d killed by SIGKILL at start-up
 * under load, with gmsh running on inside it.  So each run also gets a
 * watchdog, a second child that holds the read end of a pipe whose only
 * write end contact2d keeps: a byte on it means the run is over (exit);
 * end of file means contact2d is gone, and the watchdog kills the run's
 * process group. */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "process_runner.h"

/* the group of the program running now, 0 when none: read by the signal
 * handler (c2d_kill_running), hence sig_atomic_t-sized and volatile */
static volatile sig_atomic_t running_group = 0;

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

/* The child: own group, dies with its parent, stdin /dev/null, stdout and
 * stderr to log (kept as they are when log < 0); reports exec's errno on the
 * close-on-exec pipe. */
static void start_child(char **argv, int log, int report, pid_t parent)
{
    int null = open("/dev/null", O_RDONLY | O_CLOEXEC);
    int e;
    setpgid(0, 0);
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(127);            /* the parent died before prctl */
    if (null < 0 || dup2(null, 0) < 0 || (log >= 0 && (dup2(log, 1) < 0 || dup2(log, 2) < 0))) {
        e = errno;
    } else {
        execv(argv[0], argv);
        e = errno;
    }
    if (write(report, &e, sizeof e) < 0) _exit(127);
    _exit(127);
}

/* Wait up to `timeout` seconds for pid; 1 when it ended (*wstatus set).
 * A pidfd (Linux 5.3) wakes poll(2) the moment the child ends; without one,
 * waitpid is polled every 1 ms, doubling to 50 ms. */
static int wait_until(pid_t pid, double timeout, int *wstatus)
{
    struct timespec start, now, nap = {0, 1000000};
    int pidfd = (int)syscall(SYS_pidfd_open, pid, 0);
    clock_gettime(CLOCK_MONOTONIC, &start);
    for (;;) {
        double left;
        pid_t r = waitpid(pid, wstatus, WNOHANG);
        if (r == pid || (r < 0 && errno != EINTR)) {
            if (pidfd >= 0) close(pidfd);
            return 1;
        }
        clock_gettime(CLOCK_MONOTONIC, &now);
        left = timeout - ((double)(now.tv_sec - start.tv_sec) + 1e-9 * (double)(now.tv_nsec - start.tv_nsec));
        if (left <= 0.0) {
            if (pidfd >= 0) close(pidfd);
            return 0;
        }
        if (pidfd >= 0) {
            struct pollfd pfd;
            pfd.fd = pidfd;
            pfd.events = POLLIN;
            poll(&pfd, 1, left > 1000.0 ? 1000000 : (int)(1000.0 * left) + 1);
        } else {
            nanosleep(&nap, NULL);
            if (nap.tv_nsec < 50000000) nap.tv_nsec *= 2;
        }
    }
}

/* The watchdog of the group `group` (module header): returns its pid, or -1
 * (the run goes on without it) when it cannot be started; *done is the
 * write end to signal a normal end on (-1 without a watchdog). */
static pid_t start_watchdog(pid_t group, int *done)
{
    int fd[2];
    pid_t pid;
    char c;
    *done = -1;
    if (pipe2(fd, O_CLOEXEC) != 0) return -1;
    pid = fork();
    if (pid == 0) {
        ssize_t got;
        close(fd[1]);
        do {
            got = read(fd[0], &c, 1);
        } while (got < 0 && errno == EINTR);
        if (got != 1) kill(-group, SIGKILL);          /* end of file: contact2d is gone */
        _exit(0);
    }
    close(fd[0]);
    if (pid < 0) {
        close(fd[1]);
        return -1;
    }
    *done = fd[1];
    return pid;
}

/* The run is over: the watchdog is told so and reaped. */
static void stop_watchdog(pid_t pid, int done)
{
    const char c = 1;
    if (pid <= 0) return;
    if (write(done, &c, 1) < 0) kill(pid, SIGKILL);
    close(done);
    while (waitpid(pid, NULL, 0) < 0 && errno == EINTR) continue;
}

int c2d_run_program(const char *args, int nargs, const char *log_path, double timeout, int *how, int *status)
{
    char **argv = calloc((size_t)nargs + 1, sizeof *argv);
    const char *p = args;
    int log, pipefd[2], e = 0, wstatus = 0, i, done;
    pid_t pid, watchdog, parent = getpid();
    ssize_t got;

    *how = C2D_RUN_NOT_STARTED;
    *status = ENOMEM;
    if (argv == NULL) return 0;
    for (i = 0; i < nargs; i++) {                   /* the packed strings, in place */
        argv[i] = (char *)p;
        p += strlen(p) + 1;
    }
    log = log_path[0] == '\0' ? -1 : open(log_path, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (log < 0 && log_path[0] != '\0') {
        *status = errno;
        free(argv);
        return 0;
    }
    if (pipe2(pipefd, O_CLOEXEC) != 0) {
        *status = errno;
        if (log >= 0) close(log);
        free(argv);
        return 0;
    }
    pid = fork();
    if (pid == 0) start_child(argv, log, pipefd[1], parent);
    close(pipefd[1]);
    if (log >= 0) close(log);
    free(argv);
    if (pid < 0) {
        *status = errno;
        close(pipefd[0]);
        return 0;
    }
    setpgid(pid, pid);                              /* both sides: no race with kill(-pid) */
    running_group = pid;
    watchdog = start_watchdog(pid, &done);
    do {
        got = read(pipefd[0], &e, sizeof e);        /* EOF: exec succeeded */
    } while (got < 0 && errno == EINTR);
    close(pipefd[0]);
    if (got == (ssize_t)sizeof e) {
        waitpid(pid, &wstatus, 0);
        running_group = 0;
        stop_watchdog(watchdog, done);
        *status = e;
        return 0;
    }
    if (wait_until(pid, timeout, &wstatus)) {
        kill(-pid, SIGKILL);                        /* anything it left running in its group */
        running_group = 0;
        stop_watchdog(watchdog, done);
        if (WIFEXITED(wstatus)) {
            *how = C2D_RUN_EXITED;
            *status = WEXITSTATUS(wstatus);
        } else {
            *how = C2D_RUN_SIGNALED;
            *status = WIFSIGNALED(wstatus) ? WTERMSIG(wstatus) : 0;
        }
        return 0;
    }
    c2d_kill_running();
    stop_watchdog(watchdog, done);
    *how = C2D_RUN_TIMEOUT;
    *status = 0;
    return 0;
}

void c2d_kill_running(void)
{
    pid_t group = (pid_t)running_group;
    int saved = errno;
    if (group > 0) {
        running_group = 0;
        kill(-group, SIGKILL);
        while (waitpid(group, NULL, 0) < 0 && errno == EINTR) continue;
    }
    errno = saved;
}
