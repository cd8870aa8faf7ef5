/* cholmod_shim.c: the C glue between contact2d and CHOLMOD (see
 * include/cholmod_shim.h for the interface and its index convention).
 *
 * Ownership: a handle (struct c2d_chol) is created by c2d_chol_create and
 * freed by c2d_chol_destroy; it owns its cholmod_common and the factor L.
 * Nothing else here allocates memory that outlives a call.  Every CHOLMOD
 * allocation goes through the handle's common, so Common->memory_usage is
 * the peak memory of this factor's whole life (ordering, analysis, factor,
 * solves).
 *
 * Why a C layer at all: cholmod_common and cholmod_factor are large structs
 * whose layout changes between CHOLMOD versions; reading L->super, L->px,
 * L->Perm and the status fields is simple in C against the installed header,
 * and fragile through Fortran interoperable types.
 */
#include <malloc.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cholmod.h"
#include "metis.h"
#include "amd.h"
#include "camd.h"
#include "cholmod_shim.h"
#include "metis_guard.h"

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

/* Copy a C string into buf[len], truncated and NUL-terminated. */
/* The METIS calls of the shim, each in a frame of its own so that the jump
 * back from an abort inside METIS (include/metis_guard.h) finds nothing of
 * the caller's in registers.  Out of memory inside METIS: METIS_ERROR_MEMORY,
 * or NULL / FALSE with Common->status = CHOLMOD_OUT_OF_MEMORY. */
static int guarded_node_nd(idx_t *nv, idx_t *xadj, idx_t *adj, idx_t *vw, idx_t *perm, idx_t *iperm)
{
    int ok = METIS_ERROR_MEMORY;
    C2D_METIS_CALL(ok = METIS_NodeND(nv, xadj, adj, vw, NULL, perm, iperm), ok = METIS_ERROR_MEMORY);
    return ok;
}

static int guarded_separator(idx_t *nv, idx_t *xadj, idx_t *adj, idx_t *vw, idx_t *sepsize, idx_t *where)
{
    int ok = METIS_ERROR_MEMORY;
    C2D_METIS_CALL(ok = METIS_ComputeVertexSeparator(nv, xadj, adj, vw, NULL, sepsize, where),
                   ok = METIS_ERROR_MEMORY);
    return ok;
}

static int guarded_cholmod_metis(cholmod_sparse *S, int *perm, cholmod_common *c)
{
    int ok = 0;
    C2D_METIS_CALL(ok = cholmod_metis(S, NULL, 0, 1, perm, c), (ok = 0, c->status = CHOLMOD_OUT_OF_MEMORY));
    return ok;
}

/* cholmod_analyze orders with METIS when Common->method[0] says so */
static cholmod_factor *guarded_analyze(cholmod_sparse *A, cholmod_common *c)
{
    cholmod_factor *L = NULL;
    C2D_METIS_CALL(L = cholmod_analyze(A, c), (L = NULL, c->status = CHOLMOD_OUT_OF_MEMORY));
    return L;
}

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

void *c2d_chol_create(void)
{
    struct c2d_chol *h = malloc(sizeof(struct c2d_chol));
    if (h == NULL) return NULL;
    memset(h, 0, sizeof(struct c2d_chol));
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
static cholmod_sparse *copy_pattern(int n, const int *colptr, const int *rowind, int offset,
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

/* S = A(R,R) as a pattern (0-based, upper triangle), R the dofs with
 * map[i] >= 0; map is monotone on R, so S stays upper triangular. */
static cholmod_sparse *remaining_pattern(const cholmod_sparse *A, const int *map, int nr,
                                         cholmod_common *c)
{
    const int *Ap = A->p, *Ai = A->i;
    int n = (int) A->ncol;
    cholmod_sparse *S;
    int *Sp, *Si;
    int j, p, nzs = 0;

    for (j = 0; j < n; j++)
    {
        if (map[j] < 0) continue;
        for (p = Ap[j]; p < Ap[j + 1]; p++) nzs += (map[Ai[p]] >= 0);
    }
    S = cholmod_allocate_sparse((size_t) nr, (size_t) nr, (size_t) (nzs > 0 ? nzs : 1),
                                1, 1, 1, CHOLMOD_PATTERN, c);
    if (S == NULL) return NULL;
    Sp = S->p;
    Si = S->i;
    nzs = 0;
    for (j = 0; j < n; j++)
    {
        if (map[j] < 0) continue;
        Sp[map[j]] = nzs;
        for (p = Ap[j]; p < Ap[j + 1]; p++)
        {
            if (map[Ai[p]] >= 0) Si[nzs++] = map[Ai[p]];
        }
    }
    Sp[nr] = nzs;
    return S;
}


/* gperm (ng, the groups in elimination order) replaced by a postorder of
 * the elimination tree of the group graph (xadj, adj: symmetric, no self
 * loops) in that order.  The tree by Liu's algorithm with path compression,
 * the postorder by cholmod_postorder.  Returns CHOLMOD_OK or an error. */
static int postorder_groups(int ng, const int *xadj, const int *adj, int *gperm, cholmod_common *c)
{
    int *mem = cholmod_malloc(4 * (size_t) ng + 1, sizeof(int), c);
    int *inv, *parent, *ancestor, *post;
    int k, g, p, i, inext, status = CHOLMOD_OK;

    if (mem == NULL) return (c->status < 0) ? c->status : CHOLMOD_OUT_OF_MEMORY;
    inv = mem;
    parent = mem + ng;
    ancestor = mem + 2 * (size_t) ng;
    post = mem + 3 * (size_t) ng;
    for (k = 0; k < ng; k++) inv[gperm[k]] = k;
    for (k = 0; k < ng; k++)
    {
        parent[k] = -1;
        ancestor[k] = -1;
        g = gperm[k];
        for (p = xadj[g]; p < xadj[g + 1]; p++)
        {
            /* climb from each earlier neighbour to its root, compressing */
            for (i = inv[adj[p]]; i != -1 && i < k; i = inext)
            {
                inext = ancestor[i];
                ancestor[i] = k;
                if (inext == -1) parent[i] = k;
            }
        }
    }
    if (cholmod_postorder(parent, (size_t) ng, NULL, post, c) != ng)
    {
        status = (c->status < 0) ? c->status : CHOLMOD_INVALID;
    }
    else
    {
        for (k = 0; k < ng; k++) ancestor[k] = gperm[post[k]];
        for (k = 0; k < ng; k++) gperm[k] = ancestor[k];
    }
    cholmod_free(4 * (size_t) ng + 1, sizeof(int), mem, c);
    return status;
}

/* Graphs of at least this many groups are split at the first level of the
 * nested dissection, so that the two halves can be ordered side by side.  A
 * constant, not a thread count: the order is the same on any number of
 * threads. */
#define SPLIT_MIN_GROUPS 20000

/* METIS_NodeND of the side `side` of the top separator (where[g] == side):
 * the subgraph of its groups (loc[g]: the group's number in its side), its
 * order written as group numbers into order[0..m).  METIS's status. */
static int order_side(int ng, const int *xadj, const int *adj, const int *vw, const int *where,
                      const int *loc, int side, int m, int *order)
{
    int *sx, *sa, *sw, *sp, *sip, *glob;
    int g, p, k, nadj = 0, ok = METIS_OK;
    idx_t nv = m;

    if (m == 0) return METIS_OK;
    for (g = 0; g < ng; g++)
    {
        if (where[g] != side) continue;
        for (p = xadj[g]; p < xadj[g + 1]; p++) nadj += (where[adj[p]] == side);
    }
    sx = malloc(((size_t) m + 1) * sizeof(int));
    sa = malloc(((size_t) nadj + 1) * sizeof(int));
    sw = malloc((size_t) m * sizeof(int));
    sp = malloc((size_t) m * sizeof(int));
    sip = malloc((size_t) m * sizeof(int));
    glob = malloc((size_t) m * sizeof(int));
    if (sx == NULL || sa == NULL || sw == NULL || sp == NULL || sip == NULL || glob == NULL)
    {
        ok = METIS_ERROR_MEMORY;
    }
    else
    {
        sx[0] = 0;
        k = 0;
        for (g = 0; g < ng; g++)
        {
            if (where[g] != side) continue;
            for (p = xadj[g]; p < xadj[g + 1]; p++)
            {
                if (where[adj[p]] == side) sa[k++] = loc[adj[p]];
            }
            glob[loc[g]] = g;
            sw[loc[g]] = vw[g];
            sx[loc[g] + 1] = k;
        }
        if (m > 1)
        {
            ok = guarded_node_nd(&nv, sx, sa, sw, sp, sip);
        }
        else
        {
            sp[0] = 0;
        }
        if (ok == METIS_OK)
        {
            for (k = 0; k < m; k++) order[k] = glob[sp[k]];
        }
    }
    free(sx);
    free(sa);
    free(sw);
    free(sp);
    free(sip);
    free(glob);
    return ok;
}

/* METIS nested dissection of the group graph into gperm[0..ng).  From
 * SPLIT_MIN_GROUPS groups on, its first level is taken apart: the top vertex
 * separator (METIS_ComputeVertexSeparator), each side ordered by METIS_NodeND
 * as an OpenMP task (another thread of the caller's team takes one when it is
 * free), the separator last: the order METIS_NodeND builds, its two halves
 * side by side.  giperm: [ng] workspace.  METIS's status. */
static int nested_dissection(int ng, int *xadj, int *adj, int *vw, int *gperm, int *giperm)
{
    idx_t nv = ng, sepsize = 0;
    int *where, *loc;
    int g, k, m[3] = {0, 0, 0}, ok, ok0 = METIS_OK, ok1 = METIS_OK;

    if (ng < SPLIT_MIN_GROUPS)
    {
        ok = guarded_node_nd(&nv, xadj, adj, vw, gperm, giperm);
        return ok;
    }
    where = giperm;
    loc = malloc((size_t) ng * sizeof(int));
    if (loc == NULL) return METIS_ERROR_MEMORY;
    ok = guarded_separator(&nv, xadj, adj, vw, &sepsize, where);
    if (ok == METIS_OK)
    {
        for (g = 0; g < ng; g++) loc[g] = m[where[g]]++;
        #pragma omp task default(none) shared(ok1, ng, xadj, adj, vw, where, loc, m, gperm)
        ok1 = order_side(ng, xadj, adj, vw, where, loc, 1, m[1], gperm + m[0]);
        ok0 = order_side(ng, xadj, adj, vw, where, loc, 0, m[0], gperm);
        #pragma omp taskwait
        k = m[0] + m[1];
        for (g = 0; g < ng; g++)
        {
            if (where[g] == 2) gperm[k++] = g;
        }
        ok = (ok0 != METIS_OK) ? ok0 : ok1;
    }
    free(loc);
    return ok;
}

/* The fill-reducing ordering of the graph of dof groups (the nodes of the
 * mesh: the dofs of a node share their neighbours), expanded to the dofs and
 * postordered by the elimination tree: the ordering cholmod_metis (or
 * cholmod_amd) gives, from a graph with a quarter of the edges.
 *   S      symmetric pattern (upper triangle, 0-based), n x n
 *   group  [n] group of each column, 0 <= group < n
 *   method C2D_ORDER_METIS: METIS nested dissection (vertex weights: the
 *          group's dofs); C2D_ORDER_AMD: approximate minimum degree
 *   cset   [n] or NULL: with AMD, a constraint set per column (0 or 1, the
 *          same within a group): CAMD orders set 0 before set 1
 *   perm   [n] out: the permutation (perm[k] = column at pivot k) */
/* The graph of the dof groups of the pattern S (n x n, upper triangle):
 * compact group numbers gid[n] (in order of first appearance), the dofs of
 * each group (gptr[ng+1], gdof[n]), its dof count vw[ng] (METIS vertex
 * weights) and the graph xadj[ng+1], adj (g ~ h when a dof of g and a dof of
 * h are coupled; symmetric, no self loops, no repeats).  work holds them at
 * the offsets below (10 n + 2 ints), adj: 2 nnz(S) + 1 ints.  Returns
 * CHOLMOD_OK or C2D_CHOL_BAD_ARGUMENT (a group out of 0..n-1). */
#define GG_GID(w, n)    (w)
#define GG_GPTR(w, n)   ((w) + (n))
#define GG_GDOF(w, n)   ((w) + 2 * (n) + 1)
#define GG_DEG(w, n)    ((w) + 3 * (n) + 1)
#define GG_XADJ(w, n)   ((w) + 4 * (n) + 1)
#define GG_MARK(w, n)   ((w) + 5 * (n) + 2)
#define GG_VW(w, n)     ((w) + 6 * (n) + 2)
static int group_graph(const cholmod_sparse *S, const int *group, int *work, int *adj, int *ngroups)
{
    int n = (int) S->ncol;
    const int *Sp = S->p, *Si = S->i;
    int *gid = GG_GID(work, n), *gptr = GG_GPTR(work, n), *gdof = GG_GDOF(work, n);
    int *deg = GG_DEG(work, n), *xadj = GG_XADJ(work, n), *mark = GG_MARK(work, n), *vw = GG_VW(work, n);
    int i, j, p, g, h, ng, nadj;

    /* compact group numbers in order of first appearance */
    for (i = 0; i < n; i++) mark[i] = -1;
    ng = 0;
    for (j = 0; j < n; j++)
    {
        g = group[j];
        if (g < 0 || g >= n) return C2D_CHOL_BAD_ARGUMENT;
        if (mark[g] < 0) mark[g] = ng++;
        gid[j] = mark[g];
    }
    for (g = 0; g <= ng; g++) gptr[g] = 0;
    for (j = 0; j < n; j++) gptr[gid[j] + 1]++;
    for (g = 0; g < ng; g++) gptr[g + 1] += gptr[g];
    for (g = 0; g < ng; g++) deg[g] = gptr[g];
    for (j = 0; j < n; j++) gdof[deg[gid[j]]++] = j;
    for (g = 0; g < ng; g++) vw[g] = gptr[g + 1] - gptr[g];

    /* group graph: g ~ h when a dof of g and a dof of h are coupled */
    for (g = 0; g < ng; g++) deg[g] = 0;
    for (j = 0; j < n; j++)
    {
        for (p = Sp[j]; p < Sp[j + 1]; p++)
        {
            i = Si[p];
            if (gid[i] != gid[j]) { deg[gid[i]]++; deg[gid[j]]++; }
        }
    }
    xadj[0] = 0;
    for (g = 0; g < ng; g++) xadj[g + 1] = xadj[g] + deg[g];
    for (g = 0; g < ng; g++) deg[g] = xadj[g];
    for (j = 0; j < n; j++)
    {
        for (p = Sp[j]; p < Sp[j + 1]; p++)
        {
            i = Si[p];
            if (gid[i] != gid[j]) { adj[deg[gid[i]]++] = gid[j]; adj[deg[gid[j]]++] = gid[i]; }
        }
    }
    /* remove repeated neighbours, compacting in place */
    for (g = 0; g < ng; g++) mark[g] = -1;
    nadj = 0;
    for (g = 0; g < ng; g++)
    {
        int start = xadj[g], end = xadj[g + 1];
        xadj[g] = nadj;
        for (p = start; p < end; p++)
        {
            h = adj[p];
            if (mark[h] != g) { mark[h] = g; adj[nadj++] = h; }
        }
    }
    xadj[ng] = nadj;
    *ngroups = ng;
    return CHOLMOD_OK;
}

static int order_groups(cholmod_sparse *S, const int *group, int method, const int *cset, int *perm,
                        cholmod_common *c)
{
    int n = (int) S->ncol;
    const int *Sp = S->p;
    int *gptr, *gdof, *xadj, *adj, *vw, *gperm, *giperm, *gset;
    int p, g, h, k, ng, ok;
    int status = CHOLMOD_OK;
    size_t nnz = (size_t) Sp[n];
    int *work = cholmod_malloc(10 * (size_t) n + 2, sizeof(int), c);
    int *adjmem = cholmod_malloc(2 * nnz + 1, sizeof(int), c);

    if (work == NULL || adjmem == NULL)
    {
        cholmod_free(10 * (size_t) n + 2, sizeof(int), work, c);
        cholmod_free(2 * nnz + 1, sizeof(int), adjmem, c);
        return (c->status < 0) ? c->status : CHOLMOD_OUT_OF_MEMORY;
    }
    /* ng <= n groups: the CSR pointers take n + 1 entries (ng = n when every
     * group is one dof, e.g. every node with one dof held) */
    gptr = GG_GPTR(work, n);
    gdof = GG_GDOF(work, n);
    xadj = GG_XADJ(work, n);
    vw = GG_VW(work, n);
    gperm = work + 7 * n + 2;  /* [ng] */
    giperm = work + 8 * n + 2; /* [ng] */
    gset = work + 9 * n + 2;   /* [ng] constraint set of each group (CAMD) */
    adj = adjmem;
    status = group_graph(S, group, work, adj, &ng);
    if (status != CHOLMOD_OK) goto done;
    for (g = 0; g < ng; g++) gset[g] = (cset != NULL) ? cset[gdof[gptr[g]]] : 0;

    /* the ordering of the group graph, then the dofs group by group */
    if (ng > 1 && method == C2D_ORDER_AMD)
    {
        double control[AMD_CONTROL], info[AMD_INFO];
        if (cset == NULL)
        {
            amd_defaults(control);
            ok = amd_order(ng, xadj, adj, gperm, control, info);
            if (ok < AMD_OK) { status = (ok == AMD_OUT_OF_MEMORY) ? CHOLMOD_OUT_OF_MEMORY : CHOLMOD_INVALID; goto done; }
        }
        else
        {
            camd_defaults(control);
            ok = camd_order(ng, xadj, adj, gperm, control, info, gset);
            if (ok < CAMD_OK) { status = (ok == CAMD_OUT_OF_MEMORY) ? CHOLMOD_OUT_OF_MEMORY : CHOLMOD_INVALID; goto done; }
        }
    }
    else if (ng > 1)
    {
        ok = nested_dissection(ng, xadj, adj, vw, gperm, giperm);
        if (ok != METIS_OK) { status = (ok == METIS_ERROR_MEMORY) ? CHOLMOD_OUT_OF_MEMORY : CHOLMOD_INVALID; goto done; }
    }
    else
    {
        gperm[0] = 0;
    }
    /* postorder the elimination tree of the group graph in that order: an
     * equivalent order (the same fill) whose subtrees are contiguous, as the
     * supernodal analysis wants; a group's dofs are coupled, so the dofs'
     * tree is the groups' tree with each group a chain */
    status = postorder_groups(ng, xadj, adj, gperm, c);
    if (status != CHOLMOD_OK) goto done;
    k = 0;
    for (g = 0; g < ng; g++)
    {
        h = gperm[g];
        for (p = gptr[h]; p < gptr[h + 1]; p++) perm[k++] = gdof[p];
    }

done:
    cholmod_free(10 * (size_t) n + 2, sizeof(int), work, c);
    cholmod_free(2 * nnz + 1, sizeof(int), adjmem, c);
    return status;
}

/* gS[k] = the group (0-based, numbered by first appearance) of the k-th
 * remaining dof rem[k], k < nr, from the 1-based groups of all n dofs.
 * seen: [n] workspace. */
static void rest_groups(int n, int nr, const int *group, const int *rem, int *seen, int *gS)
{
    int i, k, ng = 0;
    for (i = 0; i < n; i++) seen[i] = -1;
    for (k = 0; k < nr; k++)
    {
        i = group[rem[k]] - 1;
        if (i < 0 || i >= n) i = n - 1;        /* checked by the caller */
        if (seen[i] < 0) seen[i] = ng++;
        gS[k] = seen[i];
    }
}

/* perm = [order of the remaining dofs R, last(:)] (0-based): the METIS order
 * computed on the submatrix A(R,R) alone, or with AMD on node groups the
 * CAMD order of the whole graph with `last` constrained to come last.  Workspace: map[n], rem[n],
 * permS[n].  Returns CHOLMOD_OK, C2D_CHOL_BAD_ARGUMENT (a dof of `last` out
 * of range or repeated) or CHOLMOD's error status. */
static int order_block_last(const cholmod_sparse *A, int nlast, const int *last, const int *group,
                            int method, int *perm, int *map, int *rem, int *permS, cholmod_common *c)
{
    int n = (int) A->ncol;
    int nr = n - nlast;
    cholmod_sparse *S;
    int i, k, ok;

    /* map[i] = position of dof i in R (monotone), -1 for the dofs of `last` */
    for (i = 0; i < n; i++) map[i] = 0;
    for (k = 0; k < nlast; k++)
    {
        i = last[k] - 1;
        if (i < 0 || i >= n || map[i] != 0) return C2D_CHOL_BAD_ARGUMENT;
        map[i] = -1;
    }
    for (i = 0, k = 0; i < n; i++)
    {
        if (map[i] == 0)
        {
            rem[k] = i;
            map[i] = k++;
        }
    }

    if (nr > 0 && group != NULL && method == C2D_ORDER_AMD)
    {
        /* CAMD on the node graph of the whole pattern, each dof of `last` a
         * group of its own in the constraint set ordered last: the other dofs
         * are ordered knowing that the block comes after them */
        int *gz = cholmod_malloc((size_t) n, sizeof(int), c);
        int *cset = cholmod_malloc((size_t) n, sizeof(int), c);
        int *seen = cholmod_malloc((size_t) n, sizeof(int), c);
        int *pf = cholmod_malloc((size_t) n, sizeof(int), c);
        int ng = 0, g, st = CHOLMOD_OUT_OF_MEMORY;
        if (gz != NULL && cset != NULL && seen != NULL && pf != NULL)
        {
            for (i = 0; i < n; i++) seen[i] = -1;
            for (i = 0; i < n; i++)
            {
                if (map[i] < 0) continue;
                g = group[i] - 1;
                if (g < 0 || g >= n) g = n - 1;        /* checked by the caller */
                if (seen[g] < 0) seen[g] = ng++;
                gz[i] = seen[g];
                cset[i] = 0;
            }
            for (k = 0; k < nlast; k++)
            {
                gz[last[k] - 1] = ng++;
                cset[last[k] - 1] = 1;
            }
            st = order_groups((cholmod_sparse *) A, gz, method, cset, pf, c);
            if (st == CHOLMOD_OK)
            {
                for (i = 0, k = 0; i < n; i++)
                {
                    if (map[pf[i]] >= 0) permS[k++] = map[pf[i]];
                }
            }
        }
        else if (c->status < 0)
        {
            st = c->status;
        }
        cholmod_free((size_t) n, sizeof(int), gz, c);
        cholmod_free((size_t) n, sizeof(int), cset, c);
        cholmod_free((size_t) n, sizeof(int), seen, c);
        cholmod_free((size_t) n, sizeof(int), pf, c);
        if (st != CHOLMOD_OK) return st;
    }
    else if (nr > 0)
    {
        S = remaining_pattern(A, map, nr, c);
        if (S == NULL) return (c->status < 0) ? c->status : CHOLMOD_OUT_OF_MEMORY;
        /* METIS nested dissection of S, followed by its etree postorder */
        if (group != NULL)
        {
            /* the groups of the remaining dofs (0-based, < nr: first appearance) */
            int *gS = cholmod_malloc((size_t) n, sizeof(int), c);
            int *seen = cholmod_malloc((size_t) n, sizeof(int), c);
            int st;
            if (gS == NULL || seen == NULL)
            {
                cholmod_free((size_t) n, sizeof(int), gS, c);
                cholmod_free((size_t) n, sizeof(int), seen, c);
                cholmod_free_sparse(&S, c);
                return (c->status < 0) ? c->status : CHOLMOD_OUT_OF_MEMORY;
            }
            rest_groups(n, nr, group, rem, seen, gS);
            st = order_groups(S, gS, method, NULL, permS, c);
            cholmod_free((size_t) n, sizeof(int), gS, c);
            cholmod_free((size_t) n, sizeof(int), seen, c);
            cholmod_free_sparse(&S, c);
            if (st != CHOLMOD_OK) return st;
        }
        else
        {
            if (method == C2D_ORDER_AMD)
            {
                ok = cholmod_amd(S, NULL, 0, permS, c);
            }
            else
            {
                ok = guarded_cholmod_metis(S, permS, c);
            }
            cholmod_free_sparse(&S, c);
            if (!ok) return (c->status < 0) ? c->status : CHOLMOD_INVALID;
        }
    }
    for (k = 0; k < nr; k++) perm[k] = rem[permS[k]];      /* remaining dofs */
    for (k = 0; k < nlast; k++) perm[nr + k] = last[k] - 1; /* then the block */
    return CHOLMOD_OK;
}

/* Analysis with the block last: the given permutation, not postordered (a
 * postorder of the elimination tree could move the block away from the last
 * pivots).  Returns the symbolic factor or NULL with the status in *status. */
static cholmod_factor *analyze_block_last(cholmod_sparse *A, int nlast, const int *last,
                                          const int *group, int method, cholmod_common *c, int *status)
{
    size_t n = A->ncol;
    int *work = cholmod_malloc(4 * n, sizeof(int), c); /* perm, map, rem, permS */
    cholmod_factor *L = NULL;

    if (work == NULL)
    {
        *status = (c->status < 0) ? c->status : CHOLMOD_OUT_OF_MEMORY;
        return NULL;
    }
    *status = order_block_last(A, nlast, last, group, method, work, work + n, work + 2 * n, work + 3 * n, c);
    if (*status == CHOLMOD_OK)
    {
        c->nmethods = 1;
        c->method[0].ordering = CHOLMOD_GIVEN;
        c->postorder = 0;
        L = cholmod_analyze_p(A, work, NULL, 0, c);
        c->postorder = 1;
        if (L == NULL) *status = (c->status < 0) ? c->status : CHOLMOD_INVALID;
    }
    cholmod_free(4 * n, sizeof(int), work, c);
    return L;
}

/* After a successful factorization: min_k L(k,k)^2 / A(p_k,p_k), and the
 * first non-finite diagonal of L if any (then the ratio is NaN there). */
static void scan_pivots(struct c2d_chol *h, const double *adiag)
{
    cholmod_factor *L = h->L;
    const int *Super = L->super, *Lpi = L->pi, *Lpx = L->px, *Perm = L->Perm;
    const double *Lx = L->x;
    int s, k, k1, k2, nsrow;
    double lkk, ratio;

    h->pivot_ratio = HUGE_VAL;
    h->pivot_column = 0;
    h->pivot_equation = 0;
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
                h->pivot_ratio = lkk - lkk; /* NaN */
                h->pivot_column = k + 1;
                h->pivot_equation = Perm[k] + 1;
                return;
            }
            ratio = (adiag[Perm[k]] > 0.0) ? lkk * lkk / adiag[Perm[k]] : 0.0;
            if (ratio < h->pivot_ratio)
            {
                h->pivot_ratio = ratio;
                h->pivot_column = k + 1;
                h->pivot_equation = Perm[k] + 1;
            }
        }
    }
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
            status = order_groups(A, gz, h->method, NULL, perm, c);
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
        h->L = (h->method == C2D_ORDER_METIS) ? guarded_analyze(A, c) : cholmod_analyze(A, c);
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
    scan_pivots(h, adiag);
    return CHOLMOD_OK;
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
    A = copy_pattern(n, colptr, rowind, offset, c, &status);
    if (A != NULL)
    {
        status = analyze_pattern(h, A, nlast, last, ngroup > 0 ? group : NULL);
        cholmod_free_sparse(&A, c);
    }
    if (status != CHOLMOD_OK && h->L != NULL) cholmod_free_factor(&h->L, c);
    return status;
}

/* The top vertex separator of the node graph of the pattern without its
 * `last` dofs (METIS_ComputeVertexSeparator, as the first level of a nested
 * dissection): side[k] (k < n) = 0 or 1 for the two halves, 2 for the
 * separator, 3 for a dof of `last`.  Arguments as c2d_chol_analyze's, the
 * groups required. */
int c2d_chol_separator(void *handle, int n, const int *colptr, const int *rowind, int offset,
                       int nlast, const int *last, const int *group, int *side)
{
    struct c2d_chol *h = handle;
    cholmod_common *c;
    cholmod_sparse *A, *S = NULL;
    int *map = NULL, *rem = NULL, *seen = NULL, *gS = NULL, *work = NULL, *adj = NULL, *where = NULL;
    int i, k, nr, ng = 0, status;
    size_t nnz = 0;

    if (h == NULL) return C2D_CHOL_NO_HANDLE;
    c = &h->common;
    if (n < 1 || nlast < 0 || nlast >= n || (nlast > 0 && last == NULL) || group == NULL || side == NULL)
    {
        return C2D_CHOL_BAD_ARGUMENT;
    }
    A = copy_pattern(n, colptr, rowind, offset, c, &status);
    if (A == NULL) return status;
    nr = n - nlast;
    map = cholmod_malloc((size_t) n, sizeof(int), c);
    rem = cholmod_malloc((size_t) n, sizeof(int), c);
    seen = cholmod_malloc((size_t) n, sizeof(int), c);
    gS = cholmod_malloc((size_t) n, sizeof(int), c);
    status = CHOLMOD_OUT_OF_MEMORY;
    if (map == NULL || rem == NULL || seen == NULL || gS == NULL) goto done;
    status = C2D_CHOL_BAD_ARGUMENT;
    for (i = 0; i < n; i++) map[i] = 0;
    for (k = 0; k < nlast; k++)
    {
        i = last[k] - 1;
        if (i < 0 || i >= n || map[i] != 0) goto done;
        map[i] = -1;
        side[i] = 3;
    }
    for (i = 0, k = 0; i < n; i++)
    {
        if (map[i] == 0) { rem[k] = i; map[i] = k++; }
    }
    status = CHOLMOD_OUT_OF_MEMORY;
    S = remaining_pattern(A, map, nr, c);
    if (S == NULL) goto done;
    rest_groups(n, nr, group, rem, seen, gS);
    nnz = (size_t) ((int *) S->p)[nr];
    work = cholmod_malloc(10 * (size_t) nr + 2, sizeof(int), c);
    adj = cholmod_malloc(2 * nnz + 1, sizeof(int), c);
    where = cholmod_malloc((size_t) nr, sizeof(int), c);
    if (work == NULL || adj == NULL || where == NULL) goto done;
    status = group_graph(S, gS, work, adj, &ng);
    if (status != CHOLMOD_OK) goto done;
    if (ng < 3)
    {
        status = C2D_CHOL_BAD_ARGUMENT;
    }
    else
    {
        idx_t nv = ng, sepsize = 0;
        int ok;
        ok = guarded_separator(&nv, GG_XADJ(work, nr), adj, GG_VW(work, nr), &sepsize, where);
        status = (ok == METIS_OK) ? CHOLMOD_OK : (ok == METIS_ERROR_MEMORY) ? CHOLMOD_OUT_OF_MEMORY : CHOLMOD_INVALID;
        if (status == CHOLMOD_OK)
        {
            for (k = 0; k < nr; k++) side[rem[k]] = where[GG_GID(work, nr)[k]];
        }
    }

done:
    if (status != CHOLMOD_OK && c->status < 0 && status == CHOLMOD_OUT_OF_MEMORY) status = c->status;
    cholmod_free_sparse(&S, c);
    cholmod_free_sparse(&A, c);
    cholmod_free((size_t) n, sizeof(int), map, c);
    cholmod_free((size_t) n, sizeof(int), rem, c);
    cholmod_free((size_t) n, sizeof(int), seen, c);
    cholmod_free((size_t) n, sizeof(int), gS, c);
    cholmod_free(10 * (size_t) nr + 2, sizeof(int), work, c);
    cholmod_free(2 * nnz + 1, sizeof(int), adj, c);
    cholmod_free((size_t) nr, sizeof(int), where, c);
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
    if (h->L == NULL || h->valid) return C2D_CHOL_NO_FACTOR;
    if (n != h->n || val == NULL) return C2D_CHOL_BAD_ARGUMENT;
    c = &h->common;
    adiag = cholmod_malloc((size_t) n, sizeof(double), c);
    if (adiag == NULL) return (c->status < 0) ? c->status : CHOLMOD_OUT_OF_MEMORY;
    /* the 0-based pattern is copied; the values are the caller's own array,
     * lent to CHOLMOD for the factorization (read only) and taken back
     * before the matrix is freed: no second copy of K's values */
    A = copy_pattern(n, colptr, rowind, offset, c, &status);
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

int c2d_chol_factorize(void *handle, int n, const int *colptr, const int *rowind,
                       const double *val, int nlast, const int *last)
{
    int status = c2d_chol_analyze(handle, n, colptr, rowind, 0, nlast, last, 0, NULL);
    if (status == CHOLMOD_OK) status = c2d_chol_factorize_values(handle, n, colptr, rowind, 0, val);
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

void c2d_chol_ordering_name(const void *handle, char *buf, int len)
{
    const struct c2d_chol *h = handle;
    const char *name = "none";
    if (h != NULL && h->L != NULL)
    {
        int amd = h->method == C2D_ORDER_AMD;
        if (h->nlast > 0 && h->grouped)
        {
            name = amd ? "amd(nodes)+last" : "metis(nodes)+last";
        }
        else if (h->nlast > 0)
        {
            name = amd ? "amd+last" : "metis+last";
        }
        else if (h->grouped)
        {
            name = amd ? "amd(nodes)" : "metis(nodes)";
        }
        else
        {
            switch (h->L->ordering)
            {
            case CHOLMOD_NATURAL: name = "natural"; break;
            case CHOLMOD_GIVEN: name = "given"; break;
            case CHOLMOD_AMD: name = "amd"; break;
            case CHOLMOD_METIS: name = "metis"; break;
            case CHOLMOD_NESDIS: name = "nesdis"; break;
            case CHOLMOD_COLAMD: name = "colamd"; break;
            case CHOLMOD_POSTORDERED: name = "postordered"; break;
            default: name = "unknown"; break;
            }
        }
    }
    copy_name(name, buf, len);
}

void c2d_chol_status_name(int status, char *buf, int len)
{
    const char *name;
    switch (status)
    {
    case CHOLMOD_OK: name = "CHOLMOD_OK"; break;
    case CHOLMOD_NOT_INSTALLED: name = "CHOLMOD_NOT_INSTALLED"; break;
    case CHOLMOD_OUT_OF_MEMORY: name = "CHOLMOD_OUT_OF_MEMORY"; break;
    case CHOLMOD_TOO_LARGE: name = "CHOLMOD_TOO_LARGE"; break;
    case CHOLMOD_INVALID: name = "CHOLMOD_INVALID"; break;
    case CHOLMOD_GPU_PROBLEM: name = "CHOLMOD_GPU_PROBLEM"; break;
    case CHOLMOD_NOT_POSDEF: name = "CHOLMOD_NOT_POSDEF"; break;
    case CHOLMOD_DSMALL: name = "CHOLMOD_DSMALL"; break;
    case C2D_CHOL_NO_HANDLE: name = "C2D_CHOL_NO_HANDLE"; break;
    case C2D_CHOL_NO_FACTOR: name = "C2D_CHOL_NO_FACTOR"; break;
    case C2D_CHOL_NOT_SUPER_LL: name = "C2D_CHOL_NOT_SUPER_LL"; break;
    case C2D_CHOL_BLOCK_MOVED: name = "C2D_CHOL_BLOCK_MOVED"; break;
    case C2D_CHOL_BAD_ARGUMENT: name = "C2D_CHOL_BAD_ARGUMENT"; break;
    default: name = "unknown status"; break;
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

int c2d_chol_solve(void *handle, int n, int nrhs, const double *b, double *x)
{
    return c2d_chol_solve_half(handle, C2D_SOLVE_WHOLE, n, nrhs, b, x);
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

/* Checks shared by the trailing-block readers: the factor is supernodal LL'
 * with `last` (nlast dofs) at its last pivots. */
static int trailing_ok(const struct c2d_chol *h, int nlast)
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
    int b0, b1, j, q, len, status;

    status = trailing_ok(h, nlast);
    if (status != CHOLMOD_OK) return status;
    if (first < 1 || count < 1 || first - 1 + count > nlast) return C2D_CHOL_BAD_ARGUMENT;
    b0 = h->n - nlast + first - 1; /* the range: pivots b0..b1-1 (0-based) */
    b1 = b0 + count;
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
    int c0, e, j, q, len, status;

    status = trailing_ok(h, nlast);
    if (status != CHOLMOD_OK) return status;
    if (first < 1 || first > nlast) return C2D_CHOL_BAD_ARGUMENT;
    c0 = h->n - nlast;
    e = c0 + first - 1; /* the block ends at pivot e so far */
    for (j = c0 + first - 1; j <= e; j++)
    {
        len = column_below(h->L, j, &rows, &vals);
        for (q = 1; q < len; q++) /* the non-zeros below the diagonal */
        {
            if (rows[q] > e && vals[q] != 0.0) e = rows[q];
        }
    }
    *last_row = e - c0 + 1;
    return CHOLMOD_OK;
}

/* OpenBLAS's own thread count, when the BLAS is OpenBLAS (weak references:
 * with another BLAS both are NULL and nothing is done). */
extern int openblas_get_num_threads(void) __attribute__((weak));
extern void openblas_set_num_threads(int) __attribute__((weak));

/* At most two malloc arenas (glibc's default is 8 per core): the parts of a
 * factor are ordered and factorized on the OpenMP threads, and each further
 * arena keeps freed pages resident, while a single arena serializes the two
 * threads' allocations (doc/performance.md, "Bodies factorized side by
 * side").  Two was measured on two cores; more threads may want more. */
void c2d_malloc_arenas(void)
{
    (void) mallopt(M_ARENA_MAX, 2);
}

/* Give the free pages of every arena back to the system (malloc_trim). */
void c2d_malloc_trim(void)
{
    (void) malloc_trim(0);
}

/* OpenBLAS's pthreads build starts its worker threads when it is loaded,
 * and a worker spins (sched_yield) for about 2^28 cycles after each piece
 * of work before it sleeps.  Spinning, it takes a core from the OpenMP
 * threads of the phases that use no BLAS (reading the meshes took twice as
 * long: doc/performance.md, "OpenBLAS's idle workers").
 * blas_thread_shutdown_ ends the workers, as OpenBLAS does before a fork;
 * the next BLAS call that wants threads starts them again. */
extern int blas_thread_shutdown_(void) __attribute__((weak));

void c2d_blas_park(void)
{
    if (blas_thread_shutdown_ != NULL) (void) blas_thread_shutdown_();
}

int c2d_blas_threads(int n)
{
    int old;
    if (openblas_get_num_threads == NULL || openblas_set_num_threads == NULL) return 0;
    old = openblas_get_num_threads();
    if (n > 0)
    {
        /* setting the count starts the workers again (OpenBLAS's re-init
         * after a fork).  With one thread they would spin unused: park
         * them until a call wants them.  With more, the calls that follow
         * want them (restarting them there cost the solve after the
         * factorization 5 ms on hertz_1e5) */
        openblas_set_num_threads(n);
        if (n == 1) c2d_blas_park();
    }
    return old;
}
