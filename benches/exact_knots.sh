#!/bin/sh
# Reproducible random knot intervals for the exact-path timings (README
# "Exact certificates" table; benches/exact.rs uses the same generator).
#
#   benches/exact_knots.sh N [SEED] [KIND]
#
# prints "p0:q0,p1:q1,..." with n = N pairs, drawn from a 32-bit linear
# congruential generator (Numerical Recipes constants) seeded with SEED
# (default 1). KIND is
#   rational (default): every p_i, q_i is a/b with a, b uniform in 1..12;
#   f64: every p_i, q_i is 10^u with u uniform in [-2, 2], printed with 17
#        significant digits (what a sweep over sampled floating-point knots
#        feeds the exact path: 53-bit mantissas, much longer rationals).
# Use as
#   B analyze --exact --knots "$(benches/exact_knots.sh 64)"
n=${1:?usage: exact_knots.sh N [SEED] [rational|f64]}
seed=${2:-1}
kind=${3:-rational}
case "$kind" in
  rational|f64) ;;
  *) echo "exact_knots.sh: KIND must be rational or f64, got $kind" >&2; exit 2 ;;
esac
awk -v n="$n" -v seed="$seed" -v kind="$kind" 'BEGIN {
  x = seed % 4294967296
  for (i = 0; i < n; i++) {
    for (k = 0; k < 4; k++) {
      x = (1664525 * x + 1013904223) % 4294967296
      u[k] = x / 4294967296
      v[k] = 1 + int(u[k] * 12)
    }
    if (kind == "f64")
      printf "%s%.17g:%.17g", (i ? "," : ""), 10 ^ (4 * u[0] - 2), 10 ^ (4 * u[1] - 2)
    else
      printf "%s%d/%d:%d/%d", (i ? "," : ""), v[0], v[1], v[2], v[3]
  }
  printf "\n"
}'
