#!/bin/sh
# A scheme file's sweep against the built-in scheme it restates: the same spec
# (valences 3..120, uniform, 6 eigenvalues and the curvature verdict), one
# thread, best of REPEAT runs (default 3) each, side by side.
# Usage: benches/scheme_file_sweep.sh [BIN]   (default target/release/subdiv-lab)
set -eu
BIN=${1:-target/release/subdiv-lab}
REPEAT=${REPEAT:-3}
DIR=$(mktemp -d)
trap 'rm -rf "$DIR"' EXIT
for s in catmull-clark loop; do
    printf 'name = "bench-%s"\nscheme = "%s"\nvalences = { from = 3, to = 120 }\n[space]\nkind = "uniform"\n[sampler]\nkind = "grid"\npoints_per_axis = 1\n[columns]\neigenvalues = 6\ncurvature = true\n' "$s" "$s" >"$DIR/$s.toml"
    for mode in builtin file; do
        best=""
        i=0
        while [ "$i" -lt "$REPEAT" ]; do
            rm -f "$DIR/out.csv"
            if [ "$mode" = builtin ]; then
                set -- "$DIR/$s.toml"
            else
                set -- "$DIR/$s.toml" --scheme-file "analysis/schemes/$s.toml"
            fi
            t0=$(date +%s.%N)
            "$BIN" sweep "$@" --threads 1 --quiet --force --out "$DIR/out.csv" >/dev/null
            t1=$(date +%s.%N)
            t=$(echo "$t1 - $t0" | bc)
            if [ -z "$best" ] || [ "$(echo "$t < $best" | bc)" = 1 ]; then best=$t; fi
            i=$((i + 1))
        done
        echo "$s $mode best of $REPEAT: $best s"
    done
done
