/* fill_ordering.c: the fill-reducing ordering of a stiffness pattern (see
 * include/fill_ordering.h).
 *
 * Why an ordering of our own around METIS and AMD rather than CHOLMOD's
 * cholmod_analyze alone: the graph of the mesh nodes has a quarter of the
 * edges of the dof graph (METIS in about half the time), a block of contact
 * dofs must come last (CAMD knows it, METIS orders the rest without it), and
 * METIS's first level taken apart runs its two halves on two threads; each
 * is measured in doc/performance.md ("The ordering on the node graph",
 * "The ordering: AMD or METIS", "METIS's first level on two threads").
 *
 * Nothing here allocates memory that outlives a call. */
#include <stdlib.h>

#include "cholmod.h"
#include "metis.h"
#include "amd.h"
#include "camd.h"
#include "cholmod_factor.h"
#include "fill_ordering.h"
#include "metis_guard.h"

/* The METIS calls of the ordering, each in a frame of its own so that the jump
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
cholmod_factor *c2d_analyze_metis(cholmod_sparse *A, cholmod_common *c)
{
    cholmod_factor *L = NULL;
    C2D_METIS_CALL(L = cholmod_analyze(A, c), (L = NULL, c->status = CHOLMOD_OUT_OF_MEMORY));
    return L;
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
static int postc2d_order_groups(int ng, const int *xadj, const int *adj, int *gperm, cholmod_common *c)
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

/* c2d_order_groups (include/fill_ordering.h): the fill-reducing ordering of the graph of dof groups (the nodes of the
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

int c2d_order_groups(cholmod_sparse *S, const int *group, int method, const int *cset, int *perm,
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
    status = postc2d_order_groups(ng, xadj, adj, gperm, c);
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
            st = c2d_order_groups((cholmod_sparse *) A, gz, method, cset, pf, c);
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
            st = c2d_order_groups(S, gS, method, NULL, permS, c);
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


/* c2d_order_block_last: order_block_last with its workspace. */
int c2d_order_block_last(const cholmod_sparse *A, int nlast, const int *last, const int *group,
                         int method, int *perm, cholmod_common *c)
{
    size_t n = A->ncol;
    int *work = cholmod_malloc(3 * n, sizeof(int), c); /* map, rem, permS */
    int status;
    if (work == NULL) return (c->status < 0) ? c->status : CHOLMOD_OUT_OF_MEMORY;
    status = order_block_last(A, nlast, last, group, method, perm, work, work + n, work + 2 * n, c);
    cholmod_free(3 * n, sizeof(int), work, c);
    return status;
}
