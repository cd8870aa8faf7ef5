/* cholmod_shim.h: the C glue between contact2d and CHOLMOD.
 *
 * One handle owns one cholmod_common and at most one factor L of a symmetric
 * positive definite matrix A (upper triangle given, compressed columns).  The
 * Fortran side sees the handle as an opaque type(c_ptr); src/cholmod_binding.f90
 * holds the matching bind(c) interfaces and src/sparse_cholesky.f90 the API.
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
#ifndef CONTACT2D_CHOLMOD_SHIM_H
#define CONTACT2D_CHOLMOD_SHIM_H

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

/* New handle with contact2d's CHOLMOD settings; NULL when out of memory. */
void *c2d_chol_create(void);

/* The ordering of the next analyses: C2D_ORDER_METIS or C2D_ORDER_AMD.
 * Returns CHOLMOD_OK, C2D_CHOL_NO_HANDLE or C2D_CHOL_BAD_ARGUMENT. */
int c2d_chol_set_ordering(void *h, int method);

/* Free the factor, finish the common and free the handle (NULL is a no-op). */
void c2d_chol_destroy(void *h);

/* Analyze and factorize A = P' L L' P; any previous factor is freed first.
 *   n       order of A, n >= 1
 *   colptr  [n+1] 1-based column pointers, colptr[0] = 1
 *   rowind  [colptr[n]-1] 1-based row indices, upper triangle, sorted per column
 *   val     [colptr[n]-1] values
 *   nlast   number of dofs to order last, 0 <= nlast <= n
 *   last    [nlast] 1-based distinct dofs, in pivot order (NULL when nlast = 0)
 * Returns CHOLMOD's status: CHOLMOD_OK, CHOLMOD_NOT_POSDEF (then
 * c2d_chol_minor tells where), another CHOLMOD code, or C2D_CHOL_BLOCK_MOVED
 * when the analysis did not keep the given block last. */
int c2d_chol_factorize(void *h, int n, const int *colptr, const int *rowind,
                       const double *val, int nlast, const int *last);

/* The two halves of c2d_chol_factorize, so that the values of A can be
 * assembled while the pattern is being ordered.  c2d_chol_analyze: the
 * ordering and symbolic analysis of the pattern (arguments as above, no
 * values; any previous factor is freed first), returns CHOLMOD_OK, a CHOLMOD
 * code or C2D_CHOL_BLOCK_MOVED.  c2d_chol_factorize_values: the numeric
 * factorization of A with the pattern analyzed (same n, colptr, rowind),
 * returns as c2d_chol_factorize, or C2D_CHOL_NO_FACTOR when no analysis is
 * held.  group (ngroup = n; ngroup = 0 and group NULL: none): the 1-based
 * group of each dof, 1 <= group[i] <= n, e.g. its mesh node: METIS then
 * orders the graph of the groups (vertex weights = group sizes, a quarter of
 * the edges of the dof graph, about half the time) and each group's dofs
 * follow one another.  offset (>= 0): A may be a diagonal block of a larger
 * matrix B given by its own columns, colptr[0..n] (any colptr[0] >= 1),
 * rowind and val from the block's first entry, and its rows as B's rows:
 * A(i,j) = B(offset+i, offset+j); 0 for a whole matrix. */
int c2d_chol_analyze(void *h, int n, const int *colptr, const int *rowind, int offset,
                     int nlast, const int *last, int ngroup, const int *group);

/* The top vertex separator of the node graph of the pattern (the arguments
 * of c2d_chol_analyze, groups required) without its nlast < n dofs `last`:
 * side[k] = 0 or 1 (the two halves), 2 (the separator) or 3 (a dof of
 * `last`), k < n.  Returns CHOLMOD_OK, C2D_CHOL_BAD_ARGUMENT (also when the
 * graph has fewer than 3 nodes) or an error status. */
int c2d_chol_separator(void *h, int n, const int *colptr, const int *rowind, int offset,
                       int nlast, const int *last, const int *group, int *side);
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

/* Smallest ratio L(k,k)^2 / A(p_k,p_k) over the pivots k (p_k the dof at pivot
 * k): the fraction of a dof's own stiffness left after eliminating the dofs
 * before it.  *ratio = 0 and *column = *equation = 0 when no factor is held. */
void c2d_chol_min_pivot_ratio(const void *h, double *ratio, int *column, int *equation);

/* Name of the ordering used, NUL-terminated in buf[len]: "metis",
 * "metis+last", or the name CHOLMOD reports ("amd" when it fell back). */
void c2d_chol_ordering_name(const void *h, char *buf, int len);

/* Name of a status code, NUL-terminated in buf[len]: "CHOLMOD_OUT_OF_MEMORY",
 * ..., or one of the C2D_CHOL_* names. */
void c2d_chol_status_name(int status, char *buf, int len);

/* X = A \ B for nrhs dense columns (column-major, leading dimension n) in one
 * cholmod_solve call.  Returns CHOLMOD_OK or an error code. */
int c2d_chol_solve(void *h, int n, int nrhs, const double *b, double *x);

/* The solve or one half of it, A = P' L L' P: C2D_SOLVE_WHOLE gives x = A^-1 b,
 * C2D_SOLVE_FORWARD y = L^-1 P b,
 * C2D_SOLVE_BACKWARD x = P' L'^-1 y; the two in turn are c2d_chol_solve.
 * With `last`, the trailing nlast entries of y belong to the block L_cc.
 * Returns CHOLMOD_OK, an error code or C2D_CHOL_BAD_ARGUMENT for another half. */
#define C2D_SOLVE_WHOLE 0
#define C2D_SOLVE_FORWARD 1
#define C2D_SOLVE_BACKWARD 2
int c2d_chol_solve_half(void *h, int half, int n, int nrhs, const double *b, double *x);

/* The diagonal sub-block of the trailing nlast-by-nlast block L_cc of L
 * (pivots n-nlast+1..n, i.e. the dofs `last` in the order given to the
 * analysis) on its rows and columns first..first+count-1 (1-based within
 * L_cc), written dense and column-major into lcc[count*count], zero above the
 * diagonal; first = 1, count = nlast gives the whole L_cc.  Read directly from
 * the supernodes that hold those columns.  Returns 0, C2D_CHOL_NO_FACTOR,
 * C2D_CHOL_NOT_SUPER_LL, C2D_CHOL_BLOCK_MOVED or C2D_CHOL_BAD_ARGUMENT. */
int c2d_chol_trailing_range(const void *h, int nlast, int first, int count, double *lcc);

/* The end of the diagonal block of L_cc that starts at `first` (1-based):
 * *last_row = the smallest e >= first with L_cc(e+1:, first:e) = 0 (exact
 * zeros: K couples no two bodies, so L_cc has a diagonal block per body).
 * Returns as c2d_chol_trailing_range. */
int c2d_chol_trailing_block_end(const void *h, int nlast, int first, int *last_row);

/* Set OpenBLAS's thread count to n (n <= 0: leave it) and return the count
 * it had; 0 and nothing done when the BLAS is not OpenBLAS.  For factors
 * computed side by side on OpenMP threads, each with a BLAS of one thread. */
int c2d_blas_threads(int n);
/* Memory of the process, for parts factorized side by side on threads:
 * c2d_malloc_arenas lets glibc keep at most two malloc arenas (mallopt
 * M_ARENA_MAX), c2d_malloc_trim gives the free pages of every arena back
 * (malloc_trim). */
void c2d_malloc_arenas(void);
void c2d_malloc_trim(void);

/* METIS orderings side by side (src/metis_random.c): METIS draws its random
 * numbers from a sequence per thread, so an ordering does not depend on what
 * runs beside it.  c2d_metis_per_thread: 1 when the per-thread sequences are
 * in use, 0 when this METIS does not call them (then METIS calls run one at a
 * time).  Every METIS call of the shim sits between c2d_metis_begin and
 * c2d_metis_end. */
/* Bytes this process can still allocate (src/memory_limit.c): the address
 * space left under RLIMIT_AS and the machine's MemAvailable + SwapFree, the
 * smaller; -1 when neither is known. */
int64_t c2d_memory_available(void);
/* The address space left under RLIMIT_AS, -1 without a limit. */
int64_t c2d_address_space_left(void);
/* OpenBLAS under an address-space limit (src/blas_start.c): the thread count
 * to use (<= n), its buffers mapped; n and nothing done without a limit or
 * without OpenBLAS; 0 when not even one buffer fits.  *left: the address
 * space left (-1: no limit), *per_thread: the cost of a further thread,
 * *first: of the first buffer. */
int c2d_blas_start(int n, int64_t *left, int64_t *per_thread, int64_t *first);

int c2d_metis_per_thread(void);
void c2d_metis_begin(void);
void c2d_metis_end(void);
#endif /* CONTACT2D_CHOLMOD_SHIM_H */
