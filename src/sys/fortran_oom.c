/* fortran_oom.c: an allocation that fails where the code does not check it
 * ends with the program's diagnosis, not with a Fortran runtime's abort or a
 * fault:
 *     contact2d: error: out of memory while PHASE (...) (about N MB needed)
 * exit status 1; exit() runs the cleanup (file_guard.c: the temporaries and
 * the private folder), so nothing is written.  PHASE is the step of the run
 * the program last entered (c2d_set_phase, called through run_phase.f90 at
 * the step boundaries of src/app/), "computing" before the first.  The
 * allocations that grow with the problem have stat= in the code and their
 * own message with the sizes (doc/robustness.md, "Memory limits"); this file
 * is for the others.
 *
 * Any compiler: the program is linked with
 * -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc (make.inc): every such call
 * of its own object code, and of a runtime linked statically (flang's), goes
 * through the wrappers below, which return what the C library returns and,
 * when it is NULL, remember the size and install two handlers.
 *   SIGSEGV: a fault at an address below that size (plus 64 kB: a lower
 *     bound's offset) is a write through the null pointer, from code that did
 *     not check: gfortran's reallocation on assignment (`a = b` with b
 *     larger, `s = s // t`), flang's ALLOCATE without stat=.  Any other
 *     fault goes to the handler that was there before.
 *   SIGABRT: a runtime that checked and aborts (after its own message, which
 *     this cannot stop) ends with the diagnosis and exit 1 all the same.
 * ALLOCATE with stat= is not changed: it gets NULL and says what it says; the
 * handlers wait for a signal that may never come.
 *
 * The runtimes' own reports of a failed allocation, each used only where
 * that runtime is linked, say it before anything is printed and add the
 * source line, "(at F.f90:L)":
 *   libgfortran: the code gfortran generates checks an ALLOCATE without
 *     stat=, the array temporaries of an expression and, under -fcheck=mem,
 *     automatic arrays, and calls
 *         _gfortran_os_error_at("In file 'F.f90', around line L",
 *                               "Error allocating %lu bytes", bytes)
 *     which would print "Operating system error", a backtrace and "Error
 *     termination".  The program defines that entry point (its object code
 *     calls it directly, so this definition is the one it runs; the
 *     runtime's own internal calls are not affected).
 *   flang's runtime (libFortranRuntime, statically linked) ends an
 *     allocation it checks (a reallocation on assignment, an intrinsic's
 *     result) through its Terminator, which calls a handler registered
 *     with Terminator::RegisterCrashHandler before it prints "fatal Fortran
 *     runtime error" and aborts.  The registration is a weak reference: with
 *     another runtime it is NULL and nothing is registered. */
#define _GNU_SOURCE
#include <signal.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "fortran_oom.h"

/* --- the phase ------------------------------------------------------------------- */

/* The step of the run: set by the main thread between steps, read by a
 * signal handler in any thread.  Two buffers: the one not in use is written,
 * then published by one atomic store. */
static char phase_buffers[2][96];
static const char *phase_now = "computing";

void c2d_set_phase(const char *phase, size_t length)
{
    char *next = phase_buffers[__atomic_load_n(&phase_now, __ATOMIC_SEQ_CST) == phase_buffers[0]];
    size_t n = length < sizeof phase_buffers[0] - 1 ? length : sizeof phase_buffers[0] - 1;
    memcpy(next, phase, n);
    next[n] = '\0';
    __atomic_store_n(&phase_now, next, __ATOMIC_SEQ_CST);
}

/* --- the diagnosis --------------------------------------------------------------- */

static size_t failed_bytes = 0;             /* the largest allocation that failed */

/* Write `contact2d: error: out of memory while PHASE (WHERE) (about N MB
 * needed)` and end the run with status 1.  Called from signal handlers too:
 * one write(2), after an snprintf of strings and integers into the stack
 * (glibc allocates nothing for those), then exit(), for the cleanup. */
static void out_of_memory(const char *where, size_t bytes) __attribute__((noreturn));
static void out_of_memory(const char *where, size_t bytes)
{
    char text[400];
    int n = snprintf(text, sizeof text, "contact2d: error: out of memory while %s (%s) (about %lu MB needed)\n",
                     __atomic_load_n(&phase_now, __ATOMIC_SEQ_CST), where,
                     (unsigned long) (bytes / 1048576 + (bytes % 1048576 != 0)));
    if (n > 0) (void) !write(STDERR_FILENO, text, (size_t) n < sizeof text ? (size_t) n : sizeof text - 1);
    exit(1);
}

/* The runtimes' hooks below can be left out (-DC2D_OOM_PORTABLE_ONLY), so
 * that tests/robust/unchecked_alloc can show the portable path alone. */
#ifndef C2D_OOM_PORTABLE_ONLY

/* The file's name without its folder. */
static const char *base_name(const char *path)
{
    const char *s, *base = path;
    for (s = path; *s != '\0'; s++)
        if (*s == '/') base = s + 1;
    return base;
}

/* --- libgfortran's entry point ------------------------------------------------------ */

void _gfortran_os_error_at(const char *where, const char *message, ...) __attribute__((noreturn));

/* "In file 'F', around line L" -> "at F:L" (F without its folder). */
static void split_where(const char *where, char *at, size_t size)
{
    const char *a = where != NULL ? strchr(where, '\'') : NULL, *b = a != NULL ? strchr(a + 1, '\'') : NULL;
    const char *l = where != NULL ? strstr(where, "line ") : NULL;
    char file[128] = "";
    if (a != NULL && b != NULL)
    {
        size_t n = (size_t) (b - (a + 1));
        if (n >= sizeof file) n = sizeof file - 1;
        memcpy(file, a + 1, n);
        file[n] = '\0';
    }
    snprintf(at, size, "at %s:%ld", base_name(file), l != NULL ? strtol(l + 5, NULL, 10) : 0L);
}

void _gfortran_os_error_at(const char *where, const char *message, ...)
{
    char at[160], text[512];
    va_list ap;
    int n;

    split_where(where, at, sizeof at);
    if (message != NULL && strstr(message, "allocat") != NULL && strstr(message, "%lu") != NULL)
    {
        unsigned long bytes;
        va_start(ap, message);
        bytes = va_arg(ap, unsigned long);
        va_end(ap);
        out_of_memory(at, bytes);
    }
    else   /* another failure the runtime reports this way: its text, as a numerical failure */
    {
        char what[256];
        va_start(ap, message);
        (void) vsnprintf(what, sizeof what, message != NULL ? message : "", ap);
        va_end(ap);
        n = snprintf(text, sizeof text, "contact2d: error: %s (%s)\n", what, at);
        if (n > 0) (void) !write(STDERR_FILENO, text, (size_t) n < sizeof text ? (size_t) n : sizeof text - 1);
        exit(1);
    }
}

/* --- flang's runtime ---------------------------------------------------------------- */

/* Fortran::runtime::Terminator::RegisterCrashHandler(void (*)(const char *
 * file, int line, const char *message, va_list &)), by its mangled name; a
 * va_list & is a pointer to the va_list's one element on x86-64 and AArch64
 * alike, as the handler below takes it. */
typedef void (*crash_handler_t)(const char *file, int line, const char *message, va_list *ap);
extern void _ZN7Fortran7runtime10Terminator20RegisterCrashHandlerEPFvPKciS3_RA1_13__va_list_tagE(
    crash_handler_t handler) __attribute__((weak));

/* The runtime is about to print `message` and abort: a failed allocation
 * ("Memory allocation failed", "could not allocate memory for result", "out
 * of memory, needed N bytes", ...)
 * ends as the program's diagnosis; anything else goes on as the runtime
 * says. */
static void on_flang_crash(const char *file, int line, const char *message, va_list *ap)
{
    char at[160];
    (void) ap;
    if (message == NULL || strcasestr(message, "memory") == NULL
        || (strcasestr(message, "alloc") == NULL && strcasestr(message, "out of memory") == NULL)) return;
    if (file != NULL) snprintf(at, sizeof at, "at %s:%d", base_name(file), line);
    else snprintf(at, sizeof at, "in the Fortran runtime");
    out_of_memory(at, __atomic_load_n(&failed_bytes, __ATOMIC_SEQ_CST));
}

__attribute__((constructor)) static void register_flang_crash_handler(void)
{
    if (_ZN7Fortran7runtime10Terminator20RegisterCrashHandlerEPFvPKciS3_RA1_13__va_list_tagE != NULL)
        _ZN7Fortran7runtime10Terminator20RegisterCrashHandlerEPFvPKciS3_RA1_13__va_list_tagE(on_flang_crash);
}

#endif /* C2D_OOM_PORTABLE_ONLY */

/* --- allocations the code does not check -------------------------------------------- */

void *__real_malloc(size_t size);
void *__real_calloc(size_t count, size_t size);
void *__real_realloc(void *p, size_t size);
void *__wrap_malloc(size_t size);
void *__wrap_calloc(size_t count, size_t size);
void *__wrap_realloc(void *p, size_t size);

static int armed = 0;                       /* the handlers are installed */
static struct sigaction segv_before;        /* the SIGSEGV action it replaced */

static void on_null_write(int sig, siginfo_t *info, void *context)
{
    size_t bytes = __atomic_load_n(&failed_bytes, __ATOMIC_SEQ_CST);
    uintptr_t at = (uintptr_t) info->si_addr;
    (void) context;
    if (bytes == 0 || at >= (uintptr_t) bytes + 65536)
    {
        sigaction(sig, &segv_before, NULL); /* not ours: the fault again, under the earlier handler */
        return;
    }
    out_of_memory("an allocation the code does not check", bytes);
}

static void on_abort(int sig)
{
    (void) sig;
    out_of_memory("an abort after a failed allocation", __atomic_load_n(&failed_bytes, __ATOMIC_SEQ_CST));
}

/* An allocation of `bytes` failed: remember it, install the handlers once. */
static void allocation_failed(size_t bytes)
{
    struct sigaction sa;
    size_t old = __atomic_load_n(&failed_bytes, __ATOMIC_SEQ_CST);
    while (bytes > old && !__atomic_compare_exchange_n(&failed_bytes, &old, bytes, 0, __ATOMIC_SEQ_CST,
                                                       __ATOMIC_SEQ_CST))
        continue;
    if (__atomic_exchange_n(&armed, 1, __ATOMIC_SEQ_CST)) return;
    memset(&sa, 0, sizeof sa);
    sa.sa_sigaction = on_null_write;
    sa.sa_flags = SA_SIGINFO;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGSEGV, &sa, &segv_before);
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_abort;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGABRT, &sa, NULL);
}

void *__wrap_malloc(size_t size)
{
    void *p = __real_malloc(size);
    if (p == NULL && size > 0) allocation_failed(size);
    return p;
}

void *__wrap_calloc(size_t count, size_t size)
{
    void *p = __real_calloc(count, size);
    if (p == NULL && count > 0 && size > 0) allocation_failed(count > SIZE_MAX / size ? SIZE_MAX : count * size);
    return p;
}

void *__wrap_realloc(void *p, size_t size)
{
    void *q = __real_realloc(p, size);
    if (q == NULL && size > 0) allocation_failed(size);
    return q;
}
