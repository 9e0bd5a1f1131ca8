#!/usr/bin/env bash
# sqrt3 and modified butterfly side by side: CGAL 5.5
# (CGAL::Subdivision_method_3::Sqrt3_subdivision on a Surface_mesh, harness
# benches/cgal/sqrt3.cpp), OpenMesh 9.0 (OpenMesh::Subdivider::Uniform::Sqrt3T
# and ModifiedButterflyT on a TriMesh with double-precision points, harness
# benches/openmesh/tri_schemes.cpp) and subdiv-lab
# (`subdiv-lab subdivide --scheme sqrt3|modified-butterfly`). Not part of the
# crate build or CI. (The original butterfly has no counterpart in either
# library; OpenMesh's modified butterfly is the butterfly between two
# valence-6 vertices.)
#
# Needs: Debian's libcgal-dev and libopenmesh-dev
# (`apt-get install -y libcgal-dev libopenmesh-dev`), g++, python3, GNU time
# (/usr/bin/time).
#
#   bash benches/openmesh/compare_tri_schemes.sh      # defaults: LEVELS=3 RUNS=3
#
# 1. Agreement on the shipped triangle meshes (tetrahedron, icosahedron,
#    analysis/meshes/triangles/*.obj) at levels 1..3: vertices matched by
#    position (one-to-one), triangles compared as oriented cycles, largest
#    distance (benches/opensubdiv/compare_meshes.py). The rules are the same
#    on closed meshes: Kobbelt's alpha_n = (4 - 2 cos(2 pi / n)) / 9 in both
#    libraries; OpenMesh's modified butterfly uses the weights of Zorin,
#    Schroder and Sweldens with 1 - sum_j s_j on the extraordinary vertex
#    (3/4 up to rounding) and averages two irregular ends. The OpenMesh
#    harness parses the OBJ itself: OpenMesh's OBJ reader stores coordinates
#    as float, which alone moves every point by ~1e-8.
# 2. Speed: input analysis/meshes/triangles/bipyramid_3_12.obj refined 6 times
#    by Loop (98,304 triangles, valences 3, 4, 5, 6, 11, 12), then LEVELS
#    levels by each tool. Refinement wall time only (each harness times its
#    refinement call, not reading or writing), the best of RUNS runs; peak
#    RSS of the whole process from /usr/bin/time (%M), including the input.
#
# The tables are in BENCHMARKS.md ("sqrt3 and modified butterfly against
# CGAL and OpenMesh").
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
LEVELS=${LEVELS:-3}
RUNS=${RUNS:-3}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

cargo build --release --quiet --manifest-path "$ROOT/Cargo.toml" --bin subdiv-lab
BIN="${CARGO_TARGET_DIR:-$ROOT/target}/release/subdiv-lab"
g++ -O2 -DNDEBUG -DCGAL_NDEBUG -std=c++17 -o "$WORK/cgal_sqrt3" "$ROOT/benches/cgal/sqrt3.cpp"
g++ -O2 -DNDEBUG -std=c++17 -o "$WORK/om" "$ROOT/benches/openmesh/tri_schemes.cpp" -lOpenMeshTools -lOpenMeshCore
CMP="python3 $ROOT/benches/opensubdiv/compare_meshes.py"

MESHES=("$ROOT/analysis/meshes/tetrahedron.obj" "$ROOT/analysis/meshes/icosahedron.obj" "$ROOT"/analysis/meshes/triangles/*.obj)
echo "agreement (reference vs ours):"
for m in "${MESHES[@]}"; do
  for l in 1 2 3; do
    name=$(basename "$m" .obj)
    "$BIN" subdivide "$m" --scheme sqrt3 --levels "$l" -o "$WORK/ours.obj"
    "$WORK/cgal_sqrt3" "$m" "$l" "$WORK/ref.obj" >/dev/null
    printf 'sqrt3 CGAL          %-18s L%d  %s\n' "$name" "$l" "$($CMP "$WORK/ref.obj" "$WORK/ours.obj")"
    "$WORK/om" sqrt3 "$m" "$l" "$WORK/ref.obj" >/dev/null
    printf 'sqrt3 OpenMesh      %-18s L%d  %s\n' "$name" "$l" "$($CMP "$WORK/ref.obj" "$WORK/ours.obj")"
    "$BIN" subdivide "$m" --scheme modified-butterfly --levels "$l" -o "$WORK/ours.obj"
    "$WORK/om" modified-butterfly "$m" "$l" "$WORK/ref.obj" >/dev/null
    printf 'mod. butterfly OM   %-18s L%d  %s\n' "$name" "$l" "$($CMP "$WORK/ref.obj" "$WORK/ours.obj")"
  done
done

"$BIN" subdivide "$ROOT/analysis/meshes/triangles/bipyramid_3_12.obj" --scheme loop --levels 6 -o "$WORK/input.obj"
IN_FACES=$(grep -c '^f ' "$WORK/input.obj")

best() { sort -g | head -1; }
# row NAME CMD...: best of RUNS refinement seconds and peak RSS of a harness
# that prints "faces=F ... seconds=S ..." (ours: the `--timing` line on
# standard error, rewritten to that form).
row() {
  local name=$1; shift
  local ts=() ms=() faces="" line
  for _ in $(seq "$RUNS"); do
    if [ "$name" = subdiv-lab ]; then
      /usr/bin/time -f "rss=%M" "$@" 2>"$WORK/time.err" >/dev/null
      line=$(grep '^refinement:' "$WORK/time.err" | sed -E 's/refinement: [0-9]+ levels, ([0-9]+) faces, ([0-9]+) vertices, ([0-9.]+) s.*/faces=\1 vertices=\2 seconds=\3/')
    else
      line=$(/usr/bin/time -f "rss=%M" "$@" 2>"$WORK/time.err")
    fi
    ts+=("$(sed -E 's/.*seconds=([^ ]+).*/\1/' <<<"$line")")
    ms+=("$(grep rss= "$WORK/time.err" | sed -E 's/rss=//')")
    faces=$(sed -E 's/.*faces=([0-9]+).*/\1/' <<<"$line")
  done
  local t m
  t=$(printf '%s\n' "${ts[@]}" | best); m=$(printf '%s\n' "${ms[@]}" | best)
  awk -v t="$t" -v f="$faces" -v m="$m" -v n="$name" 'BEGIN{printf "| %-21s | %12d | %10.3f | %16.0f | %14.1f |\n", n, f, t, f/t, m/1024}'
}
header() {
  echo
  echo "$1, $IN_FACES input triangles, $LEVELS levels (best of $RUNS runs; $(nproc) cores, $(uname -m))"
  printf '| %-21s | %12s | %10s | %16s | %14s |\n' "tool" "out faces" "refine s" "out faces / s" "peak RSS MiB"
  printf '|%s|%s|%s|%s|%s|\n' "-----------------------" "--------------" "------------" "------------------" "----------------"
}
header "sqrt3"
row "CGAL 5.5" "$WORK/cgal_sqrt3" "$WORK/input.obj" "$LEVELS"
row "OpenMesh 9.0" "$WORK/om" sqrt3 "$WORK/input.obj" "$LEVELS"
row subdiv-lab "$BIN" subdivide "$WORK/input.obj" --scheme sqrt3 --levels "$LEVELS" --timing
header "modified butterfly"
row "OpenMesh 9.0" "$WORK/om" modified-butterfly "$WORK/input.obj" "$LEVELS"
row subdiv-lab "$BIN" subdivide "$WORK/input.obj" --scheme modified-butterfly --levels "$LEVELS" --timing
