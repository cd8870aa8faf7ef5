/* fortran_oom.c: an allocation that gfortran's code checks and that fails
 * ends with the program's diagnosis, not with the runtime's abort.
 *
 * The code gfortran generates checks the result of an ALLOCATE without
 * stat=, of the array temporaries of an expression and, under
 * -fcheck=mem (make.inc), of automatic arrays; when malloc or realloc
 * returns NULL it calls the runtime's
 *     _gfortran_os_error_at("In file 'F.f90', around line L",
 *                           "Error allocating %lu bytes", bytes)
 * which prints "Operating system error", a backtrace and "Error
 * termination".  The program defines that entry point itself (its object
 * code calls it directly, so this definition is the one it runs; the
 * runtime's own internal calls are not affected) and ends the run as a
 * numerical failure does:
 *     contact2d: error: out of memory while PHASE (at F.f90:L) (about N MB needed)
 * exit status 1; exit() runs the cleanup (file_guard.c: the temporaries and
 * the private folder), so nothing is written.  PHASE is named from the
 * source file: which file allocates tells which phase of the run it is, so
 * no state has to be kept for it.
 *
 * Allocations the generated code does not check write through the null
 * pointer instead: the (re)allocation on assignment of an allocatable array
 * or a deferred-length string (`a = [a, x]`, `a = b` with b larger, `s = s
 * // t`), which calls malloc or realloc and uses the result as it is.  The
 * program is linked with -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc
 * (make.inc): every such call of the program's own object code goes through
 * the wrappers below, which return what the C library returns and, when it
 * is NULL, remember the size and install a SIGSEGV handler.  A fault then
 * at an address below that size (plus 64 kB: the lower bound's offset) is
 * the write through that null pointer: the run ends with
 *     contact2d: error: out of memory while computing (an allocation the code does not check) (about N MB needed)
 * exit status 1, through exit() as above.  Any other fault goes to the
 * handler that was there before (gfortran's backtrace).  ALLOCATE with
 * stat= is not changed: it gets NULL and says what it says; the handler
 * waits for a fault that may never come.  The large arrays are allocated
 * with stat= in the code (doc/robustness.md, "Memory limits"). */
#define _GNU_SOURCE
#include <signal.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

void _gfortran_os_error_at(const char *where, const char *message, ...) __attribute__((noreturn));

/* The phase of a run that allocates in each source file. */
static const char *const phases[][2] = {
    {"mesh_rect.f90", "meshing"},
    {"gmsh_reader.f90", "reading the meshes"},
    {"mesh.f90", "reading the meshes"},
    {"msh_data.f90", "reading the meshes"},
    {"msh_elements.f90", "reading the meshes"},
    {"msh_mesh.f90", "reading the meshes"},
    {"msh_sections.f90", "reading the meshes"},
    {"msh_text.f90", "reading the meshes"},
    {"geo_screen.f90", "screening the .geo files"},
    {"gmsh_runner.f90", "running gmsh"},
    {"deck_reader.f90", "reading the deck"},
    {"deck_types.f90", "reading the deck"},
    {"deck_syntax.f90", "reading the deck"},
    {"deck_statements.f90", "reading the deck"},
    {"deck_body_statements.f90", "reading the deck"},
    {"deck_rigid_statements.f90", "reading the deck"},
    {"deck_checks.f90", "reading the deck"},
    {"deck_expressions.f90", "reading the deck"},
    {"deck_cases.f90", "reading the deck"},
    {"case_selection.f90", "reading the deck"},
    {"text_scan.f90", "reading the input"},
    {"command_line.f90", "reading the command line"},
    {"scene.f90", "building the scene"},
    {"material.f90", "building the scene"},
    {"local_axes.f90", "building the scene"},
    {"problem_setup.f90", "building the scene"},
    {"body.f90", "assembling K"},
    {"elements.f90", "assembling K"},
    {"axisymmetric_elements.f90", "assembling K"},
    {"sparse_matrix.f90", "assembling K"},
    {"sparse_cholesky.f90", "factorizing K"},
    {"sparse_cholesky_parts.f90", "factorizing K"},
    {"sparse_cholesky_solve.f90", "factorizing K"},
    {"linear_system.f90", "factorizing K"},
    {"contact_set.f90", "building the mortar operator"},
    {"boundary_chain.f90", "building the mortar operator"},
    {"mortar_geometry.f90", "building the mortar operator"},
    {"mortar_operator.f90", "building the mortar operator"},
    {"mortar_quadratic.f90", "building the mortar operator"},
    {"rigid_obstacle.f90", "building the mortar operator"},
    {"mode_support.f90", "finding the rigid modes"},
    {"rigid_modes.f90", "finding the rigid modes"},
    {"rigid_support.f90", "finding the rigid modes"},
    {"contact_condensation.f90", "condensing the contact problem"},
    {"lcp_solvers.f90", "solving the LCP"},
    {"lcp_scaling.f90", "solving the LCP"},
    {"lcp_lemke.f90", "solving the LCP"},
    {"lcp_pgs.f90", "solving the LCP"},
    {"contact_solve.f90", "solving the LCP"},
    {"lcp_newton.f90", "solving the LCP"},
    {"contact_lcp.f90", "solving the LCP"},
    {"friction_lcp.f90", "solving the friction LCP"},
    {"friction_modes.f90", "solving the friction LCP"},
    {"post_processing.f90", "computing the results"},
    {"run_state.f90", "building the scene"},
    {"results_writer.f90", "writing the outputs"},
    {"run_outputs.f90", "writing the outputs"},
    {"run_report.f90", "writing the outputs"},
    {"text_buffer.f90", "writing the outputs"},
    {"safe_files.f90", "writing the outputs"},
};

/* "In file 'F', around line L" -> file F and line L (0 when absent). */
static void split_where(const char *where, char *file, size_t size, long *line)
{
    const char *a = where != NULL ? strchr(where, '\'') : NULL, *b = a != NULL ? strchr(a + 1, '\'') : NULL;
    const char *l = where != NULL ? strstr(where, "line ") : NULL;
    size_t n = 0;
    if (a != NULL && b != NULL)
    {
        const char *base = a + 1, *s;
        for (s = base; s < b; s++)
            if (*s == '/') base = s + 1;     /* the file's name, without its folder */
        n = (size_t) (b - base);
        if (n >= size) n = size - 1;
        memcpy(file, base, n);
    }
    file[n] = '\0';
    *line = l != NULL ? strtol(l + 5, NULL, 10) : 0;
}

void _gfortran_os_error_at(const char *where, const char *message, ...)
{
    char file[128], text[512];
    const char *phase = "computing";
    unsigned long bytes = 0;
    long line;
    size_t i;
    va_list ap;
    int n;

    split_where(where, file, sizeof file, &line);
    for (i = 0; i < sizeof phases / sizeof phases[0]; i++)
        if (strcmp(file, phases[i][0]) == 0) phase = phases[i][1];
    if (message != NULL && strstr(message, "allocat") != NULL && strstr(message, "%lu") != NULL)
    {
        va_start(ap, message);
        bytes = va_arg(ap, unsigned long);
        va_end(ap);
        n = snprintf(text, sizeof text,
                     "contact2d: error: out of memory while %s (at %s:%ld) (about %lu MB needed)\n",
                     phase, file, line, bytes / 1048576 + (bytes % 1048576 != 0));
    }
    else   /* another failure the runtime reports this way: its text, as a numerical failure */
    {
        char what[256];
        va_start(ap, message);
        (void) vsnprintf(what, sizeof what, message != NULL ? message : "", ap);
        va_end(ap);
        n = snprintf(text, sizeof text, "contact2d: error: %s (at %s:%ld)\n", what, file, line);
    }
    if (n > 0) (void) !write(STDERR_FILENO, text, (size_t) n < sizeof text ? (size_t) n : sizeof text - 1);
    exit(1);
}

/* --- allocations the generated code does not check -------------------------------- */

void *__real_malloc(size_t size);
void *__real_calloc(size_t count, size_t size);
void *__real_realloc(void *p, size_t size);
void *__wrap_malloc(size_t size);
void *__wrap_calloc(size_t count, size_t size);
void *__wrap_realloc(void *p, size_t size);

static size_t failed_bytes = 0;             /* the largest allocation that failed */
static int armed = 0;                       /* the handler is installed */
static struct sigaction before;             /* the SIGSEGV action it replaced */

static void on_null_write(int sig, siginfo_t *info, void *context)
{
    size_t bytes = __atomic_load_n(&failed_bytes, __ATOMIC_SEQ_CST);
    uintptr_t at = (uintptr_t) info->si_addr;
    char text[200];
    int n;
    (void) context;
    if (bytes == 0 || at >= (uintptr_t) bytes + 65536)
    {
        sigaction(sig, &before, NULL);      /* not ours: the fault again, under the earlier handler */
        return;
    }
    n = snprintf(text, sizeof text, "contact2d: error: out of memory while computing "
                 "(an allocation the code does not check) (about %lu MB needed)\n",
                 (unsigned long) (bytes / 1048576 + (bytes % 1048576 != 0)));
    if (n > 0) (void) !write(STDERR_FILENO, text, (size_t) n < sizeof text ? (size_t) n : sizeof text - 1);
    exit(1);
}

/* An allocation of `bytes` failed: remember it, install the handler once. */
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
    sigaction(SIGSEGV, &sa, &before);
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
