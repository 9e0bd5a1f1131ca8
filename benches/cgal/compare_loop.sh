#!/usr/bin/env bash
# Loop subdivision side by side: CGAL 5.5 (CGAL::Subdivision_method_3::Loop_subdivision
# on a Surface_mesh, harness benches/cgal/loop.cpp), OpenSubdiv 3.5 (Far
# TopologyRefiner with Sdc::SCHEME_LOOP and PrimvarRefinerReal<double>::Interpolate,
# harness benches/opensubdiv/osd_loop.cpp) and subdiv-lab
# (`subdiv-lab subdivide --scheme loop`). Not part of the crate build or CI.
#
# Needs: Debian's libcgal-dev, libosd-dev and opensubdiv-tools
# (`apt-get install -y libcgal-dev libosd-dev opensubdiv-tools`), g++, python3,
# GNU time (/usr/bin/time).
#
#   bash benches/cgal/compare_loop.sh          # defaults: LEVELS=3 RUNS=3
#   LEVELS=4 RUNS=5 bash benches/cgal/compare_loop.sh
#
# 1. Agreement with CGAL on the shipped triangle meshes (tetrahedron,
#    icosahedron, analysis/meshes/triangles/*.obj) at levels 1..3: vertices
#    matched by position (one-to-one), triangles compared as oriented cycles,
#    largest distance (benches/opensubdiv/compare_meshes.py). The rules agree
#    at every valence: CGAL's Loop_mask_3 vertex point is
#    ((n (1 - C_n) / C_n) S + R) / (n / C_n), C_n = 5/8 - (3 + 2 cos(2 pi / n))^2 / 64
#    = n beta_n with Loop's beta_n, i.e. (1 - n beta_n) S + beta_n R, and
#    (10 S + R) / 16 at n = 6; edge point (3 (p1 + p2) + f1 + f2) / 8. (Not
#    Warren's 3/(8n).) Its border rules are never reached on closed meshes.
# 2. Speed: input analysis/meshes/triangles/bipyramid_3_12.obj refined 6 times
#    by us (98,304 triangles, valences 3, 4, 5, 6, 11, 12), then LEVELS more
#    levels by each tool. Refinement wall time only (each harness times its
#    refinement call(s), not reading or writing; OpenSubdiv: topology
#    refinement plus the interpolation of the positions), the best of RUNS
#    runs; peak RSS of the whole process from /usr/bin/time (%M), including
#    the input; the timed runs write nothing.
#
# The speed table is in BENCHMARKS.md ("Loop subdivision against CGAL and
# OpenSubdiv").
#
# Agreement with CGAL at levels 1..3: counts, one-to-one matching and
# oriented triangles equal on all five meshes; largest distance 9.9e-16
# (torus_irregular, level 3; relative to the coordinates 4.0e-16), 0 on the
# octahedron, at most 3.3e-16 on the others.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
LEVELS=${LEVELS:-3}
RUNS=${RUNS:-3}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

cargo build --release --quiet --manifest-path "$ROOT/Cargo.toml" --bin subdiv-lab
BIN="$ROOT/target/release/subdiv-lab"
# ours MESH LEVELS OUT [FLAGS...]: our refinement of MESH, written to OUT
ours() { "$BIN" subdivide "$1" --scheme loop --levels "$2" -o "$3" "${@:4}"; }
g++ -O2 -DNDEBUG -DCGAL_NDEBUG -std=c++17 -o "$WORK/cgal_loop" "$ROOT/benches/cgal/loop.cpp"
g++ -O2 -std=c++14 -o "$WORK/osd_loop" "$ROOT/benches/opensubdiv/osd_loop.cpp" -losdCPU
CMP="python3 $ROOT/benches/opensubdiv/compare_meshes.py"

echo "agreement with CGAL (CGAL vs ours):"
for m in "$ROOT/analysis/meshes/tetrahedron.obj" "$ROOT/analysis/meshes/icosahedron.obj" "$ROOT"/analysis/meshes/triangles/*.obj; do
  for l in 1 2 3; do
    "$WORK/cgal_loop" "$m" "$l" "$WORK/cgal.obj" >/dev/null
    ours "$m" "$l" "$WORK/ours.obj"
    printf '%-18s L%d  %s\n' "$(basename "$m" .obj)" "$l" "$($CMP "$WORK/cgal.obj" "$WORK/ours.obj")"
  done
done

ours "$ROOT/analysis/meshes/triangles/bipyramid_3_12.obj" 6 "$WORK/input.obj"
IN_FACES=$(grep -c '^f ' "$WORK/input.obj")

best() { sort -g | head -1; }
# row NAME CMD...: best of RUNS refinement seconds and peak RSS of a harness
# that prints "faces=F ... seconds=S ..." on standard output (ours: the
# `--timing` line on standard error, rewritten to that form).
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
echo
echo "Loop, $IN_FACES input triangles, $LEVELS levels (best of $RUNS runs; $(nproc) cores, $(uname -m))"
printf '| %-21s | %12s | %10s | %16s | %14s |\n' "tool" "out faces" "refine s" "out faces / s" "peak RSS MiB"
printf '|%s|%s|%s|%s|%s|\n' "-----------------------" "--------------" "------------" "------------------" "----------------"
row "CGAL 5.5" "$WORK/cgal_loop" "$WORK/input.obj" "$LEVELS"
row "OpenSubdiv 3.5 (Far)" "$WORK/osd_loop" "$WORK/input.obj" "$LEVELS"
row subdiv-lab "$BIN" subdivide "$WORK/input.obj" --scheme loop --levels "$LEVELS" --timing
