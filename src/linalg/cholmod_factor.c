/* cholmod_factor.c: the CHOLMOD handle and its factor: analysis, numeric
 * factorization, solves, statistics (see include/cholmod_factor.h for the
 * interface and its index convention, include/cholmod_handle.h for the
 * handle and who owns what).
 *
 * Why a C layer at all: cholmod_common and cholmod_factor are large structs
 * whose layout changes between CHOLMOD versions; reading L->Perm and the
 * status fields is simple in C against the installed header, and fragile
 * through Fortran interoperable types.  The ordering is src/linalg/fill_ordering.c's,
 * reading the factor src/linalg/factor_inspection.c's.
 */
#define _GNU_SOURCE
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#include "cholmod.h"
#include "cholmod_factor.h"
#include "cholmod_handle.h"
#include "fill_ordering.h"
#include "factor_inspection.h"

/* The codes as variables, for the Fortran binding (cholmod_factor.h). */
const int c2d_cholmod_ok = CHOLMOD_OK;
const int c2d_cholmod_not_posdef = CHOLMOD_NOT_POSDEF;
const int c2d_cholmod_out_of_memory = CHOLMOD_OUT_OF_MEMORY;
const int c2d_cholmod_too_large = CHOLMOD_TOO_LARGE;
const int c2d_chol_no_handle = C2D_CHOL_NO_HANDLE;
const int c2d_chol_no_factor = C2D_CHOL_NO_FACTOR;
const int c2d_chol_not_super_ll = C2D_CHOL_NOT_SUPER_LL;
const int c2d_chol_block_moved = C2D_CHOL_BLOCK_MOVED;
const int c2d_chol_bad_argument = C2D_CHOL_BAD_ARGUMENT;
const int c2d_order_metis = C2D_ORDER_METIS;
const int c2d_order_amd = C2D_ORDER_AMD;
const int c2d_name_ordering = C2D_NAME_ORDERING;
const int c2d_name_status = C2D_NAME_STATUS;
const int c2d_solve_whole = C2D_SOLVE_WHOLE;
const int c2d_solve_forward = C2D_SOLVE_FORWARD;
const int c2d_solve_backward = C2D_SOLVE_BACKWARD;

/* Copy a C string into buf[len], truncated and NUL-terminated. */
static void copy_name(const char *name, char *buf, int len)
{
    size_t m;
    if (buf == NULL || len <= 0) return;
    m = strlen(name);
    if (m > (size_t) (len - 1)) m = (size_t) (len - 1);
    memcpy(buf, name, m);
    buf[m] = '\0';
}


/* Free the factor held by h and forget everything derived from it. */
static void clear_factor(struct c2d_chol *h)
{
    if (h->L != NULL) cholmod_free_factor(&h->L, &h->common);
    h->valid = 0;
    h->n = 0;
    h->nlast = 0;
    h->minor_column = 0;
    h->minor_equation = 0;
    h->pivot_ratio = 0.0;
    h->pivot_column = 0;
    h->pivot_equation = 0;
}

/* CHOLMOD's large blocks (the factor's values and row indices, the
 * update workspace) on transparent huge pages.  The factor is zeroed
 * supernode by supernode as it is computed, the first touch of each of its
 * pages, and a page fault each is costly on a virtual machine that backs
 * its memory lazily: in a small run the factor's page faults are a good
 * part of the factorization (doc/performance.md, "A small run's fixed
 * costs").  A block of at least hp_min bytes is allocated 2 MB-aligned, its
 * size rounded up to whole 2 MB pages (at most 2 MB more, and only for
 * these few blocks), and marked MADV_HUGEPAGE: one fault per 2 MB.  Where
 * the kernel gives no huge pages (transparent_hugepage=never) the advice is
 * a no-op; when the aligned allocation fails (an address-space limit) the
 * block is allocated as usual.  free and realloc are the C library's:
 * posix_memalign's blocks are ordinary ones to them. */
static const size_t huge_page = (size_t) 2 << 20;
static const size_t hp_min = (size_t) 512 << 10;

static void *large_malloc(size_t size)
{
    void *p = NULL;
    size_t n;
    if (size < hp_min) return malloc(size);
    n = (size + huge_page - 1) / huge_page * huge_page;
    if (n < size || posix_memalign(&p, huge_page, n) != 0) return malloc(size);
    (void) madvise(p, n, MADV_HUGEPAGE);
    return p;
}

static void *large_calloc(size_t count, size_t size)
{
    void *p;
    if (size == 0 || count < hp_min / size) return calloc(count, size);
    if (count > ((size_t) -1) / size) return NULL;
    p = large_malloc(count * size);
    if (p != NULL) memset(p, 0, count * size);
    return p;
}

static void use_large_pages(void)
{
#if defined(SUITESPARSE_MAIN_VERSION) && SUITESPARSE_MAIN_VERSION >= 7
    SuiteSparse_config_malloc_func_set(large_malloc);
    SuiteSparse_config_calloc_func_set(large_calloc);
#else
    SuiteSparse_config.malloc_func = large_malloc;
    SuiteSparse_config.calloc_func = large_calloc;
#endif
}

void *c2d_chol_create(void)
{
    struct c2d_chol *h = malloc(sizeof(struct c2d_chol));
    if (h == NULL) return NULL;
    memset(h, 0, sizeof(struct c2d_chol));
    use_large_pages();
    if (!cholmod_start(&h->common))
    {
        free(h);
        return NULL;
    }
    h->common.print = 0;                       /* library code prints nothing */
    h->common.supernodal = CHOLMOD_SUPERNODAL; /* always supernodal LL' */
    h->common.final_asis = 1;                  /* keep L as factorized */
    h->common.quick_return_if_not_posdef = 0;  /* refactor up to L->minor */
    h->L = NULL;
    clear_factor(h);
    return h;
}

int c2d_chol_set_ordering(void *handle, int method)
{
    struct c2d_chol *h = handle;
    if (h == NULL) return C2D_CHOL_NO_HANDLE;
    if (method != C2D_ORDER_METIS && method != C2D_ORDER_AMD) return C2D_CHOL_BAD_ARGUMENT;
    h->method = method;
    return CHOLMOD_OK;
}

void c2d_chol_destroy(void *handle)
{
    struct c2d_chol *h = handle;
    if (h == NULL) return;
    clear_factor(h);
    cholmod_finish(&h->common);
    free(h);
}

/* The pattern of A as a CHOLMOD matrix (0-based, upper triangle, no values):
 * what the ordering and the analysis read.  colptr and rowind may be the
 * columns of a diagonal block of a larger matrix: the entries are
 * rowind[0..colptr[n]-colptr[0]-1], their rows rowind - offset (see
 * c2d_chol_analyze).  NULL with *status set when the column pointers or row
 * indices are out of range. */
cholmod_sparse *c2d_copy_pattern(int n, const int *colptr, const int *rowind, int offset,
                                 cholmod_common *c, int *status)
{
    cholmod_sparse *A;
    int *Ap, *Ai;
    int j, p, nnz, base = colptr[0];

    *status = C2D_CHOL_BAD_ARGUMENT;
    if (base < 1 || offset < 0) return NULL;
    for (j = 0; j < n; j++)
    {
        if (colptr[j + 1] < colptr[j]) return NULL;
    }
    nnz = colptr[n] - base;
    for (p = 0; p < nnz; p++)
    {
        if (rowind[p] - offset < 1 || rowind[p] - offset > n) return NULL;
    }
    A = cholmod_allocate_sparse((size_t) n, (size_t) n, (size_t) (nnz > 0 ? nnz : 1),
                                1, 1, 1, CHOLMOD_PATTERN, c);
    if (A == NULL)
    {
        *status = c->status;
        return NULL;
    }
    Ap = A->p;
    Ai = A->i;
    for (j = 0; j <= n; j++) Ap[j] = colptr[j] - base;
    for (p = 0; p < nnz; p++) Ai[p] = rowind[p] - offset - 1;
    *status = CHOLMOD_OK;
    return A;
}


/* Analysis with the block last: the given permutation, not postordered (a
 * postorder of the elimination tree could move the block away from the last
 * pivots).  Returns the symbolic factor or NULL with the status in *status. */
static cholmod_factor *analyze_block_last(cholmod_sparse *A, int nlast, const int *last,
                                          const int *group, int method, cholmod_common *c, int *status)
{
    size_t n = A->ncol;
    int *perm = cholmod_malloc(n, sizeof(int), c);
    cholmod_factor *L = NULL;

    if (perm == NULL)
    {
        *status = (c->status < 0) ? c->status : CHOLMOD_OUT_OF_MEMORY;
        return NULL;
    }
    *status = c2d_order_block_last(A, nlast, last, group, method, perm, c);
    if (*status == CHOLMOD_OK)
    {
        c->nmethods = 1;
        c->method[0].ordering = CHOLMOD_GIVEN;
        c->postorder = 0;
        L = cholmod_analyze_p(A, perm, NULL, 0, c);
        c->postorder = 1;
        if (L == NULL) *status = (c->status < 0) ? c->status : CHOLMOD_INVALID;
    }
    cholmod_free(n, sizeof(int), perm, c);
    return L;
}

/* The ordering and symbolic analysis of the pattern A into h->L; returns the
 * status. */
static int analyze_pattern(struct c2d_chol *h, cholmod_sparse *A, int nlast, const int *last,
                           const int *group)
{
    cholmod_common *c = &h->common;
    int n = (int) A->ncol;
    int k, status = CHOLMOD_OK;
    double t0;
    const int *Perm;

    t0 = SuiteSparse_time();
    h->grouped = group != NULL;
    if (nlast == 0 && group != NULL)
    {
        /* the groups' graph ordered (postordered), then the given order */
        int *gz = cholmod_malloc((size_t) n, sizeof(int), c);
        int *perm = cholmod_malloc((size_t) n, sizeof(int), c);
        if (gz == NULL || perm == NULL)
        {
            status = (c->status < 0) ? c->status : CHOLMOD_OUT_OF_MEMORY;
        }
        else
        {
            for (k = 0; k < n; k++) gz[k] = group[k] - 1;
            status = c2d_order_groups(A, gz, h->method, NULL, perm, c);
            if (status == CHOLMOD_OK)
            {
                c->nmethods = 1;
                c->method[0].ordering = CHOLMOD_GIVEN;
                c->postorder = 0;                       /* perm is postordered already */
                h->L = cholmod_analyze_p(A, perm, NULL, 0, c);
                c->postorder = 1;
                if (h->L == NULL) status = (c->status < 0) ? c->status : CHOLMOD_INVALID;
            }
        }
        cholmod_free((size_t) n, sizeof(int), gz, c);
        cholmod_free((size_t) n, sizeof(int), perm, c);
    }
    else if (nlast == 0)
    {
        c->nmethods = 1;
        c->method[0].ordering = (h->method == C2D_ORDER_AMD) ? CHOLMOD_AMD : CHOLMOD_METIS;
        c->postorder = 1;
        h->L = (h->method == C2D_ORDER_METIS) ? c2d_analyze_metis(A, c) : cholmod_analyze(A, c);
        if (h->L == NULL) status = (c->status < 0) ? c->status : CHOLMOD_INVALID;
    }
    else
    {
        h->L = analyze_block_last(A, nlast, last, group, h->method, c, &status);
    }
    h->time_analyze = SuiteSparse_time() - t0;
    if (h->L == NULL) return status;
    h->n = n;
    h->nlast = nlast;

    /* verify that the block sits at pivots n-nlast..n-1, in the given order */
    Perm = h->L->Perm;
    for (k = 0; k < nlast; k++)
    {
        if (Perm[n - nlast + k] != last[k] - 1) return C2D_CHOL_BLOCK_MOVED;
    }
    return CHOLMOD_OK;
}

/* The numeric factorization of A (values, the pattern analyzed) into h->L;
 * returns the status. */
static int factorize_numeric(struct c2d_chol *h, cholmod_sparse *A, const double *adiag)
{
    cholmod_common *c = &h->common;
    int n = (int) A->ncol;
    int status;
    double t1;
    const int *Perm = h->L->Perm;

    /* numeric factorization P A P' = L L' */
    t1 = SuiteSparse_time();
    cholmod_factorize(A, h->L, c);
    h->time_factorize = SuiteSparse_time() - t1;
    status = c->status;

    /* "not positive definite" is a warning: CHOLMOD returns TRUE, sets
     * Common->status = CHOLMOD_NOT_POSDEF and L->minor < n.  Check both. */
    if (status >= CHOLMOD_OK && h->L->minor < (size_t) n)
    {
        h->minor_column = (int) h->L->minor + 1;
        h->minor_equation = Perm[h->L->minor] + 1;
        return (status == CHOLMOD_OK) ? CHOLMOD_NOT_POSDEF : status;
    }
    if (status != CHOLMOD_OK) return status;
    if (!h->L->is_ll || !h->L->is_super || h->L->xtype != CHOLMOD_REAL)
    {
        return C2D_CHOL_NOT_SUPER_LL; /* LDL' or simplicial: not what was asked */
    }
    h->valid = 1;
    c2d_scan_pivots(h->L, adiag, &h->pivot_ratio, &h->pivot_column, &h->pivot_equation);
    return CHOLMOD_OK;
}

/* Supernodal amalgamation (CHOLMOD's nrelax and zrelax: how many explicit
 * zeros a supernode may take to merge with its parent).  CHOLMOD's numeric
 * factorization opens OpenMP regions per supernode and per update between
 * two supernodes, and libgomp ends each region with a futex system call
 * even on a team of one thread (its barrier's wake): in a small factor
 * these calls, not the arithmetic, take most of the time.  Up to relax_max
 * rows a factor takes larger supernodes, fewer regions for some more
 * memory in L, which is small there; above it CHOLMOD's defaults keep L's
 * memory (doc/performance.md, "A small run's fixed costs"). */
static const int relax_max = 50000;

static void set_relaxation(cholmod_common *c, int n)
{
    static const size_t nrelax_small[3] = {16, 48, 128}, nrelax_default[3] = {4, 16, 48};
    static const double zrelax_small[3] = {0.8, 0.2, 0.1}, zrelax_default[3] = {0.8, 0.1, 0.05};
    int small = n <= relax_max, i;
    for (i = 0; i < 3; i++)
    {
        c->nrelax[i] = small ? nrelax_small[i] : nrelax_default[i];
        c->zrelax[i] = small ? zrelax_small[i] : zrelax_default[i];
    }
}

int c2d_chol_analyze(void *handle, int n, const int *colptr, const int *rowind, int offset,
                     int nlast, const int *last, int ngroup, const int *group)
{
    struct c2d_chol *h = handle;
    cholmod_common *c;
    cholmod_sparse *A;
    int status;

    if (h == NULL) return C2D_CHOL_NO_HANDLE;
    c = &h->common;
    clear_factor(h);
    if (n < 1 || nlast < 0 || nlast > n || (nlast > 0 && last == NULL))
    {
        return C2D_CHOL_BAD_ARGUMENT;
    }
    set_relaxation(c, n);
    A = c2d_copy_pattern(n, colptr, rowind, offset, c, &status);
    if (A != NULL)
    {
        status = analyze_pattern(h, A, nlast, last, ngroup > 0 ? group : NULL);
        cholmod_free_sparse(&A, c);
    }
    if (status != CHOLMOD_OK && h->L != NULL) cholmod_free_factor(&h->L, c);
    return status;
}

int c2d_chol_factorize_values(void *handle, int n, const int *colptr, const int *rowind, int offset,
                              const double *val)
{
    struct c2d_chol *h = handle;
    cholmod_common *c;
    cholmod_sparse *A;
    double *adiag;
    int status;

    if (h == NULL) return C2D_CHOL_NO_HANDLE;
    if (h->L == NULL) return C2D_CHOL_NO_FACTOR;
    if (n != h->n || val == NULL) return C2D_CHOL_BAD_ARGUMENT;
    /* a factor of earlier values is factorized again on the same analysis
     * (CHOLMOD refactorizes a numeric supernodal L in place): Newton's
     * tangents keep one pattern */
    h->valid = 0;
    c = &h->common;
    adiag = cholmod_malloc((size_t) n, sizeof(double), c);
    if (adiag == NULL) return (c->status < 0) ? c->status : CHOLMOD_OUT_OF_MEMORY;
    /* the 0-based pattern is copied; the values are the caller's own array,
     * lent to CHOLMOD for the factorization (read only) and taken back
     * before the matrix is freed: no second copy of K's values */
    A = c2d_copy_pattern(n, colptr, rowind, offset, c, &status);
    if (A != NULL)
    {
        int j, p;
        for (j = 0; j < n; j++)
        {
            adiag[j] = 0.0;
            for (p = colptr[j] - colptr[0]; p < colptr[j + 1] - colptr[0]; p++)
            {
                if (rowind[p] - offset - 1 == j) adiag[j] += val[p];
            }
        }
        A->x = (void *) val;
        A->xtype = CHOLMOD_REAL;
        status = factorize_numeric(h, A, adiag);
        A->x = NULL;
        A->xtype = CHOLMOD_PATTERN;
        cholmod_free_sparse(&A, c);
    }
    cholmod_free((size_t) n, sizeof(double), adiag, c);
    if (status != CHOLMOD_OK) h->valid = 0;
    return status;
}

void c2d_chol_minor(const void *handle, int *column, int *equation)
{
    const struct c2d_chol *h = handle;
    *column = (h == NULL) ? 0 : h->minor_column;
    *equation = (h == NULL) ? 0 : h->minor_equation;
}

void c2d_chol_stats(const void *handle, int64_t *lnz, double *flops, int64_t *memory_peak,
                    double *time_analyze, double *time_factorize)
{
    const struct c2d_chol *h = handle;
    if (h == NULL)
    {
        *lnz = 0;
        *flops = 0.0;
        *memory_peak = 0;
        *time_analyze = 0.0;
        *time_factorize = 0.0;
        return;
    }
    *lnz = (int64_t) h->common.lnz;
    *flops = h->common.fl;
    *memory_peak = (int64_t) h->common.memory_usage;
    *time_analyze = h->time_analyze;
    *time_factorize = h->time_factorize;
}

/* A code and its name, for the lookups of c2d_chol_name. */
struct code_name
{
    int code;
    const char *name;
};
#define CODE_NAME(code) {code, #code}

static const struct code_name cholmod_orderings[] = {
    {CHOLMOD_NATURAL, "natural"}, {CHOLMOD_GIVEN, "given"}, {CHOLMOD_AMD, "amd"},
    {CHOLMOD_METIS, "metis"}, {CHOLMOD_NESDIS, "nesdis"}, {CHOLMOD_COLAMD, "colamd"},
    {CHOLMOD_POSTORDERED, "postordered"}};

static const struct code_name status_codes[] = {
    CODE_NAME(CHOLMOD_OK), CODE_NAME(CHOLMOD_NOT_INSTALLED), CODE_NAME(CHOLMOD_OUT_OF_MEMORY),
    CODE_NAME(CHOLMOD_TOO_LARGE), CODE_NAME(CHOLMOD_INVALID), CODE_NAME(CHOLMOD_GPU_PROBLEM),
    CODE_NAME(CHOLMOD_NOT_POSDEF), CODE_NAME(CHOLMOD_DSMALL), CODE_NAME(C2D_CHOL_NO_HANDLE),
    CODE_NAME(C2D_CHOL_NO_FACTOR), CODE_NAME(C2D_CHOL_NOT_SUPER_LL), CODE_NAME(C2D_CHOL_BLOCK_MOVED),
    CODE_NAME(C2D_CHOL_BAD_ARGUMENT)};

/* The name of code in table[0..n-1], or `unknown` when it is not there. */
static const char *name_of(const struct code_name *table, size_t n, int code, const char *unknown)
{
    size_t k;
    for (k = 0; k < n; k++)
    {
        if (table[k].code == code) return table[k].name;
    }
    return unknown;
}

/* The name of the ordering of h's factor: ours when we ordered, else CHOLMOD's. */
static const char *ordering_name(const struct c2d_chol *h)
{
    int amd;
    if (h == NULL || h->L == NULL) return "none";
    amd = h->method == C2D_ORDER_AMD;
    if (h->nlast > 0 && h->grouped) return amd ? "amd(nodes)+last" : "metis(nodes)+last";
    if (h->nlast > 0) return amd ? "amd+last" : "metis+last";
    if (h->grouped) return amd ? "amd(nodes)" : "metis(nodes)";
    return name_of(cholmod_orderings, sizeof(cholmod_orderings) / sizeof(cholmod_orderings[0]),
                   h->L->ordering, "unknown");
}

void c2d_chol_name(const void *handle, int what, int status, char *buf, int len)
{
    const char *name = "unknown";
    if (what == C2D_NAME_ORDERING) name = ordering_name(handle);
    if (what == C2D_NAME_STATUS)
    {
        name = name_of(status_codes, sizeof(status_codes) / sizeof(status_codes[0]), status, "unknown status");
    }
    copy_name(name, buf, len);
}

/* x = the systems sys[0], sys[1], ... applied in turn to b (nrhs columns). */
static int solve_steps(struct c2d_chol *h, int n, int nrhs, const double *b, double *x, const int *sys, int nsys)
{
    cholmod_dense B, *cur, *next;
    int k, status;

    if (h == NULL) return C2D_CHOL_NO_HANDLE;
    if (!h->valid || h->L == NULL) return C2D_CHOL_NO_FACTOR;
    if (n != h->n || nrhs < 0) return C2D_CHOL_BAD_ARGUMENT;
    if (nrhs == 0) return CHOLMOD_OK;

    /* B: a header over the caller's array, not a copy (only read) */
    memset(&B, 0, sizeof(B));
    B.nrow = (size_t) n;
    B.ncol = (size_t) nrhs;
    B.nzmax = (size_t) n * (size_t) nrhs;
    B.d = (size_t) n;
    B.x = (void *) b;
    B.z = NULL;
    B.xtype = CHOLMOD_REAL;
    B.dtype = CHOLMOD_DOUBLE;

    cur = &B;
    for (k = 0; k < nsys; k++)
    {
        next = cholmod_solve(sys[k], h->L, cur, &h->common);
        if (cur != &B) cholmod_free_dense(&cur, &h->common);
        if (next == NULL)
        {
            status = h->common.status;
            return (status < 0) ? status : CHOLMOD_INVALID;
        }
        cur = next;
    }
    memcpy(x, cur->x, (size_t) n * (size_t) nrhs * sizeof(double));
    cholmod_free_dense(&cur, &h->common);
    return CHOLMOD_OK;
}

int c2d_chol_solve_half(void *handle, int half, int n, int nrhs, const double *b, double *x)
{
    static const int forward[2] = {CHOLMOD_P, CHOLMOD_L};   /* y = L \ (P b) */
    static const int backward[2] = {CHOLMOD_Lt, CHOLMOD_Pt}; /* x = P' (L' \ y) */
    static const int whole[1] = {CHOLMOD_A};
    if (half == C2D_SOLVE_WHOLE) return solve_steps(handle, n, nrhs, b, x, whole, 1);
    if (half == C2D_SOLVE_FORWARD) return solve_steps(handle, n, nrhs, b, x, forward, 2);
    if (half == C2D_SOLVE_BACKWARD) return solve_steps(handle, n, nrhs, b, x, backward, 2);
    return C2D_CHOL_BAD_ARGUMENT;
}

