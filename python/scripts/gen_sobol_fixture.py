#!/usr/bin/env python3
"""Regenerates tests/data/sobol_scipy.txt: unscrambled Sobol points of
scipy.stats.qmc.Sobol(d, scramble=False) (default bits = 30), as integers
k with x = k / 2^30, for the tests of src/sweep/sampler.rs.

    python3 python/scripts/gen_sobol_fixture.py > tests/data/sobol_scipy.txt
"""
import scipy
from scipy.stats import qmc

print(f"# scipy.stats.qmc.Sobol(d, scramble=False), SciPy {scipy.__version__}; x = k / 2^30")
print("# d start coordinates k_0 k_1 ... (one point per line; 'coordinates' lists the columns kept)")
cases = [(1, 0, 16, None), (2, 0, 32, None), (3, 0, 32, None), (5, 0, 16, None),
         (10, 0, 16, None), (40, 0, 8, None), (128, 0, 8, None),
         (1024, 0, 8, [0, 1, 2, 511, 1000, 1022, 1023]),
         (7, 1000003, 4, None), (64, 123456789, 2, None)]
for d, start, count, cols in cases:
    s = qmc.Sobol(d, scramble=False)
    if start:
        s.fast_forward(start)
    pts = s.random(count)
    cols = cols if cols is not None else list(range(d))
    for i, p in enumerate(pts):
        ks = [int(round(p[c] * 2**30)) for c in cols]
        assert all(k / 2**30 == p[c] for k, c in zip(ks, cols))
        print(d, start + i, ",".join(map(str, cols)), " ".join(map(str, ks)))
