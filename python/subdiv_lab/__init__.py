"""subdiv-lab from Python: the local analysis of subdivision schemes and
parameter sweeps, returning numpy arrays and pyarrow Tables.

Every function mirrors a ``subdiv-lab`` command. Bad input raises
``ValueError`` with the command's message; any other failure ``RuntimeError``.
Heavy work runs on all cores with the GIL released.
"""
from __future__ import annotations

import json
import os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native

__version__ = _native.__version__

__all__ = ["matrix", "analyze", "classify_batch", "sweep", "subdivide", "report", "__version__"]


def _knots(knots):
    return None if knots is None else [(float(p), float(q)) for p, q in knots]


def _floats(xs):
    return None if xs is None else [float(x) for x in xs]


def matrix(scheme: str = "nurds", valence: Optional[int] = None, knots=None, ratios=None,
           uniform: bool = False, c: Optional[float] = None, block: str = "full"
           ) -> Tuple[np.ndarray, List[str]]:
    """The local subdivision matrix (``subdiv-lab matrix``).

    Give one of ``knots`` (``n`` pairs ``(p_i, q_i)`` of corner knot intervals),
    ``ratios`` (``n`` edge ratios in (0, 1)) or ``uniform=True``; schemes
    without knots take ``valence`` alone. ``block="face"`` returns the ``n x n``
    face block. Returns ``(matrix, row_labels)``.
    """
    return _native.matrix(scheme, valence, _knots(knots), _floats(ratios), bool(uniform),
                          None if c is None else float(c), block)


def analyze(scheme: str = "nurds", valence: Optional[int] = None, knots=None, ratios=None,
            uniform: bool = False, c: Optional[float] = None, path: str = "full",
            levels: int = 60, seed: int = 0x5EED) -> Dict[str, Any]:
    """Spectrum, subdominant class, Theorem 1 and the characteristic-map
    verdict of one configuration: the dict of ``subdiv-lab analyze --json``
    (same keys, including ``input`` and ``tool_version``)."""
    text = _native.analyze_json(scheme, valence, _knots(knots), _floats(ratios), bool(uniform),
                                None if c is None else float(c), path, int(levels), int(seed))
    return json.loads(text)


def classify_batch(ratios, scheme: str = "nurds", columns: Optional[Mapping[str, Any]] = None,
                   threads: Optional[int] = None) -> Dict[str, np.ndarray]:
    """Classify many configurations at once: ``ratios`` is an ``(m, n)`` array,
    one row of edge ratios per configuration of valence ``n``.

    ``columns`` is the sweep spec's ``[columns]`` table (default: class,
    lambda1, lambda2, |lambda3|, gap, ratio/rho/theta, contraction rate).
    Returns a dict of numpy arrays with the sweep's column names
    (``class``, ``lambda1_re``, ``lambda1_im``, ..., missing values NaN, empty
    strings for text), the complex ``lambda1`` and ``lambda2``, and ``error``.
    The values equal those of a ratios sweep over the same configurations.
    Runs on all cores (or ``threads``) with the GIL released.
    """
    r = np.ascontiguousarray(np.asarray(ratios, dtype=np.float64))
    if r.ndim != 2:
        raise ValueError(f"ratios must be a 2-D array (m, n), got {r.ndim} dimensions")
    cols = None if columns is None else json.dumps(dict(columns))
    raw = _native.classify_batch(r, scheme, cols, threads)
    out: Dict[str, np.ndarray] = {}
    for name, value in raw.items():
        if name == "error" or len(value) == 3:
            # text: codes into a few distinct values (expanded here, in numpy)
            codes, levels = value[0], value[1]
            out[name] = np.asarray(levels, dtype=object)[codes]
        else:
            values, _valid = value
            out[name] = values
    if "lambda1_re" in out:
        out["lambda1"] = out["lambda1_re"] + 1j * out["lambda1_im"]
        out["lambda2"] = out["lambda2_re"] + 1j * out["lambda2_im"]
    return out


def _spec_text(spec: Union[str, os.PathLike, Mapping[str, Any]]) -> str:
    if isinstance(spec, Mapping):
        return _native.spec_json_to_toml(json.dumps(spec))
    if _is_path(spec):
        with open(spec, encoding="utf-8") as f:
            return f.read()
    return str(spec)


def sweep(spec: Union[str, os.PathLike, Mapping[str, Any]], threads: Optional[int] = None,
          shard: Optional[Union[str, Tuple[int, int]]] = None, limit: Optional[int] = None):
    """Run a sweep in memory and return its rows as a ``pyarrow.Table``
    (``.to_pandas()``, ``polars.from_arrow(...)``), without writing a CSV.

    ``spec`` is the TOML text, a path to a ``.toml`` file, or a dict with the
    TOML's structure. ``shard="I/N"`` or ``(I, N)`` keeps the ids ``id % N == I``;
    ``limit`` keeps the first ``limit`` ids of the shard. Columns: ``id``
    (uint64), ``valence`` (uint32), the coordinates and numeric results
    (float64, null where the CSV cell is empty), text results (string) and
    ``error`` (string, null when the row succeeded).
    """
    import pyarrow as pa

    if isinstance(shard, str):
        try:
            i, n = (int(x) for x in shard.split("/"))
        except ValueError:
            raise ValueError(f"shard must be I/N with 0 <= I < N, got {shard!r}") from None
        shard = (i, n)
    if shard is not None and (shard[0] < 0 or shard[1] <= 0):
        raise ValueError(f"shard must be I/N with 0 <= I < N, got {shard[0]}/{shard[1]}")
    if limit is not None and limit < 0:
        raise ValueError(f"limit must be >= 0, got {limit}")
    names, raw = _native.sweep(_spec_text(spec), threads, shard, limit)
    arrays = []
    for name in names:
        value = raw[name]
        if name in ("id", "valence"):
            arrays.append(pa.array(value))
        elif name == "error":
            arrays.append(pa.array([e if e else None for e in value], type=pa.string()))
        else:
            values, valid = value
            mask = ~np.asarray(valid, dtype=bool)
            if isinstance(values, np.ndarray):
                arrays.append(pa.array(values, type=pa.float64(), mask=mask))
            else:
                arrays.append(pa.array(values, type=pa.string(), mask=mask))
    return pa.Table.from_arrays(arrays, names=names)


def subdivide(vertices, faces: Sequence[Sequence[int]], scheme: str = "nurds",
              knots: Optional[Mapping[Tuple[int, int], float]] = None, levels: int = 1,
              c: Optional[float] = None) -> Tuple[np.ndarray, List[List[int]]]:
    """``levels`` refinement steps of a closed polygon mesh
    (``subdiv-lab subdivide``). ``vertices`` is ``(m, 3)``; ``faces`` lists
    vertex indices per face (counter-clockwise). ``knots`` maps a directed
    edge ``(u, v)`` to its knot interval (NURDS; default 1). Returns
    ``(vertices, faces)`` of the refined mesh."""
    v = np.ascontiguousarray(np.asarray(vertices, dtype=np.float64))
    if v.ndim != 2:
        raise ValueError(f"vertices must have shape (m, 3), got {v.shape}")
    k = None if knots is None else [((int(a), int(b)), float(x)) for (a, b), x in knots.items()]
    return _native.subdivide(v, [list(map(int, f)) for f in faces], scheme, k, int(levels),
                             None if c is None else float(c))


def report(spec: Union[str, os.PathLike, Mapping[str, Any]], out: Union[str, os.PathLike]) -> List[str]:
    """Generate a report (``subdiv-lab report SPEC --out OUT``): ``spec`` is the
    TOML text, a path to a ``.toml`` file or a dict; ``out`` must be a new or
    empty directory. Returns the names of the files written (``index.html``,
    the figures as SVG and PNG with their CSV data, ``manifest.json``)."""
    path = os.fspath(spec) if isinstance(spec, (str, os.PathLike)) and _is_path(spec) else None
    text = _spec_text(spec)
    out = os.fspath(out)
    if os.path.exists(out):
        if not os.path.isdir(out):
            raise ValueError(f"--out {out} exists and is not a directory; give a new or empty directory")
        if os.listdir(out):
            raise ValueError(f"--out {out} is not empty; give a new or empty directory")
    files = _native.report_files(text, path)
    os.makedirs(out, exist_ok=True)
    for name, data in files:
        with open(os.path.join(out, name), "wb") as f:
            f.write(data)
    return [name for name, _ in files]


def _is_path(spec) -> bool:
    return isinstance(spec, os.PathLike) or (isinstance(spec, str) and "\n" not in spec
                                             and spec.endswith(".toml"))
