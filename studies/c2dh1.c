/* c2dh1: broken H1 and energy-norm error of contact2d runs against a fine
 * reference (P1 triangle meshes; the same measure as `c2derr.py h1`, which
 * also takes Q1 cells, about a hundred times faster).
 *
 *   c2dh1 [-m E,nu ...] [--plane strain|stress] [--window x0,x1,y0,y1]
 *         REF.vtk RUN.vtk [RUN.vtk ...]
 *
 * For each run, with e = u_ref - u_h on every body B (CELL_DATA `body`):
 *   |e|_{1,h}^2 = sum_B int_B |grad e|^2,
 *   ||e||_E^2   = sum_B int_B sigma(e) : eps(e)
 *               = sum_B int_B lam (div e)^2 + 2 mu (e_xx^2 + e_yy^2) + mu g_xy^2,
 * integrated over the reference triangles.  grad u_ref and grad u_h are
 * constant on each piece T_ref & T_h, so the integral is exact: a reference
 * triangle inside one run triangle (nested meshes) takes one evaluation; a
 * cut one is clipped against every run triangle it meets (Sutherland-Hodgman
 * on the barycentric half-planes) and integrated piece by piece.  A part of a
 * reference triangle outside the run's body (a curved boundary meshed by
 * chords) takes the gradient of the nearest run triangle.  Run triangles are
 * found through a multi-level bucket grid (level L: buckets of side s0/2^L,
 * each triangle on the level just coarser than itself).
 *
 * Output, one CSV line per run:
 *   run,h1,h1_rel,energy,energy_rel,nested,h1_body1,h1_body2,...
 * h1_rel and energy_rel are relative to the reference's own seminorm and
 * energy norm over the same region; nested is the share of reference
 * triangles lying inside one run triangle.  Exit status 0, or 2 on bad input.
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAXBODY 64
#define MAXLEV 24

typedef struct {            /* one legacy VTK file of contact2d */
    long npt, ncell;
    double *x, *y;          /* [npt] coordinates */
    double *ux, *uy;        /* [npt] displacement */
    long *tri;              /* [3 ncell] vertices (triangles only) */
    int *body;              /* [ncell] 1-based body */
} vtk_t;

typedef struct {            /* one run triangle */
    double x0, y0;          /* first vertex */
    double d11, d12, d21, d22;  /* inverse Jacobian: (xi, eta) = D (x - x0) */
    double g[4];            /* grad u_h: dux/dx, dux/dy, duy/dx, duy/dy */
} rtri_t;

typedef struct {            /* one level of the bucket grid, CSR */
    double inv;             /* buckets per unit length */
    long nbx, nby;
    long *start;            /* [nbx nby + 1] */
    long *item;             /* [start[nbx nby]] triangle indices */
} level_t;

typedef struct {            /* the triangles of one body of a run */
    long n;
    rtri_t *t;
    double xmin, ymin;
    int nlev;
    level_t lev[MAXLEV + 1];
    long last;              /* the triangle found last (search hint) */
    long *mark;             /* [n] scratch for clip_pieces */
    long stamp;
} rbody_t;

static void die(const char *msg, const char *arg)
{
    fprintf(stderr, "c2dh1: %s%s\n", msg, arg ? arg : "");
    exit(2);
}

/* ---------------------------------------------------------------- reading */

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    long n;
    char *buf;
    if (!f) die("cannot open ", path);
    fseek(f, 0, SEEK_END);
    n = ftell(f);
    fseek(f, 0, SEEK_SET);
    buf = malloc((size_t)n + 1);
    if (!buf || fread(buf, 1, (size_t)n, f) != (size_t)n) die("cannot read ", path);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

static char *next_word(char **p, char *w, size_t len)
{
    char *s = *p;
    size_t k = 0;
    while (*s && isspace((unsigned char)*s)) s++;
    if (!*s) return NULL;
    while (*s && !isspace((unsigned char)*s) && k + 1 < len) w[k++] = *s++;
    while (*s && !isspace((unsigned char)*s)) s++;
    w[k] = '\0';
    *p = s;
    return w;
}

static double next_double(char **p, const char *path)
{
    char *end;
    double v = strtod(*p, &end);
    if (end == *p) die("bad number in ", path);
    *p = end;
    return v;
}

static void skip_line(char **p)
{
    while (**p && **p != '\n') (*p)++;
}

static void read_vtk(const char *path, vtk_t *m)
{
    char *buf = slurp(path), *p = buf, w[256], name[256];
    int section = 0;        /* 1 point data, 2 cell data */
    long count = 0, i, k;
    memset(m, 0, sizeof *m);
    skip_line(&p);          /* # vtk DataFile Version */
    if (*p) p++;
    skip_line(&p);          /* title */
    while (next_word(&p, w, sizeof w)) {
        if (!strcmp(w, "POINTS")) {
            m->npt = (long)next_double(&p, path);
            next_word(&p, w, sizeof w);
            m->x = malloc(sizeof(double) * (size_t)m->npt);
            m->y = malloc(sizeof(double) * (size_t)m->npt);
            for (i = 0; i < m->npt; i++) {
                m->x[i] = next_double(&p, path);
                m->y[i] = next_double(&p, path);
                (void)next_double(&p, path);
            }
        } else if (!strcmp(w, "CELLS")) {
            m->ncell = (long)next_double(&p, path);
            (void)next_double(&p, path);
            m->tri = malloc(sizeof(long) * 3 * (size_t)m->ncell);
            for (i = 0; i < m->ncell; i++) {
                long nv = (long)next_double(&p, path);
                if (nv != 3) die("only triangles are supported (use c2derr.py h1 for quads): ", path);
                for (k = 0; k < 3; k++) m->tri[3 * i + k] = (long)next_double(&p, path);
            }
        } else if (!strcmp(w, "CELL_TYPES")) {
            long n = (long)next_double(&p, path);
            for (i = 0; i < n; i++)
                if ((long)next_double(&p, path) != 5) die("only triangles are supported: ", path);
        } else if (!strcmp(w, "POINT_DATA") || !strcmp(w, "CELL_DATA")) {
            section = w[0] == 'P' ? 1 : 2;
            count = (long)next_double(&p, path);
        } else if (!strcmp(w, "SCALARS") || !strcmp(w, "VECTORS")) {
            int vec = w[0] == 'V';
            long ncomp = vec ? 3 : 1;
            char *q;
            next_word(&p, name, sizeof name);
            next_word(&p, w, sizeof w);          /* data type */
            q = p;                               /* optional component count */
            while (*q == ' ' || *q == '\t') q++;
            if (!vec && isdigit((unsigned char)*q)) ncomp = (long)next_double(&p, path);
            q = p;
            if (next_word(&q, w, sizeof w) && !strcmp(w, "LOOKUP_TABLE")) {
                p = q;
                next_word(&p, w, sizeof w);
            }
            if (section == 1 && !strcmp(name, "displacement")) {
                m->ux = malloc(sizeof(double) * (size_t)count);
                m->uy = malloc(sizeof(double) * (size_t)count);
                for (i = 0; i < count; i++) {
                    m->ux[i] = next_double(&p, path);
                    m->uy[i] = next_double(&p, path);
                    for (k = 2; k < ncomp; k++) (void)next_double(&p, path);
                }
            } else if (section == 2 && !strcmp(name, "body")) {
                m->body = malloc(sizeof(int) * (size_t)count);
                for (i = 0; i < count; i++) m->body[i] = (int)next_double(&p, path);
            } else {
                for (i = 0; i < count * ncomp; i++) (void)next_double(&p, path);
            }
        }
    }
    free(buf);
    if (!m->x || !m->tri || !m->ux || !m->body) die("missing POINTS, CELLS, displacement or body in ", path);
}

static void free_vtk(vtk_t *m)
{
    free(m->x); free(m->y); free(m->ux); free(m->uy); free(m->tri); free(m->body);
}

/* ---------------------------------------------------------------- run mesh */

/* grad u of the P1 triangle (a, b, c) and its inverse Jacobian D; returns det J */
static double triangle_gradient(const vtk_t *m, const long *v, double d[4], double g[4])
{
    long a = v[0], b = v[1], c = v[2];
    double a11 = m->x[b] - m->x[a], a12 = m->x[c] - m->x[a];
    double a21 = m->y[b] - m->y[a], a22 = m->y[c] - m->y[a];
    double det = a11 * a22 - a12 * a21;
    double dux1 = m->ux[b] - m->ux[a], dux2 = m->ux[c] - m->ux[a];
    double duy1 = m->uy[b] - m->uy[a], duy2 = m->uy[c] - m->uy[a];
    d[0] = a22 / det; d[1] = -a12 / det; d[2] = -a21 / det; d[3] = a11 / det;
    g[0] = dux1 * d[0] + dux2 * d[2]; g[1] = dux1 * d[1] + dux2 * d[3];   /* grad = (du/dxi, du/deta) D */
    g[2] = duy1 * d[0] + duy2 * d[2]; g[3] = duy1 * d[1] + duy2 * d[3];
    return det;
}

static void build_body(const vtk_t *m, int b, rbody_t *r)
{
    long c, n = 0, k, i, j;
    double s0 = 0.0, xmax = -HUGE_VAL, ymax = -HUGE_VAL;
    double *box;
    int *lev, L;
    memset(r, 0, sizeof *r);
    for (c = 0; c < m->ncell; c++) n += m->body[c] == b;
    r->n = n;
    r->t = malloc(sizeof(rtri_t) * (size_t)(n ? n : 1));
    box = malloc(sizeof(double) * 4 * (size_t)(n ? n : 1));
    lev = malloc(sizeof(int) * (size_t)(n ? n : 1));
    r->mark = calloc((size_t)(n ? n : 1), sizeof(long));
    r->xmin = r->ymin = HUGE_VAL;
    for (c = 0, k = 0; c < m->ncell; c++) {
        const long *v = m->tri + 3 * c;
        double d[4];
        if (m->body[c] != b) continue;
        triangle_gradient(m, v, d, r->t[k].g);
        r->t[k].x0 = m->x[v[0]]; r->t[k].y0 = m->y[v[0]];
        r->t[k].d11 = d[0]; r->t[k].d12 = d[1]; r->t[k].d21 = d[2]; r->t[k].d22 = d[3];
        box[4 * k] = fmin(m->x[v[0]], fmin(m->x[v[1]], m->x[v[2]]));
        box[4 * k + 1] = fmax(m->x[v[0]], fmax(m->x[v[1]], m->x[v[2]]));
        box[4 * k + 2] = fmin(m->y[v[0]], fmin(m->y[v[1]], m->y[v[2]]));
        box[4 * k + 3] = fmax(m->y[v[0]], fmax(m->y[v[1]], m->y[v[2]]));
        r->xmin = fmin(r->xmin, box[4 * k]); xmax = fmax(xmax, box[4 * k + 1]);
        r->ymin = fmin(r->ymin, box[4 * k + 2]); ymax = fmax(ymax, box[4 * k + 3]);
        s0 = fmax(s0, fmax(box[4 * k + 1] - box[4 * k], box[4 * k + 3] - box[4 * k + 2]));
        k++;
    }
    if (n == 0) { free(box); free(lev); return; }
    s0 *= 1.000001;
    r->nlev = 0;
    for (k = 0; k < n; k++) {
        double size = fmax(fmax(box[4 * k + 1] - box[4 * k], box[4 * k + 3] - box[4 * k + 2]), 1e-300);
        L = (int)floor(log2(s0 / size));
        if (L > MAXLEV) L = MAXLEV;
        /* keep a level's dense grid below 2^24 buckets */
        while (L > 0 && ((xmax - r->xmin) * (1 << L) / s0 + 2) * ((ymax - r->ymin) * (1 << L) / s0 + 2) > 16777216.0) L--;
        lev[k] = L;
        if (L + 1 > r->nlev) r->nlev = L + 1;
    }
    for (L = 0; L < r->nlev; L++) {
        level_t *q = &r->lev[L];
        long nb, pass;
        q->inv = (double)(1 << L) / s0;
        q->nbx = (long)((xmax - r->xmin) * q->inv) + 1;
        q->nby = (long)((ymax - r->ymin) * q->inv) + 1;
        nb = q->nbx * q->nby;
        q->start = calloc((size_t)nb + 1, sizeof(long));
        q->item = NULL;
        for (pass = 0; pass < 2; pass++) {      /* count, then fill */
            long *fill = pass ? calloc((size_t)nb, sizeof(long)) : NULL;
            for (k = 0; k < n; k++) {
                long i0, i1, j0, j1;
                if (lev[k] != L) continue;
                i0 = (long)((box[4 * k] - r->xmin) * q->inv); i1 = (long)((box[4 * k + 1] - r->xmin) * q->inv);
                j0 = (long)((box[4 * k + 2] - r->ymin) * q->inv); j1 = (long)((box[4 * k + 3] - r->ymin) * q->inv);
                if (i1 >= q->nbx) i1 = q->nbx - 1;
                if (j1 >= q->nby) j1 = q->nby - 1;
                for (i = i0; i <= i1; i++)
                    for (j = j0; j <= j1; j++) {
                        long bk = i * q->nby + j;
                        if (pass) q->item[q->start[bk] + fill[bk]++] = k;
                        else q->start[bk + 1]++;
                    }
            }
            if (!pass) {
                for (i = 0; i < nb; i++) q->start[i + 1] += q->start[i];
                q->item = malloc(sizeof(long) * (size_t)(q->start[nb] ? q->start[nb] : 1));
            }
            free(fill);
        }
    }
    free(box);
    free(lev);
}

static void free_body(rbody_t *r)
{
    int L;
    for (L = 0; L < r->nlev; L++) { free(r->lev[L].start); free(r->lev[L].item); }
    free(r->t);
    free(r->mark);
}

/* how far (x, y) lies outside triangle t in barycentric terms (<= 0 inside) */
static double outside(const rtri_t *t, double x, double y)
{
    double dx = x - t->x0, dy = y - t->y0;
    double xi = t->d11 * dx + t->d12 * dy, eta = t->d21 * dx + t->d22 * dy;
    return -fmin(xi, fmin(eta, 1.0 - xi - eta));
}

/* the run triangle holding (x, y), or the nearest one */
static long locate(rbody_t *r, double x, double y)
{
    const double tol = 1e-8;
    long best = -1, k;
    double bestout = HUGE_VAL, o;
    int L;
    if (outside(&r->t[r->last], x, y) <= tol) return r->last;
    for (L = 0; L < r->nlev; L++) {
        const level_t *q = &r->lev[L];
        long i = (long)floor((x - r->xmin) * q->inv), j = (long)floor((y - r->ymin) * q->inv), bk;
        if (i < 0 || j < 0 || i >= q->nbx || j >= q->nby) continue;
        bk = i * q->nby + j;
        for (k = q->start[bk]; k < q->start[bk + 1]; k++) {
            o = outside(&r->t[q->item[k]], x, y);
            if (o <= tol) return r->last = q->item[k];
            if (o < bestout) { bestout = o; best = q->item[k]; }
        }
    }
    /* inside no triangle: the nearest among the 3 x 3 buckets around, or all */
    for (L = 0; L < r->nlev; L++) {
        const level_t *q = &r->lev[L];
        long i0 = (long)floor((x - r->xmin) * q->inv), j0 = (long)floor((y - r->ymin) * q->inv), i, j;
        for (i = i0 - 1; i <= i0 + 1; i++)
            for (j = j0 - 1; j <= j0 + 1; j++) {
                long bk;
                if (i < 0 || j < 0 || i >= q->nbx || j >= q->nby) continue;
                bk = i * q->nby + j;
                for (k = q->start[bk]; k < q->start[bk + 1]; k++) {
                    o = outside(&r->t[q->item[k]], x, y);
                    if (o < bestout) { bestout = o; best = q->item[k]; }
                }
            }
    }
    if (best < 0)
        for (k = 0; k < r->n; k++) {
            o = outside(&r->t[k], x, y);
            if (o < bestout) { bestout = o; best = k; }
        }
    return best;
}

/* area of triangle (px, py) clipped by the half-planes lambda_k >= 0 of t */
static double clip_area(const rtri_t *t, const double *px, const double *py)
{
    double ax[9], ay[9], bx[9], by[9], lam[9], area = 0.0;
    int n = 3, m, i, k;
    for (i = 0; i < 3; i++) { ax[i] = px[i]; ay[i] = py[i]; }
    for (k = 0; k < 3; k++) {
        for (i = 0; i < n; i++) {
            double dx = ax[i] - t->x0, dy = ay[i] - t->y0;
            double xi = t->d11 * dx + t->d12 * dy, eta = t->d21 * dx + t->d22 * dy;
            lam[i] = k == 0 ? xi : (k == 1 ? eta : 1.0 - xi - eta);
        }
        m = 0;
        for (i = 0; i < n; i++) {
            int j = (i + 1) % n;
            if (lam[i] >= 0) { bx[m] = ax[i]; by[m] = ay[i]; m++; }
            if ((lam[i] >= 0) != (lam[j] >= 0)) {
                double s = lam[i] / (lam[i] - lam[j]);
                bx[m] = ax[i] + s * (ax[j] - ax[i]); by[m] = ay[i] + s * (ay[j] - ay[i]); m++;
            }
        }
        if (m < 3) return 0.0;
        n = m;
        for (i = 0; i < n; i++) { ax[i] = bx[i]; ay[i] = by[i]; }
    }
    for (i = 0; i < n; i++) {
        int j = (i + 1) % n;
        area += ax[i] * ay[j] - ax[j] * ay[i];
    }
    return fabs(area) / 2;
}

typedef struct { double lam, mu; } mat_t;

static double energy_density(const double d[4], mat_t c)
{
    double tr = d[0] + d[3], gxy = d[1] + d[2];
    return c.lam * tr * tr + 2 * c.mu * (d[0] * d[0] + d[3] * d[3]) + c.mu * gxy * gxy;
}

/* add w |g - g_h|^2 and w W(g - g_h) */
static void accumulate(const double g[4], const double gh[4], double w, mat_t c, double *e1, double *en)
{
    double d[4];
    int i;
    for (i = 0; i < 4; i++) d[i] = g[i] - gh[i];
    *e1 += w * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + d[3] * d[3]);
    *en += w * energy_density(d, c);
}

/* a cut reference triangle: its pieces in the run triangles it meets */
static void clip_pieces(rbody_t *r, const double *px, const double *py, double area, double cx, double cy,
                        const double g[4], mat_t c, double *e1, double *en)
{
    long first[4], k;
    double covered = 0.0, a;
    double xlo = fmin(px[0], fmin(px[1], px[2])), xhi = fmax(px[0], fmax(px[1], px[2]));
    double ylo = fmin(py[0], fmin(py[1], py[2])), yhi = fmax(py[0], fmax(py[1], py[2]));
    int i, L;
    r->stamp++;
    first[0] = locate(r, px[0], py[0]);
    first[1] = locate(r, px[1], py[1]);
    first[2] = locate(r, px[2], py[2]);
    first[3] = locate(r, cx, cy);
    for (i = 0; i < 4; i++) {
        k = first[i];
        if (r->mark[k] == r->stamp) continue;
        r->mark[k] = r->stamp;
        a = clip_area(&r->t[k], px, py);
        if (a > 0) { accumulate(g, r->t[k].g, a, c, e1, en); covered += a; }
    }
    if (covered >= area * (1 - 1e-9)) return;
    for (L = 0; L < r->nlev; L++) {
        const level_t *q = &r->lev[L];
        long i0 = (long)floor((xlo - r->xmin) * q->inv), i1 = (long)floor((xhi - r->xmin) * q->inv);
        long j0 = (long)floor((ylo - r->ymin) * q->inv), j1 = (long)floor((yhi - r->ymin) * q->inv), ii, jj, kk;
        for (ii = i0 < 0 ? 0 : i0; ii <= i1 && ii < q->nbx; ii++)
            for (jj = j0 < 0 ? 0 : j0; jj <= j1 && jj < q->nby; jj++) {
                long bk = ii * q->nby + jj;
                for (kk = q->start[bk]; kk < q->start[bk + 1]; kk++) {
                    k = q->item[kk];
                    if (r->mark[k] == r->stamp) continue;
                    r->mark[k] = r->stamp;
                    a = clip_area(&r->t[k], px, py);
                    if (a > 0) { accumulate(g, r->t[k].g, a, c, e1, en); covered += a; }
                }
            }
    }
    if (covered < area * (1 - 1e-9))      /* outside the run's body: nearest triangle */
        accumulate(g, r->t[first[3]].g, area - covered, c, e1, en);
}

/* ---------------------------------------------------------------- main */

static mat_t lame(double e, double nu, int stress)
{
    mat_t c;
    c.mu = e / (2 * (1 + nu));
    c.lam = e * nu / ((1 + nu) * (1 - 2 * nu));
    if (stress) c.lam = 2 * c.lam * c.mu / (c.lam + 2 * c.mu);
    return c;
}

int main(int argc, char **argv)
{
    double emod[MAXBODY], nu[MAXBODY], win[4] = {0, 0, 0, 0};
    int nmat = 0, stress = 0, usewin = 0, a, nfile = 0, b, nbody = 0;
    char *files[4096];
    vtk_t ref;
    long c;
    for (a = 1; a < argc; a++) {
        if (!strcmp(argv[a], "-m") && a + 1 < argc) {
            if (nmat >= MAXBODY || sscanf(argv[++a], "%lf,%lf", &emod[nmat], &nu[nmat]) != 2) die("bad -m ", argv[a]);
            nmat++;
        } else if (!strcmp(argv[a], "--plane") && a + 1 < argc) {
            stress = !strcmp(argv[++a], "stress");
        } else if (!strcmp(argv[a], "--window") && a + 1 < argc) {
            if (sscanf(argv[++a], "%lf,%lf,%lf,%lf", &win[0], &win[1], &win[2], &win[3]) != 4) die("bad --window ", argv[a]);
            usewin = 1;
        } else if (argv[a][0] == '-' && argv[a][1]) {
            die("unknown option ", argv[a]);
        } else if (nfile < 4096) {
            files[nfile++] = argv[a];
        }
    }
    if (nfile < 2) die("usage: c2dh1 [-m E,nu ...] [--plane strain|stress] [--window x0,x1,y0,y1] REF.vtk RUN.vtk [...]", NULL);
    if (nmat == 0) { emod[0] = 1.0; nu[0] = 0.0; nmat = 1; }
    read_vtk(files[0], &ref);
    for (c = 0; c < ref.ncell; c++) if (ref.body[c] > nbody) nbody = ref.body[c];
    if (nbody > MAXBODY) die("too many bodies in ", files[0]);
    for (a = 1; a < nfile; a++) {
        vtk_t run;
        double e1[MAXBODY], en[MAXBODY], r1[MAXBODY], rn[MAXBODY], s1 = 0, sn = 0, t1 = 0, tn = 0;
        long ntri = 0, nexact = 0;
        read_vtk(files[a], &run);
        for (b = 1; b <= nbody; b++) {
            rbody_t rb;
            mat_t mat = lame(emod[b - 1 < nmat ? b - 1 : nmat - 1], nu[b - 1 < nmat ? b - 1 : nmat - 1], stress);
            e1[b - 1] = en[b - 1] = r1[b - 1] = rn[b - 1] = 0.0;
            build_body(&run, b, &rb);
            if (rb.n == 0) die("a body of the reference is missing in ", files[a]);
            for (c = 0; c < ref.ncell; c++) {
                const long *v = ref.tri + 3 * c;
                double px[3], py[3], d[4], g[4], det, area, cx, cy;
                long k;
                int q, exact = 1;
                if (ref.body[c] != b) continue;
                for (q = 0; q < 3; q++) { px[q] = ref.x[v[q]]; py[q] = ref.y[v[q]]; }
                cx = (px[0] + px[1] + px[2]) / 3; cy = (py[0] + py[1] + py[2]) / 3;
                if (usewin && !(cx >= win[0] && cx <= win[1] && cy >= win[2] && cy <= win[3])) continue;
                det = triangle_gradient(&ref, v, d, g);
                area = fabs(det) / 2;
                ntri++;
                r1[b - 1] += area * (g[0] * g[0] + g[1] * g[1] + g[2] * g[2] + g[3] * g[3]);
                rn[b - 1] += area * energy_density(g, mat);
                k = locate(&rb, cx, cy);
                /* vertices carry the VTK file's 10 significant digits */
                for (q = 0; q < 3 && exact; q++) exact = outside(&rb.t[k], px[q], py[q]) <= 1e-6;
                if (exact) {
                    nexact++;
                    accumulate(g, rb.t[k].g, area, mat, &e1[b - 1], &en[b - 1]);
                } else {
                    clip_pieces(&rb, px, py, area, cx, cy, g, mat, &e1[b - 1], &en[b - 1]);
                }
            }
            free_body(&rb);
            s1 += e1[b - 1]; sn += en[b - 1]; t1 += r1[b - 1]; tn += rn[b - 1];
        }
        printf("%s,%.6e,%.6e,%.6e,%.6e,%.4f", files[a], sqrt(s1), sqrt(s1 / t1), sqrt(sn), sqrt(sn / tn),
               ntri ? (double)nexact / (double)ntri : 0.0);
        for (b = 0; b < nbody; b++) printf(",%.6e", sqrt(e1[b]));
        printf("\n");
        fflush(stdout);
        free_vtk(&run);
    }
    free_vtk(&ref);
    return 0;
}
