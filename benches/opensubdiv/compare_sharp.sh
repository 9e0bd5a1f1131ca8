#!/bin/sh
# Compare `subdiv-lab subdivide` on open meshes with crease and corner tags
# with OpenSubdiv 3.5 (Debian package libosd-dev; harness
# benches/opensubdiv/osd_sharp.cpp, Far::TopologyRefiner +
# PrimvarRefinerReal<double>). Not part of the crate's build or CI. Run from
# the repository root:
#   sh benches/opensubdiv/compare_sharp.sh [LEVELS]
#
# Meshes: analysis/meshes/sharp/grid_quads.obj (Catmull-Clark) and
# grid_tris.obj (Loop), plus grid_quads_untagged.obj with --tags
# grid_quads.tags. For every boundary mode, creasing method and level
# 1..LEVELS (default 3), benches/opensubdiv/compare_meshes.py matches the
# vertices by position, checks the matching is one-to-one and the faces (the
# ones that are not holes) agree as oriented cycles, and prints the largest
# distance; then the same with `--limit` (OpenSubdiv's
# PrimvarRefinerReal<double>::Limit on the last level). A case fails when
# counts or faces differ or the distance exceeds 1e-12.
#
# Result (Debian 12, OpenSubdiv 3.5.0-2, LEVELS=3): all 108 cases agree
# (counts, one-to-one matching, oriented faces). Largest distance over the
# boundary modes, creasing methods and levels: grid_quads (also with --tags)
# 2.0e-15 refined, 2.0e-15 limit; grid_tris 6.3e-16 refined, 1.8e-15 limit.
set -eu
LEVELS=${1:-3}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
g++ -O2 -std=c++14 -o "$TMP/osd_sharp" benches/opensubdiv/osd_sharp.cpp -losdCPU
cargo build --release -q
BIN=${CARGO_TARGET_DIR:-target}/release/subdiv-lab
D=analysis/meshes/sharp
fail=0
run() { # name scheme osd-scheme obj tags-or-dash
  for b in none edge-only edge-and-corner; do
    for c in uniform chaikin; do
      l=1
      while [ "$l" -le "$LEVELS" ]; do
       for lim in "" --limit; do
        if [ "$5" = - ]; then
          "$BIN" subdivide "$4" --scheme "$2" --boundary "$b" --creasing "$c" --levels "$l" $lim -o "$TMP/ours.obj"
        else
          "$BIN" subdivide "$4" --tags "$5" --scheme "$2" --boundary "$b" --creasing "$c" --levels "$l" $lim -o "$TMP/ours.obj"
        fi
        "$TMP/osd_sharp" "$3" "$b" "$c" "$l" "$4" "$5" "$TMP/osd.obj" $lim
        r=$(python3 benches/opensubdiv/compare_meshes.py "$TMP/osd.obj" "$TMP/ours.obj")
        echo "$1 $b $c level $l${lim:+ limit}: $r"
        case "$r" in
          *"one-to-one yes; faces equal yes; max distance "*) ;;
          *) fail=1 ;;
        esac
        d=$(echo "$r" | sed 's/.*max distance \([^ ]*\) .*/\1/')
        if python3 -c "import sys; sys.exit(0 if float('$d') <= 1e-12 else 1)"; then :; else fail=1; fi
       done
        l=$((l + 1))
      done
    done
  done
}
run grid_quads catmull-clark catmark "$D/grid_quads.obj" -
run grid_quads+tags catmull-clark catmark "$D/grid_quads_untagged.obj" "$D/grid_quads.tags"
run grid_tris loop loop "$D/grid_tris.obj" -
if [ "$fail" -ne 0 ]; then echo "DISAGREEMENT"; exit 1; fi
echo "all cases agree to 1e-12"
