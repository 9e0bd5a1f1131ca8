#!/usr/bin/env bash
# The targets of `subdiv-lab verify` (math doc section 15), with the
# numbers a shared machine needs: wall time, CPU time (user + sys) and the
# load average before and after each run.
#
#   benches/verify_targets.sh [BIN] [NAME..]     NAME among n3 n4 n5 n6 n7 n8 (default: n3 n4 n5)
#
# VERIFY_MAX_CELLS is passed as --max-cells (default: 8000000 for n5, 1.15 GB; 16000000 for n4, whose
# spec bisects to min_width 0.005 and needs 7.3M cells and 2.7 GB; 4000000,
# the CLI's default, for the others). Run it under `nice -n 19` on a shared machine and quote the CPU
# time: the specs' time_budget is wall time, so a starved run stops early.
# BIN defaults to target/release/subdiv-lab (build it first with
# `cargo build --release`). Output directories go to a fresh temporary
# directory; each run prints the CLI's summary line, then one line of
# timing: `wall S  cpu S (user U + sys Y)  load BEFORE -> AFTER`.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bin="${1:-$here/../target/release/subdiv-lab}"
shift || true
names=("$@")
[ ${#names[@]} -eq 0 ] && names=(n3 n4 n5)
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
for name in "${names[@]}"; do
    spec="$here/specs/verify-$name.toml"
    [ -f "$spec" ] || { echo "unknown target $name" >&2; exit 2; }
    before="$(cut -d' ' -f1-3 /proc/loadavg)"
    /usr/bin/time -f '%e %U %S' -o "$tmp/time" \
        "$bin" verify "$spec" --out "$tmp/$name" --threads 2 --force \
        --max-cells "${VERIFY_MAX_CELLS:-$(case "$name" in n4) echo 16000000 ;; n5) echo 8000000 ;; *) echo 4000000 ;; esac)}"
    after="$(cut -d' ' -f1-3 /proc/loadavg)"
    read -r wall user sys < "$tmp/time"
    cpu="$(echo "$user + $sys" | bc)"
    echo "$name: wall ${wall} s  cpu ${cpu} s (user ${user} + sys ${sys})  load ${before} -> ${after}"
    grep -E '"(cells|evaluated|undecided_fraction|deepest_level|stopped)"' "$tmp/$name/summary.json" | tr -d ' \n'
    echo
done
