#!/usr/bin/env python3
"""Mutation fuzzing of contact2d's input: decks and gmsh meshes.

The valid decks of the repository (input/*.deck, tests/**/*.deck) and small
decks over the gmsh meshes of tests/unit/data and tests/bad/deck_ok_square.msh
are the seeds.  Each case applies one to four random mutations to one seed
(tokens dropped, duplicated, swapped; numbers replaced by NaN, Inf, huge,
empty or garbage text; lines dropped or repeated; the whole deck in other
units, lengths and stresses scaled with its meshes; truncated files; binary
garbage; wrong MSH versions; inconsistent node ids; unknown physical groups;
broken section structure ...) and runs the program on it under a time limit.
Every outcome must be one of

  exit 0  accepted: the outputs written (a VTK file and a summary), no *.part
          left, no NaN or Inf in them (with --check: nothing written);
  exit 1  numerical failure: a stderr line `contact2d: error: ...` (warnings
          may come first), no output written, earlier outputs untouched;
  exit 2  rejected: first stderr line `contact2d: error: FILE:LINE: ...` or
          `contact2d: error: FILE: ...` with FILE one of the case's inputs (or
          the output folder) and LINE within the file, no output written,
          earlier outputs untouched;

anything else is a failure: a signal, another exit status, a Fortran runtime
error, a sanitizer report, or no answer within the time limit (a hang).

Case k is a pure function of (--seed, k) and of the seed files, so any case
can be rebuilt with --cases k --keep DIR.  The gmsh .geo meshes of the seed
decks are meshed once at the start (gmsh is never run on mutated input, so
that a mutated mesh size cannot make gmsh legitimately run for hours).

Usage (from anywhere; paths are relative to the repository root):
  tests/fuzz/fuzz.py [-n 3000] [--seed 1] [--jobs 2] [--timeout 20]
                     [--program bin/contact2d]
                     [--sanitize-program bin/contact2d-sanitize]
                     [--sanitize-fraction 0.25] [--cases 17,42]
                     [--keep DIR] [--failures DIR] [--quiet]
Exit status 0 when no case failed, 1 otherwise.
"""
import argparse
import concurrent.futures
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests" / "lib"))
import deck_scale  # noqa: E402  (tests/lib: the deck in other units)

# --------------------------------------------------------------------------- values

# Replacements for a number: non-finite, out of range, empty, garbage.
BAD_NUMBERS = [
    "NaN", "nan", "-nan", "NAN", "Inf", "-Inf", "inf", "+Infinity", "-infinity",
    "1e308", "-1.7976931348623157e308", "1.8e308", "1e309", "-1e309", "1d400",
    "1e-320", "4.9e-324", "1e-400", "0", "-0", "0.0", "-1", "-1e-300", "1e300",
    "1e30", "1e-30", "99999999999999999999", "-99999999999999999999",
    "2147483647", "2147483648", "-2147483648", "-2147483649", "9223372036854775808",
    "1" + "0" * 400, "0." + "0" * 300 + "1", "", "1.2.3", "0x10", "0x1p3", "1e",
    "e5", "1e+", "+-1", "--1", "1d", "1,5", "1_8", ".", "-", "+", "1e5x", "2.0q5",
    "\xef\xbc\x91", "TRUE", "NaN(1)", "1/0", "(1)", '"1"', "\x00", "\xff\xfe", "1\x00",
    "\xb9", "1.5", "1e3", "3.", ".5", "+7", "1E+02", "1.0D0", "-.5e-1",
]
# Integers and small perturbations for counts, tags and node numbers.
BAD_INTEGERS = ["0", "-1", "-7", "1", "2", "3", "1000000", "2147483647", "2147483648",
                "99999999999", "1.5", "1e3", "", "x", "NaN", "-2147483648"]
MSH_VERSIONS = ["3.0 0 8", "4 0 8", "4.0 0 8", "4.1 0 8", "2.2 0 8", "2.2 1 8", "4.1 1 8",
                "2.2 0 4", "2.2 0 16", "1 0 8", "2.1 0 8", "5.0 0 8", "4.1 0 8 x", "4.1",
                "2.2", "", "NaN 0 8", "4.10 0 8", "2.20 0 8", "41 0 8", "2.2 0", "2.2 0 8 0",
                "-2.2 0 8", "2.2 -1 8", "4.1 0 -8", "2.2\t0\t8"]
ELEMENT_TYPES = ["1", "2", "3", "4", "5", "8", "9", "10", "15", "16", "99", "0", "-1", "2147483648"]
DECK_KEYWORDS = ["TITLE", "PLANE", "BODY", "MESH", "MATERIAL", "DENSITY", "FIX", "TRACTION",
                 "PRESSURE", "BODYFORCE", "END", "GRAVITY", "CONTACT", "SOLVER", "OUTPUT",
                 "RIGID", "SHAPE", "REF", "FORCE"]
DECK_KEYS = ["x0", "y0", "x1", "y1", "nx", "ny", "elem", "diag", "file", "E", "nu", "E1", "E2",
             "nu12", "G12", "angle", "E3", "nu13", "nu23", "rho", "ux", "uy", "tx", "ty", "p", "fx",
             "fy", "gx", "gy", "slave", "master", "gap", "lcp", "tol", "maxit", "omega", "vtk",
             "contact", "summary", "thickness", "xc", "yc", "r", "solid", "points", "rz", "m"]
WORDS = ["rect", "gmsh", "isotropic", "orthotropic", "strain", "stress", "tri3", "quad4", "right",
         "left", "alt", "geometry", "zero", "auto", "lemke", "pgs", "top", "bottom", "lower",
         "upper", "block", "disk", "arc", "body", "rim", "corner", "quads", "whole", "2", "3",
         "Top", "", "=", ":", "a:b", "x:y:z", "!", "#", "=1", "E==1", "BODY", "END", "line", "circle",
         "polyline", "inside", "outside", "RIGID", "points=0:0", "points=0:0,0:0", "points=1:2,,3:4"]
FILE_NAMES = ["missing.msh", "missing.geo", "", ".msh", "a.msh.msh", "../x.msh", "/nonexistent/y.msh",
              "case.deck", ".", "..", "/dev/null", "sub/", "x.MSH", "x.msh ", "out", "mesh.txt"]
NUM_RE = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eEdD][+-]?\d+)?$")


# --------------------------------------------------------------------------- seeds

class Seed:
    """A valid input: files (name -> bytes) with the deck at `deck`."""

    def __init__(self, name, deck, files):
        self.name = name
        self.deck = deck
        self.files = files
        self.meshes = sorted(f for f in files if f.endswith(".msh"))


def physical_names(text):
    """(dim, tag, name) of the $PhysicalNames section of an MSH file."""
    out = []
    m = re.search(r"\$PhysicalNames\s*\n\s*(\d+)\s*\n(.*?)\$EndPhysicalNames", text, re.S)
    if m:
        for line in m.group(2).splitlines():
            w = line.split(None, 2)
            if len(w) == 3:
                out.append((int(w[0]), int(w[1]), w[2].strip().strip('"')))
    return out


def mesh_seed_decks():
    """Small decks over the repository's small gmsh meshes: (name, deck text, mesh files)."""
    data = ROOT / "tests" / "unit" / "data"
    meshes = sorted(data.glob("*.msh")) + [ROOT / "tests" / "bad" / "deck_ok_square.msh"]
    out = []
    for path in meshes:
        text = path.read_text(errors="replace")
        curves = [n for d, t, n in physical_names(text) if d == 1]
        if not curves and "sparse" in path.name:
            curves = ["2"]                       # unnamed physical curve 2
        if not curves:
            continue                             # nothing to hold the body by
        name = path.name
        fix = curves[0]
        deck = (f"! fuzz seed over {name}\nTITLE seed {name}\nPLANE strain\nBODY b\n"
                f"  MESH gmsh file={name}\n  MATERIAL isotropic E=1000 nu=0.3\n"
                f"  FIX {fix} ux=0 uy=0\n")
        if len(curves) > 1:
            deck += f"  TRACTION {curves[-1]} tx=1 ty=-2\n"
        deck += "  BODYFORCE fx=0.1 fy=-0.2\nEND\n"
        out.append((f"mesh-{path.stem}", deck, {name: path.read_bytes()}))
        # the same mesh in contact with a rect body above it (square meshes)
        if {"top", "bottom", "left"} <= set(curves):
            deck2 = (f"TITLE contact seed over {name}\nBODY lower\n  MESH gmsh file={name}\n"
                     f"  MATERIAL isotropic E=1000 nu=0.3\n  FIX bottom ux=0 uy=0\nEND\n"
                     f"BODY upper\n  MESH rect x0=0 y0=1 x1=1 y1=2 nx=3 ny=3\n"
                     f"  MATERIAL orthotropic E1=2000 E2=500 nu12=0.3 G12=300 angle=30\n"
                     f"  FIX left ux=0\n  FIX top uy=-0.01\nEND\n"
                     f"CONTACT slave=lower:top master=upper:bottom gap=zero\nSOLVER lcp=lemke\n")
            out.append((f"contact-{path.stem}", deck2, {name: path.read_bytes()}))
    return out


def mesh_geo(geo, params, msh):
    """Mesh geo with gmsh as contact2d would; the node count, or 0 on failure."""
    cmd = ["gmsh", "-2", "-order", "1", "-format", "msh41", "-v", "0"]
    for k, v in params:
        cmd += ["-setnumber", k, v]
    cmd += [str(geo), "-o", str(msh)]
    try:
        subprocess.run(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL, timeout=120, check=True)
        m = re.search(r"\$Nodes\s*\n\s*\d+\s+(\d+)", msh.read_text(errors="replace"))
        return int(m.group(1)) if m else 0
    except (OSError, subprocess.SubprocessError):
        return 0


def repo_seed_decks(work, log, only=None):
    """The repository's valid decks (names containing one of `only` when
    given), their .geo meshes meshed once into .msh files."""
    paths = sorted(ROOT.glob("input/*.deck")) + sorted(
        p for p in ROOT.glob("tests/**/*.deck") if "bad" not in p.relative_to(ROOT).parts)
    out = []
    for path in paths:
        rel = path.relative_to(ROOT)
        stem = str(rel.with_suffix("")).replace("/", "_")
        if only and not any(x in stem for x in only):
            continue
        lines = path.read_text(errors="replace").split("\n")
        files = {}
        ok = True
        for i, line in enumerate(lines):
            code = re.split(r"[!#]", line, 1)[0]
            w = code.split()
            if len(w) < 2 or w[0].upper() != "MESH" or w[1].lower() != "gmsh":
                continue
            kv = [x.split("=", 1) for x in w[2:] if "=" in x]
            fname = next((v for k, v in kv if k.lower() == "file"), None)
            if fname is None:
                ok = False
                break
            src = (path.parent / fname).resolve()
            local = f"m{len(files) + 1}_{src.stem}.msh"
            if src.suffix == ".geo":
                params = [(k, v) for k, v in kv if k.lower() != "file"]
                if any("${" in v for _, v in params):
                    ok = False                   # sizes set by PARAMETER: not meshed here
                    break
                nodes = 0
                for _ in range(4):               # coarsen the h* sizes until small
                    nodes = mesh_geo(src, params, work / local)
                    if 0 < nodes <= 3000:
                        break
                    params = [(k, repr(float(v) * 3) if k.lower().startswith("h") else v)
                              for k, v in params]
                if not 0 < nodes <= 3000:
                    ok = False
                    break
                files[local] = (work / local).read_bytes()
            elif src.is_file():
                files[local] = src.read_bytes()
            else:
                ok = False
                break
            indent = line[:len(line) - len(line.lstrip())]
            lines[i] = f"{indent}MESH gmsh file={local}"
        if not ok:
            log(f"seed {rel}: skipped (mesh not available or too large)")
            continue
        out.append((stem, "\n".join(lines), files))
    return out


def build_seeds(work, program, log, only=None):
    """Every seed (those whose name contains one of the strings `only` when
    given), each checked to exit 0 with `program` (others are dropped)."""
    seeds = []
    for name, deck, files in repo_seed_decks(work, log, only) + mesh_seed_decks():
        if only and not any(x in name for x in only):
            continue
        all_files = dict(files)
        all_files["case.deck"] = deck.encode("latin-1", "replace")
        d = work / ("seed-" + name)
        d.mkdir()
        for f, b in all_files.items():
            (d / f).write_bytes(b)
        p = subprocess.run([program, "-q", "-o", "out", "case.deck"], cwd=d, stdin=subprocess.DEVNULL,
                           capture_output=True, timeout=300)
        shutil.rmtree(d, ignore_errors=True)
        if p.returncode != 0:
            log(f"seed {name}: skipped (exit {p.returncode}: "
                f"{p.stderr.decode(errors='replace').strip()[:200]})")
            continue
        seeds.append(Seed(name, "case.deck", all_files))
    return seeds


# --------------------------------------------------------------------------- mutations
# Texts are handled as latin-1 strings: every byte maps to one character and back.

def tokens(line):
    return [(m.start(), m.end()) for m in re.finditer(r"[^ \t]+", line)]


def pick_token(rng, lines, pred=None):
    """(line index, start, end) of a random token satisfying pred(token, its index in the line)."""
    cand = []
    for i, line in enumerate(lines):
        for j, (a, b) in enumerate(tokens(line)):
            if pred is None or pred(line[a:b], j):
                cand.append((i, a, b))
    return rng.choice(cand) if cand else None


def replace_span(lines, i, a, b, new):
    lines[i] = lines[i][:a] + new + lines[i][b:]


def number_value(tok):
    """(prefix, number) when tok is a number or key=number, else None."""
    k, sep, v = tok.rpartition("=")
    if NUM_RE.match(v):
        return k + sep, v
    return None


def perturbed(rng, v):
    """A nearby or extreme value of the number text v."""
    try:
        if re.match(r"^[+-]?\d+$", v):
            n = int(v)
            return str(rng.choice([n + 1, n - 1, 0, -n, n * 1000, n + 2 ** 31, 2 * n, n // 2]))
        x = float(v.replace("d", "e").replace("D", "e"))
        return repr(rng.choice([-x, x * 1e12, x * 1e-12, x + 1e-3, x * 1.5, 0.0, x * 1e200]))
    except (ValueError, OverflowError):
        return "0"


def m_drop_token(rng, lines, ctx):
    t = pick_token(rng, lines)
    if t:
        i, a, b = t
        replace_span(lines, i, a, b, "")
        return "drop token"


def m_dup_token(rng, lines, ctx):
    t = pick_token(rng, lines)
    if t:
        i, a, b = t
        tok = lines[i][a:b]
        replace_span(lines, i, a, b, tok + " " + tok)
        return f"duplicate token {tok[:20]!r}"


def m_swap_tokens(rng, lines, ctx):
    t1, t2 = pick_token(rng, lines), pick_token(rng, lines)
    if t1 and t2 and t1 != t2:
        (i, a, b), (j, c, d) = sorted([t1, t2])
        s1, s2 = lines[i][a:b], lines[j][c:d]
        if i == j:
            lines[i] = lines[i][:a] + s2 + lines[i][b:c] + s1 + lines[i][d:]
        else:
            replace_span(lines, j, c, d, s1)
            replace_span(lines, i, a, b, s2)
        return f"swap tokens {s1[:15]!r} {s2[:15]!r}"


def m_bad_number(rng, lines, ctx):
    t = pick_token(rng, lines, lambda tok, j: number_value(tok) is not None)
    if t:
        i, a, b = t
        pre, v = number_value(lines[i][a:b])
        new = rng.choice(BAD_NUMBERS)
        replace_span(lines, i, a, b, pre + new)
        return f"number {v[:15]!r} -> {new[:20]!r}"


def m_perturb_number(rng, lines, ctx):
    t = pick_token(rng, lines, lambda tok, j: number_value(tok) is not None)
    if t:
        i, a, b = t
        pre, v = number_value(lines[i][a:b])
        new = perturbed(rng, v)
        replace_span(lines, i, a, b, pre + new)
        return f"number {v[:15]!r} -> {new[:20]!r}"


def m_drop_line(rng, lines, ctx):
    if lines:
        i = rng.randrange(len(lines))
        del lines[i]
        return f"drop line {i + 1}"


def m_dup_line(rng, lines, ctx):
    if lines:
        i = rng.randrange(len(lines))
        lines.insert(rng.randrange(len(lines) + 1), lines[i])
        return f"duplicate line {i + 1}"


def m_swap_lines(rng, lines, ctx):
    if len(lines) > 1:
        i, j = rng.sample(range(len(lines)), 2)
        lines[i], lines[j] = lines[j], lines[i]
        return f"swap lines {i + 1} {j + 1}"


def m_binary(rng, lines, ctx):
    n = rng.choice([1, 1, 4, 16, 200])
    junk = "".join(chr(rng.randrange(256)) for _ in range(n))
    if rng.random() < 0.3:
        junk = rng.choice(["\x00", "\xff", "\r", "\x1a", "\x7f", "\xef\xbb\xbf", "\t", "\x0b\x0c"])
    i = rng.randrange(len(lines)) if lines else 0
    if not lines:
        lines.append("")
    pos = rng.randrange(len(lines[i]) + 1)
    lines[i] = lines[i][:pos] + junk + lines[i][pos:]
    return f"binary garbage ({len(junk)} bytes) in line {i + 1}"


def m_long_line(rng, lines, ctx):
    n = rng.choice([5000, 70000])
    i = rng.randrange(len(lines) + 1)
    lines.insert(i, rng.choice(["x" * n, "1 " * (n // 2), "! " + "c" * n, "TITLE " + "t" * n]))
    return f"long line ({n}) at {i + 1}"


def m_crlf(rng, lines, ctx):
    for i in range(len(lines)):
        lines[i] = lines[i] + "\r"
    return "CRLF line ends"


def m_blank_words(rng, lines, ctx):
    """Tabs, non-breaking spaces, form feeds in the spacing."""
    t = pick_token(rng, lines)
    if t:
        i, a, b = t
        sep = rng.choice(["\t", "\xa0", "\x0c", "  ", "\x0b", ""])
        lines[i] = lines[i][:a] + sep + lines[i][a:]
        return f"separator {sep!r} in line {i + 1}"


# ---- deck-specific

def m_deck_key(rng, lines, ctx):
    t = pick_token(rng, lines, lambda tok, j: "=" in tok)
    if t:
        i, a, b = t
        k, _, v = lines[i][a:b].partition("=")
        new = rng.choice([rng.choice(DECK_KEYS) + "=" + v, k.upper() + "=" + v, k + "x=" + v,
                          k + " = " + v, k + "= " + v, k + " =" + v, k + v, k + "==" + v,
                          k + "=", "=" + v, k + "=" + v + "=" + v, k + "=" + rng.choice(WORDS)])
        replace_span(lines, i, a, b, new)
        return f"key {k!r} -> {new[:30]!r}"


def m_deck_keyword(rng, lines, ctx):
    t = pick_token(rng, lines, lambda tok, j: j == 0)
    if t:
        i, a, b = t
        new = rng.choice(DECK_KEYWORDS + [lines[i][a:b].lower(), lines[i][a:b].swapcase(), "BODYY", "", "END;"])
        replace_span(lines, i, a, b, new)
        return f"keyword -> {new!r}"


def m_deck_word(rng, lines, ctx):
    """A positional word or name replaced (unknown boundary, body, kind)."""
    t = pick_token(rng, lines, lambda tok, j: j > 0)
    if t:
        i, a, b = t
        old = lines[i][a:b]
        if ":" in old and "=" in old:
            k, _, v = old.partition("=")
            body, _, bnd = v.partition(":")
            new = k + "=" + rng.choice([body + ":nonexistent", "nobody:" + bnd, body, ":" + bnd, body + ":",
                                        body + ":" + bnd + ":x", bnd + ":" + body, body + "::" + bnd])
        else:
            new = rng.choice(WORDS + ["nonexistent", "Bottom", old + old, old.upper(), "a" * 300])
        replace_span(lines, i, a, b, new)
        return f"word {old[:20]!r} -> {new[:30]!r}"


def m_deck_file(rng, lines, ctx):
    t = pick_token(rng, lines, lambda tok, j: tok.lower().startswith("file="))
    if t:
        i, a, b = t
        choices = FILE_NAMES + [m for m in ctx["meshes"]] + ["m1_" + m for m in ctx["meshes"]]
        new = rng.choice(choices)
        replace_span(lines, i, a, b, "file=" + new)
        return f"file= -> {new!r}"


def m_deck_block(rng, lines, ctx):
    """Break the BODY ... END structure or insert a statement from another seed."""
    op = rng.randrange(5)
    if op == 0:
        ends = [i for i, l in enumerate(lines) if l.strip().upper().startswith("END")]
        if ends:
            i = rng.choice(ends)
            del lines[i]
            return f"drop END at line {i + 1}"
    if op == 1:
        i = rng.randrange(len(lines) + 1)
        lines.insert(i, rng.choice(["END", "BODY extra", "BODY", "BODY b", "CONTACT", "SOLVER", "OUTPUT", "RIGID",
                                    "RIGID r", "SHAPE circle xc=0 yc=0 r=1", "FORCE fy=-1", "FIX rz=0",
                                    "CONTACT slave=lower:top master=r"]))
        return f"insert block statement at {i + 1}"
    if op == 2:
        bodies = [i for i, l in enumerate(lines) if l.strip().upper().startswith("BODY")]
        if bodies:
            i = rng.choice(bodies)
            j = next((k for k in range(i, len(lines)) if lines[k].strip().upper().startswith("END")), len(lines) - 1)
            lines.extend(lines[i:j + 1])
            return f"duplicate body block at line {i + 1}"
    other = ctx["other_deck"].split("\n")
    if other:
        line = rng.choice(other)
        i = rng.randrange(len(lines) + 1)
        lines.insert(i, line)
        return f"insert line {line[:30]!r} at {i + 1}"


def m_local_axes(rng, lines, ctx):
    """Put a boundary of a body in local axes: a FIX un=/ut= on a name the body's own statements or the
    CONTACT lines use, right after its BODY line.  Local axes rotate the contact rows of every kind of pair
    (a RIGID's dofs among them once overran local_axes' arrays)."""
    bodies = [i for i, l in enumerate(lines) if l.strip().upper().startswith("BODY") and len(l.split()) > 1]
    if not bodies:
        return None
    i = rng.choice(bodies)
    body = lines[i].split()[1]
    end = next((k for k in range(i, len(lines)) if lines[k].strip().upper().startswith("END")), len(lines))
    names = set()
    for l in lines[i + 1:end]:
        w = l.split()
        if len(w) > 1 and w[0].upper() in ("FIX", "TRACTION", "PRESSURE", "SPRING") and "=" not in w[1]:
            names.add(w[1])
    for l in lines:
        for tok in l.split():
            if tok.startswith(("slave=", "master=")) and tok.split("=", 1)[1].startswith(body + ":"):
                names.add(tok.split(":", 1)[1])
    if not names:
        return None
    name = rng.choice(sorted(names))
    fix = rng.choice([f"FIX {name} ut=0", f"FIX {name} un=0", f"FIX {name} un=0 ut=0", f"FIX {name} ut=0 ramp=0:1"])
    lines.insert(i + 1, "  " + fix)
    return f"insert {fix!r} at {i + 2}"


# ---- MSH-specific

def sections(lines):
    """name -> list of (first body line, end line) of each $Name ... $EndName section."""
    out = {}
    i = 0
    while i < len(lines):
        s = lines[i].strip()
        if s.startswith("$") and not s.startswith("$End"):
            name = s[1:]
            j = next((k for k in range(i + 1, len(lines)) if lines[k].strip() == "$End" + name), len(lines))
            out.setdefault(name, []).append((i + 1, j))
            i = j
        i += 1
    return out


def section_line(rng, lines, name, pred=lambda w: True):
    cand = [k for a, b in sections(lines).get(name, []) for k in range(a, b) if pred(lines[k].split())]
    return rng.choice(cand) if cand else None


def set_word(lines, k, j, new):
    """Replace word j of line k (negative j from the end)."""
    w = lines[k].split()
    if w and -len(w) <= j < len(w):
        old = w[j]
        w[j] = new
        lines[k] = " ".join(w)
        return old


def m_msh_version(rng, lines, ctx):
    k = section_line(rng, lines, "MeshFormat")
    new = rng.choice(MSH_VERSIONS)
    if k is None:
        lines[:0] = ["$MeshFormat", new, "$EndMeshFormat"]
    else:
        lines[k] = new
    return f"MSH version line -> {new!r}"


def m_msh_node_id(rng, lines, ctx):
    """Inconsistent node ids: a node tag changed, or an element refers to a bad node."""
    v41 = ctx["v41"]
    if rng.random() < 0.5:
        if v41:
            k = section_line(rng, lines, "Nodes", lambda w: len(w) == 1)
            col = 0
        else:
            k = section_line(rng, lines, "Nodes", lambda w: len(w) == 4)
            col = 0
        where = "node tag"
    else:
        k = section_line(rng, lines, "Elements", lambda w: len(w) in (2, 3, 4, 5) if v41 else len(w) >= 6)
        col = -rng.randrange(1, 3)
        where = "element node"
    if k is None:
        return None
    w = lines[k].split()
    other = rng.choice(lines[k - 1].split() or ["1"]) if k > 0 else "1"
    new = rng.choice(BAD_INTEGERS + [other, str(ctx["nnode"] + 1), str(ctx["nnode"])])
    old = set_word(lines, k, col, new)
    return f"{where} {old!r} -> {new!r} (line {k + 1}; {len(w)} words)"


def m_msh_physical(rng, lines, ctx):
    """Unknown or renamed physical groups."""
    op = rng.randrange(3)
    if op == 0:
        k = section_line(rng, lines, "PhysicalNames", lambda w: len(w) >= 3)
        if k is not None:
            col = rng.randrange(3)
            new = rng.choice(['"renamed"', '"top"', '""', '"a b"', "noquote", "0", "3", "7", "-1", "999"]) \
                if col == 2 else rng.choice(BAD_INTEGERS)
            old = set_word(lines, k, col, new)
            return f"physical name field {col} {old!r} -> {new!r}"
    if op == 1 and not ctx["v41"]:
        k = section_line(rng, lines, "Elements", lambda w: len(w) >= 6)
        if k is not None:
            new = rng.choice(["999", "0", "-1", "5", "2147483648"])
            old = set_word(lines, k, 3, new)
            return f"element physical tag {old!r} -> {new!r}"
    k = section_line(rng, lines, "Entities" if ctx["v41"] else "Elements", lambda w: len(w) >= 5)
    if k is not None:
        j = rng.randrange(len(lines[k].split()))
        new = rng.choice(["999", "0", "-1", "1", "2", "100000000000"])
        old = set_word(lines, k, j, new)
        return f"entity/element field {j} {old!r} -> {new!r}"


def m_msh_count(rng, lines, ctx):
    """The count line after a section header perturbed."""
    cand = [a for name, spans in sections(lines).items() for a, b in spans
            if name in ("Nodes", "Elements", "PhysicalNames", "Entities") and a < len(lines)]
    if cand:
        k = rng.choice(cand)
        w = lines[k].split()
        if w:
            j = rng.randrange(len(w))
            new = rng.choice([perturbed(rng, w[j]) if NUM_RE.match(w[j]) else "0"] + BAD_INTEGERS)
            old = set_word(lines, k, j, new)
            return f"count field {j} of line {k + 1} {old!r} -> {new!r}"


def m_msh_type(rng, lines, ctx):
    if ctx["v41"]:
        k = section_line(rng, lines, "Elements", lambda w: len(w) == 4)
        j = 2
    else:
        k = section_line(rng, lines, "Elements", lambda w: len(w) >= 6)
        j = 1
    if k is not None:
        new = rng.choice(ELEMENT_TYPES)
        old = set_word(lines, k, j, new)
        return f"element type {old!r} -> {new!r} (line {k + 1})"


def m_msh_coordinate(rng, lines, ctx):
    k = section_line(rng, lines, "Nodes", lambda w: len(w) in (3, 4, 5))
    if k is not None:
        w = lines[k].split()
        j = rng.randrange(len(w) - 3 if len(w) == 4 and not ctx["v41"] else 0, len(w))
        if len(w) == 4 and not ctx["v41"]:
            j = rng.randrange(1, 4)
        new = rng.choice(BAD_NUMBERS + ["1e-3", "0.5", "1", "-1"])
        old = set_word(lines, k, j, new)
        return f"coordinate {old!r} -> {new!r} (line {k + 1})"


def m_msh_section(rng, lines, ctx):
    secs = [(n, a, b) for n, spans in sections(lines).items() for a, b in spans]
    if not secs:
        return None
    name, a, b = rng.choice(secs)
    op = rng.randrange(6)
    if op == 0 and b < len(lines):
        del lines[b]
        return f"drop $End{name}"
    if op == 1:
        del lines[a - 1]
        return f"drop ${name} header"
    if op == 2:
        block = lines[a - 1:b + 1]
        lines[b + 1:b + 1] = block
        return f"duplicate section {name}"
    if op == 3:
        del lines[a - 1:b + 1]
        return f"drop section {name}"
    if op == 4:
        lines[a:b] = ["".join(chr(rng.randrange(256)) for _ in range(rng.randrange(1, 80)))]
        return f"section {name} body -> binary garbage"
    other = [s for s in secs if s[0] != name]
    if other:
        n2, c, d = rng.choice(other)
        blk1, blk2 = lines[a - 1:b + 1], lines[c - 1:d + 1]
        if a < c:
            lines[c - 1:d + 1] = blk1
            lines[a - 1:b + 1] = blk2
        else:
            lines[a - 1:b + 1] = blk2
            lines[c - 1:d + 1] = blk1
        return f"swap sections {name} {n2}"


def m_msh_element_degenerate(rng, lines, ctx):
    """Repeated or reversed nodes in an element."""
    k = section_line(rng, lines, "Elements", lambda w: len(w) == (4 if ctx["v41"] else 8) or len(w) >= 7)
    if k is not None:
        w = lines[k].split()
        if rng.random() < 0.5:
            w[-1] = w[-2]
            what = "repeated node"
        else:
            w[-1], w[-2] = w[-2], w[-1]
            what = "reversed"
        lines[k] = " ".join(w)
        return f"element line {k + 1}: {what}"


def m_scale(rng, lines, ctx):
    """The whole deck in other units: every length times s, every stress
    (moduli, tractions, Tresca bounds) times t, forces and moments and
    springs as their dimensions say (tests/lib/deck_scale.py), the meshes
    scaled with it (make_case): the program must take it as it took the
    seed, whatever s and t, within the range its checks accept."""
    s = 10.0 ** rng.choice([-6, -3, -1, 1, 3, 6])
    t = 10.0 ** rng.choice([-6, -3, 0, 3, 6])
    try:
        new = deck_scale.scale_text("\n".join(lines), s, t)
    except (deck_scale.Unscalable, ValueError, ZeroDivisionError, SyntaxError, NameError, TypeError):
        return None
    lines[:] = new.split("\n")
    ctx["mesh_scale"] = s
    return f"scaled: lengths x{s:g}, stresses x{t:g}"


GENERIC = [(m_drop_token, 3), (m_dup_token, 2), (m_swap_tokens, 2), (m_bad_number, 6), (m_perturb_number, 3),
           (m_drop_line, 2), (m_dup_line, 2), (m_swap_lines, 2), (m_binary, 1), (m_long_line, 0.3),
           (m_crlf, 0.3), (m_blank_words, 1)]
DECK_OPS = GENERIC + [(m_deck_key, 3), (m_deck_keyword, 2), (m_deck_word, 3), (m_deck_file, 1),
                      (m_deck_block, 2), (m_local_axes, 2), (m_scale, 2)]
MSH_OPS = GENERIC + [(m_msh_version, 2), (m_msh_node_id, 4), (m_msh_physical, 3), (m_msh_count, 3),
                     (m_msh_type, 2), (m_msh_coordinate, 3), (m_msh_section, 3), (m_msh_element_degenerate, 2)]


def choose(rng, ops):
    total = sum(w for _, w in ops)
    x = rng.random() * total
    for f, w in ops:
        x -= w
        if x <= 0:
            return f
    return ops[-1][0]


def mutate_text(rng, text, ops, ctx, nmut):
    """Apply nmut mutations (and maybe a truncation) to text; the new text and a log."""
    final_newline = text.endswith("\n")
    lines = text.split("\n")
    if final_newline:
        lines.pop()
    done = []
    tries = 0
    while len(done) < nmut and tries < 50:
        tries += 1
        what = choose(rng, ops)(rng, lines, ctx)
        if what:
            done.append(what)
    out = "\n".join(lines) + ("\n" if final_newline and rng.random() < 0.9 else "")
    if rng.random() < 0.08:                        # truncated file
        cut = rng.randrange(len(out) + 1)
        out = out[:cut]
        done.append(f"truncated at byte {cut}")
    return out, done


def too_big(deck):
    """True when a mutated deck asks, validly, for a mesh too large to be a small case."""
    for line in deck.split("\n"):
        w = re.split(r"[!#]", line, 1)[0].split()
        if len(w) >= 2 and w[0].upper() == "MESH" and w[1].lower() == "rect":
            kv = dict(x.split("=", 1) for x in w[2:] if "=" in x)
            kv = {k.lower(): v for k, v in kv.items()}
            try:
                nx, ny = int(kv.get("nx", "1")), int(kv.get("ny", "1"))
                if nx * ny > 20000 or max(nx, ny) > 500:   # many cells, or many contact nodes
                    return True
            except ValueError:
                pass
    return False


def make_case(seeds, base_seed, k):
    """Case k: (seed name, files, mutation log, options); a pure function of (base_seed, k)."""
    rng = random.Random(f"{base_seed}:{k}")
    for _ in range(20):
        mesh_case = rng.random() < 0.45
        seed = rng.choice([s for s in seeds if s.meshes] if mesh_case else seeds)
        files = {n: b.decode("latin-1") for n, b in seed.files.items()}
        nmut = rng.choices([1, 2, 3, 4], [55, 25, 12, 8])[0]
        if mesh_case:
            target = rng.choice(seed.meshes)
            text = files[target]
            nnode = max([int(w) for w in re.findall(r"^\s*(\d+)\s", text, re.M)] or [1])
            ctx = {"v41": bool(re.search(r"\$MeshFormat\s*\n\s*4", text)), "nnode": nnode}
            ops = MSH_OPS
        else:
            target = seed.deck
            other = rng.choice(seeds)
            ctx = {"meshes": seed.meshes, "other_deck": other.files[other.deck].decode("latin-1")}
            ops = DECK_OPS
        new, log = mutate_text(rng, files[target], ops, ctx, nmut)
        files[target] = new
        if ctx.get("mesh_scale"):                  # m_scale: the meshes in the deck's new units
            for name in seed.meshes:
                try:
                    files[name] = deck_scale.scale_msh_text(files[name], ctx["mesh_scale"], name)
                except (deck_scale.Unscalable, ValueError, IndexError):
                    pass
        if not too_big(files[seed.deck]):
            break
    opts = {"check": rng.random() < 0.08, "quiet": rng.random() < 0.7, "preexisting": rng.random() < 0.5}
    return seed.name, {n: t.encode("latin-1") for n, t in files.items()}, [f"{target}: {x}" for x in log], opts


# --------------------------------------------------------------------------- running

CRASH_MARKS = ["runtime error", "Backtrace", "AddressSanitizer", "UndefinedBehaviorSanitizer",
               "LeakSanitizer", "SUMMARY:", "Program received signal", "Error termination",
               "Segmentation fault", "Fortran runtime error"]
OUTPUT_NAMES = ["case.vtk", "case_contact.csv", "case.summary"]
PRLIMIT = shutil.which("prlimit")
NONFINITE = re.compile(rb"(?i)(?<![A-Za-z0-9_])[+-]?(nan|inf|infinity)(?![A-Za-z0-9_])")


def run_program(cmd, cwd, timeout, env):
    """(status or None on timeout, stdout, stderr, seconds); the process group is killed on timeout."""
    t0 = time.time()
    if PRLIMIT:                                  # a run writing more than 1 GB is stopped (SIGXFSZ)
        cmd = [PRLIMIT, f"--fsize={2 ** 30}", "--"] + cmd
    p = subprocess.Popen(cmd, cwd=cwd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, env=env, start_new_session=True)
    try:
        out, err = p.communicate(timeout=timeout)
        return p.returncode, out, err, time.time() - t0
    except subprocess.TimeoutExpired:
        try:
            os.killpg(p.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        out, err = p.communicate()
        return None, out, err, time.time() - t0


ARRAY_TEMPORARY = re.compile(rb"At line \d+ of file [^\n]*\nFortran runtime warning: An array temporary was created[^\n]*\n")


def strip_array_temporary_warnings(err):
    """stderr without -fcheck=array-temps warnings (the sanitize build prints them); their count."""
    return ARRAY_TEMPORARY.subn(b"", err)


def line_count(path):
    try:
        return path.read_bytes().count(b"\n") + 1
    except OSError:
        return None


def classify(case_dir, files, opts, rc, stderr, sentinels):
    """(outcome, problem or None) of one run."""
    out = case_dir / "out"
    text = stderr.decode("latin-1")
    first = text.split("\n", 1)[0]
    if rc is None:
        return "hang", "no answer within the time limit"
    marks = [m for m in CRASH_MARKS if m in text]
    if rc < 0:
        return "crash", f"killed by signal {-rc}: {first[:200]}"
    if marks:
        line = next(l for l in text.split("\n") if any(m in l for m in marks))
        return "crash", f"exit {rc}, stderr has {marks[0]!r}: {line[:200]}"
    produced = sorted(p.name for p in out.iterdir()) if out.is_dir() else []
    parts = [n for n in produced if n.endswith(".part") or (n.startswith(".") and "~" in n)]   # temporaries
    changed = [n for n, b in sentinels.items() if not (out / n).is_file() or (out / n).read_bytes() != b]
    new = [n for n in produced if n not in sentinels]
    if parts:
        return "contract", f"exit {rc} left {parts}"
    if rc == 0:
        if opts["check"]:
            if new or changed:
                return "contract", f"--check wrote {new + changed}"
            return "accepted", None
        heads = {n: (out / n).read_bytes() for n in produced if (out / n).is_file()}
        vtk = [n for n, b in heads.items() if b.startswith(b"# vtk DataFile") and (n in new or n in changed)]
        summ = [n for n, b in heads.items() if re.search(rb"(?m)^dofs \d+", b) and (n in new or n in changed)]
        if not vtk or not summ:
            return "contract", f"exit 0 without a new VTK file and summary (folder: {produced})"
        for n in vtk + summ + [n for n in new if n.endswith(".csv")]:
            b = heads[n]
            if n in vtk:                         # line 2 is the deck's free TITLE
                lines = b.split(b"\n")
                b = b"\n".join(lines[:1] + lines[2:])
            m = NONFINITE.search(b)
            if m:
                return "contract", f"exit 0 but {n} holds {m.group(0).decode()!r}"
        return "accepted", None
    if rc not in (1, 2):
        return "crash", f"exit status {rc}: {first[:200]}"
    if new or changed:
        return "contract", f"exit {rc} but wrote/changed {new + changed}: {first[:150]}"
    if rc == 1:                                  # warnings may come before the diagnostic
        if not re.search(r"(?m)^contact2d: error: \S", text):
            return "contract", f"exit 1 without a `contact2d: error: ...` line: {first[:200]!r}"
        return "numerical", None
    if not first.startswith("contact2d: error: "):
        return "contract", f"exit 2, first stderr line {first[:200]!r}"
    msg = first[len("contact2d: error: "):]
    m = re.match(r"([^:]+):(\d+): \S", msg) or re.match(r"([^:]+): \S", msg)
    if not m:
        return "contract", f"exit 2 without FILE:LINE or FILE: {first[:200]!r}"
    fname = m.group(1)
    deck_text = files["case.deck"].decode("latin-1")
    known = set(files) | {"out"} | set(re.findall(r"(?i)file\s*=\s*(\S+)", deck_text))
    if fname not in known and os.path.basename(fname) not in known:
        return "contract", f"exit 2 names unknown file {fname!r}: {first[:200]!r}"
    if len(m.groups()) == 2:
        n = line_count(case_dir / fname)
        if n is not None and not 1 <= int(m.group(2)) <= n:
            return "contract", f"line {m.group(2)} outside {fname} ({n} lines): {first[:200]!r}"
    return "rejected", None


def run_case(k, args, seeds, programs, work):
    name, files, log, opts = make_case(seeds, args.seed, k)
    use_san = programs[1] is not None and random.Random(f"san:{args.seed}:{k}").random() < args.sanitize_fraction
    program = programs[1] if use_san else programs[0]
    case_dir = Path(tempfile.mkdtemp(prefix=f"case{k}-", dir=work))
    for n, b in files.items():
        (case_dir / n).write_bytes(b)
    sentinels = {}
    if opts["preexisting"]:
        (case_dir / "out").mkdir()
        for n in OUTPUT_NAMES:
            sentinels[n] = f"earlier successful run {k} {n}\n".encode()
            (case_dir / "out" / n).write_bytes(sentinels[n])
    cmd = [str(program)] + (["-q"] if opts["quiet"] else []) + (["--check"] if opts["check"] else []) + \
          ["-o", "out", "case.deck"]
    env = dict(os.environ)
    env["ASAN_OPTIONS"] = args.asan_options
    env["UBSAN_OPTIONS"] = "print_stacktrace=1:halt_on_error=1:exitcode=87"
    rc, _, raw_err, secs = run_program(cmd, case_dir, args.timeout, env)
    err, nwarn = strip_array_temporary_warnings(raw_err)
    outcome, problem = classify(case_dir, files, opts, rc, err, sentinels)
    res = {"case": k, "seed": name, "mutations": log, "program": program.name, "rc": rc,
           "mesh": bool(log) and log[0].split(":", 1)[0].endswith(".msh"),
           "outcome": outcome, "problem": problem, "seconds": secs, "sanitize": use_san,
           "stderr": err.decode("latin-1")[:2000], "cmd": " ".join(cmd[1:]), "warnings": nwarn}
    keep = problem is not None or args.keep
    if keep:
        dest = Path(args.keep or args.failures) / f"case{k}"
        shutil.rmtree(dest, ignore_errors=True)
        shutil.copytree(case_dir, dest)
        (dest / "stderr").write_bytes(raw_err)
        (dest / "README").write_text(
            f"case {k} (--seed {args.seed}) from seed {name}\nmutations:\n  " + "\n  ".join(log) +
            f"\ncommand (in this folder; out/ holds what was there before the run when it had sentinels):\n"
            f"  {program} {res['cmd']}\nstatus {rc}, {outcome}: {problem}\nstderr:\n{res['stderr']}\n")
    shutil.rmtree(case_dir, ignore_errors=True)
    return res


def run_case_guarded(k, args, seeds, programs, work):
    """run_case; an exception of the driver itself is reported as a failing case."""
    try:
        return run_case(k, args, seeds, programs, work)
    except Exception as e:                       # a bug of this script: report it, go on
        return {"case": k, "seed": "?", "mutations": [], "program": "fuzz.py", "rc": None,
                "outcome": "driver", "problem": f"{type(e).__name__}: {e}", "seconds": 0.0,
                "sanitize": False, "stderr": "", "cmd": "", "warnings": 0}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("-n", "--count", type=int, default=3000, help="number of cases (default 3000)")
    ap.add_argument("--seed", type=int, default=1, help="base seed (default 1)")
    ap.add_argument("--jobs", type=int, default=2, help="parallel runs (default 2)")
    ap.add_argument("--timeout", type=float, default=20.0, help="seconds per run (default 20)")
    ap.add_argument("--program", default="bin/contact2d", help="the program (default bin/contact2d)")
    ap.add_argument("--sanitize-program", default=None,
                    help="a -fsanitize build run on --sanitize-fraction of the cases")
    ap.add_argument("--sanitize-fraction", type=float, default=0.25)
    ap.add_argument("--asan-options", default="detect_leaks=1:exitcode=86:abort_on_error=0",
                    help="ASAN_OPTIONS for the runs")
    ap.add_argument("--seeds", default=None,
                    help="comma-separated strings: only the seeds whose name contains one (e.g. force_control)")
    ap.add_argument("--cases", default=None, help="comma-separated case numbers to run instead of 0..n-1")
    ap.add_argument("--keep", default=None, help="copy every case (input, README) into this folder")
    ap.add_argument("--failures", default=None, help="copy failing cases here (default: a new /tmp folder)")
    ap.add_argument("--quiet", action="store_true", help="print only the summary and failures")
    args = ap.parse_args()

    def resolve(p):
        p = Path(p)
        return p if p.is_absolute() else (ROOT / p)
    prog = resolve(args.program)
    san = resolve(args.sanitize_program) if args.sanitize_program else None
    for p in [prog] + ([san] if san else []):
        if not os.access(p, os.X_OK):
            sys.exit(f"fuzz.py: {p}: not an executable program (build it first: make, make MODE=sanitize)")
    if san is None:
        args.sanitize_fraction = 0.0
    work = Path(tempfile.mkdtemp(prefix="contact2d-fuzz-"))
    # run copies, so that a rebuild during the run cannot swap the program under it
    (work / "bin").mkdir()
    prog = Path(shutil.copy2(prog, work / "bin" / prog.name))
    if san is not None:
        san = Path(shutil.copy2(san, work / "bin" / san.name))
    if args.failures is None:
        args.failures = str(work) + "-failures"
    say = (lambda s: None) if args.quiet else (lambda s: print(s, flush=True))
    t0 = time.time()
    seeds = build_seeds(work, prog, say, args.seeds.split(",") if args.seeds else None)
    if not seeds or not any(s.meshes for s in seeds):
        sys.exit("fuzz.py: no valid seed deck (or none with a gmsh mesh)")
    say(f"{len(seeds)} seeds: {' '.join(s.name for s in seeds)}")
    ks = [int(x) for x in args.cases.split(",")] if args.cases else list(range(args.count))
    results = []
    lock = threading.Lock()
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as ex:
        futs = [ex.submit(run_case_guarded, k, args, seeds, (prog, san), work) for k in ks]
        for f in concurrent.futures.as_completed(futs):
            r = f.result()
            with lock:
                results.append(r)
                if r["problem"]:
                    print(f"FAIL case {r['case']} ({r['seed']}, {r['program']}): {r['outcome']}: {r['problem']}\n"
                          f"     mutations: {'; '.join(r['mutations'])}", flush=True)
                if len(results) % 250 == 0:
                    say(f"... {len(results)}/{len(ks)} cases, {time.time() - t0:.0f} s")
    shutil.rmtree(work, ignore_errors=True)
    results.sort(key=lambda r: r["case"])
    count = {o: sum(r["outcome"] == o for r in results)
             for o in ["accepted", "rejected", "numerical", "crash", "hang", "contract", "driver"]}
    nmesh = sum(bool(r.get("mesh")) for r in results)
    slow = max(results, key=lambda r: r["seconds"])
    runs = ", ".join(f"{n} {sum(r['program'] == n for r in results)}"
                     for n in sorted({r["program"] for r in results if r["program"] != "fuzz.py"}))
    print(f"cases {len(results)} ({len(results) - nmesh} deck mutations, {nmesh} mesh mutations; "
          f"runs: {runs}), seeds {len(seeds)}, --seed {args.seed}, {time.time() - t0:.0f} s")
    print(f"accepted (exit 0) {count['accepted']}, rejected (exit 2) {count['rejected']}, "
          f"numerical failure (exit 1) {count['numerical']}")
    print(f"crashes {count['crash']}, hangs {count['hang']}, contract violations {count['contract']}")
    if count["driver"]:
        print(f"driver errors (bugs of fuzz.py) {count['driver']}")
    nwarn = sum(r["warnings"] for r in results)
    print(f"slowest case {slow['case']}: {slow['seconds']:.1f} s; -fcheck=array-temps warnings ignored: {nwarn}")
    nfail = count["crash"] + count["hang"] + count["contract"] + count["driver"]
    if nfail:
        print(f"failing cases copied to {args.failures}")
    return 1 if nfail else 0


if __name__ == "__main__":
    sys.exit(main())
