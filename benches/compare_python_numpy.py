#!/usr/bin/env python3
"""Side by side, in one run: `subdiv_lab.classify_batch` from Python, the CLI
sweep (`subdiv-lab sweep --threads 1`) and the numpy face-block peer
(../shared/bench/numpy_faceblock.py: face block only, batched LAPACK, one BLAS
thread), at n = 3, 5, 8, 16, 64, random edge ratios uniform in [0.01, 0.99].

    python3 benches/compare_python_numpy.py [SCALE]

Needs the package installed (`pip install ./python`) and a release binary
(`cargo build --release`; SUBDIV_LAB_BIN overrides). Rates are configurations
per CPU-second (user + sys of this process or of the child), so they measure
the per-core cost even on a busy machine:

* classify_batch: threads=1, default columns (class, lambda1, lambda2,
  |lambda3|, gap, ratio/rho/theta, contraction rate), and the classification
  columns only; the ratios are drawn before the clock starts;
* CLI sweep: the same default columns, one thread, writing its CSV;
* numpy: numpy_faceblock.run() in this process (its ratios drawn inside).
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
ref = None
for d in [ROOT, *ROOT.parents]:
    if (d.parent / "shared" / "bench" / "numpy_faceblock.py").exists():
        ref = d.parent / "shared" / "bench"
        break
if ref is None:
    sys.exit("numpy_faceblock.py not found beside the repository (../shared/bench)")
sys.path.insert(0, str(ref))
import numpy_faceblock  # noqa: E402


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
print("| n | configs | numpy configs/CPU-s | classify_batch configs/CPU-s | speed-up per core | "
      "classify_batch, classification only | speed-up | CLI sweep configs/CPU-s | "
      "classify_batch / CLI sweep |")
print("|---|---|---|---|---|---|---|---|---|")
tmp = Path(tempfile.mkdtemp())
for n in (3, 5, 8, 16, 64):
    base = {3: 200000, 5: 200000, 8: 100000, 16: 40000, 64: 2000}[n]
    count = max(1, int(base * SCALE))
    c0 = cpu_self()
    numpy_faceblock.run(n, count, 1)
    np_rate = count / (cpu_self() - c0)

    x = np.random.default_rng(1).uniform(0.01, 0.99, (count, n))
    c0 = cpu_self()
    sl.classify_batch(x, threads=1)
    cb_rate = count / (cpu_self() - c0)
    c0 = cpu_self()
    sl.classify_batch(x, columns={"gap": False, "contraction": False}, threads=1)
    cls_rate = count / (cpu_self() - c0)

    spec = tmp / "spec.toml"
    spec.write_text(f'name = "bench"\nscheme = "nurds"\nvalences = [{n}]\n[space]\nkind = "ratios"\n'
                    f'ratio_range = [0.01, 0.99]\n[sampler]\nkind = "random"\ncount = {count}\nseed = 1\n')
    out = tmp / "out.csv"
    for p in (out, tmp / "out.summary.json"):
        p.unlink(missing_ok=True)
    c0 = cpu_children()
    subprocess.run([BIN, "sweep", str(spec), "--out", str(out), "--threads", "1"],
                   check=True, capture_output=True)
    cli_rate = count / (cpu_children() - c0)
    print(f"| {n} | {count} | {np_rate:.0f} | {cb_rate:.0f} | {cb_rate / np_rate:.1f}x | "
          f"{cls_rate:.0f} | {cls_rate / np_rate:.1f}x | {cli_rate:.0f} | {cb_rate / cli_rate:.2f} |",
          flush=True)
print()
print(f"load average at the end: {os.getloadavg()[0]:.2f}")
