#!/bin/sh
# Closed-mesh refinement speed of two builds of subdiv-lab, side by side in
# one run: `subdivide --timing` (refinement only, no OBJ reading or writing)
# on a closed quad torus of N x N quads, LEVELS levels, for Catmull-Clark and
# the Doo-Sabin family (NURDS with non-uniform knots, Doo-Sabin), best of
# RUNS runs each, the two binaries alternating. Not part of the crate's build
# or CI. Run from the repository root:
#   sh benches/closed_speed.sh BASE_BIN NEW_BIN [N] [LEVELS] [RUNS]
# (defaults: N 320 = 102400 quads, LEVELS 3, RUNS 5).
# The current result is in BENCHMARKS.md ("Closed meshes: two builds").
set -eu
BASE=$1
NEW=$2
N=${3:-320}
LEVELS=${4:-3}
RUNS=${5:-5}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
python3 - "$N" "$TMP/torus.obj" "$TMP/torus.knots" <<'PY'
import math, sys
n, path, kpath = int(sys.argv[1]), sys.argv[2], sys.argv[3]
with open(path, "w") as f, open(kpath, "w") as k:
    for j in range(n):
        for i in range(n):
            u, v = 2 * math.pi * i / n, 2 * math.pi * j / n
            r = 3 + math.cos(v)
            f.write(f"v {r * math.cos(u):.9f} {r * math.sin(u):.9f} {math.sin(v):.9f}\n")
    idx = lambda i, j: (j % n) * n + (i % n) + 1
    c = 0
    for j in range(n):
        for i in range(n):
            q = [idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)]
            f.write("f " + " ".join(map(str, q)) + "\n")
            for a in range(4):
                k.write(f"{q[a]} {q[(a + 1) % 4]} {0.5 + (c * 7919 % 13) / 8}\n")
                c += 1
PY
best() { sort -g | head -1; }
for scheme in catmull-clark nurds doo-sabin; do
  KN=""
  if [ "$scheme" = nurds ]; then KN="--knots $TMP/torus.knots"; fi
  : > "$TMP/base.t"
  : > "$TMP/new.t"
  for run in $(seq "$RUNS"); do
    for which in base new; do
      if [ "$which" = base ]; then BIN=$BASE; else BIN=$NEW; fi
      # shellcheck disable=SC2086
      "$BIN" subdivide "$TMP/torus.obj" --scheme "$scheme" $KN --levels "$LEVELS" --timing 2>&1 \
        | sed -n 's/.*faces, [0-9]* vertices, \([0-9.]*\) s,.*/\1/p' >> "$TMP/$which.t"
    done
  done
  b=$(best < "$TMP/base.t")
  w=$(best < "$TMP/new.t")
  echo "$scheme: base $b s, new $w s (best of $RUNS; new/base $(python3 -c "print(f'{$w/$b:.3f}')"))"
done
