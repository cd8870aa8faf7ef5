/* cholmod_handle.h: the handle behind the opaque pointer of cholmod_factor.h,
 * shared by the files of the C layer that read it (src/linalg/cholmod_factor.c, which
 * owns it, and src/linalg/factor_inspection.c).  Not for Fortran.
 *
 * Ownership: a handle is created by c2d_chol_create and freed by
 * c2d_chol_destroy; it owns its cholmod_common and the factor L.  Every
 * CHOLMOD allocation goes through the handle's common, so
 * Common->memory_usage is the peak memory of this factor's whole life
 * (ordering, analysis, factor, solves). */
#ifndef CONTACT2D_CHOLMOD_HANDLE_H
#define CONTACT2D_CHOLMOD_HANDLE_H

#include "cholmod.h"

/* One factorization and the CHOLMOD workspace that built it. */
struct c2d_chol
{
    cholmod_common common;  /* CHOLMOD parameters, statistics, workspace */
    cholmod_factor *L;      /* the factor of the last factorization, or NULL */
    int valid;              /* 1 when L holds a complete numeric LL' */
    int n;                  /* order of A */
    int nlast;              /* size of the block ordered last (0: none) */
    int minor_column;       /* 1-based failing pivot, 0 if none */
    int minor_equation;     /* 1-based dof at that pivot, 0 if none */
    double pivot_ratio;     /* min_k L(k,k)^2 / A(p_k,p_k) */
    int pivot_column;       /* 1-based pivot where the minimum occurs */
    int pivot_equation;     /* 1-based dof at that pivot */
    double time_analyze;    /* wall seconds: ordering and symbolic analysis */
    double time_factorize;  /* wall seconds: numeric factorization */
    int grouped;            /* 1 when the graph of dof groups (nodes) was ordered */
    int method;             /* C2D_ORDER_METIS (nested dissection) or C2D_ORDER_AMD */
};

/* The pattern of A as a CHOLMOD matrix (0-based, upper triangle, no values):
 * what the ordering and the analysis read.  colptr and rowind may be the
 * columns of a diagonal block of a larger matrix: the entries are
 * rowind[0..colptr[n]-colptr[0]-1], their rows rowind - offset (see
 * c2d_chol_analyze).  NULL with *status set when the column pointers or row
 * indices are out of range or CHOLMOD is out of memory. */
cholmod_sparse *c2d_copy_pattern(int n, const int *colptr, const int *rowind, int offset,
                                 cholmod_common *c, int *status);
#endif /* CONTACT2D_CHOLMOD_HANDLE_H */
