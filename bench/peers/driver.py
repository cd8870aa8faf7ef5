#!/usr/bin/python3
"""Accuracy per second on Hertz H: contact2d against GetFEM and CalculiX.

    driver.py --prog CONTACT2D --out DIR [--codes contact2d,getfem,ccx]
              [--hc 0.04,...] [--reps 5] [--point-budget 150] [--timeout 900]

1. Meshes every hc of the sweep with gmsh (hertz_block.geo, hertz_disk.geo,
   hf = 0.5, MSH 2.2) and writes each code's input from the same two meshes
   (contact2d deck, CalculiX .inp); none of this is timed.
2. Runs every code on every mesh once, then again (round robin over codes and
   meshes) up to --reps runs per point; a point whose first run took t seconds
   gets min(reps, max(1, floor(point_budget / t))) runs.  Time = median
   whole-process wall time of the solver process, from fork to exit; memory =
   peak resident set of that process.
   The user+sys CPU time of the process is recorded too: on a shared machine
   it is far less disturbed by other load than the wall time.
3. Error = relative L2 pressure error over the nodes |x| < a (hertz_err.py),
   from each code's own load P.  Runs that fail or report no convergence are
   listed but not used for matching.
4. Matched error e (1% and 0.5%): along the sweep (coarse to fine),
   "first"  = the first mesh with error <= e;
   "stays"  = the first mesh from which every finer mesh has error <= e;
   the time (and dofs) is interpolated in log-log between that mesh and the
   one before it (error against time).  The speedup is the faster peer's
   matched time over contact2d's.
Prints the sweep and the matched table; writes DIR/runs.csv and
DIR/results.txt.
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
from hertz_err import evaluate          # noqa: E402

PY = "/usr/bin/python3"
GNU_TIME = "/usr/bin/time" if os.access("/usr/bin/time", os.X_OK) else None
NAMES = {"contact2d": "contact2d", "getfem": "GetFEM", "ccx": "CalculiX"}
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
    """Run cmd; return (exit code or None on timeout, wall s, user+sys s, peak RSS MB or None).

    The peak memory comes from GNU time when it is installed: the rusage of a
    child forked straight from this (large) process would count this
    process's own memory at the fork.
    """
    memfile = log + ".mem"
    if GNU_TIME:
        cmd = [GNU_TIME, "-f", "%M", "-o", memfile] + cmd   # its rusage covers its child
    with open(log, "w") as f:
        t0 = time.perf_counter()
        p = subprocess.Popen(cmd, cwd=cwd, stdout=f, stderr=subprocess.STDOUT, env=env, start_new_session=True)
        killed = []
        timer = threading.Timer(timeout, lambda: (killed.append(1), os.killpg(p.pid, signal.SIGKILL)))
        timer.start()
        _, status, ru = os.wait4(p.pid, 0)
        t1 = time.perf_counter()
        timer.cancel()
        p.returncode = os.waitstatus_to_exitcode(status)
    mem = None
    try:
        with open(memfile) as f:
            mem = float(f.read().split()[-1]) / 1024.0
    except (OSError, ValueError, IndexError):
        pass
    return (None if killed else p.returncode), t1 - t0, ru.ru_utime + ru.ru_stime, mem


class Point:
    """One (code, hc) point of the sweep."""

    def __init__(self, code, hc, wdir):
        self.code, self.hc, self.wdir = code, hc, wdir
        self.times, self.cpus, self.mems = [], [], []
        self.err = self.dofs = self.P = None
        self.status = "ok"          # ok | not converged | failed | timeout
        self.note = ""

    def median(self, cpu=False):
        v = self.cpus if cpu else self.times
        return statistics.median(v) if v else None

    def usable(self):
        return self.status == "ok" and self.err is not None and not math.isnan(self.err)


def setup(args, hcs):
    """Mesh the sweep and write the inputs; return {(code, hc): Point}."""
    geo = os.path.join(args.top, "input")
    pts = {}
    for hc in hcs:
        tag = f"hc{hc:g}"
        mdir = os.path.join(args.out, "mesh")
        os.makedirs(mdir, exist_ok=True)
        msh = {}
        for body in ("block", "disk"):
            msh[body] = os.path.join(mdir, f"{body}_{tag}.msh")
            if not os.path.exists(msh[body]):
                subprocess.run(["gmsh", "-2", "-format", "msh22", "-v", "0", "-setnumber", "hc", repr(hc),
                                "-setnumber", "hf", "0.5", os.path.join(geo, f"hertz_{body}.geo"),
                                "-o", msh[body] + ".tmp"], check=True, stdout=subprocess.DEVNULL)
                os.replace(msh[body] + ".tmp", msh[body])
        for code in args.codes:
            w = os.path.join(args.out, code, tag)
            os.makedirs(w, exist_ok=True)
            pt = Point(code, hc, w)
            pt.block, pt.disk = msh["block"], msh["disk"]
            if code == "contact2d":
                with open(os.path.join(w, "hertz.deck"), "w") as f:
                    f.write(DECK.format(b=msh["block"], d=msh["disk"]))
            elif code == "ccx":
                write_inp(msh["block"], msh["disk"], os.path.join(w, "hertz.inp"))
            pts[code, hc] = pt
    return pts


def run_once(pt, args, env):
    """Run one point once; the first run also evaluates the error."""
    w = pt.wdir
    prof = os.path.join(w, "profile.txt")
    if pt.code == "contact2d":
        cmd = [args.prog, "-q", "-o", os.path.join(w, "o"), os.path.join(w, "hertz.deck")]
    elif pt.code == "getfem":
        cmd = [PY, os.path.join(HERE, "getfem_hertz.py"), pt.block, pt.disk, prof]
    else:
        cmd = ["ccx", "-i", "hertz"]
    rc, t, cpu, mem = timed(cmd, w, os.path.join(w, f"log{len(pt.times) + 1}.txt"), args.timeout, env)
    if rc is None:
        pt.status, pt.note = "timeout", f"killed after {args.timeout:g} s"
        return
    if pt.times == [] and pt.err is None:
        try:
            if pt.code == "contact2d":
                if rc != 0:
                    raise RuntimeError(f"exit status {rc}")
                c2d_profile(os.path.join(w, "o", "hertz_contact.csv"), os.path.join(w, "o", "hertz.summary"), prof)
            elif pt.code == "ccx":
                if rc != 0:
                    raise RuntimeError(f"exit status {rc}")
                ccx_profile(pt.block, pt.disk, os.path.join(w, "hertz"), prof)
            elif rc not in (0, 3):
                raise RuntimeError(f"exit status {rc}")
            pt.dofs, pt.P, _, _, pt.err = evaluate(prof)
            if pt.code == "getfem":
                meta = dict(ln.split()[1:3] for ln in open(prof) if ln.startswith("#"))
                pt.note = f"{meta.get('newton_iterations', '?')} Newton it."
                if rc == 3:
                    pt.status = "not converged"
            if pt.code == "ccx":
                it = sum(1 for ln in open(os.path.join(w, "log1.txt")) if ln.startswith(" iteration"))
                pt.note = f"{it} iterations"
        except (OSError, ValueError, KeyError, RuntimeError) as e:
            pt.status, pt.note = "failed", str(e).splitlines()[0][:60]
    pt.times.append(t)
    pt.cpus.append(cpu)
    if mem is not None:
        pt.mems.append(mem)


def interp(e, lo, hi, cpu):
    """Log-log interpolation at error e between points lo (error > e) and hi (error <= e)."""
    if lo is None:
        return hi.median(cpu), hi.dofs
    s = math.log(e / lo.err) / math.log(hi.err / lo.err)
    tl, th = lo.median(cpu), hi.median(cpu)
    t = math.exp(math.log(tl) + s * (math.log(th) - math.log(tl)))
    d = math.exp(math.log(lo.dofs) + s * (math.log(hi.dofs) - math.log(lo.dofs)))
    return t, d


def match(series, e, rule, cpu=False):
    """(time, dofs, (lo, hi)) at error e along a code's usable sweep, or None."""
    good = [p for p in series if p.usable()]
    j = None
    if rule == "first":
        j = next((k for k, p in enumerate(good) if p.err <= e), None)
    else:
        for k in range(len(good) - 1, -1, -1):
            if good[k].err <= e:
                j = k
            else:
                break
    if j is None:
        return None
    lo = good[j - 1] if j > 0 else None
    t, d = interp(e, lo, good[j], cpu)
    return t, d, (lo, good[j])


def versions(args):
    v = {}
    r = subprocess.run([args.prog, "--version"], capture_output=True, text=True)
    v["contact2d"] = (r.stdout.strip().splitlines() or ["?"])[0]
    if "getfem" in args.codes:
        r = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "python3-getfem"], capture_output=True, text=True)
        v["getfem"] = "GetFEM " + (r.stdout.strip() or "?") + " (python3-getfem, nodal contact brick, MUMPS)"
    if "ccx" in args.codes:
        r = subprocess.run(["ccx", "-v"], capture_output=True, text=True)
        ver = next((ln.split()[-1] for ln in r.stdout.splitlines() if "Version" in ln), "?")
        v["ccx"] = f"CalculiX {ver} (calculix-ccx, CPE3, surface-to-surface penalty K = 500 E, SPOOLES)"
    return v


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--prog", required=True)
    ap.add_argument("--top", default=os.path.dirname(os.path.dirname(HERE)))
    ap.add_argument("--out", required=True)
    ap.add_argument("--codes", default="contact2d,getfem,ccx")
    ap.add_argument("--hc", default="0.04,0.028,0.02,0.014,0.01,0.007,0.005,0.0035,0.0025")
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--point-budget", type=float, default=150.0)
    ap.add_argument("--timeout", type=float, default=900.0)
    ap.add_argument("--threads", default="1")
    args = ap.parse_args()
    args.codes = [c for c in args.codes.split(",") if c]
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
    pts = setup(args, hcs)
    ver = versions(args)

    # pass 1: one run per point, then the repeats, round robin
    for hc in hcs:
        for code in args.codes:
            pt = pts[code, hc]
            run_once(pt, args, env)
            print(f"  {NAMES[code]:9s} hc={hc:<7g} {pt.times[-1] if pt.times else float('nan'):8.3f} s  "
                  f"err {pt.err * 100 if pt.err is not None else float('nan'):.3f}%  {pt.status} {pt.note}",
                  file=sys.stderr, flush=True)
    for pt in pts.values():
        t1 = pt.times[0] if pt.times else math.inf
        pt.want = 0 if pt.status in ("failed", "timeout") else \
            min(args.reps, max(1, int(args.point_budget // t1) if t1 > 0 else args.reps))
    for r in range(2, args.reps + 1):
        for hc in hcs:
            for code in args.codes:
                pt = pts[code, hc]
                if pt.want >= r and pt.status not in ("failed", "timeout"):
                    run_once(pt, args, env)
        print(f"  repeat {r} done ({time.time() - start:.0f} s)", file=sys.stderr, flush=True)
    load1 = os.getloadavg()

    out = []
    out.append("Hertz H (BENCHMARKS.md): pressure L2 error over |x| < a against whole-process wall and CPU time")
    out.append(f"machine: {platform.machine()}, {os.cpu_count()} cpus; threads per process: {args.threads} "
               f"(OMP/OpenBLAS/CalculiX); load average {load0[0]:.2f} at start, {load1[0]:.2f} at end; "
               f"run took {time.time() - start:.0f} s")
    for c in args.codes:
        out.append(f"  {NAMES[c]:9s} {ver[c]}")
    out.append("")
    out.append("Sweep: gmsh meshes hc (contact zone), hf = 0.5; dofs = 2 x nodes of the two meshes (the same for")
    out.append("every code); err = relative L2 pressure error over the nodes |x| < a with a, p0 from the code's own P;")
    out.append("t = median wall time of n runs (s); cpu = median user+sys time (s); mem = peak resident memory")
    out.append("(MB, needs GNU time).")
    hdr = f"{'hc':>7s} {'dofs':>7s}"
    for c in args.codes:
        hdr += f" | {NAMES[c] + ' err%':>14s} {'t':>7s} {'cpu':>7s} {'n':>1s} {'mem':>5s}"
    out.append(hdr)
    notes = []
    for hc in hcs:
        row = f"{hc:7g} {pts[args.codes[0], hc].dofs or 0:7d}"
        for c in args.codes:
            pt = pts[c, hc]
            mark = {"ok": " ", "not converged": "*", "failed": "!", "timeout": "!"}[pt.status]
            err = f"{pt.err * 100:.3f}" if pt.err is not None else "-"
            t = f"{pt.median():.3f}" if pt.times else "-"
            cpu = f"{pt.median(True):.3f}" if pt.cpus else "-"
            mem = f"{max(pt.mems):.0f}" if pt.mems else "-"
            row += f" | {err + mark:>14s} {t:>7s} {cpu:>7s} {len(pt.times):1d} {mem:>5s}"
            if pt.status != "ok":
                notes.append(f"  {NAMES[c]} hc={hc:g}: {pt.status} ({pt.note})")
        out.append(row)
    if notes:
        out.append("(* = the code reported no convergence, ! = failed; neither is used for matching)")
        out += notes
    for c in ("getfem", "ccx"):
        if c in args.codes:
            out.append(f"  {NAMES[c]} iterations: " + ", ".join(f"{pts[c, h].note}" for h in hcs))
    for cpu in (False, True):
        out.append("")
        out.append(f"Matched error, {'user+sys CPU' if cpu else 'wall'} time (time and dofs interpolated log-log between "
                   "the two sweep meshes around the target):")
        out.append("  first = first mesh reaching the target; stays = first mesh from which every finer one stays "
                   "at or below it.")
        hdr = f"{'target':>6s} {'rule':>5s}"
        for c in args.codes:
            hdr += f" | {NAMES[c]:>9s} {'t (s)':>7s} {'dofs':>7s}"
        hdr += " | speedup vs faster peer"
        out.append(hdr)
        for e in (0.01, 0.005):
            for rule in ("first", "stays"):
                row = f"{e * 100:5.1f}% {rule:>5s}"
                res = {}
                for c in args.codes:
                    m = match([pts[c, h] for h in hcs], e, rule, cpu)
                    res[c] = m
                    if m is None:
                        row += f" | {'not reached':>25s}"
                    else:
                        row += f" | {'':>9s} {m[0]:7.3f} {m[1]:7.0f}"
                peers = [(res[c][0], NAMES[c]) for c in args.codes if c != "contact2d" and res[c] is not None]
                if "contact2d" not in args.codes or res["contact2d"] is None:
                    row += " | contact2d does not reach it"
                elif not peers:
                    row += " | no peer reaches it"
                else:
                    tp, name = min(peers)
                    sp = tp / res["contact2d"][0]
                    row += f" | {sp:6.1f}x ({name}) {'met' if sp >= 10 else 'NOT met'} (goal 10x)"
                out.append(row)
    best = []
    for c in args.codes:
        good = [p for p in (pts[c, h] for h in hcs) if p.usable()]
        if good:
            b = min(good, key=lambda p: p.err)
            best.append(f"{NAMES[c]} {b.err * 100:.2f}% at hc={b.hc:g}")
    out.append("Best error in the sweep: " + "; ".join(best))
    text = "\n".join(out)
    print(text)
    with open(os.path.join(args.out, "results.txt"), "w") as f:
        f.write(text + "\n")
    with open(os.path.join(args.out, "runs.csv"), "w", newline="") as f:
        wr = csv.writer(f)
        wr.writerow(["code", "hc", "dofs", "P", "err", "status", "note", "wall_s", "cpu_s", "mem_mb"])
        for (c, h), p in pts.items():
            wr.writerow([c, h, p.dofs, p.P, p.err, p.status, p.note, " ".join(f"{t:.4f}" for t in p.times),
                         " ".join(f"{t:.4f}" for t in p.cpus), f"{max(p.mems):.0f}" if p.mems else ""])
    return 0


if __name__ == "__main__":
    if shutil.which("gmsh") is None:
        sys.exit("peers: gmsh not found")
    sys.exit(main())
