#!/usr/bin/env bash
# The Slurm array recipe of docs/guide/sweeps.md, run verbatim without Slurm:
# the `sweep.sbatch` block is taken from the guide as it is written, and each
# of its array tasks runs as a plain process (`srun` is a shim that runs its
# arguments; SLURM_ARRAY_TASK_ID, SLURM_ARRAY_TASK_COUNT and
# SLURM_CPUS_PER_TASK are set as Slurm sets them, the count and the CPUs from
# the #SBATCH lines). Then the guide's polars snippet reads the dataset
# without `merge`, the guide's `merge` line compacts it, and the compacted
# rows must equal an unsharded run's (same ids, same values, same labels).
#
#     benches/slurm_recipe.sh            # needs python3 with polars and pyarrow
#
# SUBDIV_LAB_BIN overrides the binary (default target/release/subdiv-lab);
# PYTHON the interpreter (default python3).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BIN="$(realpath "${SUBDIV_LAB_BIN:-$ROOT/target/release/subdiv-lab}")"
PY="${PYTHON:-python3}"
W="$(mktemp -d)"
trap 'rm -rf "$W"' EXIT
GUIDE="$ROOT/docs/guide/sweeps.md"

# The fenced block that starts with `#!/bin/bash` / `# sweep.sbatch`, and the
# python block after it, verbatim.
block() { awk -v want="$1" '
  /^```/ { if (inb) { if (hit) exit; inb = 0; buf = ""; next } inb = 1; buf = ""; next }
  inb { buf = buf $0 "\n"; if (index($0, want)) hit = 1 }
  END { printf "%s", hit ? buf : "" }' "$GUIDE"; }
block "# sweep.sbatch" > "$W/sweep.sbatch"
block "pl.scan_parquet" > "$W/lazy.py"
grep -m1 '^subdiv-lab merge ' "$GUIDE" > "$W/merge.sh"
[ -s "$W/sweep.sbatch" ] && [ -s "$W/lazy.py" ] && [ -s "$W/merge.sh" ] || { echo "recipe not found in $GUIDE"; exit 1; }

mkdir -p "$W/bin" "$W/run/analysis" "$W/run/out"
ln -s "$BIN" "$W/bin/subdiv-lab"
printf '#!/bin/sh\nexec "$@"\n' > "$W/bin/srun"
chmod +x "$W/bin/srun"
cp "$ROOT/analysis/sweep-random.toml" "$W/run/analysis/"
count=$(sed -n 's/^#SBATCH --array=0-\([0-9]*\).*/\1/p' "$W/sweep.sbatch")
count=$((count + 1))
cpus=$(sed -n 's/^#SBATCH --cpus-per-task=\([0-9]*\).*/\1/p' "$W/sweep.sbatch")
cd "$W/run"
export PATH="$W/bin:$PATH"
t0=$(date +%s)
for i in $(seq 0 $((count - 1))); do
  SLURM_ARRAY_TASK_ID=$i SLURM_ARRAY_TASK_COUNT=$count SLURM_CPUS_PER_TASK=$cpus \
    bash "$W/sweep.sbatch" > "out/sweep-$i.log" 2>&1 || { cat "out/sweep-$i.log"; exit 1; }
done
# A requeued task runs the same line again: it finds its shard complete.
SLURM_ARRAY_TASK_ID=0 SLURM_ARRAY_TASK_COUNT=$count SLURM_CPUS_PER_TASK=$cpus \
  bash "$W/sweep.sbatch" > out/requeued.log 2>&1
echo "$count array tasks in $(( $(date +%s) - t0 )) s; $(ls out/random.parquet | wc -l) part files, $(ls out/random.shard-*.summary.json | wc -l) summaries"
echo "the guide's polars snippet, without merge:"
"$PY" "$W/lazy.py"
bash "$W/merge.sh"
subdiv-lab sweep analysis/sweep-random.toml --out plain.parquet --quiet
"$PY" - <<'EOF'
import pyarrow.parquet as pq
import pyarrow.dataset as ds
merged = pq.read_table("random.parquet")
plain = ds.dataset("plain.parquet", format="parquet").to_table()
assert merged.num_rows == plain.num_rows == 280000, (merged.num_rows, plain.num_rows)
assert merged.column_names == plain.column_names
assert merged.equals(plain), "the compacted shards differ from the unsharded run"
print(f"merge: {merged.num_rows} rows, equal to the unsharded run (every column)")
EOF
