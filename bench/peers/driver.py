#!/usr/bin/python3
"""Accuracy per second on Hertz H: contact2d (P1, quadratic) against GetFEM
and CalculiX (their linear and quadratic elements), the error measured against
a reference solution of the same finite problem.

    driver.py --prog CONTACT2D --out DIR [--series code:kind,...] [--hc 0.04,...]
              [--reps 3] [--grade 8] [--ref-hc 0.00125] [--timeout 900]

kind: p1 / p2 = linear / quadratic elements on the even meshes of
input/hertz_*.geo (size hc around the zone, hf = 0.5 far away); p1g / p2g =
the same graded toward the zone's ends (geo/hertz_*_graded.geo: size hc / GRADE
at (+-a, 0), growing at rate 0.2 with the distance, capped by the even size).

1. Locate: one contact2d P1 run at hc = 0.005 gives the half-width a of the
   finite problem (the middle between the last node in contact and the next).
2. Reference: contact2d on graded meshes at 4, 2 and 1 x ref-hc, quadratic
   when this contact2d takes contact on quadratic elements (else P1).  The
   three levels show the reference's own convergence: the distances of
   consecutive levels give the observed rate and the finest level's error
   estimate; a target below three times that estimate is flagged as not
   resolved.  The H1 (energy) error is measured against the finest P1 graded
   reference (studies/c2dh1 reads P1 fields).
3. Sweep: every series on every hc (meshing and input writing not timed);
   each point runs once, then again round robin up to --reps runs; a point
   whose first run took t CPU seconds gets min(reps, max(1, 60 / t)) runs.
   Time = median user+sys CPU time of the solver process (getrusage of the
   child, its children included), wall time next to it.
4. Errors of each point (ref_err.py, studies/c2dh1.f90):
   pressure: || p_h - p_ref ||_L2 / || p_ref ||_L2 along the block top, by
   quadrature exact for the piecewise polynomials (no node sampling);
   H1: the energy-norm error || u_ref - u_h ||_E / || u_ref ||_E over the
   window |x| <= 0.3, -0.3 <= y <= 0.3 around the zone (P1 fields only).
5. Matched error e: along a series (coarse to fine), the first mesh from
   which every finer mesh stays at or below e, the CPU time interpolated
   log-log (error against time) between it and the mesh before it: a time
   read off the sweep's curve, not one lucky mesh.  The speedup is the faster
   peer's matched time over contact2d's.
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
WINDOW = "-0.3,0.3,-0.3,0.3"
PRESSURE_TARGETS = (0.01, 0.003, 0.001)
H1_TARGETS = (0.05, 0.02, 0.01)
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
CONTACT slave=block:top master=disk:arc gap=geometry
SOLVER lcp=auto tol=1e-10
"""


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

    @property
    def degree(self):
        return 2 if self.kind.startswith("p2") else 1

    def cpu(self):
        return statistics.median(self.cpus) if self.cpus else None

    def wall(self):
        return statistics.median(self.times) if self.times else None

    def usable(self):
        return self.status == "ok" and self.perr is not None


def mesh(args, body, hc, kind):
    """The gmsh mesh (MSH 2.2) of body for size hc and kind (p1/p2 even, p1g/p2g graded toward the
    zone's ends, size hc / grade there; p2s: P1 geometry for a P2 field); made once, not timed."""
    graded = kind.endswith("g")
    order = 2 if kind.startswith("p2") and not kind.startswith("p2s") else 1
    hz = hc / args.grade
    tag = f"{body}_hc{hc:g}{'_g' + format(hz, 'g') if graded else ''}_o{order}"
    path = os.path.join(args.out, "mesh", tag + ".msh")
    if not os.path.exists(path):
        os.makedirs(os.path.dirname(path), exist_ok=True)
        geo = os.path.join(HERE, "geo", f"hertz_{body}_graded.geo") if graded else \
            os.path.join(args.top, "input", f"hertz_{body}.geo")
        cmd = ["gmsh", "-2", "-order", str(order), "-format", "msh22", "-v", "0",
               "-setnumber", "hc", repr(hc), "-setnumber", "hf", "0.5"]
        if graded:
            cmd += ["-setnumber", "a", repr(args.a), "-setnumber", "hz", repr(hz)]
        subprocess.run(cmd + [geo, "-o", path + ".tmp"], check=True, stdout=subprocess.DEVNULL)
        os.replace(path + ".tmp", path)
    return path


def prepare(pt, args):
    """Mesh and write the input of a point."""
    os.makedirs(pt.wdir, exist_ok=True)
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
    vtk = os.path.join(w, "field.vtk") if pt.degree == 1 else None
    if pt.code == "contact2d":
        cmd = [args.prog, "-q", "-o", os.path.join(w, "o"), os.path.join(w, "hertz.deck")]
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


def locate_a(args, env):
    """Half-width of the contact zone of the finite problem from a P1 run at hc = 0.005."""
    pt = Point("contact2d", "p1", 0.005, os.path.join(args.out, "locate"))
    prepare(pt, args)
    run_once(pt, args, env)
    if pt.status != "ok":
        sys.exit(f"peers: the locating run failed: {pt.note}")
    _, xs, ps = read_profile(pt.prof)
    ends = []
    for side in (1.0, -1.0):
        pts = sorted((side * x, p) for x, p in zip(xs, ps) if side * x >= 0.0)
        k = max(i for i, (_, p) in enumerate(pts) if p > 0.0)
        ends.append(0.5 * (pts[k][0] + pts[min(k + 1, len(pts) - 1)][0]))
    return 0.5 * (ends[0] + ends[1]), pt


def h1_errors(c2dh1, ref_vtk, pts):
    """Energy-norm error over the window of each point with a P1 field, against ref_vtk."""
    todo = [p for p in pts if p.vtk and p.status in ("ok", "not converged")]
    if not todo:
        return
    r = subprocess.run([c2dh1, "-m", "200000,0.3", "--window", WINDOW, ref_vtk] + [p.vtk for p in todo],
                       capture_output=True, text=True, check=True)
    byfile = {ln.split(",")[0]: float(ln.split(",")[4]) for ln in r.stdout.splitlines() if ln.count(",") >= 4}
    for p in todo:
        p.herr = byfile.get(p.vtk)


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
    return f"{NAMES[code]} {kind.upper()}"


def fit_rate(series, attr):
    """Least-squares slope of log(error) against log(hc) over a series' usable points (None if < 3)."""
    good = [(math.log(p.hc), math.log(getattr(p, attr))) for p in series
            if p.usable() and getattr(p, attr) is not None and getattr(p, attr) > 0.0]
    if len(good) < 3:
        return None
    mx = sum(x for x, _ in good) / len(good)
    my = sum(y for _, y in good) / len(good)
    return sum((x - mx) * (y - my) for x, y in good) / sum((x - mx) ** 2 for x, _ in good)


def reference_convergence(c2dh1, refs):
    """{kind: {"p": (d01, d12, rate, estimate), "h1": (...)}} for the reference kinds with three levels:
    d01, d12 the relative distances of consecutive levels (hc halved each time), rate = log2(d01 / d12),
    estimate = d12 / (2^rate - 1), the finest level's error if the rate holds."""
    out = {}
    for kind in ("p2g", "p1g"):
        lv = [refs.get((kind, f"L{k}")) for k in range(3)]
        if not all(p is not None and p.status == "ok" for p in lv):
            continue
        out[kind] = {}
        d = []
        for a, b in ((lv[0], lv[1]), (lv[1], lv[2])):
            num, den = l2_diff(load(a.prof)[1], load(b.prof)[1])
            d.append(num / den)
        out[kind]["p"] = d
        if kind == "p1g":
            d = []
            for a, b in ((lv[0], lv[1]), (lv[1], lv[2])):
                r = subprocess.run([c2dh1, "-m", "200000,0.3", "--window", WINDOW, b.vtk, a.vtk],
                                   capture_output=True, text=True, check=True)
                d.append(float(r.stdout.split(",")[4]))
            out[kind]["h1"] = d
        for key, (d01, d12) in list(out[kind].items()):
            rate = math.log2(d01 / d12) if d01 > 0.0 and d12 > 0.0 else float("nan")
            est = d12 / (2.0 ** rate - 1.0) if rate > 0.0 else float("inf")
            out[kind][key] = (d01, d12, rate, est)
    return out


def report(args, series, hcs, pts, refs, conv, pref, href, codes, ver, load0, load1, took):
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
    W(f"Zone half-width of the finite problem: a = {args.a:.5f} (contact2d P1, hc = 0.005, the middle between "
      f"the last node in contact and the next); graded meshes: size hc/{args.grade:g} at (+-a, 0), growing "
      "at 0.2 times the distance, capped by the even mesh's size.")
    W("")
    W(f"**The reference**: contact2d on graded meshes, three levels hc = 4, 2, 1 x {args.ref_hc:g}, quadratic "
      "when this contact2d takes contact on quadratic elements; 'vs Hertz' is the L2 distance of the pressure "
      "to Hertz's half-space pressure for the level's own load (the model's difference, not an error):")
    W("")
    W("| kind | level | hc | dofs | CPU (s) | vs Hertz | status |")
    W("| --- | --- | ---: | ---: | ---: | ---: | --- |")
    for (kind, lev), p in refs.items():
        hz = f"{hertz_distance(p.prof) * 100:.3f}%" if p.status == "ok" else "-"
        W(f"| {kind} | {lev} | {p.hc:g} | {p.dofs or 0} | {p.cpu() or 0:.2f} | {hz} | {p.status} {p.note} |")
    W("")
    W("Its convergence: d01, d12 = relative distances L0-L1 and L1-L2 (pressure L2; energy norm over the "
      "window), rate = log2(d01/d12), and the finest level's error estimated as d12 / (2^rate - 1):")
    W("")
    W("| kind | measure | d01 | d12 | rate | estimated error of L2 |")
    W("| --- | --- | ---: | ---: | ---: | ---: |")
    for kind, m in conv.items():
        for key, (d01, d12, rate, est) in m.items():
            W(f"| {kind} | {'pressure' if key == 'p' else 'H1'} | {d01 * 100:.4f}% | {d12 * 100:.4f}% | "
              f"{rate:.2f} | {est * 100:.4f}% |")
    W("")
    W(f"The pressure reference is the {pref.kind} L2 level, the H1 reference the p1g L2 level.  An error "
      "measured against it is the run's error to within the reference's own (the estimate above): read only "
      "the errors well above that estimate.")
    W("")
    W("**The sweep.** p err = || p_h - p_ref ||_L2 / || p_ref ||_L2 along the block top (quadrature exact for "
      f"the piecewise polynomials, no node sampled); H1 = energy-norm error over the window {WINDOW} relative to "
      "the reference's energy norm there (P1 fields only: `studies/c2dh1` reads P1 triangles); CPU = median "
      "user+sys time of n runs of the whole process (s), wall = median wall time (s).")
    W("")
    W("| series | hc | dofs | p err (%) | H1 (%) | CPU (s) | wall (s) | n | note |")
    W("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |")
    for code, kind in series:
        for hc in hcs:
            p = pts[code, kind, hc]
            if p.status == "refused" and hc != hcs[0]:
                continue
            pe = f"{p.perr * 100:.4f}" if p.perr is not None else "-"
            he = f"{p.herr * 100:.3f}" if p.herr is not None else "-"
            mark = {"ok": "", "not converged": " (not converged: not matched)", "failed": " FAILED",
                    "timeout": " TIMEOUT", "refused": " REFUSED"}[p.status]
            W(f"| {label(code, kind)} | {hc:g} | {p.dofs or 0} | {pe} | {he} | {p.cpu() or 0:.3f} | "
              f"{p.wall() or 0:.3f} | {len(p.cpus)} | {p.note}{mark} |")
    W("")
    W("Observed rates (least-squares slope of log error against log hc over the sweep):")
    W("")
    W("| series | pressure L2 | H1 |")
    W("| --- | ---: | ---: |")
    for code, kind in series:
        sp = [pts[code, kind, h] for h in hcs]
        rp, rh = fit_rate(sp, "perr"), fit_rate(sp, "herr")
        W(f"| {label(code, kind)} | {'-' if rp is None else format(rp, '.2f')} | "
          f"{'-' if rh is None else format(rh, '.2f')} |")
    for what, attr, targets in (("pressure L2 error", "perr", PRESSURE_TARGETS),
                                ("H1 (energy) error", "herr", H1_TARGETS)):
        W("")
        W(f"**CPU time (s) at matched {what}**: along each series the first mesh from which every finer one "
          "stays at or below the target, the time interpolated log-log against the mesh before it (`=`: the "
          "coarsest mesh is already below); dofs interpolated the same way in brackets.")
        W("")
        W("| target | " + " | ".join(label(c, k) for c, k in series) + " | contact2d / faster peer |")
        W("| ---: | " + " | ".join("---:" for _ in series) + " | --- |")
        ref_est = conv.get(pref.kind if attr == "perr" else "p1g", {}).get("p" if attr == "perr" else "h1")
        for e in targets:
            unresolved = ref_est is None or e < 3.0 * ref_est[3]
            row = f"| {e * 100:g}%{' (not resolved: reference error ~' + format(ref_est[3] * 100, '.2g') + '%)' if unresolved and ref_est else ''} |"
            res = {}
            for code, kind in series:
                m = match([pts[code, kind, h] for h in hcs], e, attr)
                res[code, kind] = m
                row += " - |" if m is None else f" {m[0]:.3f}{'=' if m[2] else ''} ({m[1]:.0f}) |"
            mine = [(m[0], k) for (c, k), m in res.items() if c == "contact2d" and m is not None]
            peers = [(m[0], label(c, k)) for (c, k), m in res.items() if c != "contact2d" and m is not None]
            if not mine:
                row += " contact2d does not reach it |"
            elif not peers:
                row += f" contact2d {min(mine)[1].upper()} reaches it, no peer does |"
            else:
                tm, km = min(mine)
                tp, name = min(peers)
                row += f" **{tp / tm:.1f}x** (contact2d {km.upper()} vs {name}) |"
            W(row)
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
                    "getfem:p1,getfem:p1g,getfem:p2,getfem:p2g,ccx:p1,ccx:p1g,ccx:p2,ccx:p2g")
    ap.add_argument("--hc", default="0.04,0.028,0.02,0.014,0.01,0.007,0.005,0.0035,0.0025")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--point-budget", type=float, default=60.0)
    ap.add_argument("--grade", type=float, default=8.0)
    ap.add_argument("--ref-hc", type=float, default=0.00125)
    ap.add_argument("--timeout", type=float, default=900.0)
    ap.add_argument("--threads", default="1")
    ap.add_argument("--c2dh1", required=True)
    ap.add_argument("--doc", default="")
    args = ap.parse_args()
    series = [tuple(s.split(":")) for s in args.series.split(",") if s]
    codes = sorted({c for c, _ in series}, key=list(NAMES).index)
    hcs = sorted((float(h) for h in args.hc.split(",")), reverse=True)
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
    args.a, _ = locate_a(args, env)
    log(f"  located a = {args.a:.5f}")

    # 2. the references: contact2d on graded meshes, three levels (hc = 4, 2, 1 x ref-hc), quadratic
    #    when it takes contact on quadratic elements
    refs = {}
    for kind in ("p2g", "p1g"):
        for lev, f in (("L0", 4.0), ("L1", 2.0), ("L2", 1.0)):
            pt = Point("contact2d", kind, f * args.ref_hc, os.path.join(args.out, "ref", f"{kind}_{lev}"))
            prepare(pt, args)
            run_once(pt, args, env)
            log(f"  reference {kind} {lev} hc={pt.hc:g}: {pt.status} {pt.note} "
                f"{pt.cpus[-1] if pt.cpus else 0:.1f} s")
            refs[kind, lev] = pt
            if pt.status != "ok":
                break
    pref = next((refs[k, "L2"] for k in ("p2g", "p1g") if (k, "L2") in refs and refs[k, "L2"].status == "ok"),
                None)
    href = refs.get(("p1g", "L2"))
    if pref is None or href is None or href.status != "ok":
        sys.exit("peers: the reference runs failed: " + "; ".join(f"{k}: {p.note}" for k, p in refs.items()))

    # 3. the sweep
    pts = {}
    for code, kind in series:
        for hc in hcs:
            pt = Point(code, kind, hc, os.path.join(args.out, code, f"{kind}_hc{hc:g}"))
            prepare(pt, args)
            pts[code, kind, hc] = pt
    ver = versions(args, codes)
    for hc in hcs:
        for code, kind in series:
            pt = pts[code, kind, hc]
            if any(p.status == "refused" for (c, k, _), p in pts.items() if (c, k) == (code, kind)):
                pt.status, pt.note = "refused", "see the coarsest mesh"
                continue
            run_once(pt, args, env)
            log(f"  {label(code, kind):16s} hc={hc:<7g} cpu {pt.cpus[-1] if pt.cpus else float('nan'):8.3f} s  "
                f"{pt.status} {pt.note}")
    for pt in pts.values():
        t1 = pt.cpus[0] if pt.cpus else math.inf
        pt.want = 0 if pt.status not in ("ok", "not converged") else \
            min(args.reps, max(1, int(args.point_budget // t1) if t1 > 0 else args.reps))
    for r in range(2, args.reps + 1):
        for hc in hcs:
            for key in series:
                pt = pts[key + (hc,)]
                if pt.want >= r and pt.status in ("ok", "not converged"):
                    run_once(pt, args, env)
        log(f"  repeat {r} done ({time.time() - start:.0f} s)")
    load1 = os.getloadavg()

    # 4. the errors
    for pt in list(pts.values()) + [p for p in refs.values() if p.status == "ok"]:
        if pt.status in ("ok", "not converged") and pt.dofs is not None:
            num, den = l2_diff(load(pt.prof)[1], load(pref.prof)[1])
            pt.perr = num / den
    h1_errors(args.c2dh1, href.vtk, list(pts.values()))
    conv = reference_convergence(args.c2dh1, refs)

    text = report(args, series, hcs, pts, refs, conv, pref, href, codes, ver, load0, load1, time.time() - start)
    print(text)
    with open(os.path.join(args.out, "results.md"), "w") as f:
        f.write(text + "\n")
    if args.doc:
        splice(args.doc, text)
    with open(os.path.join(args.out, "runs.csv"), "w", newline="") as f:
        wr = csv.writer(f)
        wr.writerow(["code", "kind", "hc", "dofs", "P", "perr", "herr", "status", "note", "cpu_s", "wall_s"])
        for p in list(refs.values()) + list(pts.values()):
            wr.writerow([p.code if p not in refs.values() else "reference", p.kind, p.hc, p.dofs, p.P, p.perr,
                         p.herr, p.status, p.note, " ".join(f"{t:.4f}" for t in p.cpus),
                         " ".join(f"{t:.4f}" for t in p.times)])
    return 0


if __name__ == "__main__":
    if shutil.which("gmsh") is None:
        sys.exit("peers: gmsh not found")
    sys.exit(main())
