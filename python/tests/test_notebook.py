"""The example notebook runs from top to bottom with the package built from this
tree (every cell, in a fresh kernel, in a temporary directory)."""
from pathlib import Path

import nbformat
from nbclient import NotebookClient

NOTEBOOK = Path(__file__).resolve().parents[1] / "examples" / "first_sweep.ipynb"


def test_first_sweep_notebook_runs(tmp_path):
    nb = nbformat.read(NOTEBOOK, as_version=4)
    NotebookClient(nb, timeout=300, kernel_name="python3",
                   resources={"metadata": {"path": str(tmp_path)}}).execute()
    outputs = ["".join(o.get("text", "")) for c in nb.cells if c.cell_type == "code"
               for o in c.get("outputs", [])]
    assert any("standard" in o for o in outputs), outputs
    assert any("4000 configurations plotted" in o for o in outputs), outputs
    assert (tmp_path / "sweep_n3.png").stat().st_size > 1000
