#!/usr/bin/env bash
# Sweep rate by output format: configurations per CPU-second
# (user + sys) of `subdiv-lab sweep` at n = 3, 5, 8, 16 (nurds, edge ratios in
# [0.01, 0.99], Halton points, default columns), on one thread, for
#   * classification only: `[columns] gap = false, contraction = false`, CSV
#     to /dev/null (the evaluation with the least output);
#   * csv: default columns, CSV to /dev/null (evaluation + CSV text);
#   * csv file: the same written to a file (--out);
#   * parquet: the same written as a Parquet dataset (--out NAME.parquet).
# Best of RUNS (default 3). BIN=path picks the binary (default: this checkout's
# release build). Prints a Markdown table and the load average.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BIN="${BIN:-$ROOT/target/release/subdiv-lab}"
RUNS="${RUNS:-3}"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT

spec() { # n count extra-columns
  cat > "$TMP/s.toml" <<SPEC
name = "rate"
scheme = "nurds"
valences = [$1]
[space]
kind = "ratios"
ratio_range = [0.01, 0.99]
[sampler]
kind = "halton"
count = $2
$3
SPEC
}

cpu() { # best user+sys over RUNS of the command
  local best=""
  for _ in $(seq "$RUNS"); do
    rm -rf "$TMP"/out.* "$TMP"/.out.*
    /usr/bin/time -f "%U %S" -o "$TMP/time" "$@" >/dev/null 2>"$TMP/err" || { cat "$TMP/err" >&2; exit 1; }
    read -r u s < "$TMP/time"
    c=$(awk "BEGIN { print $u + $s }")
    if [ -z "$best" ] || awk "BEGIN { exit !($c < $best) }"; then best=$c; fi
  done
  echo "$best"
}

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| n | rows | classification only | csv (stdout) | csv file | parquet file | parquet / csv | parquet / classification only |"
echo "|---|---|---|---|---|---|---|---|"
for nc in "3 400000" "5 200000" "8 100000" "16 40000"; do
  read -r n count <<< "$nc"
  spec "$n" "$count" $'[columns]\ngap = false\ncontraction = false'
  c0=$(cpu "$BIN" sweep "$TMP/s.toml" --threads 1 --quiet)
  spec "$n" "$count" ""
  c1=$(cpu "$BIN" sweep "$TMP/s.toml" --threads 1 --quiet)
  c2=$(cpu "$BIN" sweep "$TMP/s.toml" --threads 1 --quiet --out "$TMP/out.csv")
  c3=$(cpu "$BIN" sweep "$TMP/s.toml" --threads 1 --quiet --out "$TMP/out.parquet" --format parquet)
  awk -v n="$n" -v r="$count" -v a="$c0" -v b="$c1" -v c="$c2" -v d="$c3" 'BEGIN {
    printf "| %d | %d | %.0fk/s | %.0fk/s | %.0fk/s | %.0fk/s | %.2f | %.2f |\n", n, r, r/a/1e3, r/b/1e3, r/c/1e3, r/d/1e3, d/c, d/a }'
done
echo
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
