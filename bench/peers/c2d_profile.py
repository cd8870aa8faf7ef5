#!/usr/bin/python3
"""contact2d Hertz output -> profile file (see hertz_err.py and ref_err.py).

    c2d_profile.py CONTACT.csv SUMMARY OUT.prof [ORDER]
P is |Fy| of the reaction on disk:top; the rows are every slave node of the
contact table with its contact pressure (0 where no master faces it);
ORDER (1 or 2, default 1) is the degree of the slave trace, written to the
profile for ref_err.py.
"""
import csv
import sys

from hertz_err import write_profile


def c2d_profile(csvfile, summary, out, order=1):
    """Write the profile of one contact2d run."""
    P, dofs = None, 0
    with open(summary) as f:
        for line in f:
            w = line.split()
            if len(w) >= 4 and w[0] == "reaction" and w[1] == "disk:top":
                P = abs(float(w[3]))
            elif len(w) >= 2 and w[0] == "dofs":
                dofs = int(w[1])
    if P is None:
        raise ValueError(f"{summary}: no reaction disk:top")
    xs, ps = [], []
    with open(csvfile) as f:
        for r in csv.DictReader(f):
            xs.append(float(r["x"]))
            ps.append(float(r["pressure"]) if int(r["status"]) >= 0 else 0.0)
    write_profile(out, xs, ps, P=P, dofs=dofs, order=int(order))


if __name__ == "__main__":
    c2d_profile(*sys.argv[1:5])
