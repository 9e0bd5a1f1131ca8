#!/usr/bin/env python3
"""Side by side, in one run: `subdiv_lab.classify_batch` from Python, the CLI
sweep (`subdiv-lab sweep --threads 1`) and the two numpy baselines, at n = 3,
5, 8, 16, 64, random edge ratios uniform in [0.01, 0.99]:

* numpy_faceblock.py, the face-block peer (face block only, batched LAPACK,
  one BLAS thread): its run(n, count, seed);
* numpy_reference.py, the reference (the whole 4n x 4n S_n, batched LAPACK
  eigvals, sort, classify; one BLAS thread): the loop of its main() (batches
  of 4096, its build(r) and classify(eigenvalues)), on fewer configurations
  (the 256 x 256 matrices of n = 64 cost about 20 ms each).

The numpy baselines are in benches/baselines/; NUMPY_BASELINES (environment)
names another directory holding the two scripts.

    python3 benches/compare_python_numpy.py [SCALE]

Needs the package installed (`pip install ./python`) and a release binary
(`cargo build --release`; SUBDIV_LAB_BIN overrides). Rates are configurations
per CPU-second (user + sys of this process or of the child), so they measure
the per-core cost even on a busy machine:

* classify_batch: threads=1, default columns (class, lambda1, lambda2,
  |lambda3|, gap, ratio/rho/theta, contraction rate), and the classification
  columns only; the ratios are drawn before the clock starts;
* CLI sweep: the same default columns, one thread, writing its CSV;
* numpy: numpy_faceblock.run() and the numpy_reference loop in this process
  (their ratios drawn inside).

Each configuration is measured REPEAT times (environment, default 1), the
fastest run kept for each column; VALENCES (environment, e.g. "3 64") picks
some of the valences.
"""
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")
import numpy as np  # noqa: E402

import subdiv_lab as sl  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SCALE = float(sys.argv[1]) if len(sys.argv) > 1 else 1.0
BIN = os.environ.get("SUBDIV_LAB_BIN", str(ROOT / "target" / "release" / "subdiv-lab"))
ref = Path(os.environ.get("NUMPY_BASELINES") or ROOT / "benches" / "baselines")
if not all((ref / f).is_file() for f in ("numpy_faceblock.py", "numpy_reference.py")):
    sys.exit(f"{ref} lacks numpy_faceblock.py or numpy_reference.py (NUMPY_BASELINES)")
sys.path.insert(0, str(ref))
import numpy_faceblock  # noqa: E402
import numpy_reference  # noqa: E402

REPEAT = int(os.environ.get("REPEAT", "1"))


def reference_run(n, count, seed=1, batch=4096):
    """The measured loop of numpy_reference.main() (without its CSV option)."""
    rng = np.random.default_rng(seed)
    done = 0
    counts = np.zeros(3, dtype=np.int64)
    while done < count:
        b = min(batch, count - done)
        r = rng.uniform(0.01, 0.99, size=(b, n))
        ev, cx, dbl, sep = numpy_reference.classify(np.linalg.eigvals(numpy_reference.build(r)))
        counts += [cx.sum(), dbl.sum(), (~cx & ~dbl).sum()]
        done += b
    return counts


def cpu_self():
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def cpu_children():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


with open("/proc/cpuinfo") as f:
    model = next((l.split(":", 1)[1].strip() for l in f if l.startswith("model name")), "?")
print(f"machine: {os.cpu_count()} cores, {model}, load average {os.getloadavg()[0]:.2f}")
print()
print("| n | configs (reference) | numpy_reference configs/CPU-s | numpy_faceblock configs/CPU-s | "
      "classify_batch configs/CPU-s | vs reference | vs faceblock | "
      "classify_batch, classification only | vs faceblock | CLI sweep configs/CPU-s | "
      "classify_batch / CLI sweep |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
tmp = Path(tempfile.mkdtemp())


def rate(count, f, cpu=cpu_self):
    """count / the least CPU time of REPEAT runs of f."""
    best = None
    for _ in range(REPEAT):
        c0 = cpu()
        f()
        dt = cpu() - c0
        best = dt if best is None else min(best, dt)
    return count / best


VALENCES = [int(v) for v in os.environ.get("VALENCES", "3 5 8 16 64").split()]
for n in VALENCES:
    base = {3: 200000, 5: 200000, 8: 100000, 16: 40000, 64: 2000}[n]
    ref_base = {3: 20000, 5: 20000, 8: 10000, 16: 4000, 64: 200}[n]
    count = max(1, int(base * SCALE))
    ref_count = max(1, int(ref_base * SCALE))
    ref_rate = rate(ref_count, lambda: reference_run(n, ref_count))
    np_rate = rate(count, lambda: numpy_faceblock.run(n, count, 1))

    x = np.random.default_rng(1).uniform(0.01, 0.99, (count, n))
    cb_rate = rate(count, lambda: sl.classify_batch(x, threads=1))
    cls_rate = rate(count, lambda: sl.classify_batch(
        x, columns={"gap": False, "contraction": False}, threads=1))

    spec = tmp / "spec.toml"
    spec.write_text(f'name = "bench"\nscheme = "nurds"\nvalences = [{n}]\n[space]\nkind = "ratios"\n'
                    f'ratio_range = [0.01, 0.99]\n[sampler]\nkind = "random"\ncount = {count}\nseed = 1\n')
    out = tmp / "out.csv"

    def cli():
        for p in (out, tmp / "out.summary.json"):
            p.unlink(missing_ok=True)
        subprocess.run([BIN, "sweep", str(spec), "--out", str(out), "--threads", "1"],
                       check=True, capture_output=True)
    cli_rate = rate(count, cli, cpu_children)
    print(f"| {n} | {count} ({ref_count}) | {ref_rate:.0f} | {np_rate:.0f} | {cb_rate:.0f} | "
          f"{cb_rate / ref_rate:.0f}x | {cb_rate / np_rate:.1f}x | "
          f"{cls_rate:.0f} | {cls_rate / np_rate:.1f}x | {cli_rate:.0f} | {cb_rate / cli_rate:.2f} |",
          flush=True)
print()
print(f"load average at the end: {os.getloadavg()[0]:.2f}")
