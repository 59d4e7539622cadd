"""The chapter notebooks run top to bottom in a real Jupyter kernel (nbclient), with no
display, on the backend under test; each checks numbers against the notes (its asserts)
and shows pictures rendered headless (image outputs in the executed notebook)."""

import json

import nbformat
import pytest
from nbclient import NotebookClient

from tests.conftest import BACKEND, ROOT

pytestmark = pytest.mark.gl
NOTEBOOKS = sorted((ROOT / "docs" / "notebooks").glob("*.ipynb"))
CHAPTERS = ("shading", "newell", "quaternions", "brep", "csg", "hidden", "radiosity")


def test_every_chapter_has_a_notebook():
    names = " ".join(p.stem for p in NOTEBOOKS)
    assert all(c in names for c in CHAPTERS), names


def execute(path, tmp_path, monkeypatch):
    monkeypatch.setenv("GLSHADE_BACKEND", BACKEND)  # (the kernel inherits it)
    monkeypatch.delenv("DISPLAY", raising=False)      # no display, as on a server
    nb = nbformat.read(path, as_version=4)
    NotebookClient(nb, timeout=600, kernel_name="python3",
                   resources={"metadata": {"path": str(tmp_path)}}).execute()
    return nb


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_the_notebook_runs_and_checks_its_numbers(path, tmp_path, monkeypatch):
    source = "\n".join(c.source for c in nbformat.read(path, as_version=4).cells
                       if c.cell_type == "code")
    assert "assert " in source  # (a notebook that checks nothing is only a picture)
    nb = execute(path, tmp_path, monkeypatch)  # (an error in any cell raises here)
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs]
    kinds = {k for o in outputs for k in o.get("data", {})}
    assert {"image/png"} & kinds or any("<img" in o.get("data", {}).get("text/html", "")
                                        for o in outputs), kinds
    text = json.dumps([o.get("text", "") for o in outputs])
    assert "Traceback" not in text
