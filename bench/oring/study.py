#!/usr/bin/python3
"""Mesh-convergence study of the GetFEM O-ring reference (getfem_oring.py).

    study.py [OUTDIR]          (default bench/out/oring)

Meshes oring_quarter.geo with gmsh at each level (size hc near the contact,
second order for P2), runs getfem_oring.py under `nice`, collects the per-
squeeze rows into OUTDIR/runs.tsv, prints the convergence tables (markdown)
and writes OUTDIR/reference.csv from the two finest P2 levels: the value of
the finest level, and as its error estimate the difference to the level
before (for b at least half the finest level's bracket [b_in, b_out]).
Levels are set by ORING_P2 (default 0.2,0.1,0.05,0.025), ORING_P2_FINE (a
finer level solved only at the squeezes ORING_FINE_STEPS, default
0.0125 at 0.01,0.10,0.20,0.30; empty: none) and ORING_P1 (the P1/P0 series,
default 0.1,0.05,0.025).  A level whose output file exists is not solved
again.  Meshing is not timed.
"""
import csv
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
KEYS = ("F", "b", "pmax")


def levels(var, default):
    v = os.environ.get(var, default)
    return [float(x) for x in v.split(",") if x]


def run(outdir, hc, degree, steps=""):
    tag = f"p{degree}_{hc:g}"
    msh = os.path.join(outdir, tag + ".msh")
    if not os.path.exists(msh):
        subprocess.run(["gmsh", "-2", "-format", "msh22", "-setnumber", "hc", repr(hc), "-order", str(degree),
                        os.path.join(HERE, "oring_quarter.geo"), "-o", msh], check=True, stdout=subprocess.DEVNULL)
    out = os.path.join(outdir, tag + ".txt")
    if os.path.exists(out):                 # a level already solved (delete OUTDIR to redo all)
        rc = 0 if "NOT CONVERGED" not in open(out).read() else 3
    else:
        with open(os.path.join(outdir, tag + ".log"), "w") as log:
            rc = subprocess.run(["nice", "/usr/bin/python3", os.path.join(HERE, "getfem_oring.py"), msh, str(degree), out,
                                 steps], stdout=log, stderr=subprocess.STDOUT).returncode
    rows = []
    with open(out) as f:
        meta = {}
        lines = [ln.rstrip("\n") for ln in f]
    for ln in lines:
        if ln.startswith("# dofs "):
            meta["dofs"] = int(ln.split()[2])
    body = [ln for ln in lines if not ln.startswith("#")]
    head = body[0].split("\t")
    for ln in body[1:]:
        r = dict(zip(head, ln.split("\t")))
        r.update(hc=hc, degree=degree, dofs=meta["dofs"], rc=rc)
        rows.append(r)
    print(f"# {tag}: dofs {meta['dofs']} exit {rc}", file=sys.stderr, flush=True)
    return rows


def main():
    outdir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "..", "out", "oring")
    os.makedirs(outdir, exist_ok=True)
    rows = []
    for hc in levels("ORING_P2", "0.2,0.1,0.05,0.025"):
        rows += run(outdir, hc, 2)
    for hc in levels("ORING_P1", "0.1,0.05,0.025"):
        rows += run(outdir, hc, 1)
    fine = levels("ORING_P2_FINE", "0.0125")
    for hc in fine:
        rows += run(outdir, hc, 2, os.environ.get("ORING_FINE_STEPS", "0.01,0.1,0.2,0.3"))
    cols = ["degree", "hc", "dofs", "squeeze", "F", "Fsym", "b", "b_in", "b_out", "pmax", "pnom_max",
            "stretch0", "min_gap", "Jmin", "nit", "converged", "cpu", "res"]
    with open(os.path.join(outdir, "runs.tsv"), "w") as f:
        f.write("\t".join(cols) + "\n")
        for r in rows:
            f.write("\t".join(str(r[c]) for c in cols) + "\n")
    squeezes = (0.01, 0.1, 0.2, 0.3)
    for deg in (2, 1):
        print(f"\n### P{deg}" + (" (u P2, p P1: Taylor-Hood)" if deg == 2 else " (u P1, p P0)") + "\n")
        print("| hc | dofs | squeeze | F (N/mm) | b (mm) | [b_in, b_out] | pmax (MPa) | Newton it | cpu (s) |")
        print("| ---: | ---: | ---: | ---: | ---: | --- | ---: | ---: | ---: |")
        for r in rows:
            if r["degree"] == deg and float(r["squeeze"]) in squeezes:
                print(f"| {r['hc']:g} | {r['dofs']} | {float(r['squeeze']):g} | {float(r['F']):.6f} | {float(r['b']):.4f} "
                      f"| [{float(r['b_in']):.4f}, {float(r['b_out']):.4f}] | {float(r['pmax']):.5f} | {r['nit']} "
                      f"| {float(r['cpu']):.2f} |")
    # reference: the two finest P2 levels holding each squeeze
    ref = []
    for sq in squeezes:
        lv = sorted((r for r in rows if r["degree"] == 2 and float(r["squeeze"]) == sq and r["converged"] == "1"),
                    key=lambda r: r["hc"])
        if len(lv) < 2:
            continue
        f0, f1 = lv[0], lv[1]
        e = {k: abs(float(f0[k]) - float(f1[k])) for k in KEYS}
        e["b"] = max(e["b"], 0.5 * (float(f0["b_out"]) - float(f0["b_in"])))
        ref.append(dict(squeeze=sq, F=float(f0["F"]), F_err=e["F"], b=float(f0["b"]), b_err=e["b"],
                        pmax=float(f0["pmax"]), pmax_err=e["pmax"], hc=f0["hc"], hc_prev=f1["hc"],
                        dofs=f0["dofs"]))
    with open(os.path.join(outdir, "reference.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["squeeze", "F_per_length_N_per_mm", "F_err", "half_width_mm", "half_width_err",
                    "p_max_MPa", "p_max_err", "hc_finest", "hc_previous", "dofs_finest"])
        for r in ref:
            w.writerow([f"{r['squeeze']:g}", f"{r['F']:.6g}", f"{r['F_err']:.2g}", f"{r['b']:.5g}",
                        f"{r['b_err']:.2g}", f"{r['pmax']:.6g}", f"{r['pmax_err']:.2g}", f"{r['hc']:g}",
                        f"{r['hc_prev']:g}", r["dofs"]])
    print("\n### Reference (finest P2 level; error = difference to the previous level)\n")
    print("| squeeze | F (N/mm) | err | b (mm) | err | pmax (MPa) | err |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for r in ref:
        print(f"| {r['squeeze']:g} | {r['F']:.6g} | {r['F_err']:.1e} ({r['F_err'] / r['F']:.2%}) | {r['b']:.5g} "
              f"| {r['b_err']:.1e} ({r['b_err'] / r['b']:.2%}) | {r['pmax']:.6g} "
              f"| {r['pmax_err']:.1e} ({r['pmax_err'] / r['pmax']:.2%}) |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
