"""The example notebook examples/python/paper.ipynb runs from top to bottom (so it cannot
rot): Figs. 4, 6 and 7 of the paper and a map on a Dask LocalCluster."""

from __future__ import annotations


import pytest

from conftest import ROOT, TARGET

NOTEBOOK = ROOT / "examples" / "python" / "paper.ipynb"


def test_the_paper_notebook_runs(tmp_path):
    nbformat = pytest.importorskip("nbformat", reason="the notebook test needs nbformat")
    nbclient = pytest.importorskip("nbclient", reason="the notebook test needs nbclient")
    notebook = nbformat.read(NOTEBOOK, as_version=4)
    client = nbclient.NotebookClient(notebook, timeout=600, kernel_name="python3",
                                     resources={"metadata": {"path": str(tmp_path)}})
    client.execute()
    outputs = [o for cell in notebook.cells if cell.cell_type == "code" for o in cell.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    # Four figures: Figs. 4, 6 and 7, and the Dask map.
    images = [o for o in outputs if "image/png" in o.get("data", {})]
    assert len(images) == 4, f"{len(images)} figures"
    text = "".join(o.get("text", "") for o in outputs if o.output_type == "stream")
    assert "identical to the local map" in text
    # The executed notebook, for a look (target/ is not committed).
    out = TARGET / "notebooks"
    out.mkdir(parents=True, exist_ok=True)
    nbformat.write(notebook, out / NOTEBOOK.name)
