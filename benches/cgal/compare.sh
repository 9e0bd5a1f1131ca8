#!/usr/bin/env bash
# Side-by-side: CGAL's Doo-Sabin (CGAL::Subdivision_method_3::DooSabin_subdivision
# on a Surface_mesh) and subdiv-lab's `subdivide --scheme doo-sabin`, same input
# mesh, same number of levels. Not part of the crate build or CI.
#
# Needs: Debian's libcgal-dev (header-only; `apt-get install -y libcgal-dev`),
# g++, python3, GNU time (/usr/bin/time).
#
#   bash benches/cgal/compare.sh            # defaults: LEVELS=4 RUNS=3
#   LEVELS=3 RUNS=5 bash benches/cgal/compare.sh
#
# Input: analysis/meshes/truncated_icosahedron.obj refined 4 times with the
# Catmull-Clark variant (11,522 faces: hexagons, pentagons, valence-3 vertices).
# Timing: refinement wall time only (both tools exclude reading and writing);
# the best of RUNS runs. Memory: whole-process peak RSS from /usr/bin/time
# (%M), runs without output files (the timed runs write nothing).
# Agreement: both results at 2 levels are written and their vertex sets compared
# (sorted coordinates, max abs difference).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
LEVELS=${LEVELS:-4}
RUNS=${RUNS:-3}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

cargo build --release --quiet --manifest-path "$ROOT/Cargo.toml" --bin subdiv-lab
BIN="$ROOT/target/release/subdiv-lab"
g++ -O2 -DNDEBUG -DCGAL_NDEBUG -std=c++17 -o "$WORK/cgal_doo_sabin" "$ROOT/benches/cgal/doo_sabin.cpp"

"$BIN" subdivide "$ROOT/analysis/meshes/truncated_icosahedron.obj" --scheme cc-variant --levels 4 -o "$WORK/input.obj"
IN_FACES=$(grep -c '^f ' "$WORK/input.obj")

best() { sort -g | head -1; }

cgal_t=(); ours_t=(); cgal_m=(); ours_m=()
for _ in $(seq "$RUNS"); do
  line=$(/usr/bin/time -f "rss=%M" "$WORK/cgal_doo_sabin" "$WORK/input.obj" "$LEVELS" 2>"$WORK/cgal.time")
  cgal_t+=("$(sed -E 's/.*seconds=([^ ]+).*/\1/' <<<"$line")")
  cgal_m+=("$(sed -E 's/rss=//' "$WORK/cgal.time")")
  CGAL_FACES=$(sed -E 's/faces=([0-9]+).*/\1/' <<<"$line")
  /usr/bin/time -f "rss=%M" "$BIN" subdivide "$WORK/input.obj" --scheme doo-sabin --levels "$LEVELS" --timing 2>"$WORK/ours.err"
  ours_t+=("$(grep refinement "$WORK/ours.err" | sed -E 's/.* ([0-9.]+) s,.*/\1/')")
  ours_m+=("$(grep rss= "$WORK/ours.err" | sed -E 's/rss=//')")
  OURS_FACES=$(grep refinement "$WORK/ours.err" | sed -E 's/.*levels, ([0-9]+) faces.*/\1/')
done
CT=$(printf '%s\n' "${cgal_t[@]}" | best); OT=$(printf '%s\n' "${ours_t[@]}" | best)
CM=$(printf '%s\n' "${cgal_m[@]}" | best); OM=$(printf '%s\n' "${ours_m[@]}" | best)

# agreement at 2 levels
"$WORK/cgal_doo_sabin" "$WORK/input.obj" 2 "$WORK/cgal2.obj" >/dev/null
"$BIN" subdivide "$WORK/input.obj" --scheme doo-sabin --levels 2 -o "$WORK/ours2.obj"
AGREE=$(python3 - "$WORK/cgal2.obj" "$WORK/ours2.obj" <<'PY'
import sys
def load(p):
    vs, fs = [], 0
    for line in open(p):
        if line.startswith('v '):
            vs.append(tuple(float(x) for x in line.split()[1:4]))
        elif line.startswith('f '):
            fs += 1
    return vs, fs
a, fa = load(sys.argv[1]); b, fb = load(sys.argv[2])
if len(a) != len(b) or fa != fb:
    print(f"MISMATCH counts: cgal {len(a)} v {fa} f, ours {len(b)} v {fb} f"); sys.exit(0)
# match every vertex of ours to CGAL's through a grid hash (cell 1e-6), then
# report the largest distance of a matched pair and the number left unmatched
cell = 1e-6
grid = {}
for p in a:
    grid.setdefault(tuple(round(x / cell) for x in p), []).append(p)
worst, unmatched = 0.0, 0
for q in b:
    k = tuple(round(x / cell) for x in q)
    best = None
    for dx in (-1, 0, 1):
        for dy in (-1, 0, 1):
            for dz in (-1, 0, 1):
                for p in grid.get((k[0] + dx, k[1] + dy, k[2] + dz), ()):
                    d = max(abs(x - y) for x, y in zip(p, q))
                    best = d if best is None else min(best, d)
    if best is None:
        unmatched += 1
    else:
        worst = max(worst, best)
print(f"{len(a)} vertices, {fa} faces; unmatched vertices: {unmatched}; max |coordinate difference| of matched = {worst:.3e}")
PY
)

echo
echo "Doo-Sabin, $IN_FACES input faces, $LEVELS levels (best of $RUNS runs; $(nproc) cores, $(uname -m))"
printf '| %-21s | %12s | %10s | %16s | %14s |\n' "tool" "out faces" "refine s" "out faces / s" "peak RSS MiB"
printf '|%s|%s|%s|%s|%s|\n' "-----------------------" "--------------" "------------" "------------------" "----------------"
awk -v t="$CT" -v f="$CGAL_FACES" -v m="$CM" 'BEGIN{printf "| %-21s | %12d | %10.3f | %16.0f | %14.1f |\n", "CGAL 5.5", f, t, f/t, m/1024}'
awk -v t="$OT" -v f="$OURS_FACES" -v m="$OM" 'BEGIN{printf "| %-21s | %12d | %10.3f | %16.0f | %14.1f |\n", "subdiv-lab", f, t, f/t, m/1024}'
# our other schemes on the same input, for context (no CGAL counterpart)
for scheme in nurds cc-variant; do
  bt=""; bm=""
  for _ in $(seq "$RUNS"); do
    /usr/bin/time -f "rss=%M" "$BIN" subdivide "$WORK/input.obj" --scheme "$scheme" --levels "$LEVELS" --timing 2>"$WORK/s.err"
    t=$(grep refinement "$WORK/s.err" | sed -E 's/.* ([0-9.]+) s,.*/\1/'); m=$(grep rss= "$WORK/s.err" | sed -E 's/rss=//')
    f=$(grep refinement "$WORK/s.err" | sed -E 's/.*levels, ([0-9]+) faces.*/\1/')
    bt=$(printf '%s\n%s\n' "$bt" "$t" | grep . | best); bm=$(printf '%s\n%s\n' "$bm" "$m" | grep . | best)
  done
  awk -v t="$bt" -v f="$f" -v m="$bm" -v n="subdiv-lab $scheme" 'BEGIN{printf "| %-21s | %12d | %10.3f | %16.0f | %14.1f |\n", n, f, t, f/t, m/1024}'
done
echo "(the last rows are our NURDS (uniform default intervals; face weights computed per face) and CC variant: no CGAL counterpart)"
echo
echo "agreement at 2 levels: $AGREE"
