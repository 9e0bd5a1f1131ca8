#!/bin/sh
# Side-by-side speed of Catmull-Clark refinement of a creased open mesh:
# `subdiv-lab subdivide --timing` against OpenSubdiv 3.5's
# Far::TopologyRefiner + PrimvarRefinerReal<double> (harness
# benches/opensubdiv/osd_sharp.cpp --time). Not part of the crate's build or
# CI. Run from the repository root:
#   sh benches/opensubdiv/speed_sharp.sh [N] [LEVELS]
# The mesh: an open N x N grid of quads (default 320: 102400 quads) with a
# wavy height, a semi-sharp crease (sharpness 2.5) along every 16th row, an
# infinitely sharp crease along every 32nd column and a corner of sharpness 3
# where they cross; LEVELS (default 3) uniform refinement steps, boundary
# edge-only, uniform creasing. Best of 3 runs each. Our time covers the
# refinement of every level (topology, sharpness and positions); OpenSubdiv's
# covers topology construction from the descriptor, RefineUniform and
# Interpolate of every level. Neither includes reading or writing OBJ text.
# Peak resident memory of each whole process (reading, refining, writing) is
# printed by /usr/bin/time when it is installed.
#
# The current result is in BENCHMARKS.md ("Creased open meshes against OpenSubdiv").
set -eu
N=${1:-320}
LEVELS=${2:-3}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
g++ -O2 -std=c++14 -o "$TMP/osd_sharp" benches/opensubdiv/osd_sharp.cpp -losdCPU
cargo build --release -q
BIN=${CARGO_TARGET_DIR:-target}/release/subdiv-lab
python3 - "$N" "$TMP/grid.obj" <<'PY'
import math, sys
n, path = int(sys.argv[1]), sys.argv[2]
w = n + 1
with open(path, "w") as f:
    for j in range(w):
        for i in range(w):
            f.write(f"v {i} {j} {math.sin(i / 7) * math.cos(j / 5):.6f}\n")
    for j in range(n):
        for i in range(n):
            a = j * w + i
            f.write(f"f {a + 1} {a + 2} {a + w + 2} {a + w + 1}\n")
    for j in range(16, n, 16):
        for i in range(n):
            f.write(f"t crease 2/1/0 {j * w + i} {j * w + i + 1} 2.5\n")
    for i in range(32, n, 32):
        for j in range(n):
            f.write(f"t crease 2/1/0 {j * w + i} {(j + 1) * w + i} 10\n")
    for j in range(32, n, 32):
        for i in range(32, n, 32):
            f.write(f"t corner 1/1/0 {j * w + i} 3\n")
PY
TIME=""
if [ -x /usr/bin/time ]; then TIME="/usr/bin/time -f peak-rss-kb=%M"; fi
for run in 1 2 3; do
  $TIME "$BIN" subdivide "$TMP/grid.obj" --scheme catmull-clark --levels "$LEVELS" --timing -o "$TMP/ours.obj" 2>&1 | sed "s/^/subdiv-lab run $run: /"
done
# one run that only refines and writes, for its memory (no timing loop)
$TIME "$TMP/osd_sharp" catmark edge-only uniform "$LEVELS" "$TMP/grid.obj" - "$TMP/osd.obj" 2>&1 | sed "s/^/opensubdiv single run: /"
"$TMP/osd_sharp" catmark edge-only uniform "$LEVELS" "$TMP/grid.obj" - "$TMP/osd.obj" --time
python3 benches/opensubdiv/compare_meshes.py "$TMP/osd.obj" "$TMP/ours.obj"
