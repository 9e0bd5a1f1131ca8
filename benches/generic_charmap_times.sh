#!/usr/bin/env bash
# The generic C1 certificate per valence (math doc sections 20.7 and 20.9):
# `analyze --scheme S --valence n --charmap generic --json` for the modified
# butterfly, the butterfly and sqrt(3) at n = 3..16; prints one table row per
# valence with each scheme's verdict code, the deepest level, wall time and
# CPU time (user + sys) of the whole process.
#
#   benches/generic_charmap_times.sh [BIN] [NMIN] [NMAX]
#
# BIN defaults to target/release/subdiv-lab (`cargo build --release` first).
# One process at a time (the certificate is single-threaded); run it under
# `nice` on a shared machine and quote the CPU time.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
bin="${1:-$here/../target/release/subdiv-lab}"
nmin="${2:-3}"
nmax="${3:-16}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
schemes=(modified-butterfly butterfly sqrt3)

printf '| n |'
for s in "${schemes[@]}"; do printf ' %s | wall (s) | CPU (s) |' "$s"; done
printf '\n|---|'
for _ in "${schemes[@]}"; do printf -- '---|---|---|'; done
printf '\n'
for n in $(seq "$nmin" "$nmax"); do
    printf '| %s |' "$n"
    for s in "${schemes[@]}"; do
        /usr/bin/time -f '%e %U %S' -o "$tmp/time" \
            "$bin" analyze --scheme "$s" --valence "$n" --charmap generic --json >"$tmp/out.json"
        read -r wall user sys <"$tmp/time"
        verdict="$(python3 -c '
import json, sys
c = json.load(open(sys.argv[1]))["charmap"]
level = c.get("level")
print(c["verdict_code"] + ("" if level is None else " (level %d)" % level))
' "$tmp/out.json")"
        cpu="$(python3 -c "print(f'{$user + $sys:.2f}')")"
        printf ' %s | %s | %s |' "$verdict" "$wall" "$cpu"
    done
    printf '\n'
done
