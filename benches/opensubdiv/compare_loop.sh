#!/bin/sh
# Compare subdiv-lab's Loop subdivision (library functions
# `subdiv-lab subdivide --scheme loop [--limit]`) with OpenSubdiv 3.5's Loop scheme (Debian packages
# libosd-dev, opensubdiv-tools; harness benches/opensubdiv/osd_loop.cpp) on the
# shipped triangle meshes. Not part of the crate's build or CI. Run from the
# repository root:
#   sh benches/opensubdiv/compare_loop.sh [LEVELS]
#
# For every mesh and every level 1..LEVELS (default 3): the refined meshes
# (OpenSubdiv PrimvarRefinerReal<double>::Interpolate vs our refine), and the
# limit positions of the vertices of the refined mesh at levels 0..LEVELS
# (OpenSubdiv PrimvarRefinerReal<double>::Limit vs our closed-form stencil).
# benches/opensubdiv/compare_meshes.py matches the vertices by position (the
# numberings differ), checks that the matching is one-to-one and that the
# triangles agree as oriented cycles, and prints the largest distance.
#
# What is compared to what: both sides use Loop's original weights at every
# valence (OpenSubdiv's sdc/loopScheme.h: beta_n = (5/8 - (3/8 + cos(2 pi /
# n) / 4)^2) / n, 1/16 hard-coded at n = 6; edge 3/8, 3/8, 1/8, 1/8; limit
# chi_n = 1 / (n + 3 / (8 beta_n)), 1/12 and 1/2 at n = 6). Closed meshes
# without creases only: OpenSubdiv's boundary and crease rules are never
# reached (we refuse meshes with boundary).
#
# Result on this machine (2 cores shared, Debian 12, OpenSubdiv 3.5.0-2,
# LEVELS=3): counts, one-to-one vertex matching and oriented triangles equal on
# all five meshes at every level. Largest distance, refined vertices at levels
# 1..3 / limit positions at levels 0..3:
#   tetrahedron      0 / 4.8e-17     icosahedron      4.6e-16 / 4.4e-16
#   bipyramid_3_12   2.5e-16 / 2.5e-16   octahedron   0 / 0
#   torus_irregular  9.2e-16 / 9.2e-16 (relative to the coordinates 3.7e-16)
# i.e. agreement to a few units in the last place (target 1e-12).
set -eu
LEVELS=${1:-3}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
g++ -O2 -std=c++14 -o "$TMP/osd_loop" benches/opensubdiv/osd_loop.cpp -losdCPU
cargo build --release -q --bin subdiv-lab
# ours MESH LEVELS OUT [FLAGS...]: `subdiv-lab subdivide --scheme loop`
ours() { ./target/release/subdiv-lab subdivide "$1" --scheme loop --levels "$2" -o "$3" "${@:4}"; }
CMP="python3 benches/opensubdiv/compare_meshes.py"
printf '%-22s %-7s %s\n' "mesh" "what" "OpenSubdiv vs ours"
for m in analysis/meshes/tetrahedron.obj analysis/meshes/icosahedron.obj analysis/meshes/triangles/*.obj; do
  name=$(basename "$m" .obj)
  for l in $(seq 0 "$LEVELS"); do
    if [ "$l" -gt 0 ]; then
      ours "$m" "$l" "$TMP/ours.obj"
      "$TMP/osd_loop" "$m" "$l" "$TMP/osd.obj" >/dev/null
      printf '%-22s %-7s %s\n' "$name" "L$l" "$($CMP "$TMP/osd.obj" "$TMP/ours.obj")"
    fi
    ours "$m" "$l" "$TMP/ours_limit.obj" --limit
    "$TMP/osd_loop" "$m" "$l" "$TMP/osd_limit.obj" --limit >/dev/null
    printf '%-22s %-7s %s\n' "$name" "limit$l" "$($CMP "$TMP/osd_limit.obj" "$TMP/ours_limit.obj")"
  done
done
