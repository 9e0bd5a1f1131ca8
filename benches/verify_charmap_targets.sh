#!/usr/bin/env bash
# The `charmap` property over cells (math doc section 15, "The
# characteristic map over a cell"): the numbers of BENCHMARKS.md,
# with wall time, CPU time (user + sys) and the load average around each run.
#
#   benches/verify_charmap_targets.sh [BIN] [NAME..]    NAME: cc (n = 3..16), n3, n4, n5
#                                                        (default: cc n3)
#
# cc: the adjustable Catmull-Clark scheme over c in [0.001, 1] for n = 3..16
#     (benches/specs/verify-cc.toml with the valence substituted); prints per n
#     the fraction of the c range certified for charmap, the lowest certified c,
#     cells, wall and CPU time.
# n3: NURDS n = 3 over [0.01, 0.99]^3, class + separation + charmap
#     (benches/specs/verify-charmap-n3.toml).
# n4, n5: NURDS n = 4, 5 over [0.05, 0.95]^n with charmap
#     (benches/specs/verify-charmap-n4.toml, -n5.toml; capped by VERIFY_MAX_CELLS,
#     default 4000000, and the specs' time_budget).
# BIN defaults to target/release/subdiv-lab (`cargo build --release` first).
# Run it under `nice -n 19` on a shared machine and quote the CPU time.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bin="${1:-$here/../target/release/subdiv-lab}"
shift || true
names=("$@")
[ ${#names[@]} -eq 0 ] && names=(cc n3)
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# run NAME SPEC: one verify run with timing; leaves $tmp/NAME/summary.json
run() {
    local name="$1" spec="$2"
    before="$(cut -d' ' -f1-3 /proc/loadavg)"
    /usr/bin/time -f '%e %U %S' -o "$tmp/time" \
        "$bin" verify "$spec" --out "$tmp/$name" --threads 2 --force --quiet \
        --max-cells "${VERIFY_MAX_CELLS:-4000000}"
    after="$(cut -d' ' -f1-3 /proc/loadavg)"
    read -r wall user sys < "$tmp/time"
    cpu="$(echo "$user + $sys" | bc)"
    timing="wall ${wall} s  cpu ${cpu} s  load ${before} -> ${after}"
}

# fraction NAME PROPERTY STATUS: the volume fraction from summary.json
fraction() {
    python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print('%.4f' % (100*d['property_volume_fraction'][sys.argv[2]][sys.argv[3]]))" \
        "$tmp/$1/summary.json" "$2" "$3"
}

for name in "${names[@]}"; do
    case "$name" in
    cc)
        for n in $(seq 3 16); do
            sed "s/^valence = .*/valence = $n/" "$here/specs/verify-cc.toml" > "$tmp/cc$n.toml"
            run "cc$n" "$tmp/cc$n.toml"
            low="$(awk -F, 'NR > 1 && $NF == "certified" { if (m == "" || $1 + 0 < m + 0) m = $1 } END { print m }' "$tmp/cc$n/cells.csv")"
            cells="$(grep -o '"cells": [0-9]*' "$tmp/cc$n/summary.json" | grep -o '[0-9]*$')"
            echo "cc n=$n: charmap certified $(fraction "cc$n" charmap certified)% of [0.001, 1] (lowest certified c $low), standard $(fraction "cc$n" class certified)%, $cells cells, $timing"
        done
        ;;
    n3 | n4 | n5)
        run "$name" "$here/specs/verify-charmap-$name.toml"
        echo "$name: charmap certified $(fraction "$name" charmap certified)%, class $(fraction "$name" class certified)%, separation $(fraction "$name" separation certified)%, $timing"
        grep -E '"(cells|evaluated|deepest_level|stopped)"' "$tmp/$name/summary.json" | tr -d ' \n'
        echo
        ;;
    *)
        echo "unknown target $name" >&2
        exit 2
        ;;
    esac
done
