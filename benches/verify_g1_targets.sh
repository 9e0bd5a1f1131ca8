#!/usr/bin/env bash
# The class-free `g1` property of `verify` (math doc section 15, "G1 over a
# cell"): the numbers of BENCHMARKS.md ("Certified regions", g1 rows), with
# wall time and CPU time (user + sys) per run.
#
#   benches/verify_g1_targets.sh [BIN] [NAME..]
#
# NAME: n3 (n = 3 over [0.01, 0.99]^3), n4, n5 (over [0.05, 0.95]^n),
# n6, n7, n8 (over [0.05, 0.95]^n, a shorter budget), c3, c4, c5 (the
# corner-interval box p_i, q_i in [1, 100], log-scaled). Default: n3 n4 n5.
# BIN is the example binary (`cargo build --release --example verify_g1`
# first; default target/release/examples/verify_g1). Each run prints the
# certified g1 share, the cells, why refinement stopped and the witnesses
# found in the largest open cells. G1_BUDGET overrides the time budget
# (seconds of wall time of the branch and bound, default 570, so that a
# run with its witness search ends within 10 minutes). G1_SYMMETRY (none, rotations or
# dihedral; default none) runs the ratio boxes n3..n8 with that symmetry
# (math doc section 15, "Symmetry of the ratio box"; dihedral verifies the
# smallest box [1 - h, h]^n of floats containing the one named, and the
# share printed is a lower bound through the group); the corner boxes
# c3..c5 always run without. Run it under `nice` on a shared machine and
# quote the CPU time.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bin="${1:-$here/../target/release/examples/verify_g1}"
shift || true
names=("$@")
[ ${#names[@]} -eq 0 ] && names=(n3 n4 n5)
budget="${G1_BUDGET:-570}"
symmetry="${G1_SYMMETRY:-none}"
case "$symmetry" in
    none|rotations|dihedral) ;;
    *) echo "G1_SYMMETRY must be none, rotations or dihedral, got $symmetry" >&2; exit 2 ;;
esac
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
for name in "${names[@]}"; do
    case "$name" in
        n3) args=(3 0.01 0.99 0.004 "$budget" 200 "$symmetry") ;;
        n4) args=(4 0.05 0.95 0.005 "$budget" 200 "$symmetry") ;;
        n5) args=(5 0.05 0.95 0.01 "$budget" 200 "$symmetry") ;;
        n6) args=(6 0.05 0.95 0.02 "$budget" 200 "$symmetry") ;;
        n7) args=(7 0.05 0.95 0.02 "$budget" 200 "$symmetry") ;;
        n8) args=(8 0.05 0.95 0.02 "$budget" 200 "$symmetry") ;;
        c3) args=(3 1 100 0.004 "$budget" 200 corners) ;;
        c4) args=(4 1 100 0.005 "$budget" 200 corners) ;;
        c5) args=(5 1 100 0.01 "$budget" 200 corners) ;;
        *) echo "unknown target $name" >&2; exit 2 ;;
    esac
    /usr/bin/time -f '%e %U %S' -o "$tmp/time" "$bin" "${args[@]}"
    read -r wall user sys < "$tmp/time"
    echo "  $name: wall ${wall} s, cpu $(echo "$user + $sys" | bc) s"
done
