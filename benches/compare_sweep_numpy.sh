#!/usr/bin/env bash
# Side-by-side throughput: subdiv-lab sweep vs the vectorised numpy reference
# (shared/bench/numpy_reference.py), same valence, same number of random
# configurations (edge ratios uniform in [0.01, 0.99]), in one run.
#
#   benches/compare_sweep_numpy.sh [COUNT_SMALL] [COUNT_64]
#
# For each n in 3 5 8 16 64 it runs
#   * numpy (OPENBLAS/OMP/MKL threads forced to 1 by the script it runs),
#   * `subdiv-lab sweep` with --threads 1 and --threads 2 on a generated spec
#     (scheme nurds, space ratios [0.01, 0.99], sampler random, default columns:
#     class, lambda1, lambda2, |lambda3|, gap, modulus ratio, angle, contraction
#     rate), writing the full CSV to a temporary file,
# and prints a markdown table: configurations per second, the speed-up per core
# (sweep 1 thread / numpy) and the thread scaling (2 threads / 1 thread).
# Our numbers include enumeration, CSV formatting and writing; numpy's do not
# include any output.
#
# Needs python3 with numpy (installed with `pip install --user numpy` if
# missing). The reference script is looked up at $NUMPY_REFERENCE, then
# ../shared/bench/numpy_reference.py from the repository root and its parents.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
SMALL="${1:-20000}"
BIG="${2:-2000}"

REF="${NUMPY_REFERENCE:-}"
if [ -z "$REF" ]; then
  d="$ROOT"
  while [ "$d" != "/" ]; do
    if [ -f "$d/../shared/bench/numpy_reference.py" ]; then REF="$d/../shared/bench/numpy_reference.py"; break; fi
    d="$(dirname "$d")"
  done
fi
[ -n "$REF" ] && [ -f "$REF" ] || { echo "numpy_reference.py not found; set NUMPY_REFERENCE" >&2; exit 1; }
python3 -c 'import numpy' 2>/dev/null || python3 -m pip install --user numpy >&2

(cd "$ROOT" && cargo build --release --quiet)
BIN="$ROOT/target/release/subdiv-lab"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo
echo "| n | configs | numpy configs/s | sweep 1 thread configs/s | speed-up per core | sweep 2 threads configs/s | 2-thread scaling |"
echo "|---|---|---|---|---|---|---|"
for n in 3 5 8 16 64; do
  count="$SMALL"; [ "$n" -ge 64 ] && count="$BIG"
  np=$(python3 "$REF" --valence "$n" --count "$count" | sed -n 's/.*configs_per_s=\([0-9.]*\).*/\1/p')
  cat > "$TMP/spec.toml" <<SPEC
name = "compare-n$n"
scheme = "nurds"
valences = [$n]
[space]
kind = "ratios"
ratio_range = [0.01, 0.99]
[sampler]
kind = "random"
count = $count
seed = 1
SPEC
  rate() {
    rm -f "$TMP/out.csv" "$TMP/out.summary.json"
    "$BIN" sweep "$TMP/spec.toml" --out "$TMP/out.csv" --threads "$1" 2>&1 >/dev/null \
      | sed -n 's/.* \([0-9]*\) configurations\/s.*/\1/p'
  }
  one=$(rate 1)
  two=$(rate 2)
  up=$(python3 -c "print(f'{$one / $np:.1f}x')")
  sc=$(python3 -c "print(f'{$two / $one:.2f}x')")
  echo "| $n | $count | $np | $one | $up | $two | $sc |"
done
