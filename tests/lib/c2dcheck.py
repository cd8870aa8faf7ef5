"""Checks for the deck cases of contact2d: read the summary, the contact
table and the VTK file, and print one `PASS name` / `FAIL name: detail` line
per check.  The references are independent of the code: closed forms,
invariants, or reference files whose provenance is recorded beside them."""
import functools
import math
import mmap
import re
import os
import shutil
import struct
import subprocess
import sys
import zlib

PROGRAM = os.environ.get("CONTACT2D", "contact2d")
failures = 0


def run(deck, outdir, *options, expect=0):
    """Run contact2d on deck into outdir; FAIL (and exit) unless status == expect."""
    os.makedirs(outdir, exist_ok=True)
    cmd = [PROGRAM, "-q", "-o", outdir, *options, deck]
    p = subprocess.run(cmd, capture_output=True, text=True)
    ok = p.returncode == expect
    check(ok, f"run {os.path.basename(deck)} exits {expect}",
          f"status {p.returncode}: {p.stderr.strip()[:300]}")
    if not ok:
        finish()
    return p


def summary(path):
    """Dict key -> list of words; 'reaction' -> dict label -> (Fx, Fy)."""
    d = {"reaction": {}}
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "reaction":
                d["reaction"][w[1]] = (float(w[2]), float(w[3]))
            elif w[0] == "estimate" and len(w) > 1:    # estimate energy, pressure (the last pair's), cost_to_halve
                d["estimate " + w[1]] = w[2:]
            else:
                d[w[0]] = w[1:]
    return d


def value(s, key):
    return float(s[key][0])


def contact_table(path):
    """List of dicts with float fields (gap0, gap empty -> None)."""
    rows = []
    with open(path) as f:
        head = f.readline().strip().split(",")
        for line in f:
            w = line.strip().split(",")
            r = {}
            for k, v in zip(head, w):
                r[k] = float(v) if v != "" else None
            rows.append(r)
    return rows


def vtk(path):
    """Points, cells and the named POINT_DATA / CELL_DATA arrays of a legacy file."""
    with open(path) as f:
        tok = f.read().split("\n")
    out = {"point": {}, "cell": {}}
    i = 0
    section = None
    words = []
    # a simple streaming parser over whitespace tokens, keeping the keywords
    for line in tok:
        words.extend(line.split())
    n = len(words)
    i = words.index("POINTS")
    npt = int(words[i + 1]); i += 3
    out["points"] = [(float(words[i + 3 * k]), float(words[i + 3 * k + 1])) for k in range(npt)]
    i += 3 * npt
    assert words[i] == "CELLS"
    ncell = int(words[i + 1]); i += 3
    cells = []
    for _ in range(ncell):
        m = int(words[i]); cells.append([int(x) for x in words[i + 1:i + 1 + m]]); i += 1 + m
    out["cells"] = cells
    while i < n:
        w = words[i]
        if w == "POINT_DATA":
            section, count = "point", int(words[i + 1]); i += 2
        elif w == "CELL_DATA":
            section, count = "cell", int(words[i + 1]); i += 2
        elif w == "CELL_TYPES":
            i += 2 + int(words[i + 1])
        elif w in ("SCALARS", "VECTORS"):
            name = words[i + 1]
            ncomp = 3 if w == "VECTORS" else (int(words[i + 3]) if i + 3 < n and words[i + 3].isdigit() else 1)
            i += 3 if w == "VECTORS" else 4
            if words[i] == "LOOKUP_TABLE":
                i += 2
            vals = [float(x) for x in words[i:i + ncomp * count]]
            out[section][name] = [vals[k * ncomp:(k + 1) * ncomp] for k in range(count)]
            i += ncomp * count
            if i < n and words[i] == "METADATA":         # the array's component names
                assert words[i + 1] == "COMPONENT_NAMES", f"{path}: METADATA of {name} without COMPONENT_NAMES"
                out.setdefault("component_names", {})[name] = words[i + 2:i + 2 + ncomp]
                i += 2 + ncomp
        else:
            # every value belongs to a section of the size its header says:
            # a stray one means a section has more rows than points or cells
            raise ValueError(f"{path}: unexpected {w!r} after the values of a section")
    return out


def vtu(path):
    """Points, cells and the named point and cell arrays of a VTK XML
    UnstructuredGrid with raw appended data (UInt64 headers, zlib blocks or
    none), as vtk() returns them for a legacy file; read after VTK's file
    format description, independently of contact2d's writer."""
    import xml.etree.ElementTree as ET
    with open(path, "rb") as f:
        data = f.read()
    start = data.index(b"<AppendedData")
    start = data.index(b"_", start) + 1
    head = data[:data.index(b"<AppendedData")].decode() + "</VTKFile>"
    root = ET.fromstring(head)
    assert root.get("header_type") == "UInt64" and root.get("byte_order") == "LittleEndian"
    zipped = root.get("compressor") == "vtkZLibDataCompressor"
    kinds = {"Float64": "d", "Int32": "i", "Int64": "q", "UInt8": "B"}

    def values(el):
        at = start + int(el.get("offset"))
        if zipped:
            nblock, block, last = struct.unpack_from("<3Q", data, at)
            sizes = struct.unpack_from(f"<{nblock}Q", data, at + 24)
            at += 24 + 8 * nblock
            raw = b""
            for k, c in enumerate(sizes):
                part = zlib.decompress(data[at:at + c])
                want = last if (k == nblock - 1 and last) else block
                assert len(part) == want, f"{path}: block {k} inflates to {len(part)} bytes, {want} expected"
                raw += part
                at += c
        else:
            (n,) = struct.unpack_from("<Q", data, at)
            raw = data[at + 8:at + 8 + n]
        t = kinds[el.get("type")]
        vals = struct.unpack(f"<{len(raw) // struct.calcsize(t)}{t}", raw)
        m = int(el.get("NumberOfComponents", "1"))
        return [list(vals[k * m:(k + 1) * m]) for k in range(len(vals) // m)]

    piece = root.find("./UnstructuredGrid/Piece")
    out = {"point": {}, "cell": {}}
    for sec, key in (("PointData", "point"), ("CellData", "cell")):
        for el in piece.findall(f"./{sec}/DataArray"):
            out[key][el.get("Name")] = values(el)
    out["points"] = [tuple(p[:2]) for p in values(piece.find("./Points/DataArray"))]
    cells = {el.get("Name"): [v[0] for v in values(el)] for el in piece.findall("./Cells/DataArray")}
    begin = [0] + cells["offsets"][:-1]
    out["cells"] = [cells["connectivity"][a:b] for a, b in zip(begin, cells["offsets"])]
    out["types"] = cells["types"]
    return out


def check(ok, name, detail=""):
    global failures
    if ok:
        print(f"PASS {name}")
    else:
        failures += 1
        print(f"FAIL {name}: {detail}")
    sys.stdout.flush()


def close(got, want, rtol, name, floor=0.0):
    scale = max(abs(want), floor)
    ok = math.isfinite(got) and abs(got - want) <= rtol * scale
    check(ok, name, f"got {got:.10g}, expected {want:.10g} (rtol {rtol:g})")


_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def text_difference(a, b, rtol, scale=None):
    """None when texts a and b are the same apart from floating-point numbers
    that agree to rtol * scale (scale: the largest float magnitude in a unless
    given); integers must be identical.  Else the first difference."""
    wa, wb = _NUMBER.split(a), _NUMBER.split(b)
    ta, tb = _NUMBER.findall(a), _NUMBER.findall(b)
    if wa != wb or len(ta) != len(tb):
        return "the texts differ apart from their numbers"
    isint = [not any(c in t for c in ".eE") for t in ta]
    fa = [abs(float(t)) for t, k in zip(ta, isint) if not k]
    if scale is None:
        scale = max((x for x in fa if math.isfinite(x)), default=0.0)
    for i, (x, y, k) in enumerate(zip(ta, tb, isint)):
        if k and x != y or not k and not abs(float(x) - float(y)) <= rtol * scale:
            return f"number {i + 1}: {x} against {y}"
    return None


def small(got, tol, name):
    """|got| <= tol, as check_small of tests/unit/testing.f90; a NaN or an
    infinity fails.  A one-sided bound (a penetration, a tension) is passed
    as its violation, max(0, -x), which is never negative."""
    check(math.isfinite(got) and abs(got) <= tol, name, f"|{got:.3e}| > {tol:.1e}")


def skip(name, why):
    """A check this build or machine cannot make: counted neither way."""
    print(f"SKIP {name}: {why}")
    sys.stdout.flush()


# why a sanitized build cannot be run under an address-space limit
NO_ADDRESS_LIMIT = ("an AddressSanitizer build reserves terabytes of shadow address space at start: "
                    "no ulimit -v leaves it that room")


@functools.lru_cache(maxsize=None)
def sanitized(program=None):
    """True when program (PROGRAM unless given) is built with AddressSanitizer:
    its binary names __asan_init, the runtime's entry point that every
    instrumented object calls at start, whether libasan is linked dynamically
    (an undefined dynamic symbol) or statically (a defined one)."""
    path = shutil.which(program or PROGRAM) or program or PROGRAM
    with open(path, "rb") as f, mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ) as m:
        return m.find(b"__asan_init") >= 0


def finish():
    sys.exit(1 if failures else 0)
