#!/usr/bin/env python3
"""The sharper numpy peer: knowing spec(S_n) = spec(A) with 1/4, 1/8 and 1/16,
build only the n x n face block A = (I + R + 1 c^T)/4 for a batch of edge-ratio
vectors, take batched LAPACK eigenvalues, add the competing 1/4 and sort by
modulus. One BLAS thread.

    python3 benches/baselines/numpy_faceblock.py --valence 8 --count 20000 [--seed 1]

Prints: valence count seconds configs_per_s frac_complex
"""
import argparse
import os
import time

for var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(var, "1")
import numpy as np  # noqa: E402

from numpy_reference import face_weights, ratio_matrix  # noqa: E402


def spectra(r):
    """Sorted spectra (the face block's and 1/4) of a batch of ratio vectors."""
    b, n = r.shape
    R = ratio_matrix(r)
    A = (np.eye(n) + R + face_weights(R)[:, None, :]) / 4.0
    ev = np.concatenate([np.linalg.eigvals(A), np.full((b, 1), 0.25)], axis=1)
    order = np.argsort(-np.abs(ev), axis=1, kind="stable")
    return np.take_along_axis(ev, order, axis=1)


def run(n, count, seed, chunk=20000):
    """Seconds for `count` random configurations, and the complex fraction."""
    rng = np.random.default_rng(seed)
    t0 = time.perf_counter()
    done = ncomplex = 0
    while done < count:
        b = min(chunk, count - done)
        ev = spectra(rng.uniform(0.01, 0.99, (b, n)))
        ncomplex += int((np.abs(ev[:, 1].imag) > 1e-9).sum())
        done += b
    return time.perf_counter() - t0, ncomplex / count


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--valence", type=int, required=True)
    ap.add_argument("--count", type=int, default=20000)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    dt, fc = run(a.valence, a.count, a.seed)
    print(a.valence, a.count, f"{dt:.3f}", f"{a.count / dt:.0f}", f"{fc:.4f}")
