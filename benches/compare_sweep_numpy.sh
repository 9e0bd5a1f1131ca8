#!/usr/bin/env bash
# Side-by-side throughput: subdiv-lab sweep vs a vectorised numpy reference,
# same valence, same number of random configurations (edge ratios uniform in
# [0.01, 0.99]), in one run.
#
#   benches/compare_sweep_numpy.sh [SCALE]
#
# SCALE (default 1) multiplies the configuration counts: 200000 (n = 3, 5),
# 100000 (n = 8), 40000 (n = 16), 2000 (n = 64) -- large enough that the 10 ms
# resolution of the CPU-time measurement does not matter.
#
# For each n in 3 5 8 16 64 it runs
#   * numpy (OPENBLAS/OMP/MKL threads forced to 1 by the script it runs),
#   * `subdiv-lab sweep` with --threads 1 and --threads 2 on a generated spec
#     (scheme nurds, space ratios [0.01, 0.99], sampler random, default columns:
#     class, lambda1, lambda2, |lambda3|, gap, ratio / rho / theta, contraction
#     rate), writing the full CSV to a temporary file,
#   * `subdiv-lab sweep` with --threads 1 on the same spec with only the
#     classification columns (`gap = false`, `contraction = false`: class,
#     lambda1, lambda2, |lambda3|, numpy's content),
# and prints a markdown table: wall-clock configurations per second, the same per
# CPU-second (user + sys time of the process, numpy's interpreter start-up
# subtracted), the speed-up per core (CPU rates) for both column sets, and the
# thread scaling (2 threads / 1 thread wall rate, and CPU time 1 thread /
# 2 threads: 1.0 = no parallel overhead).
# Our numbers include enumeration, CSV formatting (shortest round-trip digits
# of every coordinate and result) and writing; numpy's do not include any
# output.
#
# SWEEP_BIN=/path/to/subdiv-lab runs that binary instead of building this
# checkout (comparisons between builds).
#
# Needs python3 with numpy (installed with `pip install --user numpy` if
# missing). The numpy reference is benches/baselines/numpy_reference.py (the
# full 4n x 4n S_n for random ratios, numpy.linalg.eigvals, the subdominant
# pair classified; prints `configs_per_s=R`); NUMPY_REFERENCE names another.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
SCALE="${1:-1}"

REF="${NUMPY_REFERENCE:-$ROOT/benches/baselines/numpy_reference.py}"
[ -n "$REF" ] && [ -f "$REF" ] || { echo "numpy reference script not found; check NUMPY_REFERENCE (see the header)" >&2; exit 1; }
python3 -c 'import numpy' 2>/dev/null || python3 -m pip install --user numpy >&2

if [ -n "${SWEEP_BIN:-}" ]; then
  BIN="$SWEEP_BIN"   # e.g. another build, for a comparison
else
  (cd "$ROOT" && cargo build --release --quiet)
  BIN="$ROOT/target/release/subdiv-lab"
fi
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT

# CPU seconds (user + sys) of a command; its stdout+stderr go to "$TMP/log".
cpu() {
  /usr/bin/time -f "%U %S" -o "$TMP/time" "$@" > "$TMP/log" 2>&1
  awk '{print $1 + $2}' "$TMP/time"
}
numpy_startup=$(cpu python3 -c 'import numpy')

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), load average $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "Wall-clock rates depend on what else runs on the machine; the CPU-time rates"
echo "(configurations per CPU-second of the process, numpy's interpreter start-up"
echo "subtracted) measure the per-core cost even on a busy machine."
echo
echo "| n | configs | numpy configs/s (wall) | sweep 1 thread (wall) | numpy configs/CPU-s | sweep configs/CPU-s | speed-up per core (CPU) | classification columns only: configs/CPU-s | speed-up | sweep 2 threads (wall) | 2-thread wall scaling | CPU-s 1 thread / 2 threads |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for n in 3 5 8 16 64; do
  case "$n" in 3|5) base=200000;; 8) base=100000;; 16) base=40000;; *) base=2000;; esac
  count=$(python3 -c "print(max(1, int($base * $SCALE)))")
  np_cpu=$(cpu python3 "$REF" --valence "$n" --count "$count")
  np=$(sed -n 's/.*configs_per_s=\([0-9.]*\).*/\1/p' "$TMP/log")
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
  run_sweep() {
    rm -f "$TMP/out.csv" "$TMP/out.summary.json"
    c=$(cpu "$BIN" sweep "$TMP/spec.toml" --out "$TMP/out.csv" --threads "$1")
    r=$(sed -n 's/.* \([0-9]*\) configurations\/s.*/\1/p' "$TMP/log")
    echo "$r $c"
  }
  read -r one one_cpu <<< "$(run_sweep 1)"
  read -r two two_cpu <<< "$(run_sweep 2)"
  printf '[columns]\ngap = false\ncontraction = false\n' >> "$TMP/spec.toml"
  read -r _ cls_cpu <<< "$(run_sweep 1)"
  python3 - "$n" "$count" "$np" "$np_cpu" "$numpy_startup" "$one" "$one_cpu" "$two" "$two_cpu" "$cls_cpu" <<'PY'
import sys
n, count, np_wall, np_cpu, np_start, one, one_cpu, two, two_cpu, cls_cpu = sys.argv[1:]
count = int(count)
np_rate_cpu = count / max(float(np_cpu) - float(np_start), 1e-9)
sw_rate_cpu = count / max(float(one_cpu), 1e-9)
cls_rate_cpu = count / max(float(cls_cpu), 1e-9)
print(f"| {n} | {count} | {float(np_wall):.0f} | {float(one):.0f} | {np_rate_cpu:.0f} | {sw_rate_cpu:.0f} | "
      f"{sw_rate_cpu / np_rate_cpu:.1f}x | {cls_rate_cpu:.0f} | {cls_rate_cpu / np_rate_cpu:.1f}x | "
      f"{float(two):.0f} | {float(two) / float(one):.2f}x | "
      f"{float(one_cpu) / max(float(two_cpu), 1e-9):.2f} |")
PY
done
echo
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
