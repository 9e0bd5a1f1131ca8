#!/bin/sh
# Reproducible random rational knot intervals for the exact-path timings
# (README "Exact certificates" table, benches/exact.rs uses the same generator).
#
#   benches/exact_knots.sh N [SEED]
#
# prints "p0:q0,p1:q1,..." with n = N pairs; every p_i, q_i is a/b with
# a, b uniform in 1..12 drawn from a 32-bit linear congruential generator
# (Numerical Recipes constants) seeded with SEED (default 1). Use as
#   B analyze --exact --knots "$(benches/exact_knots.sh 64)"
n=${1:?usage: exact_knots.sh N [SEED]}
seed=${2:-1}
awk -v n="$n" -v seed="$seed" 'BEGIN {
  x = seed % 4294967296
  for (i = 0; i < n; i++) {
    for (k = 0; k < 4; k++) {
      x = (1664525 * x + 1013904223) % 4294967296
      v[k] = 1 + int(x / 4294967296 * 12)
    }
    printf "%s%d/%d:%d/%d", (i ? "," : ""), v[0], v[1], v[2], v[3]
  }
  printf "\n"
}'
