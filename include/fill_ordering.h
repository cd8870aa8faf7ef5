/* fill_ordering.h: the fill-reducing ordering of a stiffness pattern
 * (src/linalg/fill_ordering.c), for the analysis of src/linalg/cholmod_factor.c.
 *
 * The ordering works on the graph of dof groups (the mesh nodes: a node's
 * dofs share their neighbours), a quarter of the edges of the dof graph, and
 * expands it to the dofs, each group's dofs one after the other; METIS nested
 * dissection (its first level taken apart into two OpenMP tasks on graphs of
 * SPLIT_MIN_GROUPS groups or more, doc/performance.md "METIS's first level on
 * two threads"), or AMD, or CAMD with a block constrained last.  Every METIS
 * call runs under C2D_METIS_CALL (include/metis_guard.h).
 *
 * Index convention: 0-based on the CHOLMOD objects, 1-based for `last` and
 * `group` as the Fortran side gives them. */
#ifndef CONTACT2D_FILL_ORDERING_H
#define CONTACT2D_FILL_ORDERING_H

#include "cholmod.h"

/* The ordering of the graph of dof groups of S (symmetric pattern, upper
 * triangle, 0-based, n x n), expanded to the dofs and postordered by the
 * elimination tree.
 *   group  [n] group of each column, 0 <= group < n
 *   method C2D_ORDER_METIS or C2D_ORDER_AMD
 *   cset   [n] or NULL: with AMD, a constraint set per column (0 or 1, the
 *          same within a group): CAMD orders set 0 before set 1
 *   perm   [n] out: perm[k] = column at pivot k
 * Returns CHOLMOD_OK, C2D_CHOL_BAD_ARGUMENT or CHOLMOD's error status. */
int c2d_order_groups(cholmod_sparse *S, const int *group, int method, const int *cset, int *perm,
                     cholmod_common *c);

/* perm[n] = [order of the other dofs, last(:)] (0-based): the order of the
 * submatrix on the other dofs (METIS, or AMD; on the node graph when group
 * is not NULL, then with AMD the CAMD order of the whole graph with `last`
 * constrained to come last).  last: [nlast] 1-based; group: [n] 1-based or
 * NULL.  Returns CHOLMOD_OK, C2D_CHOL_BAD_ARGUMENT (a dof of `last` out of
 * range or repeated) or CHOLMOD's error status. */
int c2d_order_block_last(const cholmod_sparse *A, int nlast, const int *last, const int *group,
                         int method, int *perm, cholmod_common *c);

/* cholmod_analyze with CHOLMOD's own METIS ordering, under C2D_METIS_CALL. */
cholmod_factor *c2d_analyze_metis(cholmod_sparse *A, cholmod_common *c);

#endif /* CONTACT2D_FILL_ORDERING_H */
