#!/bin/bash
# Crash safety of `sweep --resume`: for CSV and Parquet, on 1 and 2 threads,
# a sweep is killed with SIGKILL KILLS times at random moments (each restart
# with --resume), then resumed to the end; the output must equal an
# uninterrupted run's row for row (CSV: the same bytes; Parquet: every part
# file the same bytes), and the summary must be the same (its throughput
# aside).
#
#     benches/crash_resume.sh [KILLS] [COUNT]     # defaults: 20 kills, 400000 rows
#
# SUBDIV_LAB_BIN overrides the binary (default target/release/subdiv-lab).
set -euo pipefail
KILLS=${1:-20}
COUNT=${2:-400000}
BIN=${SUBDIV_LAB_BIN:-target/release/subdiv-lab}
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
cat > "$W/spec.toml" <<EOF
name = "crash"
scheme = "nurds"
valences = [3, 4]
[space]
kind = "ratios"
ratio_range = [0.01, 0.99]
[sampler]
kind = "halton"
count = $((COUNT / 2))
EOF
# The summary without its throughput.
strip() { python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); d.pop("throughput"); print(json.dumps(d, sort_keys=True))' "$1"; }
# Every part of a dataset, or the CSV, as one checksum per file.
digest() { if [ -d "$1" ]; then (cd "$1" && sha256sum part-*.parquet); else sha256sum < "$1"; fi; }
fail=0
for fmt in csv parquet; do
  for threads in 1 2; do
    ref="$W/ref-$threads.$fmt"
    "$BIN" sweep "$W/spec.toml" --out "$ref" --threads "$threads" --quiet
    t0=$(date +%s.%N)
    "$BIN" sweep "$W/spec.toml" --out "$W/time.$fmt" --threads "$threads" --quiet
    run=$(echo "$(date +%s.%N) - $t0" | bc)
    rm -rf "$W/time.$fmt" "$W/time.summary.json"
    out="$W/killed-$threads.$fmt"
    killed=0
    for k in $(seq 1 "$KILLS"); do
      "$BIN" sweep "$W/spec.toml" --out "$out" --threads "$threads" --resume --quiet &
      pid=$!
      # A random moment: uniform in (0.02 s, 1.5 T / KILLS), T an uninterrupted
      # run's time, so that the kills spread over the whole run (a restart
      # first re-checks the rows present: some kills land there).
      sleep "$(python3 -c "import random; print(random.uniform(0.02, max(0.05, 1.5 * $run / $KILLS)))")"
      if kill -9 "$pid" 2>/dev/null; then killed=$((killed + 1)); fi
      wait "$pid" 2>/dev/null || true
    done
    "$BIN" sweep "$W/spec.toml" --out "$out" --threads "$threads" --resume --quiet
    base="${out%.*}"
    if [ "$(digest "$out")" == "$(digest "$ref")" ] &&
       [ "$(strip "$base.summary.json")" == "$(strip "${ref%.*}.summary.json")" ]; then
      echo "$fmt, $threads threads: $killed of $KILLS runs killed mid-way, resumed: equal to the uninterrupted run"
    else
      echo "$fmt, $threads threads: DIFFERS from the uninterrupted run"
      fail=1
    fi
  done
done
exit $fail
