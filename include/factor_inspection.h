/* factor_inspection.h: reading a supernodal factor (src/linalg/factor_inspection.c):
 * its pivots, and its trailing block L_cc when a block of dofs was ordered
 * last (include/cholmod_factor.h).  Indices 1-based, as Fortran holds them.
 *
 * Return codes as cholmod_factor.h: 0, C2D_CHOL_NO_HANDLE, C2D_CHOL_NO_FACTOR,
 * C2D_CHOL_NOT_SUPER_LL, C2D_CHOL_BLOCK_MOVED or C2D_CHOL_BAD_ARGUMENT. */
#ifndef CONTACT2D_FACTOR_INSPECTION_H
#define CONTACT2D_FACTOR_INSPECTION_H

#include "cholmod.h"

/* After a successful factorization of L (supernodal LL', P A P' = L L'):
 * *ratio = min_k L(k,k)^2 / A(p_k,p_k) over the pivots k (p_k the dof at
 * pivot k; adiag[n] the diagonal of A), *column = the 1-based pivot of the
 * minimum, *equation = its 1-based dof; *ratio is NaN at the first
 * non-finite diagonal of L, if any.  For the C layer. */
void c2d_scan_pivots(const cholmod_factor *L, const double *adiag, double *ratio, int *column, int *equation);

/* The smallest pivot ratio of the handle's factor (c2d_scan_pivots): the
 * fraction of a dof's own stiffness left after eliminating the dofs before
 * it.  *ratio = 0 and *column = *equation = 0 when no factor is held. */
void c2d_chol_min_pivot_ratio(const void *h, double *ratio, int *column, int *equation);

/* The diagonal sub-block of the trailing nlast-by-nlast block L_cc of L
 * (pivots n-nlast+1..n, i.e. the dofs `last` in the order given to the
 * analysis) on its rows and columns first..first+count-1 (1-based within
 * L_cc), written dense and column-major into lcc[count*count], zero above the
 * diagonal; first = 1, count = nlast gives the whole L_cc.  Read directly from
 * the supernodes that hold those columns. */
int c2d_chol_trailing_range(const void *h, int nlast, int first, int count, double *lcc);

/* The end of the diagonal block of L_cc that starts at `first` (1-based):
 * *last_row = the smallest e >= first with L_cc(e+1:, first:e) = 0 (exact
 * zeros: K couples no two bodies, so L_cc has a diagonal block per body). */
int c2d_chol_trailing_block_end(const void *h, int nlast, int first, int *last_row);
#endif /* CONTACT2D_FACTOR_INSPECTION_H */
