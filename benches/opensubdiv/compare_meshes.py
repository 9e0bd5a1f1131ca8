#!/usr/bin/env python3
"""Compare two OBJ meshes whose vertices are numbered differently (used by
benches/opensubdiv/compare_loop.sh and benches/cgal/compare_loop.sh; not part
of the crate's build or CI).

    compare_meshes.py REFERENCE.obj OURS.obj

Every vertex of OURS is matched to the nearest vertex of REFERENCE through a
grid hash (cell 1e-6 of the bounding box; a vertex with no reference vertex in
its 27 neighbouring cells is "unmatched"). Then the triangles of OURS, mapped
through the matching, are compared with REFERENCE's as oriented cycles.
Prints one line:

    <V> vertices, <F> faces; unmatched <u>; matching one-to-one <yes|no>;
    faces equal <yes|no: k differ>; max distance <d> (relative <d / size>)

where the distance is Euclidean and size is the largest coordinate magnitude.
"""
import math
import sys


def load(path):
    vs, fs = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                vs.append(tuple(float(x) for x in line.split()[1:4]))
            elif line.startswith("f "):
                fs.append(tuple(int(t.split("/")[0]) - 1 for t in line.split()[1:]))
    return vs, fs


def canonical(face):
    i = face.index(min(face))
    return face[i:] + face[:i]


def main():
    ref_v, ref_f = load(sys.argv[1])
    our_v, our_f = load(sys.argv[2])
    if len(ref_v) != len(our_v) or len(ref_f) != len(our_f):
        print(f"MISMATCH counts: reference {len(ref_v)} v {len(ref_f)} f, ours {len(our_v)} v {len(our_f)} f")
        return
    size = max(max(abs(x) for x in p) for p in ref_v)
    lo = [min(p[k] for p in ref_v) for k in range(3)]
    hi = [max(p[k] for p in ref_v) for k in range(3)]
    cell = 1e-6 * max(max(h - l for h, l in zip(hi, lo)), 1e-300)
    grid = {}
    for i, p in enumerate(ref_v):
        grid.setdefault(tuple(math.floor(x / cell) for x in p), []).append(i)
    worst, unmatched = 0.0, 0
    to_ref = []
    for q in our_v:
        k = tuple(math.floor(x / cell) for x in q)
        best, best_i = None, -1
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for i in grid.get((k[0] + dx, k[1] + dy, k[2] + dz), ()):
                        d = math.dist(ref_v[i], q)
                        if best is None or d < best:
                            best, best_i = d, i
        if best is None:
            unmatched += 1
        else:
            worst = max(worst, best)
        to_ref.append(best_i)
    one_to_one = unmatched == 0 and len(set(to_ref)) == len(to_ref)
    ref_faces = {canonical(f) for f in ref_f}
    differ = sum(1 for f in our_f if canonical(tuple(to_ref[v] for v in f)) not in ref_faces)
    faces = "yes" if differ == 0 else f"no: {differ} differ"
    print(
        f"{len(ref_v)} vertices, {len(ref_f)} faces; unmatched {unmatched}; "
        f"matching one-to-one {'yes' if one_to_one else 'no'}; faces equal {faces}; "
        f"max distance {worst:.3e} (relative {worst / size:.3e})"
    )


if __name__ == "__main__":
    main()
