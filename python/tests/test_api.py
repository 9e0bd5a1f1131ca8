"""The Python API against the CLI (same JSON, same rows, same messages) and
its own invariants. Needs the release binary (built by `cargo test --release`
or `cargo build --release`; override with SUBDIV_LAB_BIN)."""
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pyarrow as pa
import pytest

import subdiv_lab as sl

ROOT = Path(__file__).resolve().parents[2]
BIN = os.environ.get("SUBDIV_LAB_BIN", str(ROOT / "target" / "release" / "subdiv-lab"))


def cli(*args, check=True):
    assert Path(BIN).exists(), f"{BIN} missing: run cargo build --release first"
    p = subprocess.run([BIN, *args], capture_output=True, text=True)
    if check:
        assert p.returncode == 0, p.stderr
    return p


SPEC = """name = "py"
scheme = "nurds"
valences = [3, 5]
[space]
kind = "ratios"
ratio_range = [0.01, 0.99]
[sampler]
kind = "random"
count = 300
seed = 4
"""


def test_matrix_equals_cli_json():
    m, labels = sl.matrix(ratios=[0.3, 0.5, 0.7, 0.2])
    doc = json.loads(cli("matrix", "--ratios", "0.3,0.5,0.7,0.2", "--format", "json").stdout)
    assert labels == doc["rows"]
    assert m.shape == (16, 16)
    assert np.array_equal(m, np.array(doc["matrix"], dtype=float))
    # affine invariance: every row of S_n sums to 1
    assert np.allclose(m.sum(axis=1), 1.0, atol=1e-14)
    face, flabels = sl.matrix(ratios=[0.3, 0.5, 0.7, 0.2], block="face")
    assert face.shape == (4, 4) and flabels == labels[:4]
    assert np.array_equal(face, m[:4, :4])


def test_analyze_equals_cli_json():
    a = sl.analyze(knots=[(1, 2), (2.5, 1), (0.3, 1), (1, 4), (2, 0.5)])
    doc = json.loads(cli("analyze", "--knots", "1:2,2.5:1,0.3:1,1:4,2:0.5", "--json").stdout)
    assert a == doc
    assert a["input"]["knots"][1] == [2.5, 1.0]
    assert a["tool_version"] == sl.__version__
    cc = sl.analyze(scheme="adjustable-cc", valence=4, c=0.25)
    assert cc["input"] == {"scheme": "adjustable-cc", "valence": 4, "knots": None,
                           "ratios": None, "uniform": False, "c": 0.25}


def test_analyze_scheme_file_equals_cli_json():
    for name, n in [("catmull-clark", 5), ("loop", 7)]:
        f = str(ROOT / "analysis" / "schemes" / f"{name}.toml")
        a = sl.analyze(scheme_file=f, valence=n)
        doc = json.loads(cli("analyze", "--scheme-file", f, "--valence", str(n), "--json").stdout)
        assert a == doc
        assert a["input"]["scheme"] == f"{name}-file"
        builtin = sl.analyze(scheme=name, valence=n)
        assert a["subdominant"]["class"] == builtin["subdominant"]["class"]


def _cc_one_ring(n, a, b, g):
    """The (2n + 1) one-ring matrix of a Catmull-Clark-type vertex rule
    (v' = a v + b sum e + g sum f), as a user would write it in numpy; rows
    and columns v, e0.., f0.. (f_i between e_i and e_i+1)."""
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


class _CC:
    """Catmull-Clark from Python: an object with name and matrix(valence)."""
    name = "py-cc"

    def __init__(self):
        self.calls = []

    def matrix(self, valence):
        self.calls.append(valence)
        n = valence
        return _cc_one_ring(n, 1 - 7 / (4 * n), 3 / (2 * n * n), 1 / (4 * n * n))


def _close(xs, ys, tol=1e-12):
    return len(xs) == len(ys) and all(abs(complex(*x) - complex(*y)) < tol for x, y in zip(xs, ys))


def test_analyze_matrix_and_object_equal_the_builtin():
    for n in (3, 5, 8):
        builtin = sl.analyze(scheme="catmull-clark", valence=n)
        s, labels = _CC().matrix(n)
        a = sl.analyze(matrix=s, labels=labels)
        b = sl.analyze(scheme=_CC(), valence=n)
        for r in (a, b):
            assert r["subdominant"]["class"] == builtin["subdominant"]["class"] == "standard"
            assert r["curvature"]["verdict"] == builtin["curvature"]["verdict"]
            assert _close(r["eigenvalues"], builtin["eigenvalues"])
            assert r["input"]["valence"] == n
        assert a["input"]["scheme"] == "matrix" and b["input"]["scheme"] == "py-cc"
    # without labels: the same spectrum, but no symmetry certificate for the
    # double subdominant pair; valence defaults to the number of rows
    s, _ = _CC().matrix(5)
    u = sl.analyze(matrix=s)
    assert u["input"]["valence"] == 11
    assert _close(u["eigenvalues"], sl.analyze(scheme="catmull-clark", valence=5)["eigenvalues"])
    assert u["subdominant"]["class"] == "indeterminate"


def test_analyze_generic_charmap_equals_the_cli_and_reaches_user_schemes():
    for scheme, n in [("loop", 5), ("catmull-clark", 7), ("butterfly", 3), ("sqrt3", 4)]:
        a = sl.analyze(scheme=scheme, valence=n, charmap="generic")
        doc = json.loads(cli("analyze", "--scheme", scheme, "--valence", str(n), "--charmap",
                             "generic", "--json").stdout)
        assert a == doc, (scheme, n)
        assert a["charmap"]["method"] == "generic"
    # the ring certificate stays the default
    assert "method" not in sl.analyze(scheme="loop", valence=5)["charmap"]
    # a scheme object gives its regular rules through its own matrix at the
    # regular valence (here read from its labels: f without g -> 4)
    obj = _CC()
    b = sl.analyze(scheme=obj, valence=5, charmap="generic")
    assert b["charmap"]["verdict_code"] == "c1"
    assert obj.calls == [5, 4]
    # a bare matrix has no regular rules: indeterminate, with that reason
    s, labels = _CC().matrix(5)
    m = sl.analyze(matrix=s, labels=labels, charmap="generic")["charmap"]
    assert m["verdict_code"] == "indeterminate" and "regular configuration" in m["reason"]


def test_the_triangle_schemes_equal_the_cli():
    for scheme, n, rows in [("sqrt3", 5, 16), ("butterfly", 5, 31), ("modified-butterfly", 4, 25)]:
        m, labels = sl.matrix(scheme=scheme, valence=n)
        doc = json.loads(cli("matrix", "--scheme", scheme, "--valence", str(n), "--format",
                             "json").stdout)
        assert m.shape == (rows, rows) and labels == doc["rows"]
        assert np.array_equal(m, np.array(doc["matrix"], dtype=float))
        assert np.allclose(m.sum(axis=1), 1.0, atol=1e-14)
        a = sl.analyze(scheme=scheme, valence=n)
        assert a == json.loads(cli("analyze", "--scheme", scheme, "--valence", str(n),
                                   "--json").stdout)
    # the modified butterfly's subdominant eigenvalue is 1/2 at every valence
    mb = sl.analyze(scheme="modified-butterfly", valence=7)
    assert abs(mb["subdominant"]["lambda1"][0] - 0.5) < 1e-12


def test_sweep_with_a_scheme_file_or_object_runs_the_spec_engine():
    spec = {"name": "u", "scheme": "catmull-clark", "valences": [3, 5, 6],
            "space": {"kind": "uniform"}, "sampler": {"kind": "grid", "points_per_axis": 1},
            "columns": {"eigenvalues": 4, "curvature": True}}
    builtin = sl.sweep(spec, threads=1).to_pydict()
    f = str(ROOT / "analysis" / "schemes" / "catmull-clark.toml")
    by_file = sl.sweep(spec, threads=1, scheme_file=f).to_pydict()
    obj = _CC()
    by_obj = sl.sweep(spec, threads=1, scheme=obj).to_pydict()
    assert obj.calls[:2] == [3, 4] and sorted(obj.calls[2:]) == [3, 5, 6]
    for t in (by_file, by_obj):
        assert list(t) == list(builtin)
        assert t["class"] == builtin["class"]
        assert all(e is None for e in t["error"])
        for k, col in builtin.items():
            if col and isinstance(col[0], float):
                assert all(abs(x - y) < 1e-12 for x, y in zip(t[k], col)), k


def test_exceptions_of_the_users_code_propagate_as_they_are():
    class Boom(Exception):
        pass

    class Bad:
        name = "bad"

        def matrix(self, valence):
            if valence == 5:
                raise Boom(f"no rule at {valence}")
            return sl.matrix(scheme="catmull-clark", valence=valence)

    with pytest.raises(Boom, match="no rule at 5"):
        sl.analyze(scheme=Bad(), valence=5)
    spec = {"name": "u", "scheme": "catmull-clark", "valences": [3, 5],
            "space": {"kind": "uniform"}, "sampler": {"kind": "grid", "points_per_axis": 1}}
    with pytest.raises(Boom, match="no rule at 5"):
        sl.sweep(spec, threads=1, scheme=Bad())


def test_bad_input_is_value_error_with_the_cli_message():
    p = cli("analyze", "--ratios", "0.3,1.5,0.7", "--json", check=False)
    assert p.returncode == 2
    with pytest.raises(ValueError) as e:
        sl.analyze(ratios=[0.3, 1.5, 0.7])
    assert str(e.value) in p.stderr
    with pytest.raises(ValueError, match="unknown scheme"):
        sl.matrix(scheme="midedge", valence=3)
    with pytest.raises(ValueError, match="mutually exclusive"):
        sl.matrix(ratios=[0.5] * 3, uniform=True)
    with pytest.raises(ValueError, match="sampler.count"):
        sl.sweep(SPEC.replace("count = 300", "count = 0"))
    with pytest.raises(ValueError, match="ratios row 1"):
        sl.classify_batch(np.array([[0.5, 0.5, 0.5], [0.5, 2.0, 0.5]]))
    with pytest.raises(ValueError, match="shard"):
        sl.sweep(SPEC, shard="3/2")


def test_sweep_equals_the_cli_csv(tmp_path):
    spec = tmp_path / "s.toml"
    spec.write_text(SPEC)
    out = tmp_path / "s.csv"
    cli("sweep", str(spec), "--out", str(out))
    t = sl.sweep(SPEC, threads=2)
    assert isinstance(t, pa.Table)
    lines = out.read_text().splitlines()
    header = lines[0].split(",")
    assert t.column_names == header
    assert t.num_rows == len(lines) - 1 == 600
    assert t.schema.field("id").type == pa.uint64()
    assert t.schema.field("valence").type == pa.uint32()
    cols = {name: t.column(name).to_pylist() for name in header}
    for i, line in enumerate(lines[1:]):
        for name, text in zip(header, line.split(",")):
            got = cols[name][i]
            if text == "":
                assert got is None, (i, name, got)
            elif isinstance(got, str):
                assert got == text
            else:
                assert got == float(text), (i, name, got, text)  # shortest round trip: exact


def test_sector_sweep_equals_the_cli_csv(tmp_path):
    """A ``[sector]`` spec (boundary vertices over K) runs through Python's
    sweep with the CLI's rows."""
    spec = ROOT / "analysis" / "sweep-boundary-k.toml"
    out = tmp_path / "k.csv"
    cli("sweep", str(spec), "--out", str(out), "--threads", "1")
    t = sl.sweep(spec.read_text(), threads=2)
    lines = out.read_text().splitlines()
    header = lines[0].split(",")
    assert t.column_names == header and t.num_rows == len(lines) - 1 == 5
    assert t.column("valence").to_pylist() == [2, 3, 4, 5, 6]
    for i, line in enumerate(lines[1:]):
        for name, text in zip(header, line.split(",")):
            got = t.column(name)[i].as_py()
            if text == "":
                assert got is None, (i, name, got)
            elif isinstance(got, str):
                assert got == text
            else:
                assert got == float(text), (i, name, got, text)
    # the regular boundary (K = 2) keeps the subdominant 1/2; the sector map is C1 there
    assert t.column("charmap_verdict")[0].as_py() == "c1"


def test_sweep_files_open_in_every_reader_without_options(tmp_path):
    """The sweep CSV's first line is its header: pandas reads it with no
    options. The Parquet dataset directory (parts of two shards written into
    one directory) opens as one table in pyarrow.dataset, pandas, polars and
    DuckDB, with the rows of the in-memory sweep."""
    import duckdb
    import pandas as pd
    import polars as pl
    import pyarrow.dataset as ds

    spec = tmp_path / "s.toml"
    spec.write_text(SPEC)
    out = tmp_path / "s.csv"
    cli("sweep", str(spec), "--out", str(out), "--quiet")
    want = sl.sweep(SPEC)
    df = pd.read_csv(out)
    assert list(df.columns) == want.column_names
    assert df["id"].tolist() == list(range(600))
    assert df["class"].tolist() == want.column("class").to_pylist()
    data = tmp_path / "s.parquet"
    for i in range(2):
        cli("sweep", str(spec), "--out", str(data), "--shard", f"{i}/2", "--resume", "--quiet")
    assert sorted(p.name for p in data.iterdir()) == [
        "part-0-of-2-000000.parquet", "part-1-of-2-000000.parquet"]
    t = ds.dataset(data, format="parquet").to_table().sort_by("id")
    assert t.equals(want)
    assert t.schema.metadata[b"subdiv-lab.format"] == b"sweep dataset part 1"
    p = pd.read_parquet(data).sort_values("id", ignore_index=True)
    assert p["class"].tolist() == want.column("class").to_pylist()
    lf = pl.scan_parquet(str(data / "*.parquet"))
    assert lf.filter(pl.col("valence") == 5).select(pl.len()).collect().item() == 300
    assert pl.scan_parquet(str(data)).sort("id").collect()["id"].to_list() == list(range(600))
    [(n, k)] = duckdb.sql(
        f"select count(*), count(distinct id) from read_parquet('{data}/*.parquet')").fetchall()
    assert n == k == 600


def test_sweep_into_files_resumes_and_equals_the_cli(tmp_path):
    """``sweep(spec, out=...)`` writes the command's files byte for byte
    (CSV and its summary, a Parquet dataset of shards), refuses an existing
    output without ``resume=True``, and a resumed run after a torn write
    gives the uninterrupted file."""
    spec = tmp_path / "s.toml"
    spec.write_text(SPEC)
    ref = tmp_path / "ref.csv"
    cli("sweep", str(spec), "--out", str(ref), "--threads", "1", "--quiet")
    out = tmp_path / "py.csv"
    summary = sl.sweep(SPEC, out=out, threads=2)
    assert out.read_bytes() == ref.read_bytes()
    assert summary["rows"] == 600 and summary["spec_digest"]
    assert json.loads((tmp_path / "py.summary.json").read_text())["rows"] == 600
    with pytest.raises(ValueError, match="exists; pass resume=True"):
        sl.sweep(SPEC, out=out)
    with pytest.raises(ValueError, match="needs out"):
        sl.sweep(SPEC, resume=True)
    # Killed mid-write: a torn last line, then resumed.
    data = ref.read_bytes()
    out.write_bytes(data[: len(data) // 2 + 7])
    assert sl.sweep(SPEC, out=out, resume=True)["rows"] == 600
    assert out.read_bytes() == ref.read_bytes()
    # A foreign file is refused, never overwritten.
    other = SPEC.replace("seed = 4", "seed = 5")
    assert other != SPEC
    with pytest.raises(ValueError, match="another spec"):
        sl.sweep(other, out=out, resume=True)
    assert out.read_bytes() == ref.read_bytes()
    # Shards into one Parquet dataset, merged by the command, equal the CSV.
    ds_dir = tmp_path / "d.parquet"
    for i in range(3):
        sl.sweep(SPEC, out=ds_dir, shard=(i, 3), resume=True)
    cli("merge", str(ds_dir), "--spec", str(spec), "--out", str(tmp_path / "m.parquet"))
    assert (tmp_path / "m.summary.json").exists()
    table, _ = sl.merge([ds_dir], SPEC)
    assert table.equals(sl.sweep(SPEC))


def test_sweep_from_dict_shard_and_limit():
    d = {"name": "py", "scheme": "nurds", "valences": [3, 5],
         "space": {"kind": "ratios", "ratio_range": [0.01, 0.99]},
         "sampler": {"kind": "random", "count": 300, "seed": 4}}
    full = sl.sweep(SPEC)
    assert sl.sweep(d).equals(full)
    s1 = sl.sweep(d, shard=(1, 3))
    assert s1.column("id").to_pylist() == list(range(1, 600, 3))
    assert s1.equals(full.take(list(range(1, 600, 3))))
    assert sl.sweep(d, shard="1/3", limit=5).equals(s1.slice(0, 5))
    assert sl.sweep(d, threads=1).equals(full)


def test_classify_batch_equals_a_sweep():
    for n in (3, 5, 8):
        spec = SPEC.replace("valences = [3, 5]", f"valences = [{n}]")
        t = sl.sweep(spec)
        ratios = np.column_stack([t.column(f"r{k}").to_numpy() for k in range(n)])
        r = sl.classify_batch(ratios, threads=2)
        assert list(r["class"]) == t.column("class").to_pylist()
        for name in ("lambda1_re", "lambda1_im", "lambda2_re", "lambda2_im", "abs_lambda3",
                     "gap", "ratio", "rho", "theta", "contraction_rate"):
            want = np.array([np.nan if x is None else x for x in t.column(name).to_pylist()])
            assert np.array_equal(r[name], want, equal_nan=True), (n, name)
        assert (r["lambda1"].real == r["lambda1_re"]).all()
        # classification columns only
        c = sl.classify_batch(ratios, columns={"gap": False, "contraction": False}, threads=1)
        assert set(c) == {"class", "lambda1_re", "lambda1_im", "lambda2_re", "lambda2_im",
                          "abs_lambda3", "error", "lambda1", "lambda2"}
        assert np.array_equal(c["abs_lambda3"], r["abs_lambda3"])
    # odd sizes (not a multiple of the batch width) and one row
    x = np.random.default_rng(3).uniform(0.05, 0.95, (13, 6))
    whole = sl.classify_batch(x)
    one = sl.classify_batch(x[7:8])
    assert one["class"][0] == whole["class"][7]
    assert one["gap"][0] == whole["gap"][7]


def test_classify_batch_blocks_merge_their_texts():
    """Rows run in blocks of 1024 on the pool, each block coding its texts in
    order of first appearance; the codes are merged at the end. Blocks whose
    first classes differ, on two threads, must give the classes and values of
    small batches of the same rows."""
    x = np.random.default_rng(11).uniform(0.01, 0.99, (3000, 3))
    probe = sl.classify_batch(x, threads=1)
    kinds = sorted(set(probe["class"]))
    assert len(kinds) >= 2, kinds
    # block 0 starts with one class, block 1 with another, block 2 with the first
    a = np.flatnonzero(probe["class"] == kinds[0])
    b = np.flatnonzero(probe["class"] == kinds[1])
    order = list(range(3000))
    for pos, row in zip((0, 1024, 2048), (int(a[0]), int(b[0]), int(a[1]))):
        order.remove(row)
        order.insert(pos, row)
    x = x[order]
    whole = sl.classify_batch(x, threads=2)
    parts = [sl.classify_batch(x[i:i + 700], threads=1) for i in range(0, 3000, 700)]
    assert whole["class"][0] == kinds[0] and whole["class"][1024] == kinds[1]
    assert list(whole["class"]) == [c for p in parts for c in p["class"]]
    assert list(whole["error"]) == [""] * 3000
    for name in ("lambda1_re", "lambda1_im", "ratio", "rho", "theta", "contraction_rate"):
        want = np.concatenate([p[name] for p in parts])
        assert np.array_equal(whole[name], want, equal_nan=True), name


def test_subdivide():
    v = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], dtype=float)
    faces = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]]
    pv, pf = sl.subdivide(v, faces, scheme="catmull-clark", levels=1)
    assert pv.shape == (8 + 12 + 6, 3) and len(pf) == 24
    dv, df = sl.subdivide(v, faces, scheme="nurds", levels=1)
    assert dv.shape == (24, 3) and len(df) == 6 + 12 + 8
    # each new vertex is a convex combination of its face's corners: on the cube
    assert (dv >= 0).all() and (dv <= 1).all()
    assert sorted(set(dv.ravel())) == [0.0, 0.25, 0.75, 1.0]
    with pytest.raises(ValueError):
        sl.subdivide(v, faces[:-1], levels=1)  # open mesh


TINY_REPORT = ('name = "t"\n[[figure]]\nkind = "table"\nid = "a"\n'
               'configs = [{ scheme = "cc-variant", valence = 4 }]\n')


def test_report_writes_the_cli_files(tmp_path):
    files = sl.report(TINY_REPORT, tmp_path / "py")
    spec = tmp_path / "t.toml"
    spec.write_text(TINY_REPORT)
    cli("report", str(spec), "--out", str(tmp_path / "cli"), "--quiet")
    assert sorted(files) == sorted(p.name for p in (tmp_path / "cli").iterdir())
    assert "index.html" in files and "manifest.json" in files
    for name in files:
        if name.endswith((".csv", ".svg")):
            assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    with pytest.raises(ValueError, match="not empty"):
        sl.report(TINY_REPORT, tmp_path / "py")
    with pytest.raises(ValueError, match="kind"):
        sl.report(TINY_REPORT.replace('"table"', '"nope"'), tmp_path / "bad")
    assert not (tmp_path / "bad").exists()


def test_report_reads_scheme_files_beside_the_spec(tmp_path):
    (tmp_path / "schemes").mkdir()
    (tmp_path / "schemes" / "cc.toml").write_text(
        (ROOT / "analysis" / "schemes" / "catmull-clark.toml").read_text()
    )
    spec = tmp_path / "s.toml"
    spec.write_text(
        'name = "f"\n[[figure]]\nkind = "table"\nid = "tab"\n'
        'configs = [{ scheme_file = "schemes/cc.toml", valence = 5 }, { scheme = "catmull-clark", valence = 5 }]\n'
    )
    sl.report(spec, tmp_path / "out")
    rows = (tmp_path / "out" / "tab.csv").read_text().splitlines()
    assert rows[1].split(",")[2] == "catmull-clark-file"
    # the same class and subdominant eigenvalue as the built-in it restates
    f, b = rows[1].split(","), rows[2].split(",")
    assert f[5] == b[5]
    assert abs(float(f[6]) - float(b[6])) < 1e-12
    with pytest.raises(ValueError, match="scheme_file"):
        sl.report(spec.read_text(), tmp_path / "text")  # text: read from the current directory
    assert not (tmp_path / "text").exists()
