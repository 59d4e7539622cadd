"""Notebooks in a real Jupyter kernel (nbclient), with no display, on the backend under
test: progress widgets and every result's picture. The chapter notebooks themselves run top
to bottom once, in the documentation build (tests/docs/test_docs_build.py: executed there,
an error or a failed check in any cell fails the build), where their numbers are checked
and their pictures looked for."""


import nbformat
import pytest
from nbclient import NotebookClient

from tests.conftest import BACKEND, ROOT

pytestmark = [pytest.mark.gl, pytest.mark.once]
NOTEBOOKS = sorted((ROOT / "docs" / "notebooks").glob("*.ipynb"))
CHAPTERS = ("shading", "newell", "quaternions", "brep", "csg", "hidden", "radiosity",
            "patches")


def test_every_chapter_has_a_notebook():
    names = " ".join(p.stem for p in NOTEBOOKS)
    assert all(c in names for c in CHAPTERS), names


def test_every_chapter_notebook_checks_numbers():
    for path in NOTEBOOKS:
        source = "\n".join(c.source for c in nbformat.read(path, as_version=4).cells
                           if c.cell_type == "code")
        # (a notebook that checks nothing is only a picture)
        assert "assert " in source, path.name


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


REPRS = {
    "mesh": "primitives.cube()",
    "scene": "scene",
    "solid": "Box(2) - Sphere(1.2)",
    "patches": "glshade.patches.named('teapot')",
    "octree": "Octree.from_solid(Box(2) - Sphere(1.2), 4)",
    "frame": "renderer.render_frame(scene, camera)",
    "hidden": "zbuffer(scene, camera, (64, 48))",
    "camera path": ("glshade.CameraPath([glshade.Keyframe.look_at(0, (4, 1, 0), (0, 0, 0)), "
                    "glshade.Keyframe.look_at(2, (0, 1, 4), (0, 0, 0))])"),
    "solution": "solution",
    "path traced": "trace(box, box_camera, size=(32, 24), spp=4, progress=False)",
    "comparison": "compare(scene, camera, size=(48, 48))",
}


def test_every_public_result_shows_a_picture_in_a_real_kernel(tmp_path, monkeypatch):
    """Each displayable result type, as the last expression of a cell in a Jupyter kernel:
    its HTML (or PNG) output holds a picture -- the objects' reprs rendered where users
    see them, not only called in-process."""
    setup = ("import glshade\n"
             "from glshade import Camera, Scene\n"
             "from glshade.geometry import primitives\n"
             "from glshade.solids import Box, Sphere\n"
             "from glshade.octree import Octree\n"
             "from glshade.hidden import zbuffer\n"
             "from glshade.compare import compare\n"
             "from glshade.pathtrace import trace\n"
             "from glshade.radiosity import cornell_scene, solve\n"
             "scene = Scene()\n"
             "scene.add(primitives.cube())\n"
             "camera = Camera.look_at((3, 2, 4), (0, 0, 0))\n"
             "renderer = glshade.Renderer(64, 48, samples=0)\n"
             "box, box_camera = cornell_scene()\n"
             "solution = solve(box, patch_size=250, until=0.2, progress=False)\n")
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell(setup)] + \
        [nbformat.v4.new_code_cell(code) for code in REPRS.values()]
    monkeypatch.setenv("GLSHADE_BACKEND", BACKEND)
    monkeypatch.delenv("DISPLAY", raising=False)
    NotebookClient(nb, timeout=600, kernel_name="python3",
                   resources={"metadata": {"path": str(tmp_path)}}).execute()
    for name, cell in zip(REPRS, nb.cells[1:]):
        data = {k: v for o in cell.outputs for k, v in o.get("data", {}).items()}
        html = data.get("text/html", "")
        assert "data:image/png;base64," in html or "image/png" in data, (name, list(data))
