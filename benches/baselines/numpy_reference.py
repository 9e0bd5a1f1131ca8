#!/usr/bin/env python3
"""The NURDS local analysis as a researcher writes it in numpy: the whole
4n x 4n matrix S_n for a batch of edge-ratio vectors, all its eigenvalues by
batched LAPACK (numpy.linalg.eigvals), sorted by modulus, and the subdominant
pair classified with a fixed tolerance. The side-by-side baseline of
benches/compare_numpy.sh, compare_sweep_numpy.sh and compare_python_numpy.py.

    python3 benches/baselines/numpy_reference.py --valence 8 --count 20000 [--seed 1] [--csv F]

Point order (math doc section 4): P_0..P_{n-1}, then E_{i,1}, E_{i,2} for each
edge i, then C_0..C_{n-1}. One BLAS thread, for a per-core comparison.
"""
import argparse
import os
import sys
import time

for var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(var, "1")
import numpy as np  # noqa: E402


def ratio_matrix(r):
    """The batch of n x n matrices R: row i holds r_{i-1} at i-1,
    1 - r_{i-1} + r_i at i and 1 - r_i at i+1 (indices mod n)."""
    b, n = r.shape
    r_prev = np.roll(r, 1, axis=1)
    R = np.zeros((b, n, n))
    rows = np.arange(n)
    R[:, rows, (rows - 1) % n] = r_prev
    R[:, rows, rows] += 1.0 - r_prev + r
    R[:, rows, (rows + 1) % n] += 1.0 - r
    return R


def face_weights(R):
    """The stationary distribution c of R/2 (c^T R/2 = c^T, sum c = 1): the
    singular system with its first equation replaced by the normalisation."""
    b, n, _ = R.shape
    M = np.swapaxes(R / 2.0, 1, 2) - np.eye(n)
    M[:, 0, :] = 1.0
    rhs = np.zeros((b, n, 1))
    rhs[:, 0, 0] = 1.0
    return np.linalg.solve(M, rhs)[:, :, 0]


def build(r):
    """The batch of 4n x 4n matrices S_n."""
    b, n = r.shape
    R = ratio_matrix(r)
    c = face_weights(R)
    S = np.zeros((b, 4 * n, 4 * n))
    S[:, :n, :n] = (np.eye(n) + R + c[:, None, :]) / 4.0
    for i in range(n):
        j = (i + 1) % n
        e1, e2, ci = n + 2 * i, n + 2 * i + 1, 3 * n + i
        ri = r[:, i]
        # E_{i,1}, E_{i,2}: the edge rule of the ratio r_i between P_i and P_{i+1}
        S[:, e1, i] = 0.375 * (1.0 + ri)
        S[:, e1, j] = 0.375 * (1.0 - ri)
        S[:, e1, e1] = 0.125 * (1.0 + ri)
        S[:, e1, e2] = 0.125 * (1.0 - ri)
        S[:, e2, i] = 0.375 * ri
        S[:, e2, j] = 0.375 * (2.0 - ri)
        S[:, e2, e1] = 0.125 * ri
        S[:, e2, e2] = 0.125 * (2.0 - ri)
        # C_i: the uniform corner rule
        S[:, ci, i] = 9.0 / 16.0
        S[:, ci, e1] = 3.0 / 16.0
        S[:, ci, n + 2 * ((i - 1) % n) + 1] = 3.0 / 16.0
        S[:, ci, ci] = 1.0 / 16.0
    return S


def classify(ev, tol=1e-9):
    """Eigenvalues sorted by non-increasing modulus, and per row: a complex
    subdominant pair, a double real one, lambda_2 separated from lambda_3."""
    order = np.argsort(-np.abs(ev), axis=1, kind="stable")
    ev = np.take_along_axis(ev, order, axis=1)
    l1, l2, l3 = ev[:, 1], ev[:, 2], ev[:, 3]
    complex_pair = np.abs(l1.imag) > tol
    double = ~complex_pair & (np.abs(l1 - l2) <= tol)
    separated = np.abs(l2) > np.abs(l3) + tol
    return ev, complex_pair, double, separated


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--valence", type=int, default=8)
    ap.add_argument("--count", type=int, default=20000)
    ap.add_argument("--batch", type=int, default=4096)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--csv")
    a = ap.parse_args()
    rng = np.random.default_rng(a.seed)
    n, done, table = a.valence, 0, []
    counts = np.zeros(3, dtype=np.int64)
    t0 = time.perf_counter()
    while done < a.count:
        b = min(a.batch, a.count - done)
        r = rng.uniform(0.01, 0.99, size=(b, n))
        ev, cx, dbl, sep = classify(np.linalg.eigvals(build(r)))
        counts += [cx.sum(), dbl.sum(), (~cx & ~dbl).sum()]
        if a.csv:
            table.append(np.column_stack([np.abs(ev[:, 1]), np.abs(ev[:, 2]), cx, dbl, sep]))
        done += b
    dt = time.perf_counter() - t0
    if a.csv:
        np.savetxt(a.csv, np.vstack(table), delimiter=",",
                   header="abs_l1,abs_l2,complex,double,separated")
    print(f"valence={n} configs={a.count} seconds={dt:.3f} configs_per_s={a.count / dt:.0f} "
          f"complex={counts[0]} double={counts[1]} real_distinct={counts[2]}")


if __name__ == "__main__":
    sys.exit(main())
