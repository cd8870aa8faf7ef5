"""The decks of the batch tests: a gmsh block (block.geo, width w) under a
rect block pressed down by d, in a folder of its own; every deck is named
plate.deck with bodies lower and upper, so that decks in different folders
share every name and differ only in their parameters."""
import os
import shutil

HERE = os.path.dirname(os.path.abspath(__file__))

DECK = """TITLE {title}
BODY lower
  MESH gmsh file=block.geo h=0.25 w={w}
  MATERIAL isotropic E=1000 nu=0.3
  FIX bottom ux=0 uy=0
END
BODY upper
  MESH rect x0=0 y0=1 x1=1 y1=1.5 nx=3 ny=2
  MATERIAL isotropic E=1000 nu=0.3
  FIX top ux=0 uy={d}
END
CONTACT slave=lower:top master=upper:bottom gap=zero
{extra}"""


def make_deck(folder, title, w, d, extra="", geo=None):
    """folder/plate.deck (and folder/block.geo, or geo's text); returns the deck's path."""
    os.makedirs(folder, exist_ok=True)
    if geo is None:
        shutil.copy(os.path.join(HERE, "block.geo"), os.path.join(folder, "block.geo"))
    else:
        with open(os.path.join(folder, "block.geo"), "w") as f:
            f.write(geo)
    path = os.path.join(folder, "plate.deck")
    with open(path, "w") as f:
        f.write(DECK.format(title=title, w=w, d=d, extra=extra))
    return path


RECT = """TITLE case {title}
BODY lower
  MESH rect x0=0 y0=0 x1=1 y1=1 nx={n} ny={n}
  MATERIAL isotropic E=1000 nu=0.3
  FIX bottom ux=0 uy=0
END
BODY upper
  MESH rect x0=0 y0=1 x1=1 y1=1.5 nx=20 ny=10
  MATERIAL isotropic E=1000 nu=0.3
  FIX top ux=0 uy={d}
END
CONTACT slave=lower:top master=upper:bottom gap=zero
"""


def make_rect_deck(folder, title, n, d):
    """folder/plate.deck without gmsh (n x n lower block): runs started
    together stay in step up to their outputs."""
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "plate.deck")
    with open(path, "w") as f:
        f.write(RECT.format(title=title, n=n, d=d))
    return path


def read(path):
    with open(path, "rb") as f:
        return f.read()


def untimed(summary_bytes):
    """The summary without its timing and memory lines (they differ run to run)."""
    return b"".join(l for l in summary_bytes.splitlines(True)
                    if not l.startswith((b"time_", b"cpu_total", b"estimate cost_to_halve", b"memory_peak", b"factor_memory")))
