"""The functions that mirror `verify`, `g2-cap`, `plot`, `cc-study`, `merge`,
`ccss-bound` and `subdivide` against the release binary: same JSON, same rows,
same bytes; and the limits' messages equal the CLI's. Needs the release
binary (see test_api.py)."""
import json

import numpy as np
import pyarrow as pa
import pyarrow.csv as pacsv
import pytest

import subdiv_lab as sl
from test_api import ROOT, SPEC, cli


def test_refusals_are_the_cli_messages():
    p = cli("analyze", "--uniform", "--valence", "600", check=False)
    assert p.returncode == 2
    with pytest.raises(ValueError) as e:
        sl.analyze(uniform=True, valence=600)
    assert "error: " + str(e.value).replace("force=True", "--force") == p.stderr.strip()
    p = cli("ccss-bound", "--valence", "1000", check=False)
    with pytest.raises(ValueError) as e:
        sl.ccss_bound(valence=1000)
    assert str(e.value).replace("force=True", "--force").replace("ccss_bound", "ccss-bound") in p.stderr
    p = cli("sweep", str(ROOT / "analysis" / "sweep-random.toml"), "--threads", "0", check=False)
    with pytest.raises(ValueError) as e:
        sl.sweep(ROOT / "analysis" / "sweep-random.toml", threads=0)
    assert str(e.value).replace("threads", "--threads", 1) in p.stderr


def test_a_spec_path_without_toml_extension(tmp_path):
    spec = tmp_path / "plain"
    spec.write_text(SPEC)
    assert sl.sweep(str(spec), limit=3).equals(sl.sweep(SPEC, limit=3))
    with pytest.raises(ValueError, match="cannot read spec"):
        sl.sweep(str(tmp_path / "other"))


VERIFY = ('name = "v"\nscheme = "nurds"\nvalence = 3\nbox = [[0.3, 0.4], [0.3, 0.4], [0.3, 0.4]]\n'
          'properties = ["class", "separation"]\nmin_width = 0.02\n')


def test_verify_equals_the_cli_files(tmp_path):
    spec = tmp_path / "v.toml"
    spec.write_text(VERIFY)
    cli("verify", str(spec), "--out", str(tmp_path / "out"), "--quiet", "--threads", "2")
    summary, cells = sl.verify(spec, threads=2)
    want = json.loads((tmp_path / "out" / "summary.json").read_text())
    for s in (summary, want):
        s.pop("seconds")
    assert summary == want
    cli_cells = pacsv.read_csv(tmp_path / "out" / "cells.csv")
    assert cells.column_names == cli_cells.column_names
    assert cells.num_rows == want["cells"] > 0
    for name in cells.column_names:
        assert cells.column(name).to_pylist() == cli_cells.column(name).to_pylist(), name
    # the same from a dict and from text
    d = {"name": "v", "scheme": "nurds", "valence": 3, "box": [[0.3, 0.4]] * 3,
         "properties": ["class", "separation"], "min_width": 0.02}
    assert sl.verify(d)[1].equals(cells)
    assert sl.verify(VERIFY, max_cells=1)[0]["evaluated"] == 1


def test_g2_cap_equals_the_cli(tmp_path):
    out = tmp_path / "cap.obj"
    doc = json.loads(cli("g2-cap", "--valence", "5", "--random-net", "3", "--c", "0.5",
                         "--json", "-o", str(out), "--samples", "3").stdout)
    cap = sl.g2_cap(0.5, valence=5, random_net=3, samples=3)
    mesh = cap.pop("mesh")
    assert cap == doc
    lines = out.read_text().splitlines()
    v = np.array([[float(x) for x in l.split()[1:]] for l in lines if l.startswith("v ")])
    f = np.array([[int(x) - 1 for x in l.split()[1:]] for l in lines if l.startswith("f ")])
    assert np.array_equal(mesh["vertices"], v)
    assert np.array_equal(mesh["quads"], f)
    assert "mesh" not in sl.g2_cap(0.5, valence=5, random_net=3)
    # from a mesh: a cube's corner is valence 3, its 2-ring is not all quads
    with pytest.raises(ValueError):
        sl.g2_cap(0.5, vertices=np.eye(3), faces=[[0, 1, 2]], vertex=0)


def test_plot_equals_the_cli_bytes(tmp_path):
    spec = tmp_path / "s.toml"
    spec.write_text(SPEC)
    rows = tmp_path / "s.csv"
    cli("sweep", str(spec), "--out", str(rows), "--quiet")
    for ext in ("svg", "png"):
        fig = tmp_path / f"cli.{ext}"
        cli("plot", str(rows), "-o", str(fig))
        out = tmp_path / f"py.{ext}"
        data = sl.plot(rows, out=out)
        assert data == fig.read_bytes() == out.read_bytes(), ext
    fig = tmp_path / "map.svg"
    cli("plot", str(rows), "-o", str(fig), "--kind", "scatter", "--x", "r0", "--y", "r1",
        "--width", "800", "--height", "600", "--title", "T")
    assert sl.plot(rows, kind="scatter", x="r0", y="r1", width=800, height=600,
                   title="T") == fig.read_bytes()
    # a table of sweep(): the same figure as its CSV
    assert sl.plot(sl.sweep(SPEC)).startswith(b"<svg")
    # out= replaces a file
    out = tmp_path / "py.svg"
    out.write_text("old")
    sl.plot(rows, out=out)
    assert out.read_bytes().startswith(b"<svg")


def test_cc_study_equals_the_cli_csv():
    curves = sl.cc_study(n_min=3, n_max=5, samples=8, curves=True)
    p = cli("cc-study", "--n-min", "3", "--n-max", "5", "--samples", "8", "--curves")
    want = pacsv.read_csv(pa.py_buffer(p.stdout.encode()),
                          convert_options=pacsv.ConvertOptions(strings_can_be_null=True))
    assert curves.column_names == want.column_names
    assert curves.num_rows == want.num_rows == 3 * 9
    for name in curves.column_names:
        assert curves.column(name).to_pylist() == want.column(name).to_pylist(), name
    iv = sl.cc_study(n_min=3, n_max=5, samples=20, criterion="standard")
    p = cli("cc-study", "--n-min", "3", "--n-max", "5", "--samples", "20", "--criterion", "standard")
    want = pacsv.read_csv(pa.py_buffer(p.stdout.encode()),
                          convert_options=pacsv.ConvertOptions(
                              column_types={"below": pa.string(), "above": pa.string()}))
    assert iv.column_names == want.column_names and iv.num_rows == want.num_rows > 0
    for name in iv.column_names:
        a, b = iv.column(name).to_pylist(), want.column(name).to_pylist()
        if name.startswith("c_"):
            assert np.allclose(a, b, rtol=1e-9, atol=0), name  # the CLI prints 10 digits
        else:
            assert a == b, name


def test_ccss_bound_equals_the_cli(tmp_path):
    assert sl.ccss_bound(valence=5) == json.loads(cli("ccss-bound", "--valence", "5", "--json").stdout)
    net = np.random.default_rng(2).normal(size=(18, 3))
    path = tmp_path / "net.txt"
    path.write_text("\n".join(" ".join(repr(float(x)) for x in p) for p in net) + "\n")
    doc = json.loads(cli("ccss-bound", "--valence", "5", "--json", "--net", str(path),
                         "--epsilon", "1e-3").stdout)
    got = sl.ccss_bound(valence=5, net=net, epsilon=1e-3)
    assert got == doc and got["steps"]["steps"] > 0
    table = sl.ccss_bound(table_to=5, levels=1)
    want = pacsv.read_csv(pa.py_buffer(cli("ccss-bound", "--table-to", "5", "--levels", "1").stdout.encode()))
    assert table.column_names == want.column_names
    for name in table.column_names:
        assert table.column(name).to_pylist() == want.column(name).to_pylist(), name


@pytest.mark.parametrize("fmt", ["csv", "parquet"])
def test_merge_equals_the_cli_and_the_sweep(tmp_path, fmt):
    spec = tmp_path / "s.toml"
    spec.write_text(SPEC)
    shards = []
    for i in range(3):
        out = tmp_path / f"part{i}.{fmt}"
        cli("sweep", str(spec), "--shard", f"{i}/3", "--out", str(out), "--format", fmt, "--quiet")
        shards.append(out)
    merged = tmp_path / f"all.{fmt}"
    cli("merge", *map(str, shards), "--spec", str(spec), "--out", str(merged))
    table, summary = sl.merge(shards, spec)
    assert table.equals(sl.sweep(SPEC))
    assert summary == json.loads((tmp_path / "all.summary.json").read_text())
    # shards missing or of another spec are refused as the CLI refuses them
    p = cli("merge", *map(str, shards[:2]), "--spec", str(spec), "--out", str(tmp_path / f"x.{fmt}"),
            check=False)
    with pytest.raises(ValueError) as e:
        sl.merge(shards[:2], spec)
    assert p.returncode == 2 and str(e.value) in p.stderr
    other = SPEC.replace("seed = 4", "seed = 5")
    with pytest.raises(ValueError, match="the summary of another spec"):
        sl.merge(shards, other)


@pytest.mark.parametrize("scheme", ["nurds", "doo-sabin", "cc-variant", "catmull-clark", "loop"])
def test_subdivide_equals_the_cli(tmp_path, scheme):
    mesh = ROOT / "analysis" / "meshes" / ("icosahedron.obj" if scheme == "loop" else "cube.obj")
    lines = mesh.read_text().splitlines()
    v = np.array([[float(x) for x in l.split()[1:4]] for l in lines if l.startswith("v ")])
    f = [[int(x.split("/")[0]) - 1 for x in l.split()[1:]] for l in lines if l.startswith("f ")]
    out = tmp_path / "out.obj"
    cli("subdivide", str(mesh), "--scheme", scheme, "--levels", "2", "-o", str(out))
    pv, pf = sl.subdivide(v, f, scheme=scheme, levels=2)
    lines = out.read_text().splitlines()
    want_v = np.array([[float(x) for x in l.split()[1:4]] for l in lines if l.startswith("v ")])
    want_f = [[int(x) - 1 for x in l.split()[1:]] for l in lines if l.startswith("f ")]
    assert np.array_equal(pv, want_v)
    assert pf == want_f
