#!/usr/bin/python3
"""Accuracy per second on Hertz H: contact2d (P1, quadratic) against GetFEM
and CalculiX (their linear and quadratic elements), the error measured against
a reference solution of the same finite problem.

    driver.py --prog CONTACT2D --out DIR [--series code:kind,...] [--hc 0.08,...]
              [--reps 3] [--ref-hc 0.005] [--timeout 300] [--series-stop 30] [--a A]
              [--adapt-targets 0.03,0.01,0.003,0.001] [--adapt-max-dofs 500000]

kind: p1 / p2 = linear / quadratic elements on the even meshes of
input/hertz_*.geo (size hc around the zone, hf = min(0.5, 12.5 hc) far away); p1g / p2g =
the same graded toward the zone's ends (geo/hertz_*_graded.geo, grading(): size
hc^2/4 at the ends, growing at min(0.2, 5 hc) times the distance, capped by hc).
contact2d's slave is the block's "contact" curve (|x| <= 0.3 of its top),
which the disk's arc covers whole (quadratic traces need it).
adapt1 / adapt2 (contact2d only): ADAPT quantity=pressure on P1 / P2 elements,
from the even mesh at --adapt-hc (0.08), one point per target of
--adapt-targets (coarse to fine: the larger target first), each mesh at most
--adapt-max-dofs; the start meshes are the sweep's .msh files with the .geo
that made them beside them (ADAPT re-meshes from it), so, as for every other
point, making the start mesh is not timed, while every re-meshing by gmsh is.

1. Locate: a contact2d P1 run at hc = 0.005 gives a first half-width a of the
   finite problem (zone_end: p^2 extrapolated to 0 from the nodes before the
   end), two quadratic runs graded toward it refine it (zone_end_fit).
2. Reference: contact2d quadratic on graded meshes at 4, 2 and 1 x ref-hc.
   The three levels show the reference's own convergence: the distances of
   consecutive levels (pressure and energy norm) give the observed rate and
   the finest level's error estimate; a target below three times that
   estimate is flagged as not resolved.
3. Sweep: every series on every hc (meshing and input writing not timed);
   each point runs once, then again round robin up to --reps runs; a point
   whose first run took t CPU seconds gets min(reps, max(1, 60 / t)) runs;
   after a point that took more than --series-stop CPU seconds (or timed
   out) a series runs no finer point.
   Time = median user+sys CPU time of the solver process (getrusage of the
   child, its children included), wall time next to it.  An adaptive point's
   time is that of its whole run, every mesh's solve and every gmsh
   re-meshing (gmsh is contact2d's child); the summary's cpu_total, which
   counts the same, is recorded beside it.
4. Errors of each point (ref_err.py, h1_err.py):
   pressure: || p_h - p_ref ||_L2 / || p_ref ||_L2 along the block top, by
   quadrature exact for the piecewise polynomials (no node sampling);
   H1: the energy-norm error || u_ref - u_h ||_E / || u_ref ||_E over the
   window |x| <= 0.3, -0.3 <= y <= 0.3 around the zone (P1 and P2 fields).
   An adaptive point's errors are those of its final mesh's outputs, measured
   the same way; contact2d's own pressure estimate (the summary's `estimate
   pressure`) is set against the measured pressure error (effectivity).
5. Matched error e: along a series (coarse to fine), the first mesh from
   which every finer mesh stays at or below e, the CPU time interpolated
   log-log (error against time) between it and the mesh before it: a time
   read off the sweep's curve, not one lucky mesh (an adaptive series: its
   targets in place of the meshes).  The speedup is the faster peer's matched
   time over the faster contact2d series' (adaptive series included).
Prints the sweep, the reference's convergence and the matched tables; writes
DIR/runs.csv and DIR/results.md.
"""
import argparse
import csv
import math
import os
import platform
import shutil
import signal
import statistics
import subprocess
import sys
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.dont_write_bytecode = True
from c2d_profile import c2d_profile   # noqa: E402
from ccx_inp import write_inp          # noqa: E402
from ccx_profile import ccx_profile    # noqa: E402
from hertz_err import read_profile, hertz  # noqa: E402
from ref_err import Profile, l2_diff, load  # noqa: E402

PY = "/usr/bin/python3"
NAMES = {"contact2d": "contact2d", "getfem": "GetFEM", "ccx": "CalculiX"}
WINDOW = (-0.3, 0.3, -0.3, 0.3)
PRESSURE_TARGETS = (0.01, 0.003, 0.001)
KIND_NAMES = {"adapt1": "P1 ADAPT", "adapt2": "P2 ADAPT"}
H1_TARGETS = (0.05, 0.02, 0.01, 0.005)
DECK = """PLANE strain
BODY block
  MESH gmsh file={b}
  MATERIAL isotropic E=200000 nu=0.3
  FIX bottom ux=0 uy=0
END
BODY disk
  MESH gmsh file={d}
  MATERIAL isotropic E=200000 nu=0.3
  FIX top ux=0 uy=-0.01
END
CONTACT slave=block:contact master=disk:arc gap=geometry
SOLVER lcp=auto tol=1e-10
"""
ADAPT_LINE = "ADAPT target={t!r} quantity=pressure max_dofs={n}\n"


def timed(cmd, cwd, log, timeout, env):
    """Run cmd; return (exit code or None on timeout, wall s, user+sys CPU s of the child and its children)."""
    with open(log, "w") as f:
        t0 = time.perf_counter()
        p = subprocess.Popen(cmd, cwd=cwd, stdout=f, stderr=subprocess.STDOUT, env=env, start_new_session=True)
        killed = []
        timer = threading.Timer(timeout, lambda: (killed.append(1), os.killpg(p.pid, signal.SIGKILL)))
        timer.start()
        _, status, ru = os.wait4(p.pid, 0)
        t1 = time.perf_counter()
        timer.cancel()
    return (None if killed else os.waitstatus_to_exitcode(status)), t1 - t0, ru.ru_utime + ru.ru_stime


class Point:
    """One (code, kind, hc) point of the sweep (or a reference level)."""

    def __init__(self, code, kind, hc, wdir):
        self.code, self.kind, self.hc, self.wdir = code, kind, hc, wdir
        self.times, self.cpus = [], []
        self.perr = self.herr = self.dofs = self.P = None
        self.status = "ok"          # ok | not converged | failed | timeout | refused
        self.note = ""
        self.vtk = None
        self.target = None          # adaptive points: the ADAPT target
        self.est = None             # contact2d: the summary's pressure estimate
        self.meshes = self.result = self.cpu_total = None     # adaptive points: the summary's adapt lines

    @property
    def degree(self):
        return 2 if self.kind.startswith("p2") or self.kind == "adapt2" else 1

    @property
    def adaptive(self):
        return is_adaptive(self.kind)

    def cpu(self):
        return statistics.median(self.cpus) if self.cpus else None

    def wall(self):
        return statistics.median(self.times) if self.times else None

    def usable(self):
        return self.status == "ok" and self.perr is not None


def is_adaptive(kind):
    return kind.startswith("adapt")


def levels(kind, args):
    """A series' points, coarse to fine: the sweep's sizes hc, or an adaptive series' targets (both
    decreasing)."""
    return args.adapt_targets if is_adaptive(kind) else args.hcs


def far_size(hc):
    """The far-field size hf = min(0.5, 12.5 hc) (as in studies/): with hf fixed, the far field's
    discretization error (the load P, hence the pressure's scale) would stay the same at every hc,
    and every series would level off at it."""
    return min(0.5, 12.5 * hc)


def grading(hc):
    """(hz, g) of the graded meshes at size hc: element size hz = hc^2 / 4 at the zone's ends (lengths in
    units of the disk's radius R = 1), growing at g = min(0.2, 5 hc) times the distance to the nearer end,
    capped by hc.  Near an end p ~ sqrt(r): with the ratio hc / hz and the growth g fixed, the elements at
    the end and the graded region (length hc / g) hold the pressure's L2 error to O(hc) (an end missed by
    d costs about d / a); with hz ~ hc^2 and g ~ hc it is O(hc^2), as where the solution is smooth."""
    return 0.25 * hc * hc, min(0.2, 5.0 * hc)


def mesh(args, body, hc, kind):
    """The gmsh mesh (MSH 2.2) of body for size hc and kind (p1/p2 even, p1g/p2g graded toward the
    zone's ends as grading() says; p2s: P1 geometry for a P2 field); made once, not timed."""
    graded = kind.endswith("g")
    order = 2 if kind.startswith("p2") and not kind.startswith("p2s") else 1
    hz, g = grading(hc)
    tag = f"{body}_hc{hc:g}{'_g' + format(hz, 'g') + '_' + format(g, 'g') + '_a' + format(args.a, '.8g') if graded else ''}_o{order}"
    path = os.path.join(args.out, "mesh", tag + ".msh")
    if not os.path.exists(path):
        os.makedirs(os.path.dirname(path), exist_ok=True)
        # the block always from geo/ (its "contact" curve), the disk from input/ unless graded
        geo = os.path.join(HERE, "geo", f"hertz_{body}_graded.geo") if graded or body == "block" else \
            os.path.join(args.top, "input", f"hertz_{body}.geo")
        cmd = ["gmsh", "-2", "-order", str(order), "-format", "msh22", "-v", "0",
               "-setnumber", "hc", repr(hc), "-setnumber", "hf", repr(far_size(hc))]
        if body == "block":
            cmd += ["-setnumber", "graded", str(int(graded))]
        if graded:
            cmd += ["-setnumber", "a", repr(args.a), "-setnumber", "hz", repr(hz), "-setnumber", "g", repr(g)]
        subprocess.run(cmd + [geo, "-o", path + ".tmp"], check=True, stdout=subprocess.DEVNULL)
        os.replace(path + ".tmp", path)
    return path


def start_geo(top, body, hc):
    """The .geo that makes the start mesh of an adaptive point (the even mesh of mesh(): input/hertz_*.geo
    with its hc and hf, the block with its "contact" curve), self-contained: ADAPT re-meshes from it, and a
    .geo beside an .msh is screened, which refuses an Include outside the deck's folder."""
    src = open(os.path.join(top, "input", f"hertz_{body}.geo")).read()
    line = "DefineConstant[ hc = 0.02, hf = 0.5 ];"
    if line not in src:
        sys.exit(f"peers: input/hertz_{body}.geo: no '{line}' line to set the start mesh's sizes in")
    src = src.replace(line, f"DefineConstant[ hc = {hc!r}, hf = {far_size(hc)!r} ];")
    if body == "block":
        src += 'Physical Curve("contact") = {4};\n'
    return src


def prepare(pt, args):
    """Mesh and write the input of a point."""
    os.makedirs(pt.wdir, exist_ok=True)
    if pt.adaptive:
        # the sweep's even mesh at the start size, with the .geo that made it beside it
        kind = "p2" if pt.degree == 2 else "p1"
        for body in ("block", "disk"):
            shutil.copy(mesh(args, body, pt.hc, kind), os.path.join(pt.wdir, body + ".msh"))
            with open(os.path.join(pt.wdir, body + ".geo"), "w") as f:
                f.write(start_geo(args.top, body, pt.hc))
        pt.block, pt.disk = os.path.join(pt.wdir, "block.msh"), os.path.join(pt.wdir, "disk.msh")
        with open(os.path.join(pt.wdir, "hertz.deck"), "w") as f:
            f.write(DECK.format(b="block.msh", d="disk.msh") + ADAPT_LINE.format(t=pt.target, n=args.adapt_max_dofs))
        return
    # GetFEM's quadratic runs use the straight-edged meshes (see getfem_hertz.py)
    mkind = pt.kind.replace("p2", "p2s") if pt.code == "getfem" else pt.kind
    pt.block, pt.disk = mesh(args, "block", pt.hc, mkind), mesh(args, "disk", pt.hc, mkind)
    if pt.code == "contact2d":
        with open(os.path.join(pt.wdir, "hertz.deck"), "w") as f:
            f.write(DECK.format(b=pt.block, d=pt.disk))
    elif pt.code == "ccx":
        write_inp(pt.block, pt.disk, os.path.join(pt.wdir, "hertz.inp"))


def run_once(pt, args, env):
    """Run a point once; the first run also writes its profile (and P1 field)."""
    w = pt.wdir
    prof = os.path.join(w, "profile.txt")
    vtk = os.path.join(w, "field.vtk")
    if pt.code == "contact2d":
        # an adaptive run meshes as a first run does (no mesh cache read or written)
        cmd = [args.prog, "-q"] + (["--no-mesh-cache"] if pt.adaptive else []) + \
            ["-o", os.path.join(w, "o"), os.path.join(w, "hertz.deck")]
    elif pt.code == "getfem":
        cmd = [PY, os.path.join(HERE, "getfem_hertz.py"), pt.block, pt.disk, prof, "1e-5", "50", str(pt.degree)]
        if vtk and not pt.times:
            cmd.append(vtk)
    else:
        cmd = ["ccx", "-i", "hertz"]
    rc, t, cpu = timed(cmd, w, os.path.join(w, f"log{len(pt.times) + 1}.txt"), args.timeout, env)
    if pt.code == "getfem" and vtk and not pt.times and os.path.exists(vtk + ".cpu"):
        extra = float(open(vtk + ".cpu").read())    # writing the field for the H1 error is not the solve's
        t, cpu = t - extra, cpu - extra
    if rc is None:
        pt.status, pt.note = "timeout", f"killed after {args.timeout:g} s"
        return
    if not pt.times:
        try:
            if pt.code == "contact2d":
                if rc == 2:
                    msg = open(os.path.join(w, "log1.txt")).read().strip().splitlines()
                    pt.status, pt.note = "refused", (msg[0] if msg else "exit status 2")[:160]
                    return
                if rc != 0:
                    raise RuntimeError(f"exit status {rc}")
                c2d_profile(os.path.join(w, "o", "hertz_contact.csv"), os.path.join(w, "o", "hertz.summary"),
                            prof, pt.degree)
                read_estimate(pt, os.path.join(w, "o", "hertz.summary"))
                if vtk:
                    shutil.copy(os.path.join(w, "o", "hertz.vtk"), vtk)
            elif pt.code == "ccx":
                if rc != 0:
                    raise RuntimeError(f"exit status {rc}")
                ccx_profile(pt.block, pt.disk, os.path.join(w, "hertz"), prof, vtk)
                pt.note = f"{sum(1 for ln in open(os.path.join(w, 'log1.txt')) if ln.startswith(' iteration'))} it."
            else:
                if rc not in (0, 3):
                    raise RuntimeError(f"exit status {rc}")
                meta = read_profile(prof)[0]
                pt.note = f"{meta.get('newton_iterations', '?')} Newton it."
                if rc == 3:
                    pt.status = "not converged"
            meta = read_profile(prof)[0]
            pt.dofs, pt.P = int(meta["dofs"]), float(meta["P"])
            pt.prof = prof
            pt.vtk = vtk
        except (OSError, ValueError, KeyError, RuntimeError) as e:
            pt.status, pt.note = "failed", str(e).splitlines()[0][:80]
    pt.times.append(t)
    pt.cpus.append(cpu)


def read_estimate(pt, summary):
    """The summary's pressure estimate of the pair, and for ADAPT the number of meshes, the result and
    cpu_total."""
    steps = 0
    for line in open(summary):
        w = line.split()
        if len(w) >= 4 and w[:2] == ["estimate", "pressure"]:
            pt.est = float(w[3])
        elif w and w[0] == "adapt":
            steps += 1
        elif len(w) >= 2 and w[0] == "adapt_result":
            pt.result = " ".join(w[1:])
        elif len(w) >= 2 and w[0] == "cpu_total":
            pt.cpu_total = float(w[1])
    if pt.adaptive:
        pt.meshes = steps
        pt.note = f"target {pt.target * 100:g} %: {steps} meshes, {pt.result}"


def locate_a(args, env):
    """Half-width of the contact zone of the finite problem: a P1 run at hc = 0.005 (zone_end), then two
    quadratic runs graded toward the previous estimate (hc = 0.02), each refitted by zone_end_fit.  Returns
    (a, the list of estimates)."""
    pt = Point("contact2d", "p1", 0.005, os.path.join(args.out, "locate"))
    prepare(pt, args)
    run_once(pt, args, env)
    if pt.status != "ok":
        sys.exit(f"peers: the locating run failed: {pt.note}")
    _, xs, ps = read_profile(pt.prof)
    est = [zone_end(xs, ps)]
    for k in range(2):
        args.a = est[-1]
        pt = Point("contact2d", "p2g", 0.02, os.path.join(args.out, f"locate{k + 2}"))
        prepare(pt, args)
        run_once(pt, args, env)
        if pt.status != "ok":
            sys.exit(f"peers: the locating run failed: {pt.note}")
        _, xs, ps = read_profile(pt.prof)
        est.append(zone_end_fit(xs, ps))
    return est[-1], est


def zone_end_fit(xs, ps):
    """Half-width a of a pressure profile resolved at its ends (a quadratic solve graded toward them), both
    sides averaged: Hertz's p^2 = p0^2 (1 - x^2 / a^2) is linear in x^2, so p^2 is fitted by a line in x^2
    over the nodes in contact with |x| in [0.8, 0.995] x_last (x_last the last node in contact; the finite
    problem's pressure differs from Hertz's shape by some 0.3 %, locally less), and a^2 is its root."""
    ends = []
    for side in (1.0, -1.0):
        pts = [(side * x, p) for x, p in zip(xs, ps) if side * x >= 0.0 and p > 0.0]
        last = max(x for x, _ in pts)
        fit = [(x * x, p * p) for x, p in pts if 0.8 * last <= x <= 0.995 * last]
        if len(fit) < 3:
            fit = [(x * x, p * p) for x, p in sorted(pts)[-4:-1]]
        n = len(fit)
        mx, my = sum(x for x, _ in fit) / n, sum(y for _, y in fit) / n
        slope = sum((x - mx) * (y - my) for x, y in fit) / sum((x - mx) ** 2 for x, _ in fit)
        ends.append(math.sqrt(mx - my / slope))
    return 0.5 * (ends[0] + ends[1])


def zone_end(xs, ps):
    """Half-width a of a pressure profile, both sides averaged.  Near the end p ~ c sqrt(a - |x|), so p^2
    is linear in |x|: the line through p^2 at the three nodes before the last one in contact (the last
    one carries the end's error) is extrapolated to 0, and kept between the last node in contact and the
    next (the middle of the two had an error up to half a mesh size)."""
    ends = []
    for side in (1.0, -1.0):
        pts = sorted((side * x, p) for x, p in zip(xs, ps) if side * x >= 0.0)
        k = max(i for i, (_, p) in enumerate(pts) if p > 0.0)
        lo, hi = pts[k][0], pts[min(k + 1, len(pts) - 1)][0]
        fit = [(x, p * p) for x, p in pts[max(0, k - 3):k]]
        n = len(fit)
        mx, my = sum(x for x, _ in fit) / n, sum(y for _, y in fit) / n
        sxx = sum((x - mx) ** 2 for x, _ in fit)
        slope = sum((x - mx) * (y - my) for x, y in fit) / sxx if n >= 2 and sxx > 0.0 else 0.0
        root = mx - my / slope if slope < 0.0 else 0.5 * (lo + hi)
        ends.append(min(max(root, lo), hi))
    return 0.5 * (ends[0] + ends[1])


def h1_errors(ref, pts):
    """Energy-norm error over the window of each point with a field, against the reference Field ref."""
    import h1_err      # numpy and scipy: /usr/bin/python3 (Debian's), imported where used
    for p in pts:
        if p.vtk and p.status in ("ok", "not converged") and os.path.exists(p.vtk):
            p.herr = h1_err.energy_errors(ref, h1_err.Field(p.vtk), WINDOW)[1]


def hertz_distance(prof_path):
    """|| p - p_Hertz ||_L2 / || p_Hertz ||_L2 with a, p0 from the profile's own P (the model's difference)."""
    meta, prof = load(prof_path)
    a, p0 = hertz(float(meta["P"]))
    n = 20000
    xs = [a * math.sin(0.5 * math.pi * (2.0 * k / n - 1.0)) for k in range(n + 1)]   # dense at the ends
    hz = Profile(xs, [p0 * math.sqrt(max(0.0, 1.0 - (x / a) ** 2)) for x in xs])
    num, den = l2_diff(prof, hz)
    return num / den


def match(series, e, attr):
    """(CPU time, dofs) at error e along a series: the first mesh from which every finer one stays at or
    below e, interpolated log-log against the mesh before it; None if not reached."""
    good = [p for p in series if p.usable() and getattr(p, attr) is not None]
    j = None
    for k in range(len(good) - 1, -1, -1):
        if getattr(good[k], attr) <= e:
            j = k
        else:
            break
    if j is None:
        return None
    hi = good[j]
    if j == 0:
        return hi.cpu(), hi.dofs, True
    lo = good[j - 1]
    el, eh = getattr(lo, attr), getattr(hi, attr)
    s = math.log(e / el) / math.log(eh / el) if eh < el else 1.0
    t = math.exp(math.log(lo.cpu()) + s * (math.log(hi.cpu()) - math.log(lo.cpu())))
    d = math.exp(math.log(lo.dofs) + s * (math.log(hi.dofs) - math.log(lo.dofs)))
    return t, d, False


def versions(args, codes):
    v = {}
    r = subprocess.run([args.prog, "--version"], capture_output=True, text=True)
    v["contact2d"] = (r.stdout.strip().splitlines() or ["?"])[0]
    if "getfem" in codes:
        r = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "python3-getfem"], capture_output=True, text=True)
        v["getfem"] = "GetFEM " + (r.stdout.strip() or "?") + " (python3-getfem, nodal contact brick, MUMPS)"
    if "ccx" in codes:
        r = subprocess.run(["ccx", "-v"], capture_output=True, text=True)
        ver = next((ln.split()[-1] for ln in r.stdout.splitlines() if "Version" in ln), "?")
        v["ccx"] = f"CalculiX {ver} (calculix-ccx, CPE3/CPE6, surface-to-surface penalty K = 500 E, SPOOLES)"
    return v


def label(code, kind):
    return f"{NAMES[code]} {KIND_NAMES.get(kind, kind.upper())}"


def fit_rate_dofs(series, attr):
    """The rate of an adaptive series: least-squares slope of log(error) against log(dofs^(-1/2)) (an
    even mesh's size in 2D goes as dofs^(-1/2)), None if fewer than 3 usable points."""
    good = [(-0.5 * math.log(p.dofs), math.log(getattr(p, attr))) for p in series
            if p.usable() and getattr(p, attr) is not None and getattr(p, attr) > 0.0 and p.dofs]
    if len(good) < 3:
        return None
    mx = sum(x for x, _ in good) / len(good)
    my = sum(y for _, y in good) / len(good)
    return sum((x - mx) * (y - my) for x, y in good) / sum((x - mx) ** 2 for x, _ in good)


def fit_rate(series, attr):
    """Least-squares slope of log(error) against log(hc) over a series' usable points (None if < 3)."""
    good = [(math.log(p.hc), math.log(getattr(p, attr))) for p in series
            if p.usable() and getattr(p, attr) is not None and getattr(p, attr) > 0.0]
    if len(good) < 3:
        return None
    mx = sum(x for x, _ in good) / len(good)
    my = sum(y for _, y in good) / len(good)
    return sum((x - mx) * (y - my) for x, y in good) / sum((x - mx) ** 2 for x, _ in good)


def reference_convergence(refs, fields):
    """{"p": (d01, d12, rate, estimate), "h1": (...)} of the three reference levels (hc halved each time):
    d01, d12 the relative distances of consecutive levels (pressure L2; energy norm over the window),
    rate = log2(d01 / d12), estimate = d12 / (2^rate - 1), the finest level's error if the rate holds."""
    import h1_err
    lv = [refs.get(f"L{k}") for k in range(3)]
    if not all(p is not None and p.status == "ok" for p in lv):
        return {}
    out = {"p": [], "h1": []}
    for a, b in ((lv[0], lv[1]), (lv[1], lv[2])):
        num, den = l2_diff(load(a.prof)[1], load(b.prof)[1])
        out["p"].append(num / den)
        out["h1"].append(h1_err.energy_errors(fields[b.kind + b.level], fields[a.kind + a.level], WINDOW)[1])
    for key, (d01, d12) in list(out.items()):
        rate = math.log2(d01 / d12) if d01 > 0.0 and d12 > 0.0 else float("nan")
        est = d12 / (2.0 ** rate - 1.0) if rate > 0.0 else float("inf")
        out[key] = (d01, d12, rate, est)
    return out


def report(args, series, hcs, pts, refs, conv, pref, codes, ver, load0, load1, took):
    """The markdown section of doc/accuracy-cost.md, from this run's numbers."""
    out = []
    W = out.append
    commit = subprocess.run(["git", "-C", args.top, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip() or "?"
    W(f"Generated by `bench/peers.sh {args.reps}` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())} from commit "
      f"{commit}; {platform.machine()}, {os.cpu_count()} cpus, {args.threads} thread per process; load average "
      f"{load0[0]:.2f} {load0[1]:.2f} {load0[2]:.2f} at the start, {load1[0]:.2f} {load1[1]:.2f} {load1[2]:.2f} "
      f"at the end; {took / 60:.1f} minutes.")
    W("")
    for c in codes:
        W(f"* {ver[c]}")
    W("")
    how = ("located: contact2d P1 at hc = 0.005, p^2 extrapolated to 0 at the end, "
           + ", then ".join(format(e, ".6f") for e in args.a_steps[:1]) + "; quadratic at hc = 0.02 graded "
           "toward the previous value, p^2 fitted linearly in x^2 near the end: "
           + ", ".join(format(e, ".6f") for e in args.a_steps[1:])) if args.located else "given"
    hz0, g0 = grading(hcs[0])
    W(f"Zone half-width of the finite problem: a = {args.a:.6f} ({how}).  Graded meshes: size hz = hc^2/4 at "
      "the zone's ends (the block's points (+-a, 0) and the disk's (+-a, 1 - sqrt(1 - a^2)) on its arc), growing "
      f"at g = min(0.2, 5 hc) times the distance, capped by the even mesh's size hc (at hc = {hcs[0]:g}: "
      f"hz = {hz0:.3g}, g = {g0:.3g}).")
    W("")
    W(f"**The reference**: contact2d quadratic on graded meshes, three levels hc = 4, 2, 1 x {args.ref_hc:g}; "
      "'vs Hertz' is the L2 distance of the pressure to Hertz's half-space pressure for the level's own load "
      "(the model's difference, not an error):")
    W("")
    W("| level | hc | dofs | P | CPU (s) | vs Hertz | status |")
    W("| --- | ---: | ---: | ---: | ---: | ---: | --- |")
    for lev, p in refs.items():
        hz = f"{hertz_distance(p.prof) * 100:.3f}%" if p.status == "ok" else "-"
        W(f"| {lev} | {p.hc:g} | {p.dofs or 0} | {p.P or 0:.4f} | {p.cpu() or 0:.2f} | {hz} | {p.status} {p.note} |")
    W("")
    W("Its convergence: d01, d12 = relative distances L0-L1 and L1-L2 (pressure L2; energy norm over the "
      "window), rate = log2(d01/d12), and the finest level's error estimated as d12 / (2^rate - 1):")
    W("")
    W("| measure | d01 | d12 | rate | estimated error of L2 |")
    W("| --- | ---: | ---: | ---: | ---: |")
    for key, (d01, d12, rate, est) in conv.items():
        W(f"| {'pressure' if key == 'p' else 'H1 (energy)'} | {d01 * 100:.4f}% | {d12 * 100:.4f}% | "
          f"{rate:.2f} | {est * 100:.4f}% |")
    W("")
    W("Both references are the L2 level.  An error measured against it is the run's error to within the "
      "reference's own (the estimate above): a target below three times that estimate is flagged.")
    W("")
    W("**The sweep.** p err = || p_h - p_ref ||_L2 / || p_ref ||_L2 along the block top (quadrature exact for "
      "the piecewise polynomials, no node sampled); H1 = energy-norm error over the window |x|, |y| <= 0.3 "
      "relative to the reference's energy norm there (`h1_err.py`, P1 and P2 fields); CPU = median "
      "user+sys time of n runs of the whole process (s), wall = median wall time (s).  The adaptive series "
      "(P1 ADAPT, P2 ADAPT: `ADAPT target=T quantity=pressure "
      f"max_dofs={args.adapt_max_dofs}`, one run per target T) start from the even mesh at hc = "
      f"{args.adapt_hc:g} (the hc column, with the target T); their dofs and errors are the final mesh's, their CPU time the "
      "whole run's, every mesh's solve and gmsh's re-meshings included.")
    W("")
    W("| series | hc | dofs | p err (%) | H1 (%) | CPU (s) | wall (s) | n | note |")
    W("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |")
    for code, kind in series:
        for i, lev in enumerate(levels(kind, args)):
            p = pts[code, kind, lev]
            hc = p.hc
            if p.status == "refused" and i > 0:
                continue
            pe = f"{p.perr * 100:.4f}" if p.perr is not None else "-"
            he = f"{p.herr * 100:.3f}" if p.herr is not None else "-"
            mark = {"ok": "", "not converged": " (not converged: not matched)", "failed": " FAILED",
                    "timeout": " TIMEOUT", "refused": " REFUSED", "skipped": " (not run)"}[p.status]
            at = f"{hc:g} (T = {p.target * 100:g}%)" if p.adaptive else f"{hc:g}"
            W(f"| {label(code, kind)} | {at} | {p.dofs or 0} | {pe} | {he} | {p.cpu() or 0:.3f} | "
              f"{p.wall() or 0:.3f} | {len(p.cpus)} | {p.note}{mark} |")
    W("")
    W("Observed rates (least-squares slope of log error against log hc over the sweep; an adaptive series "
      "against log dofs^(-1/2), which an even mesh's hc follows in 2D):")
    W("")
    W("| series | pressure L2 | H1 |")
    W("| --- | ---: | ---: |")
    for code, kind in series:
        sp = [pts[code, kind, h] for h in levels(kind, args)]
        fit = fit_rate_dofs if is_adaptive(kind) else fit_rate
        rp, rh = fit(sp, "perr"), fit(sp, "herr")
        W(f"| {label(code, kind)} | {'-' if rp is None else format(rp, '.2f')} | "
          f"{'-' if rh is None else format(rh, '.2f')} |")
    c2d = [(c, k) for c, k in series if c == "contact2d"]
    if c2d:
        W("")
        W("**contact2d's pressure estimate against the error**: the summary's `estimate pressure` (the final "
          "mesh's for ADAPT) over the measured p err, at each point of the series, coarse to fine:")
        W("")
        W("| series | effectivity (estimate / p err) |")
        W("| --- | --- |")
        for code, kind in c2d:
            eff = [f"{p.est / p.perr:.2f}" if p.usable() and p.est is not None and p.perr else "-"
                   for p in (pts[code, kind, h] for h in levels(kind, args))]
            W(f"| {label(code, kind)} | {', '.join(eff)} |")
    adapt = [(c, k) for c, k in series if is_adaptive(k)]
    if adapt:
        W("")
        W("**The adaptive runs**: meshes solved, the result (`adapt_result`), the final mesh's dofs, the "
          "estimate and the measured errors, and the CPU time (s) as the bench measures it (getrusage of the "
          "process and its children) beside the summary's `cpu_total` (the same run's own count):")
        W("")
        W("| series | target | meshes | result | dofs | estimate (%) | p err (%) | effectivity | H1 (%) | CPU (s) "
          "| cpu_total (s) |")
        W("| --- | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
        for code, kind in adapt:
            for t in levels(kind, args):
                p = pts[code, kind, t]
                if not p.usable():
                    W(f"| {label(code, kind)} | {t * 100:g}% | - | {p.status} {p.note} | - | - | - | - | - | - | - |")
                    continue
                est = f"{p.est * 100:.4f}" if p.est is not None else "-"
                eff = f"{p.est / p.perr:.2f}" if p.est is not None and p.perr else "-"
                he = f"{p.herr * 100:.3f}" if p.herr is not None else "-"
                W(f"| {label(code, kind)} | {t * 100:g}% | {p.meshes} | {p.result} | {p.dofs} | {est} | "
                  f"{p.perr * 100:.4f} | {eff} | {he} | {p.cpu():.3f} | "
                  f"{'-' if p.cpu_total is None else format(p.cpu_total, '.3f')} |")
    for what, attr, targets in (("pressure L2 error", "perr", PRESSURE_TARGETS),
                                ("H1 (energy) error", "herr", H1_TARGETS)):
        W("")
        W(f"**CPU time (s) at matched {what}**: along each series the first mesh from which every finer one "
          "stays at or below the target, the time interpolated log-log against the mesh before it (`=`: the "
          "coarsest mesh is already below; an adaptive series: its targets in place of the meshes); dofs "
          "interpolated the same way in brackets.  The last column sets the faster peer against the faster "
          "contact2d series, adaptive ones included.")
        W("")
        W("| target | " + " | ".join(label(c, k) for c, k in series) + " | contact2d / faster peer |")
        W("| ---: | " + " | ".join("---:" for _ in series) + " | --- |")
        ref_est = conv.get("p" if attr == "perr" else "h1")
        for e in targets:
            unresolved = ref_est is None or e < 3.0 * ref_est[3]
            row = f"| {e * 100:g}%{' (not resolved: reference error ~' + format(ref_est[3] * 100, '.2g') + '%)' if unresolved and ref_est else ''} |"
            res = {}
            for code, kind in series:
                m = match([pts[code, kind, h] for h in levels(kind, args)], e, attr)
                res[code, kind] = m
                row += " - |" if m is None else f" {m[0]:.3f}{'=' if m[2] else ''} ({m[1]:.0f}) |"
            mine = [(m[0], KIND_NAMES.get(k, k.upper())) for (c, k), m in res.items()
                    if c == "contact2d" and m is not None]
            peers = [(m[0], label(c, k)) for (c, k), m in res.items() if c != "contact2d" and m is not None]
            if not mine:
                row += " contact2d does not reach it |"
            elif not peers:
                row += f" contact2d {min(mine)[1]} reaches it, no peer does |"
            else:
                tm, km = min(mine)
                tp, name = min(peers)
                row += f" **{tp / tm:.1f}x** (contact2d {km} vs {name}) |"
            W(row)
    best = match([pts["contact2d", "p2g", h] for h in levels("p2g", args)], 0.001, "perr") if ("contact2d", "p2g") in series else None
    W("")
    if best is None:
        W("**The goal** (quadratic contact2d at 0.1 % pressure error in under 1 s of CPU time): not reached in "
          "this sweep.")
    else:
        W(f"**The goal** (quadratic contact2d at 0.1 % pressure error in under 1 s of CPU time): contact2d P2G "
          f"reaches 0.1 % at {best[0]:.3f} s ({best[1]:.0f} dofs): {'met' if best[0] < 1.0 else 'not met'}"
          f"{' (the coarsest mesh of the sweep is already below it)' if best[2] else ''}.")
    return "\n".join(out)


def splice(doc, text):
    """Replace the text between the bench/peers.sh markers of doc by text."""
    begin, end = "<!-- bench/peers.sh: begin -->", "<!-- bench/peers.sh: end -->"
    with open(doc) as f:
        old = f.read()
    if begin not in old or end not in old:
        sys.exit(f"peers: {doc}: no '{begin}' ... '{end}' markers")
    i, j = old.index(begin) + len(begin), old.index(end)
    with open(doc, "w") as f:
        f.write(old[:i] + "\n" + text + "\n" + old[j:])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--prog", required=True)
    ap.add_argument("--top", default=os.path.dirname(os.path.dirname(HERE)))
    ap.add_argument("--out", required=True)
    ap.add_argument("--series", default="contact2d:p1,contact2d:p1g,contact2d:p2,contact2d:p2g,"
                    "contact2d:adapt1,contact2d:adapt2,getfem:p1,getfem:p1g,getfem:p2,getfem:p2g,ccx:p1,ccx:p1g,ccx:p2,ccx:p2g")
    # the two coarsest sizes find the cheapest graded mesh at 1 %: the quadratic
    # graded series is already at 0.2 % at hc = 0.08
    ap.add_argument("--hc", default="0.16,0.113,0.08,0.056,0.04,0.028,0.02,0.014,0.01")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--point-budget", type=float, default=60.0)
    ap.add_argument("--ref-hc", type=float, default=0.005)
    ap.add_argument("--series-stop", type=float, default=30.0,
                    help="a series whose point took more CPU seconds than this runs no finer point")
    ap.add_argument("--a", type=float, default=None, help="the zone's half-width (default: located)")
    ap.add_argument("--timeout", type=float, default=300.0)
    ap.add_argument("--threads", default="1")
    ap.add_argument("--doc", default="")
    ap.add_argument("--adapt-targets", default="0.03,0.01,0.003,0.001",
                    help="the ADAPT targets (relative pressure errors) of the adaptive series")
    ap.add_argument("--adapt-hc", type=float, default=0.08,
                    help="the even mesh size the adaptive series start from")
    ap.add_argument("--adapt-max-dofs", type=int, default=500000, help="ADAPT max_dofs of the adaptive series")
    args = ap.parse_args()
    args.located = args.a is None
    series = [tuple(s.split(":")) for s in args.series.split(",") if s]
    codes = sorted({c for c, _ in series}, key=list(NAMES).index)
    hcs = sorted((float(h) for h in args.hc.split(",")), reverse=True)
    args.hcs = hcs
    args.adapt_targets = sorted((float(t) for t in args.adapt_targets.split(",")), reverse=True)
    if any(c != "contact2d" for c, k in series if is_adaptive(k)):
        sys.exit("peers: only contact2d has the adaptive series (adapt1, adapt2)")
    os.makedirs(args.out, exist_ok=True)
    # one binary for the whole run, even if bin/ is rebuilt meanwhile
    os.makedirs(os.path.join(args.out, "bin"), exist_ok=True)
    shutil.copy2(args.prog, os.path.join(args.out, "bin", "contact2d"))
    args.prog = os.path.join(args.out, "bin", "contact2d")
    env = dict(os.environ, OMP_NUM_THREADS=args.threads, OPENBLAS_NUM_THREADS=args.threads,
               CCX_NPROC_EQUATION_SOLVER=args.threads, CCX_NPROC_STIFFNESS=args.threads,
               CCX_NPROC_RESULTS=args.threads)
    start = time.time()
    load0 = os.getloadavg()
    log = lambda *m: print(*m, file=sys.stderr, flush=True)   # noqa: E731

    # 1. the zone's half-width of the finite problem (the graded meshes' target)
    if args.a is None:
        args.a, args.a_steps = locate_a(args, env)
    log(f"  zone half-width a = {args.a:.6f}{'' if args.located else ' (given)'}")

    # 2. the reference: contact2d quadratic on graded meshes, three levels (hc = 4, 2, 1 x ref-hc)
    refs = {}
    for lev, f in (("L0", 4.0), ("L1", 2.0), ("L2", 1.0)):
        pt = Point("contact2d", "p2g", f * args.ref_hc, os.path.join(args.out, "ref", f"p2g_{lev}"))
        pt.level = lev
        prepare(pt, args)
        run_once(pt, args, env)
        log(f"  reference {lev} hc={pt.hc:g}: {pt.status} {pt.note} {pt.cpus[-1] if pt.cpus else 0:.1f} s")
        refs[lev] = pt
        if pt.status != "ok":
            sys.exit(f"peers: the reference run {lev} failed: {pt.note}")
    pref = refs["L2"]
    import h1_err
    fields = {p.kind + p.level: h1_err.Field(p.vtk) for p in refs.values()}
    conv = reference_convergence(refs, fields)
    log("  reference convergence: " + "; ".join(f"{k}: d01 {v[0]:.3e} d12 {v[1]:.3e} rate {v[2]:.2f}"
                                                 for k, v in conv.items()))

    # 3. the sweep
    pts = {}
    for code, kind in series:
        for lev in levels(kind, args):
            if is_adaptive(kind):
                pt = Point(code, kind, args.adapt_hc, os.path.join(args.out, code, f"{kind}_t{lev:g}"))
                pt.target = lev
            else:
                pt = Point(code, kind, lev, os.path.join(args.out, code, f"{kind}_hc{lev:g}"))
            prepare(pt, args)
            pts[code, kind, lev] = pt
    ver = versions(args, codes)
    # round robin: the coarsest point of every series, then the next one of each, ...
    order = [(code, kind, levels(kind, args)[i]) for i in range(max(len(hcs), len(args.adapt_targets)))
             for code, kind in series if i < len(levels(kind, args))]
    for code, kind, lev in order:
        pt = pts[code, kind, lev]
        # a larger hc or target: a coarser point of the same series
        before = [p for (c, k, h), p in pts.items() if (c, k) == (code, kind) and h > lev]
        if any(p.status == "refused" for p in before):
            pt.status, pt.note = "refused", "see the coarsest mesh"
            continue
        slow = [p for p in before if p.status in ("timeout", "skipped") or (p.cpus and p.cpus[0] > args.series_stop)]
        if slow:
            pt.status, pt.note = "skipped", f"a {'larger target' if pt.adaptive else 'coarser point'} took over " \
                f"{args.series_stop:g} s"
            continue
        run_once(pt, args, env)
        log(f"  {label(code, kind):18s} {'target' if pt.adaptive else 'hc'}={lev:<7g} "
            f"cpu {pt.cpus[-1] if pt.cpus else float('nan'):8.3f} s  {pt.status} {pt.note}")
    for pt in pts.values():
        t1 = pt.cpus[0] if pt.cpus else math.inf
        pt.want = 0 if pt.status not in ("ok", "not converged") else \
            min(args.reps, max(1, int(args.point_budget // t1) if t1 > 0 else args.reps))
    for r in range(2, args.reps + 1):
        for key in order:
            pt = pts[key]
            if pt.want >= r and pt.status in ("ok", "not converged"):
                run_once(pt, args, env)
        log(f"  repeat {r} done ({time.time() - start:.0f} s)")
    load1 = os.getloadavg()

    # 4. the errors
    for pt in list(pts.values()) + [p for p in refs.values() if p.status == "ok"]:
        if pt.status in ("ok", "not converged") and pt.dofs is not None:
            num, den = l2_diff(load(pt.prof)[1], load(pref.prof)[1])
            pt.perr = num / den
    h1_errors(fields["p2gL2"], list(pts.values()))
    for p in refs.values():
        p.herr = h1_err.energy_errors(fields["p2gL2"], fields[p.kind + p.level], WINDOW)[1] if p is not pref else 0.0

    text = report(args, series, hcs, pts, refs, conv, pref, codes, ver, load0, load1, time.time() - start)
    print(text)
    with open(os.path.join(args.out, "results.md"), "w") as f:
        f.write(text + "\n")
    if args.doc:
        splice(args.doc, text)
    with open(os.path.join(args.out, "runs.csv"), "w", newline="") as f:
        wr = csv.writer(f)
        wr.writerow(["code", "kind", "hc", "target", "dofs", "P", "perr", "herr", "estimate", "status", "note",
                     "cpu_s", "wall_s", "cpu_total_s"])
        for p in list(refs.values()) + list(pts.values()):
            wr.writerow([p.code if p not in refs.values() else "reference", p.kind, p.hc, p.target, p.dofs, p.P,
                         p.perr, p.herr, p.est, p.status, p.note, " ".join(f"{t:.4f}" for t in p.cpus),
                         " ".join(f"{t:.4f}" for t in p.times), p.cpu_total])
    return 0


if __name__ == "__main__":
    if shutil.which("gmsh") is None:
        sys.exit("peers: gmsh not found")
    sys.exit(main())
