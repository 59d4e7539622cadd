"""The chapter notebooks run top to bottom in a real Jupyter kernel (nbclient), with no
display, on the backend under test; each checks numbers against the notes (its asserts)
and shows pictures rendered headless (image outputs in the executed notebook)."""

import json

import nbformat
import pytest
from nbclient import NotebookClient

from tests.conftest import BACKEND, ROOT

pytestmark = [pytest.mark.gl, pytest.mark.once]  # (the docs build runs them too)
NOTEBOOKS = sorted((ROOT / "docs" / "notebooks").glob("*.ipynb"))
CHAPTERS = ("shading", "newell", "quaternions", "brep", "csg", "hidden", "radiosity",
            "patches")


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


def test_progress_in_a_notebook_is_tqdms_widget_and_in_a_log_plain_lines(tmp_path,
                                                                          monkeypatch):
    """In a kernel, long work's bar is a widget (tqdm.notebook: an ipywidgets view), not
    carriage-return text; the radiosity solver's default bar is one too."""
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell(
        "from glshade.parallel import Progress\n"
        "bar = Progress(5, unit='frames')\n"
        "for _ in range(5):\n"
        "    bar.update()\n"
        "bar.close()"), nbformat.v4.new_code_cell(
        "from glshade.geometry import primitives\n"
        "import glshade\n"
        "from glshade.radiosity import solve\n"
        "s = glshade.Scene()\n"
        "s.add(primitives.cube().flipped(), glshade.Material(reflectance=(0.5,) * 3,\n"
        "      emission=(1.0,) * 3))\n"
        "solution = solve(s, 1.0, until=0.05)")]
    monkeypatch.setenv("GLSHADE_BACKEND", BACKEND)
    NotebookClient(nb, timeout=300, kernel_name="python3",
                   resources={"metadata": {"path": str(tmp_path)}}).execute()
    for cell in nb.cells:
        kinds = {k for o in cell.outputs for k in o.get("data", {})}
        assert "application/vnd.jupyter.widget-view+json" in kinds, cell.outputs
        text = "".join(o.get("text", "") for o in cell.outputs)
        assert "\r" not in text
