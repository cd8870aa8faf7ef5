/* factor_inspection.c: reading a supernodal factor: the least pivot ratio
 * and the trailing block L_cc (see include/factor_inspection.h).
 *
 * Why in C: the supernodes (L->super, L->pi, L->px, L->s) are read against
 * the installed cholmod.h; through Fortran interoperable types their layout
 * would be fragile between CHOLMOD versions. */
#include <math.h>
#include <string.h>

#include "cholmod.h"
#include "cholmod_factor.h"
#include "cholmod_handle.h"
#include "factor_inspection.h"

/* After a successful factorization: min_k L(k,k)^2 / A(p_k,p_k), and the
 * first non-finite diagonal of L if any (then the ratio is NaN there). */
void c2d_scan_pivots(const cholmod_factor *L, const double *adiag, double *ratio, int *column, int *equation)
{
    const int *Super = L->super, *Lpi = L->pi, *Lpx = L->px, *Perm = L->Perm;
    const double *Lx = L->x;
    int s, k, k1, k2, nsrow;
    double lkk, r;

    *ratio = HUGE_VAL;
    *column = 0;
    *equation = 0;
    for (s = 0; s < (int) L->nsuper; s++)
    {
        k1 = Super[s];
        k2 = Super[s + 1];
        nsrow = Lpi[s + 1] - Lpi[s];
        for (k = k1; k < k2; k++)
        {
            lkk = Lx[Lpx[s] + (size_t) (k - k1) * (size_t) nsrow + (size_t) (k - k1)];
            if (!isfinite(lkk))
            {
                *ratio = lkk - lkk; /* NaN */
                *column = k + 1;
                *equation = Perm[k] + 1;
                return;
            }
            r = (adiag[Perm[k]] > 0.0) ? lkk * lkk / adiag[Perm[k]] : 0.0;
            if (r < *ratio)
            {
                *ratio = r;
                *column = k + 1;
                *equation = Perm[k] + 1;
            }
        }
    }
}


void c2d_chol_min_pivot_ratio(const void *handle, double *ratio, int *column, int *equation)
{
    const struct c2d_chol *h = handle;
    if (h == NULL || !h->valid)
    {
        *ratio = 0.0;
        *column = 0;
        *equation = 0;
        return;
    }
    *ratio = h->pivot_ratio;
    *column = h->pivot_column;
    *equation = h->pivot_equation;
}

/* Checks shared by the trailing-block readers: the factor is supernodal LL'
 * with `last` (nlast dofs) at its last pivots, and first..first+count-1
 * (1-based) is a range of L_cc; *start = the pivot of its first row
 * (0-based). */
static int trailing_start(const struct c2d_chol *h, int nlast, int first, int count, int *start)
{
    const cholmod_factor *L;
    if (h == NULL) return C2D_CHOL_NO_HANDLE;
    if (!h->valid || h->L == NULL) return C2D_CHOL_NO_FACTOR;
    L = h->L;
    if (!L->is_ll || !L->is_super || L->xtype != CHOLMOD_REAL) return C2D_CHOL_NOT_SUPER_LL;
    if (nlast < 1 || nlast != h->nlast) return C2D_CHOL_BAD_ARGUMENT;
    /* the factorization verified that Perm ends with `last`, in order; a
     * factor analyzed with any other ordering cannot hold the block there */
    if (L->ordering != CHOLMOD_GIVEN) return C2D_CHOL_BLOCK_MOVED;
    if (first < 1 || count < 1 || first - 1 + count > nlast) return C2D_CHOL_BAD_ARGUMENT;
    *start = h->n - nlast + first - 1;
    return CHOLMOD_OK;
}

/* The supernode that holds pivot j (0-based): Super is increasing. */
static int supernode_of(const cholmod_factor *L, int j)
{
    const int *Super = L->super;
    int lo = 0, hi = (int) L->nsuper - 1, mid;
    while (lo < hi)
    {
        mid = (lo + hi + 1) / 2;
        if (Super[mid] <= j) lo = mid; else hi = mid - 1;
    }
    return lo;
}

/* Column j of the supernodal L from its diagonal down: rows[0..len-1]
 * (rows[0] = j) and vals[0..len-1]; returns len.  Supernode s holds columns
 * k1..k2-1 of L as a dense nsrow-by-(k2-k1) column-major block at
 * Lx + Lpx[s]; its row indices are Ls[Lpi[s]..], the first k2-k1 of them
 * being k1..k2-1. */
static int column_below(const cholmod_factor *L, int j, const int **rows, const double **vals)
{
    const int *Super = L->super, *Lpi = L->pi, *Lpx = L->px, *Ls = L->s;
    int s = supernode_of(L, j);
    int d = j - Super[s];
    int nsrow = Lpi[s + 1] - Lpi[s];
    *rows = Ls + Lpi[s] + d;
    *vals = (const double *) L->x + Lpx[s] + (size_t) d * (size_t) nsrow + (size_t) d;
    return nsrow - d;
}

int c2d_chol_trailing_range(const void *handle, int nlast, int first, int count, double *lcc)
{
    const struct c2d_chol *h = handle;
    const int *rows;
    const double *vals;
    int b0, b1, j, q, len;
    int status = trailing_start(h, nlast, first, count, &b0);

    if (status != CHOLMOD_OK) return status;
    b1 = b0 + count; /* the range: pivots b0..b1-1 (0-based) */
    memset(lcc, 0, (size_t) count * (size_t) count * sizeof(double));
    for (j = b0; j < b1; j++)
    {
        len = column_below(h->L, j, &rows, &vals);
        for (q = 0; q < len; q++)
        {
            if (rows[q] < b1) lcc[(size_t) (j - b0) * (size_t) count + (size_t) (rows[q] - b0)] = vals[q];
        }
    }
    return CHOLMOD_OK;
}

int c2d_chol_trailing_block_end(const void *handle, int nlast, int first, int *last_row)
{
    const struct c2d_chol *h = handle;
    const int *rows;
    const double *vals;
    int b0, e, j, q, len;
    int status = trailing_start(h, nlast, first, 1, &b0);

    if (status != CHOLMOD_OK) return status;
    e = b0; /* the block ends at pivot e so far */
    for (j = b0; j <= e; j++)
    {
        len = column_below(h->L, j, &rows, &vals);
        for (q = 1; q < len; q++) /* the non-zeros below the diagonal */
        {
            if (rows[q] > e && vals[q] != 0.0) e = rows[q];
        }
    }
    *last_row = e - (h->n - nlast) + 1;
    return CHOLMOD_OK;
}
