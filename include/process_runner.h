/* process_runner: start a program with an argument vector (no shell), in a
 * process group of its own, with its output sent to a log file, and wait for
 * it with a time limit.  A watchdog process (a child subreaper, see
 * src/sys/process_runner.c) starts it and kills it and everything it started,
 * whatever group or session that moved to, when the limit passes, when the
 * program ends normally (strays it left behind), when c2d_kill_running is
 * called (the run's exit and signal cleanup, file_guard.c), and when this
 * process is gone, even by SIGKILL.
 *
 * One program at a time: the running watchdog is process state, read by the
 * signal handler, so calls must not overlap (the gmsh runs are sequential). */
#ifndef CONTACT2D_PROCESS_RUNNER_H
#define CONTACT2D_PROCESS_RUNNER_H

/* how a run ended (c2d_run_program's *how) */
enum { C2D_RUN_EXITED = 0,      /* *status = exit status                 */
       C2D_RUN_SIGNALED = 1,    /* *status = the signal that killed it   */
       C2D_RUN_TIMEOUT = 2,     /* killed at the time limit              */
       C2D_RUN_NOT_STARTED = 3  /* *status = errno of fork, open or exec */
};

/* Search PATH for an executable regular file `name` (or take `name` when it
 * holds a '/').  path: (len) receives the absolute path, NUL-terminated.
 * Returns 0 found, 1 not found, 2 too long for path. */
int c2d_find_program(const char *name, char *path, int len);

/* Run args[0] (an absolute path) with the argument vector packed in args:
 * nargs NUL-terminated strings one after the other.  Its stdin is /dev/null,
 * stdout and stderr go to log_path (created, must not exist: O_EXCL, no
 * symbolic link followed), or stay this process's when log_path is "".  It runs in a new process group;
 * when the call returns, neither it nor anything it started runs any more.
 * timeout: seconds (> 0).  Returns 0; *how and *status as above. */
int c2d_run_program(const char *args, int nargs, const char *log_path, double timeout, int *how, int *status);

/* End the running program and everything it started (the watchdog kills
 * them, then is reaped); nothing when none runs.  Async-signal-safe. */
void c2d_kill_running(void);

/* CPU seconds (user + system) of this process and of every program it has
 * run and waited for (gmsh, through its watchdog): what a run costs, where
 * the elapsed time would also count the waits. */
double c2d_cpu_seconds(void);

#endif
