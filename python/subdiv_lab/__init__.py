"""subdiv-lab from Python: the local analysis of subdivision schemes and
parameter sweeps, returning numpy arrays and pyarrow Tables.

Every function mirrors a ``subdiv-lab`` command and calls the same library
code. Bad input raises ``ValueError`` with the command's message (arguments
spelled as Python keywords: ``threads``, ``force=True``); a wrong type
``TypeError``; any other failure ``RuntimeError``. No call panics or aborts
the interpreter: a bug inside the native code is a ``RuntimeError`` naming
the function.

Heavy work is estimated first and refused with ``ValueError`` above the
command-line tool's limits (4 GB, 60 s; one hour for ``sweep``,
``classify_batch`` and ``verify``), stating the estimate; ``force=True`` runs
anyway, except above the machine's physical memory. Heavy work runs on all
cores (or ``threads``) with the GIL released.

A spec (``sweep``, ``merge``, ``verify``, ``report``) is a dict with the
TOML's structure (errors name the dict key, ``spec['sampler']['count']``), a
path (``str`` or ``os.PathLike``), or TOML text. A ``str`` is a path when it
has no line break and names an existing file, ends in ``.toml``, or holds no
``=`` (no TOML key can be set without one); otherwise it is TOML text. A path
that cannot be read raises ``ValueError`` naming it.
"""
from __future__ import annotations

import json
import math
import os
import tempfile
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native

__version__ = _native.__version__

__all__ = ["matrix", "analyze", "classify_batch", "sweep", "merge", "subdivide", "report",
           "verify", "g2_cap", "plot", "cc_study", "ccss_bound", "__version__"]

Spec = Union[str, "os.PathLike[str]", Mapping[str, Any]]


def _knots(knots):
    """``knots`` as a list of ``(p, q)`` float pairs, or ``None``."""
    return None if knots is None else [(float(p), float(q)) for p, q in knots]


def _floats(xs):
    """``xs`` as a list of floats, or ``None``."""
    return None if xs is None else [float(x) for x in xs]


def _float(x):
    """``x`` as a float, or ``None``."""
    return None if x is None else float(x)


def matrix(scheme: str = "nurds", valence: Optional[int] = None, knots=None, ratios=None,
           uniform: bool = False, c: Optional[float] = None, block: str = "full",
           force: bool = False) -> Tuple[np.ndarray, List[str]]:
    """The local subdivision matrix (``subdiv-lab matrix``).

    Give one of ``knots`` (``n`` pairs ``(p_i, q_i)`` of corner knot intervals),
    ``ratios`` (``n`` edge ratios in (0, 1)) or ``uniform=True``; schemes
    without knots take ``valence`` alone. ``block="face"`` returns the ``n x n``
    face block. Returns ``(matrix, row_labels)``. Refused above the limits
    (``force=True`` overrides, except above the physical memory).
    """
    return _native.matrix(scheme, valence, _knots(knots), _floats(ratios), bool(uniform),
                          _float(c), block, bool(force))


def _read_scheme_file(scheme_file) -> str:
    try:
        with open(os.fspath(scheme_file), encoding="utf-8") as f:
            return f.read()
    except (OSError, UnicodeDecodeError) as e:
        raise ValueError(f"scheme_file {os.fspath(scheme_file)}: cannot read: {e}") from None


def analyze(scheme=None, valence: Optional[int] = None, knots=None, ratios=None,
            uniform: bool = False, c: Optional[float] = None, path: str = "full",
            levels: int = 60, seed: int = 0x5EED, force: bool = False,
            scheme_file: Optional[Union[str, os.PathLike]] = None,
            matrix=None, labels: Optional[Sequence[str]] = None,
            charmap: str = "ring") -> Dict[str, Any]:
    """Spectrum, subdominant class, Theorem 1 and the characteristic-map
    verdict of one configuration: the dict of ``subdiv-lab analyze --json``
    (same keys, including ``input`` and ``tool_version``).

    The configuration is one of:

    * ``scheme``: a built-in scheme's name (default ``"nurds"``) with
      ``valence``, ``knots``, ``ratios``, ``uniform`` or ``c``;
    * ``scheme_file``: a scheme file (TOML, ``docs/scheme-files.md``) with
      ``valence``;
    * ``scheme``: an object of one's own with a ``name`` (str) and a method
      ``matrix(valence) -> (S, labels)``, with ``valence``: ``S`` is its local
      subdivision matrix at that valence, ``labels`` ``None`` or one label per
      row (below);
    * ``matrix``: a local subdivision matrix one computed (any array-like),
      with ``labels`` (optional) and ``valence`` (optional).

    A matrix must be square, finite, and its rows must sum to 1 within
    ``ROW_SUM_TOL = 1e-12`` (``ValueError`` naming the row or entry
    otherwise). Labels are those :func:`matrix` returns: ``v``, ``e<i>``,
    ``f<i>``, ``g<i>`` (vertex-centred), ``P<i>``, ``E<i>,1``, ``E<i>,2``,
    ``C<i>`` (face-centred), ``o<i>``, ``X<i>``; with them the analysis
    certifies double eigenvalues by the rotation symmetry of the sectors.
    Without ``valence`` it is the number of ``e`` labels, else of ``P``
    labels, else the number of rows. An exception raised by the object's
    ``matrix`` propagates as it is.

    ``charmap`` picks the characteristic-map certificate, as ``analyze
    --charmap``: ``"ring"`` (the scheme's ring of polynomial patches) or
    ``"generic"`` (any vertex-centred scheme, from its local matrix and its
    regular rules; ``docs/guide/is-it-c1.md``). A scheme object gives its
    regular rules through its own ``matrix`` at the regular valence: its
    ``regular_valence`` attribute (4 or 6) when it has one, else 6 when its
    labels include second-ring points ``g``, 4 when they include face
    neighbours ``f``. A bare ``matrix`` has no regular rules, so its generic
    verdict is ``indeterminate`` with that reason.

    ``levels`` is 1..10000. Refused above the limits, e.g. ``valence=600``
    (~7 min); ``force=True`` overrides, except above the physical memory."""
    builtin_args = knots is not None or ratios is not None or uniform or c is not None
    if matrix is not None:
        if scheme is not None or scheme_file is not None or builtin_args:
            raise ValueError("matrix is mutually exclusive with scheme, scheme_file, knots, ratios, uniform and c")
        text = _native.analyze_matrix_json(matrix, None if labels is None else [str(x) for x in labels],
                                           valence, "matrix", path, levels, seed, bool(force),
                                           charmap)
        return json.loads(text)
    if labels is not None:
        raise ValueError("labels go with matrix")
    if scheme_file is not None:
        if scheme is not None or builtin_args:
            raise ValueError("scheme_file is mutually exclusive with scheme, knots, ratios, uniform and c")
        if valence is None:
            raise ValueError("valence is required with scheme_file")
        file_text = _read_scheme_file(scheme_file)
        text = _native.analyze_file_json(file_text, valence, path, levels, seed, bool(force), charmap)
        return json.loads(text)
    if scheme is not None and not isinstance(scheme, str):
        if builtin_args:
            raise ValueError("a scheme object takes valence only (not knots, ratios, uniform or c)")
        if valence is None:
            raise ValueError("valence is required with a scheme object")
        return json.loads(_native.analyze_object_json(scheme, valence, path, levels, seed, bool(force),
                                                      charmap))
    text = _native.analyze_json(scheme if scheme is not None else "nurds", valence, _knots(knots),
                                _floats(ratios), bool(uniform), _float(c), path, levels, seed,
                                bool(force), charmap)
    return json.loads(text)


def classify_batch(ratios, scheme: str = "nurds", columns: Optional[Mapping[str, Any]] = None,
                   threads: Optional[int] = None, force: bool = False) -> Dict[str, np.ndarray]:
    """Classify many configurations at once: ``ratios`` is an ``(m, n)`` array,
    one row of edge ratios per configuration of valence ``n`` (``m = 0`` gives
    empty arrays).

    ``columns`` is the sweep spec's ``[columns]`` table (default: class,
    lambda1, lambda2, |lambda3|, gap, ratio/rho/theta, contraction rate).
    Returns a dict of numpy arrays with the sweep's column names
    (``class``, ``lambda1_re``, ``lambda1_im``, ..., missing values NaN, empty
    strings for text), the complex ``lambda1`` and ``lambda2``, and ``error``.
    The values equal those of a ratios sweep over the same configurations.
    Runs on all cores (or ``threads``) with the GIL released; refused above
    the sweep limits (``force=True`` overrides, except above the physical
    memory).
    """
    r = np.ascontiguousarray(np.asarray(ratios, dtype=np.float64))
    if r.ndim != 2:
        raise ValueError(f"ratios must be a 2-D array (m, n), got {r.ndim} dimensions")
    cols = None if columns is None else json.dumps(_plain(dict(columns), "columns"))
    raw = _native.classify_batch(r, scheme, cols, threads, bool(force))
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


def _plain(value, key):
    """A dict spec as JSON-ready values (numpy scalars and arrays as Python
    ones); anything TOML cannot hold is a ValueError naming its key."""
    if isinstance(value, Mapping):
        out = {}
        for k, v in value.items():
            if not isinstance(k, str):
                raise ValueError(f"{key}: keys must be strings, got {k!r}")
            out[k] = _plain(v, f"{key}[{k!r}]")
        return out
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        return [_plain(v, f"{key}[{i}]") for i, v in enumerate(value)]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, (bool, int, str)):
        return value
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ValueError(f"{key}: {value!r} is not a finite number")
        return value
    raise ValueError(f"{key}: {value!r} ({type(value).__name__}) is not a TOML value")


def _is_path(spec) -> bool:
    """The rule of the module docstring: a str without a line break is a
    path when it names a file, ends in .toml, or holds no '='."""
    if isinstance(spec, os.PathLike):
        return True
    return (isinstance(spec, str) and "\n" not in spec
            and (spec.endswith(".toml") or "=" not in spec or os.path.isfile(spec)))


def _spec(spec: Spec) -> Tuple[str, Optional[str], bool]:
    """``(TOML text, path or None, from a dict)`` of a spec argument."""
    if isinstance(spec, Mapping):
        return _native.spec_json_to_toml(json.dumps(_plain(spec, "spec"))), None, True
    if _is_path(spec):
        path = os.fspath(spec)
        try:
            with open(path, encoding="utf-8") as f:
                return f.read(), path, False
        except OSError as e:
            raise ValueError(f"cannot read spec {path}: {e.strerror or e}") from None
        except UnicodeDecodeError:
            raise ValueError(f"cannot read spec {path}: not UTF-8 text") from None
    if isinstance(spec, str):
        return spec, None, False
    raise TypeError(f"spec must be a dict, a path or TOML text, got {type(spec).__name__}")


def _table(names, raw):
    """The columns of the native ``sweep``/``merge`` as a ``pyarrow.Table``."""
    import pyarrow as pa

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
    # The null rules of the sweep's schema (as in its Parquet files): ``id`` and
    # ``valence`` are never null.
    fields = [pa.field(name, a.type, nullable=name not in ("id", "valence"))
              for name, a in zip(names, arrays)]
    return pa.Table.from_arrays(arrays, schema=pa.schema(fields))


def sweep(spec: Spec, threads: Optional[int] = None,
          shard: Optional[Union[str, Tuple[int, int]]] = None, limit: Optional[int] = None,
          force: bool = False, scheme_file: Optional[Union[str, os.PathLike]] = None,
          scheme=None, out: Optional[Union[str, os.PathLike]] = None, resume: bool = False):
    """Run a sweep in memory and return its rows as a ``pyarrow.Table``
    (``.to_pandas()``, ``polars.from_arrow(...)``), without writing a CSV.

    With ``out``, the rows go to that file instead, as ``subdiv-lab sweep
    --out`` writes them: ``NAME.parquet`` a Parquet dataset directory, any
    other name a CSV, with the summary JSON beside it; the summary (a dict)
    is returned. An existing output is refused unless ``resume=True``, which
    verifies its rows against the spec and continues it (the same bytes as
    an uninterrupted run). Shards (``shard=``) of one Parquet ``out`` form
    one dataset.

    ``spec`` is a dict, a path or TOML text (module docstring).
    ``shard="I/N"`` or ``(I, N)`` keeps the ids ``id % N == I``;
    ``limit`` keeps the first ``limit`` ids of the shard. Columns: ``id``
    (uint64), ``valence`` (uint32), the coordinates and numeric results
    (float64, null where the CSV cell is empty), text results (string) and
    ``error`` (string, null when the row succeeded). Refused above the sweep
    limit (one hour) or when the rows would not fit in memory
    (``force=True`` overrides the limits, never the physical memory).

    A scheme of one's own replaces the spec's scheme and sweeps the spec's
    valences through the same engine, with the same columns:
    ``scheme_file`` (a scheme file, as ``subdiv-lab sweep --scheme-file``) or
    ``scheme`` (an object with ``name`` and ``matrix(valence) -> (S,
    labels)``, as in :func:`analyze`; it is called at valences 3 and 4 first
    for the work estimate, then once per valence, with the GIL held). The
    spec's ``space.kind`` must be ``"uniform"`` and
    ``columns.exact_certificate`` off. An exception raised by the object's
    code propagates as it is.
    """
    if scheme is not None and isinstance(scheme, str):
        raise ValueError("sweep: scheme takes an object with name and matrix(valence); a built-in scheme is the spec's scheme key")
    file_text = None if scheme_file is None else _read_scheme_file(scheme_file)
    if isinstance(shard, str):
        try:
            i, n = (int(x) for x in shard.split("/"))
        except ValueError:
            raise ValueError(f"shard must be I/N with 0 <= I < N, got {shard!r}") from None
        shard = (i, n)
    text, path, from_dict = _spec(spec)
    if resume and out is None:
        raise ValueError("sweep: resume=True needs out=FILE (a CSV file or a NAME.parquet dataset)")
    result = _native.sweep(text, path, from_dict, threads, shard, limit, bool(force),
                           file_text, scheme, None if out is None else os.fspath(out),
                           bool(resume))
    if out is not None:
        return json.loads(result)
    names, raw = result
    return _table(names, raw)


def merge(inputs: Sequence[Union[str, "os.PathLike[str]"]], spec: Spec, force: bool = False):
    """Merge the shards of one sweep (``subdiv-lab merge``): CSV files
    written by ``subdiv-lab sweep --shard I/N --out ...``, each with its
    ``.summary.json`` beside it, or Parquet dataset directories (every
    shard's part files in them). Every row is verified as the
    command verifies it (fingerprints, ids, parameters re-derived, a random
    sample re-evaluated; every configuration present once; the summaries
    matching their rows).

    Returns ``(table, summary)``: the rows as the ``pyarrow.Table`` of
    :func:`sweep` and the merged summary (the dict of the command's
    ``.summary.json``). Nothing is written. Refused when the rows would not
    fit in the memory limit (``force=True`` overrides, except above the
    physical memory).
    """
    if isinstance(inputs, (str, os.PathLike)):
        inputs = [inputs]
    paths = [os.fspath(p) for p in inputs]
    text, path, from_dict = _spec(spec)
    names, raw, summary = _native.merge(paths, text, path, from_dict, bool(force))
    return _table(names, raw), json.loads(summary)


def subdivide(vertices, faces: Sequence[Sequence[int]], scheme: str = "nurds",
              knots: Optional[Mapping[Tuple[int, int], float]] = None, levels: int = 1,
              c: Optional[float] = None, force: bool = False) -> Tuple[np.ndarray, List[List[int]]]:
    """``levels`` refinement steps of a closed polygon mesh
    (``subdiv-lab subdivide``). ``vertices`` is ``(m, 3)``; ``faces`` lists
    vertex indices per face (counter-clockwise). ``knots`` maps a directed
    edge ``(u, v)`` to its knot interval (NURDS; default 1). Returns
    ``(vertices, faces)`` of the refined mesh. Refused above the limits
    (``force=True`` overrides, except above the physical memory)."""
    v = np.ascontiguousarray(np.asarray(vertices, dtype=np.float64))
    if v.ndim != 2:
        raise ValueError(f"vertices must have shape (m, 3), got {v.shape}")
    k = None if knots is None else [((a, b), float(x)) for (a, b), x in knots.items()]
    return _native.subdivide(v, [list(f) for f in faces], scheme, k, levels, _float(c),
                             bool(force))


def report(spec: Spec, out: Union[str, "os.PathLike[str]"]) -> List[str]:
    """Generate a report (``subdiv-lab report SPEC --out OUT``): ``spec`` is a
    dict, a path or TOML text (module docstring); ``out`` must be a new or
    empty directory. Returns the names of the files written (``index.html``,
    the figures as SVG and PNG with their CSV data, ``manifest.json``)."""
    text, path, from_dict = _spec(spec)
    out = os.fspath(out)
    if os.path.exists(out):
        if not os.path.isdir(out):
            raise ValueError(f"--out {out} exists and is not a directory; give a new or empty directory")
        if os.listdir(out):
            raise ValueError(f"--out {out} is not empty; give a new or empty directory")
    files = _native.report_files(text, path, from_dict)
    os.makedirs(out, exist_ok=True)
    for name, data in files:
        with open(os.path.join(out, name), "wb") as f:
            f.write(data)
    return [name for name, _ in files]


def verify(spec: Spec, threads: Optional[int] = None, max_cells: Optional[int] = None,
           force: bool = False):
    """Certified verdicts over a box of edge ratios or an interval of ``c``
    (``subdiv-lab verify``): ``spec`` is a dict, a path or TOML text (module
    docstring) with scheme, valence, box or c_range, properties, min_width,
    time_budget. ``max_cells`` caps the evaluated cells (default 4,000,000).

    Returns ``(summary, cells)``: the dict of the command's ``summary.json``
    and its ``cells.csv`` as a ``pyarrow.Table``. Nothing is written. Refused
    above the limits (one hour; ``force=True`` overrides, except above the
    physical memory).
    """
    import pyarrow as pa
    import pyarrow.csv as pacsv

    text, path, from_dict = _spec(spec)
    summary, cells = _native.verify(text, path, from_dict, threads, max_cells, bool(force))
    header = cells.split("\n", 1)[0].split(",")
    ends = ("c_lo", "c_hi")
    types = {name: (pa.float64() if name in ends or (name[:2] in ("lo", "hi") and name[2:].isdigit())
                    else pa.string())
             for name in header}
    table = pacsv.read_csv(pa.py_buffer(cells.encode()),
                           convert_options=pacsv.ConvertOptions(column_types=types))
    return json.loads(summary), table


def g2_cap(c: float, vertices=None, faces: Optional[Sequence[Sequence[int]]] = None,
           vertex: Optional[int] = None, valence: Optional[int] = None,
           random_net: Optional[int] = None, samples: Optional[int] = None) -> Dict[str, Any]:
    """The G2 cap of bidegree (7, 7) around an extraordinary vertex
    (``subdiv-lab g2-cap``): give ``vertices`` (``(m, 3)``), ``faces`` and
    ``vertex`` (its 0-based index; the mesh may be open away from its 2-ring),
    or ``valence`` and ``random_net`` (the seed of a generated test net).
    ``c`` is the shape parameter in [0, 1] (0.5 = Catmull-Clark).

    Returns the dict of ``g2-cap --json`` (patches, residuals and their
    definitions, energy). With ``samples`` (1..256), also ``"mesh"``:
    ``{"vertices": (k, 3) array, "quads": (q, 4) array}``, the cap sampled on
    ``samples x samples`` quads per patch (the OBJ that ``-o`` writes). A
    residual above the tolerance raises ``RuntimeError``.
    """
    v = None if vertices is None else np.ascontiguousarray(np.asarray(vertices, dtype=np.float64))
    if v is not None and v.ndim != 2:
        raise ValueError(f"vertices must have shape (m, 3), got {v.shape}")
    f = None if faces is None else [list(face) for face in faces]
    text, mesh = _native.g2_cap(float(c), v, f, vertex, valence, random_net, samples)
    out = json.loads(text)
    if mesh is not None:
        pts, quads = mesh
        out["mesh"] = {"vertices": pts, "quads": np.asarray(quads, dtype=np.int64).reshape(-1, 4)}
    return out


def plot(data, out: Optional[Union[str, "os.PathLike[str]"]] = None, kind: Optional[str] = None,
         x: Optional[str] = None, y: Optional[str] = None, color: Optional[str] = None,
         title: Optional[str] = None, width: int = 1600, height: int = 1000,
         format: Optional[str] = None, force: bool = False) -> bytes:
    """A figure of a sweep's results (``subdiv-lab plot``): ``data`` is the
    path of a sweep CSV or Parquet file, or a ``pyarrow.Table`` (e.g. of
    :func:`sweep`). ``kind`` is fractions, histogram, scatter or map (default:
    chosen from the data); ``x``, ``y``, ``color`` name columns; ``width`` and
    ``height`` are pixels (400..8000).

    Returns the figure's bytes (SVG text or PNG). ``out`` (``.svg`` or
    ``.png``) also writes it, replacing an existing file atomically;
    without ``out``, ``format`` is ``"svg"`` (default) or ``"png"``. Refused
    above the limits (``force=True`` overrides, except above the physical
    memory).
    """
    if out is not None:
        target = os.fspath(out)
        ext = os.path.splitext(target)[1]
        if ext not in (".svg", ".png") or (format is not None and format != ext[1:]):
            raise ValueError(f"out {target}: give a file name ending in .svg or .png"
                             + ("" if format is None else f" matching format={format!r}"))
        if os.path.isdir(target):
            raise ValueError(f"out {target} is a directory; give a file path")
        svg = ext == ".svg"
    else:
        if format not in (None, "svg", "png"):
            raise ValueError(f"format must be \"svg\" or \"png\", got {format!r}")
        svg = format != "png"
    if isinstance(data, (str, os.PathLike)):
        name = os.fspath(data)
        try:
            with open(name, "rb") as f:
                raw = f.read()
        except OSError as e:
            raise ValueError(f"cannot read {name}: {e.strerror or e}") from None
    else:
        import pyarrow as pa
        import pyarrow.csv as pacsv

        if not isinstance(data, pa.Table):
            raise TypeError(f"data must be a path or a pyarrow.Table, got {type(data).__name__}")
        sink = pa.BufferOutputStream()
        pacsv.write_csv(data, sink)
        raw, name = sink.getvalue().to_pybytes(), "the table"
    figure = _native.plot(raw, name, svg, kind, x, y, color, title, width, height, bool(force))
    if out is not None:
        target = os.fspath(out)
        fd, tmp = tempfile.mkstemp(dir=os.path.dirname(target) or ".",
                                   prefix="." + os.path.basename(target) + ".")
        try:
            with os.fdopen(fd, "wb") as f:
                f.write(figure)
            os.replace(tmp, target)
        except BaseException:
            os.unlink(tmp)
            raise
    return figure


def cc_study(n_min: int = 3, n_max: int = 32, samples: int = 100, tol: float = 1e-6,
             curves: bool = False, criterion: str = "c1", force: bool = False):
    """The shape-adjustable Catmull-Clark parameter study (``subdiv-lab
    cc-study``) as a ``pyarrow.Table`` with the command's CSV columns: the
    certified intervals of ``c`` per valence (``criterion`` ``"c1"`` or
    ``"standard"``, ends bisected to ``tol``), or with ``curves=True`` one row
    per ``(n, c)`` on ``samples + 1`` values of ``c`` (eigenvalues, class,
    characteristic-map verdict). Refused above the limits (``force=True``
    overrides, except above the physical memory)."""
    import pyarrow as pa

    rows = json.loads(_native.cc_study(n_min, n_max, samples, float(tol), bool(curves),
                                       criterion, bool(force)))
    if curves:
        schema = pa.schema([("n", pa.int64()), ("c", pa.float64()),
                            ("lambda1_re", pa.float64()), ("lambda1_im", pa.float64()),
                            ("lambda2_re", pa.float64()), ("lambda2_im", pa.float64()),
                            ("abs_lambda3", pa.float64()), ("class", pa.string()),
                            ("fourier_subdominant", pa.float64()), ("charmap", pa.string()),
                            ("error", pa.string())])
    else:
        schema = pa.schema([("n", pa.int64()), ("interval", pa.int64()),
                            ("c_lo", pa.float64()), ("c_hi", pa.float64()),
                            ("c_lo_outside", pa.float64()), ("c_hi_outside", pa.float64()),
                            ("below", pa.string()), ("above", pa.string())])
    return pa.Table.from_pylist(rows, schema=schema)


def ccss_bound(valence: Optional[int] = None, levels: int = 4, table_to: Optional[int] = None,
               net=None, epsilon: Optional[float] = None, force: bool = False):
    """The distance bound beta(n) between an extraordinary Catmull-Clark
    patch and its limit face (``subdiv-lab ccss-bound``).

    With ``valence``: the dict of ``ccss-bound --json`` (``beta``, ``t_max``,
    ``c_omega_1_2``, ``contraction``, ...); with ``net`` (``2n + 8`` control
    points, any dimension) and ``epsilon``, ``"steps"`` holds the subdivision
    steps that bring its limit mesh within ``epsilon``. With ``table_to=N``:
    the beta(n) table for ``n = 3..N`` as a ``pyarrow.Table`` (the CSV's
    columns). ``levels`` is 1..12. Refused above the limits (``force=True``
    overrides, except above the physical memory).
    """
    pts = None
    if net is not None:
        a = np.asarray(net, dtype=np.float64)
        if a.ndim != 2:
            raise ValueError(f"net must be a 2-D array (2n + 8 points, k coordinates), got {a.ndim} dimensions")
        pts = a.tolist()
    text = _native.ccss_bound(valence, levels, table_to, pts, _float(epsilon), bool(force))
    doc = json.loads(text)
    if table_to is not None:
        import pyarrow as pa

        return pa.Table.from_pylist(doc)
    return doc
