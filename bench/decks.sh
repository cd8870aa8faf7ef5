# bench/decks.sh: the decks the benchmarks share, sourced by the scripts
# (needs $top, the repository).  Each writes DECK and appends the extra
# statements given after the sizes, one per argument (e.g. "SOLVER ordering=amd").

# plate_deck DECK N [STATEMENT...]: a clamped unit square, MESH rect tri3
# N x N, traction on top; no contact
plate_deck() {
  deck=$1 n=$2
  shift 2
  {
    cat <<DECK
PLANE strain
BODY plate
  MESH rect x0=0 y0=0 x1=1 y1=1 nx=$n ny=$n
  MATERIAL isotropic E=1000 nu=0.3
  FIX bottom ux=0 uy=0
  TRACTION top tx=1 ty=-1
END
DECK
    for s in "$@"; do echo "$s"; done
  } > "$deck"
}

# signorini_deck DECK NX1 NY1 NX2 NY2 [STATEMENT...]: Signorini S of
# doc/benchmarks.md, two MESH rect blocks (lower NX1 x NY1, upper NX2 x NY2)
signorini_deck() {
  deck=$1 nx1=$2 ny1=$3 nx2=$4 ny2=$5
  shift 5
  {
    cat <<DECK
PLANE strain
BODY lower
  MESH rect x0=0 y0=0 x1=2 y1=1 nx=$nx1 ny=$ny1
  MATERIAL isotropic E=1000 nu=0.3
  FIX bottom ux=0 uy=0
END
BODY upper
  MESH rect x0=0 y0=1 x1=2 y1=2 nx=$nx2 ny=$ny2
  MATERIAL isotropic E=1000 nu=0.3
  FIX top ux=0 uy=0
  TRACTION right tx=0 ty=-20
  TRACTION left tx=0 ty=20
END
CONTACT slave=lower:top master=upper:bottom gap=zero
DECK
    for s in "$@"; do echo "$s"; done
  } > "$deck"
}

# hertz_deck DECK MESHES HC HF [STATEMENT...]: Hertz H on graded gmsh meshes
# (hc at the contact, hf away from it) MESHES_block.msh and MESHES_disk.msh
# beside DECK, meshed once
hertz_deck() {
  deck=$1 meshes=$2 hc=$3 hf=$4
  shift 4
  dir=$(dirname "$deck")
  for part in block disk; do
    [ -f "$dir/${meshes}_$part.msh" ] || gmsh -2 -format msh41 -v 1 -setnumber hc "$hc" -setnumber hf "$hf" \
      "$top/bench/geo/hertz_${part}_graded.geo" -o "$dir/${meshes}_$part.msh"
  done
  {
    cat <<DECK
PLANE strain
BODY block
  MESH gmsh file=${meshes}_block.msh
  MATERIAL isotropic E=200000 nu=0.3
  FIX bottom ux=0 uy=0
END
BODY disk
  MESH gmsh file=${meshes}_disk.msh
  MATERIAL isotropic E=200000 nu=0.3
  FIX top ux=0 uy=-0.01
END
CONTACT slave=block:top master=disk:arc
DECK
    for s in "$@"; do echo "$s"; done
  } > "$deck"
}
