"""A deck in other units: every length times s, the moduli and stresses
kept, so that displacements, gaps and coordinates scale as s, stresses and
pressures stay, and forces scale as s (plane strain: per unit thickness)
or s^2 (plane stress with its thickness, and the full-circle forces of
axisymmetric analysis).  The same problem in millimetres instead of metres
must give the same dimensionless answer: nothing in elasticity or in the
contact conditions depends on the unit of length.

scale_deck(path, s, out_dir) writes the scaled deck (and scaled copies of
its meshes: an .msh's nodes times s; a .geo meshed by gmsh first, with the
deck's parameters, then scaled) into out_dir and returns the new deck's
path and the model ('strain', 'stress', 'axisymmetric'); it raises
Unscalable naming why a deck cannot be scaled here (a key whose dimension
this table does not know).  A ${expression} where a length or a force
stands is evaluated with the PARAMETERs as declared and written as a number
times s to its power.  dims(model) gives the kind and the power of s of each output quantity;
compare_runs(...) tells whether two runs, one in the other's units, give
the same dimensionless answer.

The dimension of each key: L a length, S a stress (force per area), F a
force (S L per unit thickness in plane strain, S L^2 in plane stress or as
a full circle), 1 a pure number."""
import math
import os
import re
import subprocess



class Unscalable(Exception):
    pass


def force_power(model):
    """The power of s of a force: S L per unit thickness in plane strain,
    S L T (T the thickness, a length) in plane stress, S L^2 as a full circle."""
    return 1 if model == "strain" else 2


def key_power(statement, key, model, context):
    """Power of s of statement's key=value (None: not a number to scale)."""
    f = force_power(model)
    k = key.lower()
    st = statement.upper()
    if k in ("slave", "master", "file", "elem", "diag", "ramp", "curve", "lcp", "gap", "interference",
             "sliding", "solid", "region", "ordering", "condense", "cut", "vtk", "contact", "summary",
             "fields", "steps", "plot", "quantity", "name", "x"
             ) and not (st in ("REF",) and k == "x"):
        return None
    if st == "MESH":
        if k in ("x0", "y0", "x1", "y1"):
            return 1
        if k in ("nx", "ny", "order"):
            return None
    if st == "MATERIAL":
        if k in ("e", "e1", "e2", "e3", "g12", "mu", "k", "c10", "c01"):
            return 0
        if k in ("nu", "nu12", "nu13", "nu23", "angle"):
            return 0
    if st == "DENSITY" and k == "rho":
        return 0                              # gravity carries the 1/s (rho g L is a stress)
    if st == "GRAVITY" and k in ("gx", "gy"):
        return -1
    if st == "FIX":
        if k in ("ux", "uy", "un", "ut"):
            return 1
        if k == "rz":
            return 0
    if st in ("TRACTION",) and k in ("tx", "ty", "tn", "tt"):
        return 0
    if st == "PRESSURE" and k == "p":
        return 0
    if st == "BODYFORCE" and k in ("fx", "fy"):
        return -1
    if st == "THERMAL" and k in ("alpha", "dt"):
        return 0
    if st == "OFFSET" and k in ("dx", "dy"):
        return 1
    if st == "FORCE":
        if k in ("fx", "fy"):
            return f
        if k == "m":
            return f + 1
    if st == "SPRING":
        if k in ("kn", "kt"):
            if model == "stress":
                raise Unscalable("SPRING kn= in plane stress (its thickness factor is not this table's)")
            return -1                         # force per length per length (or per area): S / L
        if k in ("kx", "ky"):
            return f - 1                      # a force per length
    if st == "CONTACT":
        if k == "mu":
            return 0
        if k == "tresca":
            return 0                          # a shear stress
    if st == "SHAPE":
        if k in ("x0", "y0", "x1", "y1", "xc", "yc", "r"):
            return 1
        if k == "points":
            return 1
    if st == "REF" and k in ("x", "y"):
        return 1
    if st == "PLANE" and k == "thickness":
        return 1
    if st == "SOLVER" and k in ("tol", "maxit", "omega", "updates", "newton_tol", "newton_maxit"):
        return None
    if st == "ADAPT" and k in ("target", "max_steps", "max_dofs"):
        return None
    if st == "OUTPUT":
        return None
    raise Unscalable(f"{statement} {key}=: no dimension known to the scaling table")


def key_stress(statement, key):
    """1 when statement's key=value carries a stress (a modulus, a traction,
    a force, a spring): it scales with the stresses; 0 otherwise."""
    k = key.lower()
    st = statement.upper()
    stress_keys = {
        "MATERIAL": ("e", "e1", "e2", "e3", "g12", "mu", "k", "c10", "c01"),
        "TRACTION": ("tx", "ty", "tn", "tt"), "PRESSURE": ("p",), "BODYFORCE": ("fx", "fy"),
        "GRAVITY": ("gx", "gy"), "FORCE": ("fx", "fy", "m"), "SPRING": ("kn", "kt", "kx", "ky"),
        "CONTACT": ("tresca",)}
    return 1 if k in stress_keys.get(st, ()) else 0


def number(text):
    return float(text.replace("d", "e").replace("D", "e"))


def fmt(x):
    return repr(float(x))


def scale_msh(src, dst, s):
    """A copy of an ASCII MSH 2.2 or 4.1 file with its node coordinates times s."""
    with open(src) as h:
        text = h.read()
    with open(dst, "w") as h:
        h.write(scale_msh_text(text, s, os.path.basename(src)))


def scale_msh_text(text, s, name="mesh"):
    """The text of an ASCII MSH 2.2 or 4.1 file with its node coordinates times s."""
    lines = text.split("\n")
    out = []
    i = 0
    version = None
    while i < len(lines):
        line = lines[i]
        out.append(line)
        if line.strip() == "$MeshFormat" and i + 1 < len(lines):
            version = lines[i + 1].split()[0]
        if line.strip() == "$Nodes":
            i += 1
            if version and version.startswith("2"):
                n = int(lines[i])
                out.append(lines[i])
                for j in range(n):
                    w = lines[i + 1 + j].split()
                    out.append(" ".join([w[0]] + [fmt(number(v) * s) for v in w[1:4]]))
                i += n + 1
                continue
            head = lines[i].split()
            out.append(lines[i])
            nblocks = int(head[0])
            i += 1
            for _ in range(nblocks):
                bh = lines[i].split()
                out.append(lines[i])
                count = int(bh[3])
                if int(bh[2]):
                    raise Unscalable(f"{name}: parametric nodes")
                out.extend(lines[i + 1:i + 1 + count])          # the node tags
                for j in range(count):
                    w = lines[i + 1 + count + j].split()
                    out.append(" ".join(fmt(number(v) * s) for v in w))
                i += 1 + 2 * count
            continue
        i += 1
    return "\n".join(out)


def mesh_geo(geo, words, params, out_dir):
    """The mesh gmsh makes of a deck's MESH gmsh file=X.geo [order=] [name=value ...]
    (as the program runs it: -2, MSH 4.1, -setnumber each name, its value
    evaluated), into out_dir."""
    order = "1"
    args = []
    for w in words[1:]:
        if "=" not in w:
            continue
        k, v = w.split("=", 1)
        if k.lower() == "file":
            continue
        if k.lower() == "order":
            order = v
            continue
        args += ["-setnumber", k, repr(evaluate(v, params))]
    out = os.path.join(out_dir, os.path.basename(geo)[:-4] + ".msh")
    p = subprocess.run(["gmsh", geo, "-2", "-format", "msh41", "-v", "2", "-order", order, *args, "-o", out],
                       capture_output=True, text=True, timeout=300)
    if p.returncode != 0 or not os.path.exists(out):
        raise Unscalable(f"gmsh could not mesh {os.path.basename(geo)}: {p.stderr.strip()[:200]}")
    return out


def evaluate(text, params):
    """The value of a deck word: a number, or text with ${expression}s
    substituted first (the deck's language: numbers, parameters, + - * / ^,
    parentheses, sqrt exp log sin cos tan abs min max, pi)."""
    names = {"sqrt": math.sqrt, "exp": math.exp, "log": math.log, "sin": math.sin, "cos": math.cos,
             "tan": math.tan, "abs": abs, "min": min, "max": max, "pi": math.pi}
    names.update(params)

    def value(m):
        return repr(float(eval(m.group(1).replace("^", "**"), {"__builtins__": {}}, names)))
    return number(re.sub(r"\$\{([^}]*)\}", value, text))


def scaled_value(text, factor, params):
    """The value text times factor, written as a number (an expression is
    evaluated with the deck's PARAMETERs as declared)."""
    if factor == 1.0 and "${" not in text:
        return text
    return fmt(evaluate(text, params) * factor)


def deck_model(text):
    """'strain', 'stress' or 'axisymmetric': the deck's PLANE."""
    if re.search(r"^\s*PLANE\s+stress", text, re.I | re.M):
        return "stress"
    if re.search(r"^\s*PLANE\s+axisymmetric", text, re.I | re.M):
        return "axisymmetric"
    return "strain"


def scale_text(text, s, t=1.0, deck_dir=".", out_dir=None):
    """The deck text with its lengths times s and its stresses times t
    (module header; forces then times t s^f, moments t s^(f+1)).  Its
    meshes: with out_dir, scaled copies written there and named in the
    deck (a .geo meshed by gmsh first); without, the MESH lines are kept
    and the caller scales the meshes (scale_msh_text)."""
    model = deck_model(text)
    params = {}
    lines = []
    for raw in text.split("\n"):
        code, comment = raw, ""
        m = re.search(r"[!#]", raw)
        if m:
            code, comment = raw[:m.start()], raw[m.start():]
        words = code.split()
        if not words:
            lines.append(raw)
            continue
        st = words[0].upper()
        if st == "PARAMETER":                      # declared as they are; uses are scaled where they stand
            for w in words[1:]:
                k, _, v = w.partition("=")
                params[k] = evaluate(v, params)
            lines.append(raw)
            continue
        if st in ("CURVE", "TITLE"):               # factors against the step number; free text
            lines.append(raw)
            continue
        keys = dict(w.split("=", 1) for w in words[1:] if "=" in w)
        if st == "MESH" and "file" in keys and out_dir is None:
            lines.append(raw)
            continue
        if st == "MESH" and keys.get("file", "").lower().endswith(".geo"):
            src = mesh_geo(os.path.join(deck_dir, keys["file"]), words, params, out_dir)
            dst = os.path.join(out_dir, "scaled_" + os.path.basename(src))
            scale_msh(src, dst, s)
            lines.append(f"{words[0]} gmsh file={os.path.basename(dst)}" + (" " + comment if comment else ""))
            continue
        new = [words[0]]
        for w in words[1:]:
            if "=" not in w:
                new.append(w)
                continue
            k, v = w.split("=", 1)
            if st == "MESH" and k.lower() == "file":
                src = os.path.join(deck_dir, v)
                dst = os.path.join(out_dir, "scaled_" + os.path.basename(v))
                scale_msh(src, dst, s)
                new.append(f"{k}={os.path.basename(dst)}")
                continue
            p = key_power(st, k, model, words)
            if p is None:
                new.append(w)
                continue
            factor = s ** p * t ** key_stress(st, k)
            if k.lower() == "points":
                pts = []
                for xy in v.split(","):
                    a, b = xy.split(":")
                    pts.append(f"{fmt(evaluate(a, params) * factor)}:{fmt(evaluate(b, params) * factor)}")
                new.append(f"{k}={','.join(pts)}")
                continue
            new.append(f"{k}={scaled_value(v, factor, params)}")
        lines.append(" ".join(new) + (" " + comment if comment else ""))
    return "\n".join(lines)


def scale_deck(path, s, out_dir, t=1.0):
    """The deck at path with its lengths times s and its stresses times t
    (module header) into out_dir, its meshes scaled beside it; returns (new
    deck path, model)."""
    with open(path) as h:
        text = h.read()
    os.makedirs(out_dir, exist_ok=True)
    new = scale_text(text, s, t, os.path.dirname(path), out_dir)
    out = os.path.join(out_dir, os.path.basename(path))
    with open(out, "w") as h:
        h.write(new)
    return out, deck_model(text)


def model_size(path):
    """The model's size: the largest coordinate of its meshes (MESH rect's
    corners, an .msh's nodes) and RIGID shapes."""
    size = 0.0
    with open(path) as h:
        text = h.read()
    for raw in text.split("\n"):
        code = re.split(r"[!#]", raw)[0]
        words = code.split()
        if not words:
            continue
        st = words[0].upper()
        for w in words[1:]:
            k, _, v = w.partition("=")
            k = k.lower()
            if st == "MESH" and k in ("x0", "y0", "x1", "y1") or st == "SHAPE" and k in ("x0", "y0", "x1", "y1", "xc", "yc", "r"):
                size = max(size, abs(number(v)))
            elif st == "SHAPE" and k == "points":
                for xy in v.split(","):
                    size = max(size, *(abs(number(c)) for c in xy.split(":")))
            elif st == "MESH" and k == "file" and v.lower().endswith(".msh"):
                size = max(size, msh_size(os.path.join(os.path.dirname(path), v)))
    return size


def msh_size(path):
    """The largest node coordinate of an ASCII MSH 2.2 or 4.1 file."""
    with open(path) as h:
        lines = h.read().split("\n")
    size, i, version = 0.0, 0, "4"
    while i < len(lines):
        if lines[i].strip() == "$MeshFormat":
            version = lines[i + 1].split()[0]
        if lines[i].strip() == "$Nodes":
            i += 1
            if version.startswith("2"):
                n = int(lines[i])
                for j in range(n):
                    size = max(size, *(abs(number(v)) for v in lines[i + 1 + j].split()[1:3]))
                i += n + 1
                continue
            nblocks = int(lines[i].split()[0])
            i += 1
            for _ in range(nblocks):
                count = int(lines[i].split()[3])
                for j in range(count):
                    size = max(size, *(abs(number(v)) for v in lines[i + 1 + count + j].split()[0:2]))
                i += 1 + 2 * count
            continue
        i += 1
    return size


def dims(model):
    """The kind and the power of s of the summary's quantities and of the
    contact table's columns, for the model: {key: [(kind, power), ...]}.
    Kinds: length, force, moment, energy, pressure, rotation."""
    f = force_power(model)
    p = 1 if model == "stress" else 0          # the table's pressure: T times the stress in plane stress
    L, F, M, P, R = ("length", 1), ("force", f), ("moment", f + 1), ("pressure", p), ("rotation", 0)
    return {
        "energy": [("energy", f + 1)],
        "reaction": [F, F],
        "contact_force": [F, F],
        "displacement": [L, L],
        "rigid": [L, L, R, F, F, M],
        "contact_zone": [L, L, L, L, L],
        "stick_zone": [L, L, L, L, L],
        "peak_pressure": [P, ("where", 1), ("where", 1)],
        "center_of_pressure": [L, L],
        "min_gap": [L],
        "min_pressure": [P],
        "spring": [F, F],
        "table": {"s": L, "x": L, "y": L, "gap0": L, "gap": L, "pressure": P},
    }


# each kind's power of the stress scale t
STRESS_KINDS = {"length": 0, "where": 0, "rotation": 0, "force": 1, "moment": 1, "energy": 1, "pressure": 1}


def floors(model, length, modulus):
    """Each kind's smallest scale: what a strain of 1e-6 of the largest
    modulus over the model's size gives (a quantity at round-off of such a
    scale, a reaction of a free expansion, is zero for the comparison)."""
    f = force_power(model)
    p = 1 if model == "stress" else 0
    stress = 1e-6 * modulus
    return {"length": length, "where": length, "force": stress * length ** f, "moment": stress * length ** (f + 1),
            "energy": stress * 1e-6 * length ** (f + 1), "pressure": stress * length ** p, "rotation": 1e-6}


def summary_numbers(path, d):
    """[(line's label, [(value, (kind, power)), ...])] of the mechanical lines."""
    rows = []
    with open(path) as h:
        for line in h:
            w = line.split()
            if not w or w[0] not in d or w[0] == "table":
                continue
            key = w[0]
            if key in ("reaction", "rigid", "displacement", "spring", "contact_force", "contact_zone",
                       "stick_zone", "peak_pressure", "center_of_pressure"):
                label, nums = key + " " + w[1], w[2:]
            else:
                label, nums = key, w[1:]
            rows.append((label, [(float(x), k) for x, k in zip(nums, d[key])]))
    return rows


def table_rows(path):
    with open(path) as h:
        head = h.readline().strip().split(",")
        return [dict(zip(head, line.strip().split(","))) for line in h]


def largest_modulus(deck):
    e = 0.0
    with open(deck) as h:
        for line in h:
            for w in line.split("!")[0].split("#")[0].split():
                k, _, v = w.partition("=")
                if k.lower() in ("e", "e1", "e2", "e3", "g12"):
                    e = max(e, abs(float(v.replace("d", "e").replace("D", "e"))))
    return e


def compare_runs(deck, base_dir, scaled_dir, stem, s, t, model, tol):
    """None when the run in scaled_dir (lengths times s, stresses times t)
    gives the dimensionless answer of the run in base_dir (of deck, STEM.summary
    and STEM_contact.csv) to tol of each kind's scale (the largest of the
    kind in the base run, at least its floor), else where it does not."""
    worst, where = largest_difference(deck, base_dir, scaled_dir, stem, s, t, model)
    if worst == float("inf"):
        return where
    if worst > tol:
        return f"largest relative difference {worst:.2e} at {where}"
    return None


def largest_difference(deck, base_dir, scaled_dir, stem, s, t, model):
    """(worst, where): the largest difference between the dimensionless
    answers of the two runs (compare_runs), relative to each kind's scale,
    and where it is; worst is infinite when the outputs differ in shape."""
    d = dims(model)
    a = summary_numbers(os.path.join(base_dir, stem + ".summary"), d)
    b = summary_numbers(os.path.join(scaled_dir, stem + ".summary"), d)
    if [r[0] for r in a] != [r[0] for r in b]:
        return float("inf"), f"the summary's lines differ: {[r[0] for r in a]} vs {[r[0] for r in b]}"
    ta = os.path.join(base_dir, stem + "_contact.csv")
    ra = table_rows(ta) if os.path.exists(ta) else []
    rb = table_rows(os.path.join(scaled_dir, stem + "_contact.csv")) if ra else []
    if len(ra) != len(rb):
        return float("inf"), "the contact tables differ in length"
    values = [(v, k) for _, nums in a for v, k in nums]
    values += [(float(r[c]), k) for r in ra for c, k in d["table"].items() if r[c] != ""]
    length = max([abs(v) for v, k in values if k[0] == "length"] + [model_size(deck), 1e-300])
    scale = floors(model, length, largest_modulus(deck))
    for v, (kind, _) in values:
        scale[kind] = max(scale[kind], abs(v))
    worst, where = 0.0, ""
    for (label, na), (_, nb) in zip(a, b):
        for (va, (kind, p)), (vb, _) in zip(na, nb):
            if kind == "where" and label.startswith("peak_pressure"):
                continue                              # the peak of a uniform pressure is anywhere: a tie
            e = abs(vb / (s ** p * t ** STRESS_KINDS[kind]) - va) / scale[kind]
            if e > worst:
                worst, where = e, f"{label}: {va} vs {vb / (s ** p * t ** STRESS_KINDS[kind])}"
    for i, (x, y) in enumerate(zip(ra, rb)):
        for c, (kind, p) in d["table"].items():
            if (x[c] == "") != (y[c] == ""):
                return float("inf"), f"contact table row {i + 1}: {c} empty in one run only"
            if x[c] == "":
                continue
            e = abs(float(y[c]) / (s ** p * t ** STRESS_KINDS[kind]) - float(x[c])) / scale[kind]
            if e > worst:
                worst, where = e, f"contact table row {i + 1} {c}: {x[c]} vs {float(y[c]) / (s ** p * t ** STRESS_KINDS[kind])}"
    return worst, where
