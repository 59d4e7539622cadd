"""The documentation site builds with warnings as errors (what ``make docs`` runs): the
README as its front page with its pictures, the chapter notebooks executed into tutorials,
and an API page for every public module, each documenting its objects."""

import re
import subprocess
import sys

import pytest

from tests.conftest import BACKEND, ROOT


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    import fcntl
    import tempfile
    from pathlib import Path

    out = tmp_path_factory.mktemp("docs")
    generated = tmp_path_factory.mktemp("doctrees")
    # one build at a time (a build remakes docs/api/generated: two test workers building
    # at once would delete each other's pages)
    lock = Path(tempfile.gettempdir()) / "glshade-docs-build.lock"
    with open(lock, "w") as held:
        fcntl.flock(held, fcntl.LOCK_EX)
        r = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b",
                            "html", "-d", str(generated), str(ROOT / "docs"), str(out)],
                           capture_output=True, text=True, timeout=900,
                           env={k: v for k, v in {**__import__("os").environ,
                                                   "GLSHADE_BACKEND": BACKEND}.items()
                                if k != "DISPLAY"})  # (no display, as on a server)
    assert r.returncode == 0, (r.stdout + r.stderr)[-4000:]
    return out


def test_the_front_page_is_the_readme_with_its_pictures(site):
    page = (site / "index.html").read_text(encoding="utf-8")
    assert "The two commands" in page and "Python API" in page
    for image in re.findall(r'<img[^>]+src="([^"]+)"', page):
        assert (site / image).is_file(), image
    assert "teapot-modes.png" in page


def test_the_tutorials_are_the_executed_notebooks(site):
    """Each chapter notebook ran top to bottom in the build (``nb_execution_mode`` "force",
    an error in any cell -- a failed check of its numbers among them -- fails the build:
    the one place they run) and shows its pictures rendered headless."""
    conf = (ROOT / "docs" / "conf.py").read_text(encoding="utf-8")
    assert 'GLSHADE_DOCS_EXECUTE", "force")' in conf and \
        "nb_execution_raise_on_error = True" in conf
    pages = sorted((site / "notebooks").glob("*.html"))
    assert len(pages) == len(list((ROOT / "docs" / "notebooks").glob("*.ipynb"))) == 9
    for page in pages:
        html = page.read_text(encoding="utf-8")
        assert "<img" in html or "data:image/png" in html, page.name  # (its outputs)
        assert "Traceback" not in html, page.name


def test_every_public_module_has_an_api_page_with_its_objects(site):
    import pkgutil

    import glshade
    import glshade.radiosity
    import glshade.solids

    api = site / "api" / "generated"
    # (glshade.cli is the command line, whose page is docs/guide/cli.md, not an API)
    public = [m.name for m in pkgutil.walk_packages(glshade.__path__, "glshade.")
              if not any(part.startswith("_") for part in m.name.split("."))
              and not m.name.startswith("glshade.cli")]
    missing = [name for name in public if not (api / f"{name}.html").is_file()]
    assert not missing, f"public modules without an API page: {missing}"
    assert "glshade.examples" in public and "glshade.testing.pytest_plugin" in public
    for module in ("glshade.quaternion", "glshade.solids.leaves", "glshade.radiosity.solvers",
                   "glshade.pathtrace.progressive",
                   "glshade.notebook.widget", "glshade.hidden.view", "glshade.scene.camera"):
        page = (api / f"{module}.html").read_text(encoding="utf-8")
        assert 'class="sig-name descname"' in page, module
    camera = (api / "glshade.scene.camera.html").read_text(encoding="utf-8")
    assert "A pinhole (or orthographic) camera." in camera
    solvers = (api / "glshade.radiosity.solvers.html").read_text(encoding="utf-8")
    assert "progressive" in solvers and glshade.radiosity.progressive.__doc__.split()[0] \
        in solvers
    assert glshade.solids.Torus.__doc__.split()[0] in \
        (api / "glshade.solids.leaves.html").read_text(encoding="utf-8")
