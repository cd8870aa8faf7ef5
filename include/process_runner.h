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
 * signal handler, so calls must not overlap (the gmsh runs are sequential).
 * A server (c2d_server_start) is such a program, kept running between
 * requests: starting another program stops it first. */
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

/* Start a server: args' program, watched as c2d_run_program's, its stdin
 * and stdout pipes to this process, its stderr to log_path (created).  It
 * runs until c2d_server_stop, c2d_kill_running or the next c2d_run_program
 * or c2d_server_start.  Returns 0 when started, else 1 with *status an
 * errno. */
int c2d_server_start(const char *args, int nargs, const char *log_path, int *status);

/* 1 while a server started by c2d_server_start runs, else 0. */
int c2d_server_running(void);

/* Send the server a request (len bytes) and read its reply, one line
 * "HOW STATUS CPU" (HOW and STATUS as *how and *status above for the run it
 * made, CPU its seconds so far, which c2d_cpu_seconds then counts) within
 * timeout seconds.  Returns 0 with the reply read, 1 at the time limit, 2
 * when the server has ended or answered out of protocol (the caller then
 * stops it). */
int c2d_server_call(const char *request, int len, double timeout, int *how, int *status);

/* Stop the server and everything it started (end of file on its stdin, then
 * the watchdog's end); nothing when none runs.  Its CPU time is then the
 * children's of this process. */
void c2d_server_stop(void);

/* End the running program and everything it started (the watchdog kills
 * them, then is reaped); nothing when none runs.  Async-signal-safe. */
void c2d_kill_running(void);

/* CPU seconds (user + system) of this process, of every program it has
 * run and waited for (gmsh, through its watchdog) and of a running server
 * (its last reply's figure): what a run costs, where the elapsed time would
 * also count the waits. */
double c2d_cpu_seconds(void);

#endif
