/* cholmod_factor.h: the CHOLMOD handle and its factor (src/linalg/cholmod_factor.c).
 *
 * One handle owns one cholmod_common and at most one factor L of a symmetric
 * positive definite matrix A (upper triangle given, compressed columns).  The
 * Fortran side sees the handle as an opaque type(c_ptr); src/linalg/cholmod_binding.f90
 * holds the matching bind(c) interfaces and src/linalg/sparse_cholesky.f90 the API.
 *
 * The C layer, one job per file: this one (handle, analysis, numeric
 * factorization, solves, statistics), include/fill_ordering.h (the
 * fill-reducing ordering of the node graph and the top separator),
 * include/factor_inspection.h (reading the factor: pivots, L_cc), and
 * include/runtime_tuning.h (process-wide settings made at start-up).
 *
 * Index convention: every index that crosses this interface is 1-based, as
 * Fortran holds it (column pointers, row indices, dofs, equation numbers).
 *
 * Factorization: supernodal LL' = P A P' with P from METIS, or, when a block of
 * nlast dofs is given, P = [METIS order of the remaining dofs, the given block]
 * with no postordering, so that the block occupies the last nlast pivots.
 *
 * Return codes: CHOLMOD's own status (CHOLMOD_OK = 0, warnings > 0, errors < 0)
 * or one of the C2D_CHOL_* codes below (all <= -100).
 */
#ifndef CONTACT2D_CHOLMOD_FACTOR_H
#define CONTACT2D_CHOLMOD_FACTOR_H

#include <stdint.h>

#define C2D_CHOL_NO_HANDLE      (-100) /* handle is NULL (not created) */
#define C2D_CHOL_NO_FACTOR      (-101) /* no valid numeric factor held */
#define C2D_CHOL_NOT_SUPER_LL   (-102) /* factor is not stored as supernodal LL' */
#define C2D_CHOL_BLOCK_MOVED    (-103) /* the last block is not at the last pivots */
#define C2D_CHOL_BAD_ARGUMENT   (-104) /* inconsistent argument (size, index range) */

/* Fill-reducing orderings (c2d_chol_set_ordering) */
#define C2D_ORDER_METIS 0 /* METIS nested dissection (the default) */
#define C2D_ORDER_AMD   1 /* approximate minimum degree (AMD): a cheaper
                             ordering, more fill on large meshes */

/* The codes of this interface as variables, for callers that cannot read a C
 * header (src/linalg/cholmod_binding.f90 binds them by these names): the
 * status codes, CHOLMOD's (c2d_cholmod_*, their values taken from cholmod.h
 * where they are defined) and this layer's (c2d_chol_*, the C2D_CHOL_* above),
 * and the selectors (C2D_ORDER_*, C2D_NAME_* and C2D_SOLVE_* below).  Written
 * once, in cholmod_factor.c, so that no copy of a value can drift from the
 * library's or this header's. */
extern const int c2d_cholmod_ok, c2d_cholmod_not_posdef, c2d_cholmod_out_of_memory, c2d_cholmod_too_large;
extern const int c2d_chol_no_handle, c2d_chol_no_factor, c2d_chol_not_super_ll, c2d_chol_block_moved,
    c2d_chol_bad_argument;
extern const int c2d_order_metis, c2d_order_amd, c2d_name_ordering, c2d_name_status, c2d_solve_whole,
    c2d_solve_forward, c2d_solve_backward;

/* New handle with contact2d's CHOLMOD settings; NULL when out of memory. */
void *c2d_chol_create(void);

/* The ordering of the next analyses: C2D_ORDER_METIS or C2D_ORDER_AMD.
 * Returns CHOLMOD_OK, C2D_CHOL_NO_HANDLE or C2D_CHOL_BAD_ARGUMENT. */
int c2d_chol_set_ordering(void *h, int method);

/* Free the factor, finish the common and free the handle (NULL is a no-op). */
void c2d_chol_destroy(void *h);

/* The factorization A = P' L L' P in two halves, so that the values of A
 * can be assembled while the pattern is being ordered.
 *   n       order of A, n >= 1
 *   colptr  [n+1] 1-based column pointers
 *   rowind  [colptr[n]-colptr[0]] 1-based row indices, upper triangle, sorted per column
 *   val     [colptr[n]-colptr[0]] values
 *   nlast   number of dofs to order last, 0 <= nlast <= n
 *   last    [nlast] 1-based distinct dofs, in pivot order (NULL when nlast = 0)
 * c2d_chol_analyze: the ordering and symbolic analysis of the pattern (no
 * values; any previous factor is freed first), returns CHOLMOD_OK, a CHOLMOD
 * code or C2D_CHOL_BLOCK_MOVED when the analysis did not keep the given
 * block last.  c2d_chol_factorize_values: the numeric factorization of A
 * with the pattern analyzed (same n, colptr, rowind), returns CHOLMOD's
 * status: CHOLMOD_OK, CHOLMOD_NOT_POSDEF (then c2d_chol_minor tells where),
 * another CHOLMOD code, or C2D_CHOL_NO_FACTOR when no analysis is held.
 * group (ngroup = n; ngroup = 0 and group NULL: none): the 1-based group of
 * each dof, 1 <= group[i] <= n, e.g. its mesh node: METIS then
 * orders the graph of the groups (vertex weights = group sizes, a quarter of
 * the edges of the dof graph, about half the time) and each group's dofs
 * follow one another.  offset (>= 0): A may be a diagonal block of a larger
 * matrix B given by its own columns, colptr[0..n] (any colptr[0] >= 1),
 * rowind and val from the block's first entry, and its rows as B's rows:
 * A(i,j) = B(offset+i, offset+j); 0 for a whole matrix. */
int c2d_chol_analyze(void *h, int n, const int *colptr, const int *rowind, int offset,
                     int nlast, const int *last, int ngroup, const int *group);

int c2d_chol_factorize_values(void *h, int n, const int *colptr, const int *rowind, int offset,
                              const double *val);

/* Where the last factorization failed: *column = 1-based pivot (column of the
 * permuted matrix), *equation = the 1-based dof of A at that pivot; both 0 when
 * the factorization succeeded or no factor is held. */
void c2d_chol_minor(const void *h, int *column, int *equation);

/* Statistics of the last analysis and factorization: nnz(L) without the zeros
 * of supernodal amalgamation, flop count of LL', peak memory of CHOLMOD in
 * bytes, wall seconds of the analysis (ordering included) and of the numeric
 * factorization. */
void c2d_chol_stats(const void *h, int64_t *lnz, double *flops, int64_t *memory_peak,
                    double *time_analyze, double *time_factorize);

/* A name, NUL-terminated in buf[len]: with what = C2D_NAME_ORDERING the
 * ordering of h's factor ("metis", "metis+last", "amd(nodes)", ..., the name
 * CHOLMOD reports, "amd" when it fell back, or "none"; status unused); with
 * what = C2D_NAME_STATUS the name of the status code ("CHOLMOD_OUT_OF_MEMORY",
 * ..., or one of the C2D_CHOL_* names; h unused, may be NULL). */
#define C2D_NAME_ORDERING 0
#define C2D_NAME_STATUS 1
void c2d_chol_name(const void *h, int what, int status, char *buf, int len);

/* The solve or one half of it for nrhs dense columns (column-major, leading
 * dimension n), A = P' L L' P: C2D_SOLVE_WHOLE gives x = A^-1 b,
 * C2D_SOLVE_FORWARD y = L^-1 P b,
 * C2D_SOLVE_BACKWARD x = P' L'^-1 y; the two in turn are the whole solve.
 * With `last`, the trailing nlast entries of y belong to the block L_cc.
 * Returns CHOLMOD_OK, an error code or C2D_CHOL_BAD_ARGUMENT for another half. */
#define C2D_SOLVE_WHOLE 0
#define C2D_SOLVE_FORWARD 1
#define C2D_SOLVE_BACKWARD 2
int c2d_chol_solve_half(void *h, int half, int n, int nrhs, const double *b, double *x);

#endif /* CONTACT2D_CHOLMOD_FACTOR_H */
