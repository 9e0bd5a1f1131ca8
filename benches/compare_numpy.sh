#!/usr/bin/env bash
# Side-by-side throughput: subdiv-lab vs the two numpy baselines.
#
#   benches/compare_numpy.sh [COUNT] [VALENCES...]
#
# For each valence n it runs, in one go and on one thread each,
#   * $NUMPY_REF --valence n --count COUNT
#     (numpy: build the 4n x 4n S_n for random ratios in [0.01, 0.99),
#      LAPACK eigvals, sort, classify; OPENBLAS/MKL/OMP threads = 1),
#   * $NUMPY_FACE --valence n --count COUNT
#     (what an expert writes: the n x n face block only, batched LAPACK),
#   * our structured path  (cargo bench --bench throughput -- --path structured),
#   * our full path        (cargo bench --bench throughput -- --path full:
#      assemble S_n, faer eigenvalues of the 4n x 4n matrix, numpy's classifier),
# each REPEAT times (default 3; the best run is kept, which filters out noise
# from other processes), and prints a table of configurations per second and
# the speed-up of the structured path over each baseline, and of the full path
# over the reference. Needs python3 with numpy (`pip install numpy`).
# The numpy baselines are benches/baselines/numpy_reference.py (the full
# 4n x 4n S_n for random ratios, numpy.linalg.eigvals, the subdominant pair
# classified; prints `configs_per_s=R`) and benches/baselines/numpy_faceblock.py
# (the same from the n x n face block; prints `n count seconds R fraction`).
# Environment: REPEAT (runs per cell, best kept), NUMPY_REF and NUMPY_FACE
# (other baseline scripts; relative paths from the repository root), THROUGHPUT_BIN
# (use this throughput binary, no build).
set -euo pipefail
cd "$(dirname "$0")/.."
COUNT=${1:-4000}
shift || true
VALENCES=${*:-3 5 8 16 32 64}
REPEAT=${REPEAT:-3}
NUMPY_REF=${NUMPY_REF:-benches/baselines/numpy_reference.py}
NUMPY_FACE=${NUMPY_FACE:-$(dirname "$NUMPY_REF")/numpy_faceblock.py}
python3 -c 'import numpy' 2>/dev/null || { echo "numpy missing: pip install numpy" >&2; exit 1; }
[ -f "$NUMPY_REF" ] || { echo "missing $NUMPY_REF" >&2; exit 1; }
[ -f "$NUMPY_FACE" ] || { echo "missing $NUMPY_FACE" >&2; exit 1; }
# THROUGHPUT_BIN runs a saved throughput binary instead of building one (e.g.
# the binary of another commit, for a comparison under equal load).
if [ -n "${THROUGHPUT_BIN:-}" ]; then
  BIN=$THROUGHPUT_BIN
else
  cargo build --release --bench throughput >/dev/null 2>&1
  BIN=$(ls -t target/release/deps/throughput-* | grep -v '\.d$' | head -1)
fi

# The reference baseline and our binary print `configs_per_s=R`; the
# face-block baseline prints `n count seconds R fraction`.
rate() { sed -n -e 's/.*configs_per_s=\([0-9]*\).*/\1/p' \
  -e 's/^[0-9][0-9]* [0-9][0-9]* [0-9.]* \([0-9][0-9]*\) [0-9.]*$/\1/p'; }
best() { # best of REPEAT runs of the command given as arguments
  local b=0 r
  for _ in $(seq "$REPEAT"); do
    r=$("$@" | rate)
    [ "$r" -gt "$b" ] && b=$r
  done
  echo "$b"
}

printf '%-8s %8s %12s %13s %14s %9s %9s %12s %9s\n' valence count numpy_cfg/s faceblock/s structured/s vs_numpy vs_face full_cfg/s vs_numpy
for n in $VALENCES; do
  c=$COUNT
  # Large valences are slow in numpy (4n = 256): scale the count down.
  if [ "$n" -ge 32 ]; then c=$(( COUNT / 10 > 50 ? COUNT / 10 : 50 )); fi
  np=$(best python3 "$NUMPY_REF" --valence "$n" --count "$c")
  fb=$(best python3 "$NUMPY_FACE" --valence "$n" --count "$c")
  st=$(best "$BIN" --valence "$n" --count "$c" --path structured)
  fu=$(best "$BIN" --valence "$n" --count "$c" --path full)
  printf '%-8s %8s %12s %13s %14s %8.1fx %8.1fx %12s %8.1fx\n' "$n" "$c" "$np" "$fb" "$st" \
    "$(echo "$st / $np" | bc -l)" "$(echo "$st / $fb" | bc -l)" "$fu" "$(echo "$fu / $np" | bc -l)"
done
echo "machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"
