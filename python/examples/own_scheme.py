"""A scheme of one's own from Python: a matrix, an object, a file (docs/guide/own-scheme.md).
Run from the repository root: python python/examples/own_scheme.py"""
import numpy as np
import subdiv_lab as sl

def one_ring(n, a, b, g):
    """The (2n + 1) one-ring matrix of v' = a v + b sum e + g sum f on
    Catmull-Clark's edge and face rules; rows v, e0.., f0.."""
    s = np.zeros((2 * n + 1, 2 * n + 1))
    s[0, 0], s[0, 1:n + 1], s[0, n + 1:] = a, b, g
    for i in range(n):
        e, f = 1 + i, 1 + n + i
        s[e, 0] = s[e, e] = 3 / 8
        for j in (1 + (i - 1) % n, 1 + (i + 1) % n, 1 + n + (i - 1) % n, f):
            s[e, j] += 1 / 16
        for j in (0, e, 1 + (i + 1) % n, f):
            s[f, j] = 1 / 4
    labels = ["v"] + [f"e{i}" for i in range(n)] + [f"f{i}" for i in range(n)]
    return s, labels

# 1. a matrix one computed
S, labels = one_ring(5, 1 / 2, 3 / 40, 1 / 40)
r = sl.analyze(matrix=S, labels=labels)
print(r["subdominant"]["class"], r["subdominant"]["lambda1"], r["curvature"]["verdict"])

# 2. a scheme as an object: name and matrix(valence) -> (S, labels)
class FlatCC:
    name = "flat-cc-py"
    def matrix(self, n):
        return one_ring(n, 1 / 2, 3 / (8 * n), 1 / (8 * n))

print(sl.analyze(scheme=FlatCC(), valence=5)["curvature"]["verdict"])
spec = {"name": "flat", "scheme": "catmull-clark", "valences": [3, 4, 5, 6, 8],
        "space": {"kind": "uniform"}, "sampler": {"kind": "grid", "points_per_axis": 1},
        "columns": {"curvature": True}}
t = sl.sweep(spec, scheme=FlatCC()).to_pandas()
print(t[["valence", "class", "lambda1_re", "curvature_verdict"]].to_string(index=False))

# 3. the same rule as a file: the same rows
f = sl.sweep(spec, scheme_file="tests/data/flat-cc.toml").to_pandas()
print((f["lambda1_re"] - t["lambda1_re"]).abs().max() < 1e-12, list(f["class"]) == list(t["class"]))
