#!/usr/bin/env bash
# Resume re-check speed: the time `subdiv-lab sweep SPEC --out F --resume`
# takes to re-verify a complete 1M-row CSV (every row in full, 32
# re-evaluated, nothing left to compute), for this checkout and optionally
# for another revision.
#
#   benches/resume_check.sh [OLD_REV]
#
# OLD_REV (a commit) is built in a temporary worktree with its own target
# directory (target-old/ beside target/: several minutes on a busy machine)
# and measured beside this checkout; OLD_BIN=/path/to/subdiv-lab gives that
# binary instead, NEW_BIN likewise for this checkout. Without either only
# this checkout is measured.
#
# Spec: scheme nurds, valence 3, edge ratios in [0.01, 0.99], Halton points,
# 1 000 000 configurations, default columns. Each binary writes its own CSV
# once (its own format, so that its resume accepts it), then RUNS (default 5)
# `--resume` runs that find every row present; the script prints the best
# wall time and the user+sys CPU time of each, the ratio, and the load
# average before and after (the wall times are only meaningful on an idle
# machine).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
OLD_REV="${1:-}"
RUNS="${RUNS:-5}"
TMP="$(mktemp -d)"
cleanup() {
  rm -rf "$TMP"
  if [ -n "${OLD_TREE:-}" ]; then git -C "$ROOT" worktree remove --force "$OLD_TREE" >/dev/null 2>&1 || true; fi
}
trap cleanup EXIT

if [ -z "${NEW_BIN:-}" ]; then
  (cd "$ROOT" && cargo build --release --quiet --bin subdiv-lab)
  NEW_BIN="$ROOT/target/release/subdiv-lab"
fi
if [ -z "${OLD_BIN:-}" ] && [ -n "$OLD_REV" ]; then
  OLD_TREE="$TMP/old-tree"
  git -C "$ROOT" worktree add --detach "$OLD_TREE" "$OLD_REV" >/dev/null
  (cd "$OLD_TREE" && CARGO_TARGET_DIR="$ROOT/target-old" cargo build --release --quiet --bin subdiv-lab)
  cp "$ROOT/target-old/release/subdiv-lab" "$TMP/old-bin"
  OLD_BIN="$TMP/old-bin"
fi

cat > "$TMP/spec.toml" <<SPEC
name = "resume-check"
scheme = "nurds"
valences = [3]

[space]
kind = "ratios"
ratio_range = [0.01, 0.99]

[sampler]
kind = "halton"
count = 1000000
SPEC

# best wall and its CPU (user + sys) over $RUNS resume runs: "wall cpu"
best() {
  local bin="$1" csv="$2" best_wall="" best_cpu=""
  for _ in $(seq "$RUNS"); do
    /usr/bin/time -f "%e %U %S" -o "$TMP/time" "$bin" sweep "$TMP/spec.toml" --out "$csv" --resume >/dev/null 2>"$TMP/log" \
      || { cat "$TMP/log" >&2; exit 1; }
    read -r wall user sys < "$TMP/time"
    cpu=$(awk "BEGIN { print $user + $sys }")
    if [ -z "$best_wall" ] || awk "BEGIN { exit !($wall < $best_wall) }"; then best_wall=$wall; best_cpu=$cpu; fi
  done
  echo "$best_wall $best_cpu"
}

if [ -n "${OLD_BIN:-}" ]; then "$OLD_BIN" sweep "$TMP/spec.toml" --out "$TMP/old.csv" >/dev/null 2>&1; fi
"$NEW_BIN" sweep "$TMP/spec.toml" --out "$TMP/new.csv" --quiet
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
if [ -n "${OLD_BIN:-}" ]; then read -r old_wall old_cpu <<< "$(best "$OLD_BIN" "$TMP/old.csv")"; fi
read -r new_wall new_cpu <<< "$(best "$NEW_BIN" "$TMP/new.csv")"
echo "load average after:  $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| build | best wall of $RUNS (s) | its CPU user+sys (s) |"
echo "|---|---|---|"
if [ -n "${OLD_BIN:-}" ]; then echo "| ${OLD_REV:-$OLD_BIN} | $old_wall | $old_cpu |"; fi
echo "| this checkout | $new_wall | $new_cpu |"
if [ -n "${OLD_BIN:-}" ]; then
  echo
  awk "BEGIN { printf \"speed-up: %.2fx wall, %.2fx CPU\n\", $old_wall / $new_wall, $old_cpu / $new_cpu }"
fi
