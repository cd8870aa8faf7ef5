"""Helpers shared by the hard cases (tests/hard/*/check), on top of
tests/lib/c2dcheck.py.  Every check prints `PASS name` or `FAIL name: detail`.

What a hard case checks on every successful run (`standard`):
  - no NaN/Inf anywhere in the summary, the contact table or the VTK file;
  - Signorini conditions: gap >= -tol, pressure >= -tol, complementarity
    (the summary's value and max_i |p_i g_i| recomputed from the table);
  - equilibrium of each body: sum of its FIX reactions + its applied loads +
    the contact force it receives = 0, and the global balance (all reactions +
    all loads = 0, independent of the contact forces).

The contact force is rebuilt from the table, independently of the code:
mu_i = p_i * w_i with w_i = integral of the slave hat phi_i over the part of
the slave boundary that the master covers (computed here from the geometry
the deck describes), and the force on the slave body is -sum_i mu_i n_i with
n_i the normalized sum of the outward normals of the two slave segments at
node i (the slave nodal normal; MORTAR-NOTES.md).  The master body receives
+sum_i mu_i n_i (the rows of pi_h reproduce constants)."""
import atexit
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "lib"))
import c2dcheck as cc  # noqa: E402
from c2dcheck import check, close, small, summary, contact_table, vtk, finish  # noqa: E402,F401

PROGRAM = cc.PROGRAM


def tmpdir():
    """A scratch folder for the outputs, removed at exit unless HARD_KEEP is set
    (then its path is printed)."""
    d = tempfile.mkdtemp(prefix="c2d-hard-")
    if os.environ.get("HARD_KEEP"):
        print(f"# outputs kept in {d}")
    else:
        atexit.register(shutil.rmtree, d, True)
    return d


def run_raw(deck, outdir, *options):
    """Run contact2d; return the CompletedProcess (no check on the status)."""
    os.makedirs(outdir, exist_ok=True)
    return subprocess.run([PROGRAM, "-q", "-o", outdir, *options, deck], capture_output=True, text=True)


class Run:
    """One successful run: summary, contact rows, VTK (lazily)."""

    def __init__(self, name, outdir):
        self.name = name
        self.outdir = outdir
        self.s = summary(f"{outdir}/{name}.summary")
        path = f"{outdir}/{name}_contact.csv"
        self.rows = contact_table(path) if os.path.exists(path) else []
        self._vtk = None

    @property
    def v(self):
        if self._vtk is None:
            self._vtk = vtk(f"{self.outdir}/{self.name}.vtk")
        return self._vtk

    def reaction(self, label):
        return self.s["reaction"][label]

    def pair(self, ip):
        return [r for r in self.rows if int(r["pair"]) == ip]

    def constrained(self, ip=None):
        return [r for r in self.rows if r["status"] >= 0 and (ip is None or int(r["pair"]) == ip)]

    def value(self, key):
        return float(self.s[key][0])


def solve(deck, outdir, label=None):
    """Run a deck expected to solve (exit 0).  Returns a Run, or None after a
    FAIL line (the case continues with its other decks)."""
    name = os.path.splitext(os.path.basename(deck))[0]
    p = run_raw(deck, outdir)
    label = label or name
    crashed = any(k in p.stderr.lower() for k in ("runtime error", "backtrace", "segmentation", "sanitizer"))
    ok = p.returncode == 0 and not crashed
    check(ok, f"{label}: solves (exit 0)", f"status {p.returncode}: {p.stderr.strip()[:400]}")
    return Run(name, outdir) if ok else None


def expect_failure(deck, outdir, status, label=None):
    """Run a deck expected to fail with `status`: no crash, a one-line
    `contact2d: error: ...` diagnostic, no output file.  Returns stderr."""
    name = os.path.splitext(os.path.basename(deck))[0]
    label = label or name
    out = os.path.join(outdir, "fail-" + name)
    p = run_raw(deck, out)
    err = p.stderr.strip()
    check(p.returncode == status, f"{label}: exits {status}", f"status {p.returncode}: {err[:300]}")
    crashed = any(k in err.lower() for k in ("runtime error", "backtrace", "segmentation", "sanitizer")) or \
        re.search(r"\b(nan|inf|infinity)\b", err.lower()) is not None
    check(not crashed, f"{label}: no crash, no NaN in the diagnostic", err[:300])
    first = err.splitlines()[0] if err else ""
    check(first.startswith("contact2d: error: "), f"{label}: diagnostic 'contact2d: error: ...' on stderr",
          f"got '{first[:200]}'")
    left = [f for f in os.listdir(out) if not f.startswith(".")] if os.path.isdir(out) else []
    check(not left, f"{label}: no output written", f"found {left}")
    return err


# --- finiteness ----------------------------------------------------------------

def _finite_summary(s):
    bad = []
    for k, w in s.items():
        if k == "reaction":
            for lab, f in w.items():
                if not all(math.isfinite(x) for x in f):
                    bad.append(f"reaction {lab}")
            continue
        for x in w:
            try:
                if not math.isfinite(float(x)):
                    bad.append(k)
            except ValueError:
                pass
    return bad


def check_finite(run, with_vtk=True):
    bad = _finite_summary(run.s)
    for r in run.rows:
        for k, x in r.items():
            if x is not None and not math.isfinite(x):
                bad.append(f"table {k}")
    if with_vtk:
        for sec in ("point", "cell"):
            for k, arr in run.v[sec].items():
                if not all(math.isfinite(x) for c in arr for x in c):
                    bad.append(f"vtk {k}")
    check(not bad, f"{run.name}: no NaN/Inf in the outputs", ", ".join(sorted(set(bad)))[:300])


# --- Signorini conditions ---------------------------------------------------------

def check_signorini(run, gscale, pscale=None, tol_gap=1e-8, tol_p=1e-8, tol_c=1e-8):
    """gap >= -tol_gap*gscale, pressure >= -tol_p*pscale, complementarity
    (summary and recomputed) <= tol_c, status consistent with the pressure."""
    rows = run.constrained()
    name = run.name
    if not rows:
        check(False, f"{name}: contact rows present", "no constrained slave node in the table")
        return
    ps = [r["pressure"] for r in rows]
    gs = [r["gap"] for r in rows]
    pmax = max(abs(p) for p in ps)
    pscale = pscale if pscale is not None else (pmax if pmax > 0 else 1.0)
    # one-sided: an open node's positive gap, a positive pressure are no error; the
    # deepest penetration (or tension), 0 when none, is what must be small
    small(max(0.0, -min(gs)) / gscale, tol_gap, f"{name}: gap >= -{tol_gap:g} (scale {gscale:g})")
    small(max(0.0, -min(ps)) / pscale, tol_p, f"{name}: pressure >= -{tol_p:g} (scale {pscale:.4g})")
    small(run.value("complementarity"), tol_c, f"{name}: complementarity (summary) <= {tol_c:g}")
    mine = max(abs(p * g) for p, g in zip(ps, gs)) / (max(pmax, 1e-300) * gscale) if pmax > 0 else 0.0
    small(mine, tol_c, f"{name}: complementarity max|p g|/(pmax gscale) <= {tol_c:g}")
    act = sum(1 for r in rows if r["status"] == 1)
    check(act == int(run.s["active_nodes"][0]), f"{name}: active_nodes = rows with status 1",
          f"{run.s['active_nodes'][0]} vs {act}")
    odd = [(r["x"], r["pressure"], r["status"]) for r in rows
           if (r["status"] == 1 and not r["pressure"] > 0) or (r["status"] != 1 and r["pressure"] > 1e-10 * pmax)]
    check(not odd, f"{name}: status 1 where the pressure is positive, 0 where it is zero", str(odd[:4]))


# --- contact force from the table --------------------------------------------

def flat_cover(x0, x1):
    """Cover of a horizontal slave by a master spanning x0 <= x <= x1 (vertical
    projection along the slave normal)."""
    lo, hi = min(x0, x1), max(x0, x1)

    def cover(pa, pb):
        xa, xb = pa[0], pb[0]
        if xb == xa:
            return (0.0, 0.0)
        t0, t1 = (lo - xa) / (xb - xa), (hi - xa) / (xb - xa)
        t0, t1 = min(t0, t1), max(t0, t1)
        return (max(0.0, t0), min(1.0, t1))
    return cover


def line_cover(m0, m1):
    """Cover of any slave segment by the straight master segment m0-m1,
    projected orthogonally onto the slave segment's line."""
    def cover(pa, pb):
        tx, ty = pb[0] - pa[0], pb[1] - pa[1]
        l2 = tx * tx + ty * ty
        t0 = ((m0[0] - pa[0]) * tx + (m0[1] - pa[1]) * ty) / l2
        t1 = ((m1[0] - pa[0]) * tx + (m1[1] - pa[1]) * ty) / l2
        t0, t1 = min(t0, t1), max(t0, t1)
        return (max(0.0, t0), min(1.0, t1))
    return cover


FULL = None   # the master covers every slave segment of the zone entirely
SLIVER = 0.02  # a master stopping short of the zone's end node by less than this part of its segment reaches it


def nodal_forces(rows, inside, cover=FULL):
    """Nodal contact forces of one pair: list of (row, mu_i, (n_x, n_y)) for every
    slave node (rows: all slave nodes in boundary order), mu_i = p_i w_i with
    w_i the integral of phi_i over the covered part of the slave boundary.
    inside: a point inside the slave body (orients the outward normal);
    cover(pa, pb) -> (t0, t1) the covered part of segment pa-pb."""
    n = len(rows)
    pts = [(r["x"], r["y"]) for r in rows]
    segn, w = [], [0.0] * n
    for k in range(n - 1):
        pa, pb = pts[k], pts[k + 1]
        tx, ty = pb[0] - pa[0], pb[1] - pa[1]
        L = math.hypot(tx, ty)
        nx, ny = ty / L, -tx / L
        mx, my = 0.5 * (pa[0] + pb[0]) - inside[0], 0.5 * (pa[1] + pb[1]) - inside[1]
        if nx * mx + ny * my < 0:
            nx, ny = -nx, -ny
        segn.append((nx, ny))
        if cover is FULL:
            both = rows[k]["status"] >= 0 and rows[k + 1]["status"] >= 0
            t0, t1 = (0.0, 1.0) if both else (0.0, 0.0)
        else:
            t0, t1 = cover(pa, pb)
        if 0.0 < t0 < SLIVER and rows[k]["status"] >= 0:
            t0 = 0.0          # a master that stops short of the zone's end node by a sliver reaches it
        if 1.0 - SLIVER < t1 < 1.0 and rows[k + 1]["status"] >= 0:
            t1 = 1.0
        if t1 > t0:
            w[k] += L * ((t1 - t1 * t1 / 2) - (t0 - t0 * t0 / 2))
            w[k + 1] += L * (t1 * t1 - t0 * t0) / 2
    # a zone that ends inside a slave segment: the segment's outer node has no
    # master opposite (status -1); its share of the covered part is reported
    # on the node next to it (doc/outputs.md)
    for i in range(n):
        if rows[i]["status"] < 0 and w[i] > 0.0:
            j = i + 1 if i + 1 < n and rows[i + 1]["status"] >= 0 else i - 1
            w[j] += w[i]
            w[i] = 0.0
    out = []
    for i, r in enumerate(rows):
        if i == 0:
            nx, ny = segn[0]
        elif i == n - 1:
            nx, ny = segn[-1]
        else:
            nx, ny = segn[i - 1][0] + segn[i][0], segn[i - 1][1] + segn[i][1]
            m = math.hypot(nx, ny)
            nx, ny = nx / m, ny / m
        mu = r["pressure"] * w[i] if r["status"] >= 0 else 0.0
        out.append((r, mu, (nx, ny)))
    return out


def slave_force(rows, inside, cover=FULL):
    """Force (Fx, Fy) on the slave body from one pair: -sum_i mu_i n_i."""
    fx = fy = 0.0
    for r, mu, (nx, ny) in nodal_forces(rows, inside, cover):
        fx -= mu * nx
        fy -= mu * ny
    return fx, fy


def check_equilibrium(run, bodies, pairs, tol=1e-8, fscale=0.0):
    """bodies: {body: (Lx, Ly[, M])} applied load resultant of each body (all
    bodies), M the magnitude of its applied forces (sum of |load| over its
    loaded boundaries: the scale of a balance when the loads cancel out);
    pairs: list of (ip, slave_body, master_body, inside, cover).
    fscale: a force scale of the problem, the floor of the balance's scale (for
    problems where every force is zero).
    Checks each body (reactions + loads + contact = 0) and the global balance."""
    react = run.s["reaction"]
    contact = {b: [0.0, 0.0] for b in bodies}
    for ip, sb, mb, inside, cover in pairs:
        fx, fy = slave_force(run.pair(ip), inside, cover)
        contact[sb][0] += fx; contact[sb][1] += fy
        contact[mb][0] -= fx; contact[mb][1] -= fy
    scale = 0.0
    for lab, f in react.items():
        scale = max(scale, abs(f[0]), abs(f[1]))
    for b, L in bodies.items():
        scale = max(scale, *(abs(x) for x in L), abs(contact[b][0]), abs(contact[b][1]))
    scale = max(scale, fscale, 1e-300)
    gx = gy = 0.0
    for b, L in bodies.items():
        rx = sum(f[0] for lab, f in react.items() if lab.split(":")[0] == b)
        ry = sum(f[1] for lab, f in react.items() if lab.split(":")[0] == b)
        ex, ey = rx + L[0] + contact[b][0], ry + L[1] + contact[b][1]
        gx += rx + L[0]; gy += ry + L[1]
        small(max(abs(ex), abs(ey)) / scale, tol, f"{run.name}: equilibrium of body {b} "
              f"(reactions {rx:.6g},{ry:.6g} + loads + contact {contact[b][0]:.6g},{contact[b][1]:.6g})")
    small(max(abs(gx), abs(gy)) / scale, tol, f"{run.name}: global balance, all reactions + all loads = 0")
    return contact


def standard(run, gscale, bodies, pairs, pscale=None, tol_gap=1e-8, tol_p=1e-8, tol_c=1e-8, tol_eq=1e-8,
             with_vtk=True, fscale=0.0):
    """The checks every hard case makes on every successful run."""
    check_finite(run, with_vtk)
    check_signorini(run, gscale, pscale, tol_gap, tol_p, tol_c)
    return check_equilibrium(run, bodies, pairs, tol_eq, fscale)


# --- profiles ---------------------------------------------------------------------

def sorted_rows(rows, key="x"):
    return sorted((r for r in rows if r["status"] >= 0), key=lambda r: r[key])


def cumulative(xs, ps):
    """F(x_i) = integral from x_i to the last node of p (trapezoid rule)."""
    F = [0.0] * len(xs)
    for i in range(len(xs) - 2, -1, -1):
        F[i] = F[i + 1] + 0.5 * (ps[i] + ps[i + 1]) * (xs[i + 1] - xs[i])
    return F


def interp(xs, fs, x):
    if x <= xs[0]:
        return fs[0]
    if x >= xs[-1]:
        return fs[-1]
    lo, hi = 0, len(xs) - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if xs[mid] <= x:
            lo = mid
        else:
            hi = mid
    t = (x - xs[lo]) / (xs[hi] - xs[lo])
    return (1 - t) * fs[lo] + t * fs[hi]


def patch_pressure(shortening, layers):
    """Uniform pressure of the plane-strain patch test: layers = [(E, nu, height)],
    sigma_xx = 0, eps_yy = (1 - nu^2)/E sigma_yy, compliances in series."""
    return shortening / sum((1 - nu * nu) / E * h for E, nu, h in layers)


def check_patch(run, p, label=None, tol=1e-8, top="upper:top", gap_tol=1e-8, gscale=0.01):
    """Patch test: every constrained node active, pressure = p, sigma_yy = -p,
    sigma_xx = sigma_xy = 0 in every element, gaps closed, top reaction = p * width."""
    name = label or run.name
    rows = run.constrained()
    check(len(rows) > 0 and all(r["status"] == 1 for r in rows), f"{name}: every slave node active",
          f"{sum(1 for r in rows if r['status'] == 1)} of {len(rows)}")
    small(max(abs(r["pressure"] - p) for r in rows) / p, tol, f"{name}: pressure uniform = p = {p:.8g} to {tol:g}")
    st = run.v["cell"]["stress"]
    small(max(abs(c[1] + p) for c in st) / p, tol, f"{name}: sigma_yy = -p in every element")
    small(max(max(abs(c[0]), abs(c[2])) for c in st) / p, tol, f"{name}: sigma_xx = sigma_xy = 0")
    small(max(abs(r["gap"]) for r in rows) / gscale, gap_tol, f"{name}: gap closed at every slave node")
    close(abs(run.reaction(top)[1]), p * 1.0, tol, f"{name}: reaction on {top} = p x width")
