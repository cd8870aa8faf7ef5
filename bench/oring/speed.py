#!/usr/bin/python3
"""contact2d against GetFEM on the plane-strain O-ring, at matched accuracy.

    bench/oring/speed.py [REPEATS]          (from the checkout's top folder)

Both solve the quarter O-ring of this folder's README (d = 5 mm, mu = 1 MPa,
K = 1000 MPa, rigid frictionless plate) along the same path, squeezes 5, 10,
..., 30 % as six load steps, each from the previous one:
  contact2d   tests/finite/oring/oring.deck: 4-node quadrangles with F-bar,
              size hc near the contact (CONTACT2D_LEVELS, default
              0.2,0.1,0.07,0.06,0.05), and 9-node quadrangles with F-bar
              (order=2; CONTACT2D_Q9_LEVELS, default 0.2,0.1), on gmsh's
              recombined Frontal-Delaunay triangles, and 4-node quadrangles
              on its packing of parallelograms (packed=1 of oring.geo;
              CONTACT2D_PACKED_LEVELS, default 0.1,0.07,0.06,0.05); one
              thread (-j 1), --no-mesh-cache (gmsh runs every time);
  GetFEM      getfem_oring.py, Taylor-Hood P2/P1 on curved second-order meshes
              of oring_quarter.geo (GETFEM_LEVELS, default
              0.2,0.1,0.09,0.08,0.07,0.06,0.05: its cheapest level at an
              accuracy is found only among the levels run).
CPU = user + system seconds of the whole job, its gmsh included (and
Python's start-up for GetFEM), the median of REPEATS runs (default 1), all
measured in this one run of the script.  Accuracy = the largest relative
error of the force per unit length and of the peak pressure at 10, 20 and
30 % against reference.csv (GetFEM's finest level, its provenance beside
it).  For each accuracy both reach, the cheapest run of each that reaches
it (either contact2d element), and the ratio of their CPU times.  Writes bench/out/oring_speed/ and
prints the tables (markdown).
"""
import csv
import os
import resource
import shutil
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.dirname(os.path.dirname(HERE))
OUT = os.path.join(TOP, "bench", "out", "oring_speed")
PROG = os.environ.get("CONTACT2D", os.path.join(TOP, "bin", "contact2d"))
SQUEEZES = (0.05, 0.10, 0.15, 0.20, 0.25, 0.30)
CHECKED = (0.1, 0.2, 0.3)
TARGETS = (0.01, 0.005, 0.002, 0.001)


def levels(var, default):
    return [float(x) for x in os.environ.get(var, default).split(",") if x]


def reference():
    ref = {}
    with open(os.path.join(HERE, "reference.csv")) as f:
        for r in csv.DictReader(f):
            ref[round(float(r["squeeze"]), 3)] = (float(r["F_per_length_N_per_mm"]), float(r["p_max_MPa"]))
    return ref


def cpu_of(cmds, cwd):
    """Run the commands in turn; the user + system seconds of all of them.
    A solver's non-zero exit is kept (GetFEM's 3: a step did not converge,
    the squeezes it reached are still read); gmsh's is an error."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    for cmd in cmds:
        subprocess.run(cmd, cwd=cwd, check=cmd[0] == "gmsh", stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def contact2d(hc, repeats, order=1, packed=0):
    work = os.path.join(OUT, f"c2d_{hc:g}" + ("" if order == 1 else f"_order{order}") + ("_packed" if packed else ""))
    os.makedirs(work, exist_ok=True)
    for name in ("oring.deck", "oring.geo"):
        shutil.copy(os.path.join(TOP, "tests", "finite", "oring", name), work)
    with open(os.path.join(work, "oring.deck"), "a") as f:
        f.write("OUTPUT steps=all\n")
    cmd = [PROG, "-q", "-j", "1", "--no-mesh-cache", "-o", "o", "-D", f"hc={hc}", "-D", "squeeze=0.3",
           "-D", "steps=6", "-D", f"order={order}", "-D", f"packed={packed}", "oring.deck"]
    cpu = statistics.median(cpu_of([cmd], work) for _ in range(repeats))
    rows = list(csv.DictReader(open(os.path.join(work, "o", "oring_steps.csv"))))
    got = {}
    for k, sq in enumerate(SQUEEZES):
        got[round(sq, 3)] = (2 * float(rows[k]["rigid_plate_fy"]), float(rows[k]["peak_pressure_1_p"]))
    dofs = next(int(l.split()[1]) for l in open(os.path.join(work, "o", "oring.summary")) if l.startswith("dofs "))
    code = ("contact2d Q1 F-bar" if order == 1 else "contact2d Q9 F-bar") + (" packed" if packed else "")
    return dict(code=code, hc=hc, dofs=dofs, cpu=cpu, got=got)


def getfem(hc, repeats):
    work = os.path.join(OUT, f"getfem_{hc:g}")
    os.makedirs(work, exist_ok=True)
    mesh = ["gmsh", "-2", "-format", "msh22", "-setnumber", "hc", repr(hc), "-order", "2",
            os.path.join(HERE, "oring_quarter.geo"), "-o", "q.msh"]
    solve = ["/usr/bin/python3", os.path.join(HERE, "getfem_oring.py"), "q.msh", "2", "q.txt",
             ",".join(f"{s:g}" for s in SQUEEZES)]
    cpu = statistics.median(cpu_of([mesh, solve], work) for _ in range(repeats))
    lines = [l.rstrip("\n") for l in open(os.path.join(work, "q.txt"))]
    dofs = next(int(l.split()[2]) for l in lines if l.startswith("# dofs "))
    body = [l for l in lines if not l.startswith("#")]
    head = body[0].split("\t")
    got = {}
    for l in body[1:]:
        r = dict(zip(head, l.split("\t")))
        if r.get("converged", "1") == "1":
            got[round(float(r["squeeze"]), 3)] = (float(r["F"]), float(r["pmax"]))
    return dict(code="GetFEM P2/P1", hc=hc, dofs=dofs, cpu=cpu, got=got)


def error(run, ref):
    """The largest relative error of F and p_max at the checked squeezes (inf when one is missing)."""
    e = 0.0
    for sq in CHECKED:
        if sq not in run["got"]:
            return float("inf")
        F, p = run["got"][sq]
        e = max(e, abs(F / ref[sq][0] - 1), abs(p / ref[sq][1] - 1))
    return e


def main():
    repeats = int(sys.argv[1]) if len(sys.argv) > 1 else 1
    os.makedirs(OUT, exist_ok=True)
    ref = reference()
    t0 = time.time()
    load0 = os.getloadavg()
    runs = [contact2d(hc, repeats) for hc in levels("CONTACT2D_LEVELS", "0.2,0.1,0.07,0.06,0.05")]
    runs += [contact2d(hc, repeats, 1, 1) for hc in levels("CONTACT2D_PACKED_LEVELS", "0.1,0.07,0.06,0.05")]
    runs += [contact2d(hc, repeats, 2) for hc in levels("CONTACT2D_Q9_LEVELS", "0.2,0.1")]
    runs += [getfem(hc, repeats) for hc in levels("GETFEM_LEVELS", "0.2,0.1,0.09,0.08,0.07,0.06,0.05")]
    for r in runs:
        r["err"] = error(r, ref)
    print(f"Generated by `bench/oring/speed.py {repeats}` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}; "
          f"load average {load0[0]:.2f} at the start, {os.getloadavg()[0]:.2f} at the end; "
          f"{(time.time() - t0) / 60:.1f} minutes.\n")
    print("| code | hc (mm) | dofs | F err 10/20/30 % | p_max err 10/20/30 % | accuracy | CPU (s) |")
    print("| --- | ---: | ---: | --- | --- | ---: | ---: |")
    for r in runs:
        fe = " / ".join(f"{100 * (r['got'][s][0] / ref[s][0] - 1):+.3f}" if s in r["got"] else "-" for s in CHECKED)
        pe = " / ".join(f"{100 * (r['got'][s][1] / ref[s][1] - 1):+.3f}" if s in r["got"] else "-" for s in CHECKED)
        acc = f"{100 * r['err']:.3f} %" if r["err"] < float("inf") else "not converged"
        print(f"| {r['code']} | {r['hc']:g} | {r['dofs']} | {fe} | {pe} | {acc} | {r['cpu']:.2f} |")
    print("\n| accuracy | contact2d (element, hc, CPU s) | GetFEM (hc, CPU s) | GetFEM / contact2d |")
    print("| ---: | --- | --- | ---: |")
    for a in TARGETS:
        best = {}
        for code in ("contact2d", "GetFEM"):
            ok = [r for r in runs if r["code"].startswith(code) and r["err"] <= a]
            best[code] = min(ok, key=lambda r: r["cpu"]) if ok else None
        c, g = best["contact2d"], best["GetFEM"]
        cs = f"{' '.join(c['code'].split()[1:])}, {c['hc']:g}, {c['cpu']:.2f}" if c else "not reached"
        gs = f"{g['hc']:g}, {g['cpu']:.2f}" if g else "not reached"
        ratio = f"{g['cpu'] / c['cpu']:.1f}x" if c and g else "-"
        print(f"| {100 * a:g} % | {cs} | {gs} | {ratio} |")


if __name__ == "__main__":
    main()
