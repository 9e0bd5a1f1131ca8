#!/usr/bin/env python3
"""Class fractions against valence: the share of random NURDS configurations
(edge ratios uniform in [0.01, 0.99]) whose subdominant eigenvalues are
standard, real distinct, a complex pair, ... for n = 3..12.

    python3 python/examples/class_fractions.py [OUT_DIR]

Draws class_fractions.png with matplotlib when it is installed; otherwise
writes class_fractions.csv and a small hand-made class_fractions.svg.
"""
import sys
from pathlib import Path

import numpy as np

import subdiv_lab as sl

out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")
out.mkdir(parents=True, exist_ok=True)
valences = list(range(3, 13))
count = 20000
rng = np.random.default_rng(1)
fractions = {}
for n in valences:
    r = sl.classify_batch(rng.uniform(0.01, 0.99, (count, n)),
                          columns={"gap": False, "contraction": False})
    classes, counts = np.unique(r["class"].astype(str), return_counts=True)
    fractions[n] = dict(zip(classes, counts / count))
names = sorted({c for f in fractions.values() for c in f})
print("n," + ",".join(names))
for n in valences:
    print(f"{n}," + ",".join(f"{fractions[n].get(c, 0.0):.4f}" for c in names))

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4))
    for c in names:
        ax.plot(valences, [fractions[n].get(c, 0.0) for n in valences], marker="o", label=c)
    ax.set_xlabel("valence n")
    ax.set_ylabel(f"fraction of {count} random configurations")
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "class_fractions.png", dpi=120)
    print(f"wrote {out / 'class_fractions.png'}")
except ImportError:
    with open(out / "class_fractions.csv", "w") as f:
        f.write("n," + ",".join(names) + "\n")
        for n in valences:
            f.write(f"{n}," + ",".join(repr(fractions[n].get(c, 0.0)) for c in names) + "\n")
    w, h, pad = 640, 360, 50
    colours = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2"]
    x = lambda n: pad + (n - valences[0]) / (valences[-1] - valences[0]) * (w - 2 * pad)
    y = lambda v: h - pad - v * (h - 2 * pad)
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}">',
             f'<rect width="{w}" height="{h}" fill="white"/>',
             f'<line x1="{pad}" y1="{h - pad}" x2="{w - pad}" y2="{h - pad}" stroke="black"/>',
             f'<line x1="{pad}" y1="{pad}" x2="{pad}" y2="{h - pad}" stroke="black"/>']
    for n in valences:
        parts.append(f'<text x="{x(n)}" y="{h - pad + 16}" font-size="11" text-anchor="middle">{n}</text>')
    for i, c in enumerate(names):
        pts = " ".join(f"{x(n):.1f},{y(fractions[n].get(c, 0.0)):.1f}" for n in valences)
        col = colours[i % len(colours)]
        parts.append(f'<polyline points="{pts}" fill="none" stroke="{col}" stroke-width="2"/>')
        parts.append(f'<text x="{w - pad - 120}" y="{pad + 14 * i}" font-size="11" fill="{col}">{c}</text>')
    parts.append(f'<text x="{w / 2}" y="{h - 10}" font-size="12" text-anchor="middle">valence n</text>')
    parts.append("</svg>")
    (out / "class_fractions.svg").write_text("\n".join(parts) + "\n")
    print(f"wrote {out / 'class_fractions.csv'} and {out / 'class_fractions.svg'}")
