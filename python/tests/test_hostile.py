"""Hostile calls of the Python API: each case must raise the documented
exception with a message naming the problem, or return what it promises;
none may panic, abort or hang the interpreter.

The cases run in child interpreters (so that an abort fails its case instead
of killing the test runner): one child runs the cases in order and reports
each one before and after it runs; a child that dies or stops answering is
charged to the case it was running, and a new child continues with the next
case. Needs no binary (the CLI comparisons are in test_api.py).
"""
import json
import os
import queue
import re
import subprocess
import sys
import textwrap
import threading
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "python" / "src"

# Seconds a child may take for one case before it is charged with a hang.
CASE_TIMEOUT = 60

# Names the cases use, defined in every child (and the files they read).
PRELUDE = textwrap.dedent('''
    import math, os
    import numpy as np
    import subdiv_lab as sl
    V = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    F = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
    SPEC = {"name": "h", "scheme": "nurds", "valences": [3],
            "space": {"kind": "ratios", "ratio_range": [0.2, 0.7]},
            "sampler": {"kind": "random", "count": 5, "seed": 1}}
    def spec(**over):
        s = {k: (dict(v) if isinstance(v, dict) else v) for k, v in SPEC.items()}
        for k, v in over.items():
            table, _, key = k.partition("__")
            if key:
                s[table][key] = v
            else:
                s[table] = v
        return s
    BOX = {"scheme": "nurds", "valence": 3, "box": [[0.3, 0.4]] * 3, "properties": ["class"]}
    with open("sweep.toml", "w") as f:
        f.write('name = "h"\\nscheme = "nurds"\\nvalences = [3]\\n[space]\\nkind = "ratios"\\n'
                'ratio_range = [0.2, 0.7]\\n[sampler]\\nkind = "random"\\ncount = 5\\nseed = 1\\n')
    with open("rows.csv", "w") as f:
        f.write("id,valence,x\\n0,3,0.5\\n1,3,0.25\\n")
    with open("empty.csv", "w") as f:
        f.write("")
    with open("sum.toml", "w") as f:
        f.write('name = "t"\\ntopology = "quad"\\n[vertex]\\nself = "1"\\nedge = "1/n"\\nface = "0"\\n')
    with open("div0.toml", "w") as f:
        f.write('name = "t"\\ntopology = "quad"\\n[vertex]\\nself = "1 - 1/(n-5)"\\n'
                'edge = "1/(n*(n-5))"\\nface = "0"\\n')
    with open("cc.toml", "w") as f:
        f.write('name = "t"\\ntopology = "quad"\\n[vertex]\\nself = "1 - 7/(4*n)"\\n'
                'edge = "3/(2*n^2)"\\nface = "1/(4*n^2)"\\n')
''')

# (id, call, expected): expected is (exception name, message fragments) or
# ("ok", a check on the result `r`, evaluated in the child).
CASES = [
    # item 1: no panic, empty input gives empty output
    ("classify_batch-empty-rows", "sl.classify_batch(np.zeros((0, 5)))",
     ("ok", "len(r['class']) == 0 and len(r['lambda1']) == 0 and len(r['error']) == 0")),
    ("classify_batch-empty-rows-columns",
     "sl.classify_batch(np.zeros((0, 3)), columns={'eigenvalues': 2, 'charmap': True})",
     ("ok", "all(len(v) == 0 for v in r.values())")),
    ("classify_batch-no-columns", "sl.classify_batch(np.zeros((3, 0)))",
     ("ValueError", ["one column per edge", "got 0 columns"])),
    ("classify_batch-two-columns", "sl.classify_batch(np.full((2, 2), 0.5))",
     ("ValueError", ["valence n >= 3"])),
    ("classify_batch-1d", "sl.classify_batch(np.full(5, 0.5))", ("ValueError", ["2-D array"])),
    ("classify_batch-nan", "sl.classify_batch(np.full((2, 3), np.nan))",
     ("ValueError", ["ratios row 0", "edge ratio"])),
    ("classify_batch-valence-too-large", "sl.classify_batch(np.full((1, 5000), 0.5))",
     ("ValueError", ["valence"])),
    ("classify_batch-over-time-limit", "sl.classify_batch(np.full((20000, 512), 0.5), threads=1)",
     ("ValueError", ["classify_batch: 20000 rows of valence 512", "limit 1.0 h", "force=True"])),
    ("classify_batch-threads-0", "sl.classify_batch(np.full((1, 3), 0.5), threads=0)",
     ("ValueError", ["threads must be between 1 and"])),
    ("classify_batch-threads-negative", "sl.classify_batch(np.full((1, 3), 0.5), threads=-1)",
     ("ValueError", ["threads must be >= 0, got -1"])),
    ("classify_batch-bad-columns", "sl.classify_batch(np.full((1, 3), 0.5), columns={'eigenvalues': -1})",
     ("ValueError", ["columns.eigenvalues"])),
    ("analyze-charmap-unknown", "sl.analyze(scheme='loop', valence=5, charmap='rings')",
     ("ValueError", ['charmap must be "ring" or "generic", got "rings"'])),
    ("analyze-charmap-bad-regular-valence",
     "sl.analyze(scheme=type('S', (), {'name': 's', 'regular_valence': 5,"
     " 'matrix': lambda self, n: sl.matrix('loop', valence=n)})(), valence=5, charmap='generic')",
     ("ValueError", ["scheme.regular_valence must be 4 (quad schemes) or 6 (triangle schemes), got 5"])),
    ("classify_batch-bad-scheme", "sl.classify_batch(np.full((1, 3), 0.5), scheme='midedge')",
     ("ValueError", ["midedge"])),
    # item 2: estimates and limits
    ("analyze-doo-sabin-100000", "sl.analyze(scheme='doo-sabin', valence=100000)",
     ("ValueError", ["analyze: valence 100000 needs ~", "400000 x 400000"])),
    ("analyze-doo-sabin-100000-force", "sl.analyze(scheme='doo-sabin', valence=100000, force=True)",
     ("ValueError", ["analyze: valence 100000 needs ~", "(refused even with force=True)"])),
    ("matrix-doo-sabin-100000", "sl.matrix(scheme='doo-sabin', valence=100000)",
     ("ValueError", ["matrix: valence 100000 needs ~"])),
    ("matrix-doo-sabin-100000-force", "sl.matrix(scheme='doo-sabin', valence=100000, force=True)",
     ("ValueError", ["(refused even with force=True)"])),
    ("matrix-valence-huge", "sl.matrix(scheme='catmull-clark', valence=2**64 - 1)",
     ("ValueError", ["refused even with force=True"])),
    ("analyze-valence-600", "sl.analyze(valence=600, uniform=True)",
     ("ValueError", ["analyze: valence 600 takes ~7.2 min", "(limit 60 s); use force=True to run anyway"])),
    ("sweep-count-1e13", "sl.sweep(spec(sampler__count=10**13))",
     ("ValueError", ["sweep: spec \"h\" needs ~", "10000000000000 rows"])),
    ("sweep-count-1e13-force", "sl.sweep(spec(sampler__count=10**13), force=True)",
     ("ValueError", ["refused even with force=True"])),
    ("sweep-over-time-limit",
     "sl.sweep(spec(sampler__count=3 * 10**6, columns={'exact_certificate': True}), threads=1)",
     ("ValueError", ["sweep: spec \"h\" takes ~", "(limit 1.0 h); use force=True to run anyway"])),
    ("subdivide-over-limit", "sl.subdivide(V, F, levels=11)",
     ("ValueError", ["subdivide: levels 11 needs ~", "force=True"])),
    ("subdivide-levels-1e18", "sl.subdivide(V, F, levels=10**18)",
     ("ValueError", ["the result would have 18446744073709551615 half-edges"])),
    ("verify-over-limit",
     "sl.verify(dict(BOX, valence=16, box=[[0.1, 0.9]] * 16, properties=['class', 'charmap']))",
     ("ValueError", ["verify: spec", "force=True"])),
    ("cc_study-over-limit", "sl.cc_study(n_min=3, n_max=256, samples=100000)",
     ("ValueError", ["cc_study: valences 3..256 takes ~", "force=True"])),
    ("ccss_bound-over-limit", "sl.ccss_bound(valence=1000)",
     ("ValueError", ["ccss_bound: valence 1000 takes ~", "force=True"])),
    ("ccss_bound-table-over-limit", "sl.ccss_bound(table_to=1000)",
     ("ValueError", ["ccss_bound: table_to=1000", "force=True"])),
    ("merge-missing-shard", "sl.merge(['nosuch.csv'], 'sweep.toml')",
     ("ValueError", ["reading nosuch.summary.json", "merge needs it"])),
    ("merge-no-shards", "sl.merge([], 'sweep.toml')", ("ValueError", ["at least one shard"])),
    ("merge-over-limit", "sl.merge(['nosuch.csv'], spec(sampler__count=10**13))",
     ("ValueError", ["merge: 1 shards needs ~", "rows of"])),
    # item 3: errors
    ("analyze-levels-negative", "sl.analyze(uniform=True, valence=5, levels=-1)",
     ("ValueError", ["levels must be >= 0, got -1"])),
    ("analyze-levels-0", "sl.analyze(uniform=True, valence=5, levels=0)",
     ("ValueError", ["levels must be between 1 and 10000, got 0"])),
    ("analyze-levels-huge", "sl.analyze(uniform=True, valence=5, levels=10**40)",
     ("ValueError", ["levels must be at most"])),
    ("analyze-levels-float", "sl.analyze(uniform=True, valence=5, levels=1.5)", ("TypeError", ["float"])),
    ("analyze-seed-negative", "sl.analyze(uniform=True, valence=5, seed=-1)",
     ("ValueError", ["seed must be >= 0"])),
    ("analyze-valence-negative", "sl.analyze(scheme='doo-sabin', valence=-3)",
     ("ValueError", ["valence must be >= 0, got -3"])),
    ("analyze-valence-2", "sl.analyze(scheme='doo-sabin', valence=2)",
     ("ValueError", ["valence must be at least 3, got 2"])),
    ("analyze-ratio-nan", "sl.analyze(ratios=[0.5, float('nan'), 0.5])", ("ValueError", ["r_1"])),
    ("analyze-path", "sl.analyze(uniform=True, valence=5, path='fast')", ("ValueError", ["path must be"])),
    ("analyze-scheme-file-sum", "sl.analyze(scheme_file='sum.toml', valence=5)",
     ("ValueError", ["vertex at valence 3", "sum to 2, not 1"])),
    ("analyze-scheme-file-division-by-zero", "sl.analyze(scheme_file='div0.toml', valence=4)",
     ("ValueError", ["vertex.self at valence 5: division by zero"])),
    ("analyze-scheme-file-missing", "sl.analyze(scheme_file='nope.toml', valence=5)",
     ("ValueError", ["nope.toml", "cannot read"])),
    ("analyze-scheme-file-no-valence", "sl.analyze(scheme_file='cc.toml')",
     ("ValueError", ["valence is required with scheme_file"])),
    ("analyze-scheme-file-and-scheme", "sl.analyze(scheme='loop', scheme_file='cc.toml', valence=5)",
     ("ValueError", ["mutually exclusive"])),
    ("analyze-scheme-file-valence-2", "sl.analyze(scheme_file='cc.toml', valence=2)",
     ("ValueError", ["valence: must be at least 3"])),
    ("analyze-scheme-file-ok", "sl.analyze(scheme_file='cc.toml', valence=5)",
     ("ok", "r['subdominant']['class'] == 'standard' and r['input']['scheme'] == 't'")),
    # analyze(matrix=...), a scheme object, sweep(scheme_file=..., scheme=...)
    ("analyze-matrix-not-square", "sl.analyze(matrix=np.full((2, 3), 1 / 3))",
     ("ValueError", ["matrix: must be a non-empty square 2-D array, got shape [2, 3]"])),
    ("analyze-matrix-1d", "sl.analyze(matrix=np.ones(3))", ("ValueError", ["square 2-D array"])),
    ("analyze-matrix-empty", "sl.analyze(matrix=np.zeros((0, 0)))", ("ValueError", ["non-empty"])),
    ("analyze-matrix-nan", "sl.analyze(matrix=np.array([[1.0, 0.0], [np.nan, 1.0]]))",
     ("ValueError", ["entry [1, 0] is NaN"])),
    ("analyze-matrix-row-sum", "sl.analyze(matrix=np.array([[1.0, 0.5], [0.5, 0.5]]))",
     ("ValueError", ["row 0 (X0) sums to 1.5, not 1"])),
    ("analyze-matrix-strings", "sl.analyze(matrix=[['a', 'b'], ['c', 'd']])",
     ("ValueError", ["matrix: not an array of numbers"])),
    ("analyze-matrix-labels-count", "sl.analyze(matrix=np.eye(2), labels=['v'])",
     ("ValueError", ["labels: 1 labels for 2 rows"])),
    ("analyze-matrix-labels-unknown", "sl.analyze(matrix=np.eye(2), labels=['v', 'q1'])",
     ("ValueError", ['labels[1]: "q1" is not a point label'])),
    ("analyze-matrix-labels-repeated", "sl.analyze(matrix=np.eye(2), labels=['e0', 'e0'])",
     ("ValueError", ['labels[1]: "e0" repeats labels[0]'])),
    ("analyze-matrix-and-scheme", "sl.analyze(matrix=np.eye(2), scheme='loop')",
     ("ValueError", ["matrix is mutually exclusive"])),
    ("analyze-labels-without-matrix", "sl.analyze(scheme='loop', valence=5, labels=['v'])",
     ("ValueError", ["labels go with matrix"])),
    ("analyze-matrix-valence-0", "sl.analyze(matrix=np.eye(2), valence=0)",
     ("ValueError", ["valence must be at least 1"])),
    ("analyze-matrix-identity-ok", "sl.analyze(matrix=np.eye(3))",
     ("ok", "r['input']['scheme'] == 'matrix' and r['input']['valence'] == 3")),
    ("analyze-object-no-matrix", "sl.analyze(scheme=object(), valence=5)",
     ("ValueError", ["needs a name attribute"])),
    ("analyze-object-no-valence", "sl.analyze(scheme=type('S', (), {'name': 's', 'matrix': lambda self, n: (np.eye(2), None)})())",
     ("ValueError", ["valence is required with a scheme object"])),
    ("analyze-object-bad-return", "sl.analyze(scheme=type('S', (), {'name': 's', 'matrix': lambda self, n: np.eye(2)})(), valence=5)",
     ("ValueError", ["scheme.matrix(5) must return a pair (S, labels)"])),
    ("analyze-object-bad-matrix", "sl.analyze(scheme=type('S', (), {'name': 's', 'matrix': lambda self, n: (np.ones((2, 2)), None)})(), valence=5)",
     ("ValueError", ["scheme.matrix(5): row 0 (X0) sums to 2"])),
    ("analyze-object-raises", "sl.analyze(scheme=type('S', (), {'name': 's', 'matrix': lambda self, n: 1 / 0})(), valence=5)",
     ("ZeroDivisionError", ["division by zero"])),
    ("analyze-object-bad-name", "sl.analyze(scheme=type('S', (), {'name': 3, 'matrix': lambda self, n: (np.eye(2), None)})(), valence=5)",
     ("ValueError", ["scheme.name must be a string"])),
    ("sweep-scheme-file-missing", "sl.sweep(spec(space={'kind': 'uniform'}), scheme_file='nope.toml')",
     ("ValueError", ["scheme_file nope.toml", "cannot read"])),
    ("sweep-scheme-file-invalid", "sl.sweep(spec(space={'kind': 'uniform'}), scheme_file='sum.toml')",
     ("ValueError", ["scheme_file: vertex at valence 3"])),
    ("sweep-scheme-file-ratios-space", "sl.sweep(spec(), scheme_file='cc.toml')",
     ("ValueError", ["space", "sweeps valences only"])),
    ("sweep-scheme-file-and-scheme", "sl.sweep(spec(space={'kind': 'uniform'}), scheme_file='cc.toml', scheme=type('S', (), {'name': 's', 'matrix': lambda self, n: (np.eye(2), None)})())",
     ("ValueError", ["scheme_file and scheme are mutually exclusive"])),
    ("sweep-scheme-builtin-name", "sl.sweep(spec(space={'kind': 'uniform'}), scheme='loop')",
     ("ValueError", ["a built-in scheme is the spec's scheme key"])),
    ("sweep-scheme-object-raises", "sl.sweep(spec(space={'kind': 'uniform'}), threads=1, scheme=type('S', (), {'name': 's', 'matrix': lambda self, n: 1 / 0})())",
     ("ZeroDivisionError", ["division by zero"])),
    ("sweep-scheme-file-ok", "sl.sweep(spec(space={'kind': 'uniform'}, scheme='catmull-clark'), threads=1, scheme_file='cc.toml')",
     ("ok", "r.num_rows == 5 and set(r.column('class').to_pylist()) == {'standard'}")),
    ("matrix-face-block-cc", "sl.matrix(scheme='catmull-clark', valence=5, block='face')",
     ("ValueError", ["face block"])),
    ("matrix-block", "sl.matrix(uniform=True, valence=3, block='diag')", ("ValueError", ["block must be"])),
    ("matrix-knots-loop", "sl.matrix(scheme='loop', valence=6, ratios=[0.5] * 6)",
     ("ValueError", ["knots/ratios: scheme loop takes no knot intervals"])),
    ("matrix-needs-c", "sl.matrix(scheme='adjustable-cc', valence=4)", ("ValueError", ["c: scheme adjustable-cc needs"])),
    ("matrix-c-out-of-range", "sl.matrix(scheme='adjustable-cc', valence=4, c=1.5)", ("ValueError", ["c"])),
    ("sweep-missing-path-no-toml", "sl.sweep('analysis/nosuch')",
     ("ValueError", ["cannot read spec analysis/nosuch: No such file or directory"])),
    ("sweep-missing-path", "sl.sweep('nosuch.toml')", ("ValueError", ["cannot read spec nosuch.toml"])),
    ("sweep-missing-pathlike", "sl.sweep(__import__('pathlib').Path('nosuch'))",
     ("ValueError", ["cannot read spec nosuch"])),
    ("sweep-directory", "sl.sweep('.')", ("ValueError", ["cannot read spec ."])),
    ("sweep-path-errors-name-the-file", "sl.sweep('sweep.toml', shard=(0, 1), limit=2, threads=1)",
     ("ok", "r.num_rows == 2")),
    ("sweep-text", "sl.sweep('x = [')", ("ValueError", ["line 1"])),
    ("sweep-type", "sl.sweep(42)", ("TypeError", ["spec must be"])),
    ("sweep-threads-0", "sl.sweep(SPEC, threads=0)", ("ValueError", ["threads must be between 1 and"])),
    ("sweep-threads-huge", "sl.sweep(SPEC, threads=10**6)", ("ValueError", ["threads must be between 1 and"])),
    ("sweep-limit-negative", "sl.sweep(SPEC, limit=-1)", ("ValueError", ["limit must be >= 0, got -1"])),
    ("sweep-shard-text", "sl.sweep(SPEC, shard='3/2')", ("ValueError", ["shard must be I/N"])),
    ("sweep-shard-negative", "sl.sweep(SPEC, shard=(-1, 2))", ("ValueError", ["shard must be I/N"])),
    ("sweep-shard-garbage", "sl.sweep(SPEC, shard='a/b')", ("ValueError", ["shard must be I/N"])),
    ("sweep-dict-range", "sl.sweep(spec(space={'kind': 'ratios', 'ratio_range': [0.7, 0.2]}))",
     ("ValueError", ["spec['space']['ratio_range']: lower bound 0.7 > upper bound 0.2"], ["(line"])),
    ("sweep-dict-type", "sl.sweep(spec(sampler={'kind': 'grid', 'points_per_axis': 'a'}))",
     ("ValueError", ["spec['sampler']['points_per_axis']"], ["(line"])),
    ("sweep-dict-count", "sl.sweep(spec(sampler__count=0))",
     ("ValueError", ["spec['sampler']['count']"], ["(line"])),
    ("sweep-dict-unknown-key", "sl.sweep(spec(sampler__cuont=3))",
     ("ValueError", ["spec['sampler']['cuont']", "unknown field"], ["(line"])),
    ("sweep-dict-missing-table", "sl.sweep({k: v for k, v in SPEC.items() if k != 'sampler'})",
     ("ValueError", ["sampler"], ["(line"])),
    ("sweep-dict-valence-index", "sl.sweep(spec(valences=[3, 2]))",
     ("ValueError", ["spec['valences'][1]"], ["(line"])),
    ("sweep-dict-none", "sl.sweep(spec(scheme=None))", ("ValueError", ["spec['scheme']: None"])),
    ("sweep-dict-nan", "sl.sweep(spec(space={'kind': 'ratios', 'ratio_range': [math.nan, 0.5]}))",
     ("ValueError", ["spec['space']['ratio_range'][0]", "not a finite number"])),
    ("sweep-dict-numpy", "sl.sweep(spec(valences=np.array([3]), sampler__count=np.int64(2)))",
     ("ok", "r.num_rows == 2")),
    ("subdivide-levels-negative", "sl.subdivide(V, F, levels=-1)", ("ValueError", ["levels must be >= 0, got -1"])),
    ("subdivide-vertices-shape", "sl.subdivide(V[:, :2], F)", ("ValueError", ["(m, 3)"])),
    ("subdivide-face-negative", "sl.subdivide(V, [[0, 1, 3, -2]] + F[1:])",
     ("ValueError", ["faces[0][3] must be >= 0, got -2"])),
    ("subdivide-face-out-of-range", "sl.subdivide(V, [[0, 1, 3, 99]] + F[1:])", ("ValueError", ["99"])),
    ("subdivide-nan", "sl.subdivide(V * np.nan, F)", ("ValueError", ["non-finite"])),
    ("subdivide-knot-not-an-edge", "sl.subdivide(V, F, knots={(0, 7): 2.0})", ("ValueError", ["not an edge"])),
    ("subdivide-knot-negative-vertex", "sl.subdivide(V, F, knots={(-1, 0): 2.0})", ("ValueError", [">= 0"])),
    ("subdivide-knots-cc", "sl.subdivide(V, F, scheme='catmull-clark', knots={(0, 1): 2.0})",
     ("ValueError", ["takes no knot intervals"])),
    ("subdivide-open-mesh", "sl.subdivide(V, F[:-1])", ("ValueError", [])),
    ("report-missing", "sl.report('nosuch', 'out')", ("ValueError", ["cannot read spec nosuch"])),
    ("report-dict-key", "sl.report({'name': 'x', 'figure': [{'kind': 'nope'}]}, 'out')",
     ("ValueError", ["spec['figure'][0]['kind']", "nope"], ["(line", "line "])),
    ("verify-missing", "sl.verify('nosuch.toml')", ("ValueError", ["cannot read spec nosuch.toml"])),
    ("verify-dict-valence", "sl.verify(dict(BOX, valence=100))",
     ("ValueError", ["spec['valence'] must be between 3 and 16"], ["(line"])),
    ("verify-max-cells-0", "sl.verify(BOX, max_cells=0)", ("ValueError", ["max_cells must be at least 1, got 0"])),
    ("verify-max-cells-negative", "sl.verify(BOX, max_cells=-5)", ("ValueError", ["max_cells must be >= 0"])),
    ("verify-threads-0", "sl.verify(BOX, threads=0)", ("ValueError", ["threads must be between 1 and"])),
    # item 4: the new functions' bad input
    ("g2_cap-c", "sl.g2_cap(2.0, valence=5, random_net=1)", ("ValueError", ["c = 2"])),
    ("g2_cap-c-nan", "sl.g2_cap(math.nan, valence=5, random_net=1)", ("ValueError", ["NaN"])),
    ("g2_cap-nothing", "sl.g2_cap(0.5)", ("ValueError", ["nothing to cap"])),
    ("g2_cap-both", "sl.g2_cap(0.5, vertices=V, faces=F, vertex=0, valence=5, random_net=1)",
     ("ValueError", ["not both"])),
    ("g2_cap-half-mesh", "sl.g2_cap(0.5, vertices=V)", ("ValueError", ["vertices, faces and vertex"])),
    ("g2_cap-valence", "sl.g2_cap(0.5, valence=100, random_net=1)", ("ValueError", ["100"])),
    ("g2_cap-seed-negative", "sl.g2_cap(0.5, valence=5, random_net=-1)", ("ValueError", ["random_net must be >= 0"])),
    ("g2_cap-samples", "sl.g2_cap(0.5, valence=5, random_net=1, samples=0)",
     ("ValueError", ["samples must be in 1..=256, got 0"])),
    ("g2_cap-vertex", "sl.g2_cap(0.5, vertices=V, faces=F, vertex=99)", ("ValueError", ["99"])),
    ("g2_cap-regular-vertex", "sl.g2_cap(0.5, vertices=V, faces=F, vertex=0)", ("ValueError", [])),
    ("plot-missing", "sl.plot('nosuch.csv')", ("ValueError", ["cannot read nosuch.csv"])),
    ("plot-empty", "sl.plot('empty.csv')", ("ValueError", ["empty.csv"])),
    ("plot-width", "sl.plot('rows.csv', width=10)", ("ValueError", ["width must be between 400 and 8000 pixels, got 10"])),
    ("plot-height-negative", "sl.plot('rows.csv', height=-1)", ("ValueError", ["height must be >= 0"])),
    ("plot-kind", "sl.plot('rows.csv', kind='pie')", ("ValueError", ["kind \"pie\" is not a plot kind"])),
    ("plot-column", "sl.plot('rows.csv', kind='histogram', x='nope')", ("ValueError", ["nope"])),
    ("plot-out", "sl.plot('rows.csv', out='fig.txt')", ("ValueError", [".svg or .png"])),
    ("plot-format", "sl.plot('rows.csv', format='gif')", ("ValueError", ["format must be"])),
    ("plot-data-type", "sl.plot(42)", ("TypeError", ["data must be"])),
    ("cc_study-n", "sl.cc_study(n_min=2)", ("ValueError", ["need 3 <= n_min <= n_max <= 256, got 2..32"])),
    ("cc_study-n-negative", "sl.cc_study(n_min=-3)", ("ValueError", ["n_min must be >= 0"])),
    ("cc_study-samples", "sl.cc_study(samples=0)", ("ValueError", ["samples must be in 1..=100000, got 0"])),
    ("cc_study-tol", "sl.cc_study(tol=math.nan)", ("ValueError", ["invalid parameter tol"])),
    ("cc_study-criterion", "sl.cc_study(n_max=3, criterion='c2')", ("ValueError", ["criterion must be"])),
    ("ccss_bound-valence", "sl.ccss_bound(valence=2)", ("ValueError", ["valence must be at least 3, got 2"])),
    ("ccss_bound-levels", "sl.ccss_bound(valence=5, levels=0)", ("ValueError", ["levels must be in 1..=12, got 0"])),
    ("ccss_bound-levels-huge", "sl.ccss_bound(valence=5, levels=2**40)", ("ValueError", ["levels must be at most"])),
    ("ccss_bound-table", "sl.ccss_bound(table_to=2)", ("ValueError", ["table_to must be >= 3, got 2"])),
    ("ccss_bound-nothing", "sl.ccss_bound()", ("ValueError", ["give valence"])),
    ("ccss_bound-both", "sl.ccss_bound(valence=5, table_to=5)", ("ValueError", ["not both"])),
    ("ccss_bound-net-alone", "sl.ccss_bound(valence=5, net=np.zeros((18, 3)))", ("ValueError", ["net and epsilon"])),
    ("ccss_bound-net-size", "sl.ccss_bound(valence=5, net=np.zeros((3, 3)), epsilon=1e-3)",
     ("ValueError", ["control net points (2n+8)"])),
    ("ccss_bound-net-ragged-native", "sl._native.ccss_bound(5, 4, None, [[1.0, 2.0]] * 17 + [[1.0]], 1e-3, False)",
     ("ValueError", ["control point 17 has 1 coordinates, expected 2"])),
    ("ccss_bound-epsilon", "sl.ccss_bound(valence=5, net=np.ones((18, 3)), epsilon=-1)",
     ("ValueError", ["epsilon"])),
    # the last resort: a panic reaches Python as a RuntimeError naming the function
    ("guard", "sl._native._guard_selftest('planted')",
     ("RuntimeError", ["_guard_selftest: internal error", "planted"])),
]

DRIVER = textwrap.dedent('''
    import json, sys, traceback
    cases = json.loads(sys.stdin.read())
    start = int(sys.argv[1])
    exec(compile(sys.argv[2], "<prelude>", "exec"), globals())
    def say(**kw):
        sys.stdout.write(json.dumps(kw) + "\\n")
        sys.stdout.flush()
    for i in range(start, len(cases)):
        call, check = cases[i]
        say(case=i, started=True)
        try:
            r = eval(call)
        except BaseException as e:
            say(case=i, kind=type(e).__name__, message=str(e))
            continue
        ok = True
        if check:
            try:
                ok = bool(eval(check))
            except BaseException as e:
                ok = False
        say(case=i, kind="ok", message="" if ok else "check failed on " + repr(r)[:300])
''')


def _run_all(tmp_path_factory):
    """Runs every case; returns {index: (kind, message)}, where a child that
    died or hung during a case is recorded as ("died", details)."""
    cases = [(call, exp[1] if exp[0] == "ok" else None) for _, call, exp in CASES]
    work = tmp_path_factory.mktemp("hostile")
    results = {}
    start = 0
    env = dict(os.environ, RUST_BACKTRACE="0")
    while start < len(cases):
        # standard error to a file: a pipe nobody reads would fill up with
        # panic messages and block the child (a false hang)
        err_path = work / f"stderr-{start}.txt"
        err = open(err_path, "w")
        p = subprocess.Popen([sys.executable, "-c", DRIVER, str(start), PRELUDE], cwd=work,
                             stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                             stderr=err, text=True, env=env)
        p.stdin.write(json.dumps(cases))
        p.stdin.close()
        # a thread reads the child's lines: a timeout on the queue is a case
        # that stopped answering (select() on a buffered pipe would miss lines
        # already read into the buffer)
        lines = queue.Queue()
        reader = threading.Thread(target=lambda: [lines.put(l) for l in p.stdout] + [lines.put(None)],
                                  daemon=True)
        reader.start()
        running = None
        died = None
        while True:
            try:
                line = lines.get(timeout=CASE_TIMEOUT)
            except queue.Empty:
                p.kill()
                died = f"no answer within {CASE_TIMEOUT} s (a hang)"
                break
            if line is None:
                break
            msg = json.loads(line)
            if msg.get("started"):
                running = msg["case"]
            else:
                results[msg["case"]] = (msg["kind"], msg["message"])
                running = None
        code = p.wait()
        err.close()
        stderr = err_path.read_text()
        if running is None:
            if code != 0 and len(results) < len(cases):
                pytest.fail(f"the child died outside any case (exit {code}): {stderr[-2000:]}")
            break
        results[running] = ("died", died or f"exit code {code}; stderr ends: {stderr[-300:]}")
        start = running + 1
    return results


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    return _run_all(tmp_path_factory)


@pytest.mark.parametrize("index", range(len(CASES)), ids=[c[0] for c in CASES])
def test_hostile_call(results, index):
    name, call, expected = CASES[index]
    kind, message = results.get(index, ("missing", "the case never ran"))
    if expected[0] == "ok":
        assert kind == "ok", f"{call}: {kind}: {message}"
        assert message == "", f"{call}: {message}"
        return
    want, fragments = expected[0], expected[1]
    absent = expected[2] if len(expected) > 2 else []
    assert kind == want, f"{call}: expected {want}, got {kind}: {message}"
    assert "\n" not in message.strip(), f"{call}: not one line: {message!r}"
    for f in fragments:
        assert f in message, f"{call}: {f!r} not in {message!r}"
    for f in absent:
        assert f not in message, f"{call}: {f!r} in {message!r}"


def _pyfunctions():
    """(file, name, body) of every #[pyfunction] of the binding."""
    out = []
    for path in sorted(SRC.glob("*.rs")):
        text = path.read_text()
        for m in re.finditer(r"#\[pyfunction\]", text):
            sig = re.compile(r"\bfn\s+(\w+)").search(text, m.end())
            brace = text.index("{", text.index(")", sig.end()))
            # the body up to the matching brace
            depth, i = 0, brace
            while True:
                depth += {"{": 1, "}": -1}.get(text[i], 0)
                if depth == 0:
                    break
                i += 1
            out.append((path.name, sig.group(1), text[brace + 1:i]))
    return out


def test_every_binding_function_runs_in_the_guard():
    """Every #[pyfunction] body is one call of guard(..), so that a panic
    (a bug) reaches Python as a RuntimeError, never a PanicException."""
    functions = _pyfunctions()
    assert len(functions) >= 14, functions
    for file, name, body in functions:
        code = "\n".join(l for l in body.splitlines() if not l.strip().startswith("use "))
        assert re.match(r"\s*guard\(\s*\"", code), f"{file}: fn {name} does not run in guard()"


PANICS = re.compile(r"\.unwrap\(\)|\.expect\(|\bpanic!|\bunreachable!|\btodo!|\bunimplemented!|"
                    r"\bassert(_eq|_ne)?!|\bpanic_any\(")


def test_the_binding_has_no_explicit_panic():
    """No unwrap/expect/panic!/assert! in the binding: input errors are
    exceptions. The one allowed panic is the guard's self-test, marked on
    the line before it."""
    found = []
    for path in sorted(SRC.glob("*.rs")):
        lines = path.read_text().splitlines()
        for i, line in enumerate(lines):
            code = line.split("//", 1)[0]
            if PANICS.search(code) and not (i > 0 and "allowed panic:" in lines[i - 1]):
                found.append(f"{path.name}:{i + 1}: {line.strip()}")
    assert not found, "panicking calls in the binding:\n" + "\n".join(found)
