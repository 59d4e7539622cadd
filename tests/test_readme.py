"""Every Python block of the README and of the guide's pages (docs/guide/, in the order the
README lists them) runs as written, in order, in one process, in an empty folder (no
repository files: the examples come from glshade.examples), in a fresh virtual environment
with the built wheel installed, outside the repository: what a user who ran ``pip install
glshade`` has. (Once: they ran in the checkout as well, the same blocks twice.)"""

import os
import re
import subprocess
import sys
import zipfile

import pytest

from tests.conftest import ROOT

pytestmark = pytest.mark.gl


def guide_pages() -> list:
    """The guide's pages in the order the README links them."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    return [ROOT / p for p in re.findall(r"\]\((docs/guide/[a-z-]+\.md)\)", readme)]


def readme_blocks() -> list[str]:
    pages = [ROOT / "README.md", *guide_pages()]
    return [block for page in pages for block in
            re.findall(r"```python\n(.*?)```", page.read_text(encoding="utf-8"), re.S)]


def test_the_readme_is_a_front_door_that_links_every_guide_page():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert len(readme.splitlines()) <= 200
    linked = {p.name for p in guide_pages()}
    assert linked == {p.name for p in (ROOT / "docs" / "guide").glob("*.md")}
    for heading in ("## The two commands", "## Python API", "## Command line"):
        assert heading in readme


def _check_outputs(folder, stdout):
    assert "against the phong-fine reference" in stdout
    for name in ("teapot.png", "orbit.gif", "cornell.png", "part.png"):
        assert (folder / name).stat().st_size > 0, name
    assert (folder / "thumbs" / "torus.v01.phong.png").stat().st_size > 0
    from PIL import Image

    with Image.open(folder / "orbit.gif") as gif:  # the scene file's [render] size
        assert gif.size == (512, 384) and gif.n_frames == 24


@pytest.mark.slow
def test_the_wheel_in_a_fresh_environment_runs_the_readme(tmp_path):
    """Build the release files as PyPI takes them (``python -m build``: the pure-Python
    wheel and the sdist; ``twine check`` passes), install the wheel (its dependencies and
    the notebook and formats extras) into a new venv outside the repository, and there, from an
    empty folder: the README's blocks, ``glshade doctor``, a render with exact shadows and
    transparency, a path trace, and the viewer headless (a hidden window under Xvfb)."""
    import shutil

    wheels = tmp_path / "wheels"
    out = subprocess.run([sys.executable, "-m", "build", "--no-isolation", "--wheel",
                          "--sdist", "-o", str(wheels), str(ROOT)],
                         capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-3000:]
    wheel = next(wheels.glob("glshade-*-py3-none-any.whl"))  # (pure Python: every platform)
    sdist = next(wheels.glob("glshade-*.tar.gz"))
    out = subprocess.run([sys.executable, "-m", "twine", "check", "--strict", str(wheel),
                          str(sdist)], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0 and out.stdout.count("PASSED") == 2, out.stdout + out.stderr
    names = zipfile.ZipFile(wheel).namelist()
    assert "glshade/examples/scenes/cornell-box.toml" in names
    assert "glshade/notebook/static/viewer.js" in names  # (the widget's front end)
    assert any(n.endswith(".dist-info/licenses/LICENSE") for n in names)
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    python = venv / "bin" / "python"
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    # (installed by uv where the suite's setup has it, in seconds; by pip otherwise: the
    # same wheel, the same resolved dependencies)
    import importlib.util

    install = ([sys.executable, "-m", "uv", "pip", "install", "-q", "--compile-bytecode",
                "--python", str(python)]
               if importlib.util.find_spec("uv") else
               [str(python), "-m", "pip", "install", "-q", "--disable-pip-version-check"])
    out = subprocess.run([*install, f"{wheel}[notebook,formats]"], capture_output=True, text=True,
                         env=env, timeout=900)
    assert out.returncode == 0, out.stderr[-3000:]
    work = tmp_path / "work"
    work.mkdir()
    blocks = readme_blocks()
    assert len(blocks) >= 4
    code = "\n".join(blocks)
    assert "glshade.compare(" in code and "glshade.animate(" in code
    r = subprocess.run([str(python), "-c", code], capture_output=True,
                       text=True, cwd=work, env=env, timeout=900)
    assert r.returncode == 0, r.stderr
    _check_outputs(work, r.stdout)
    # the CLI finds the examples by name there too
    cli = str(venv / "bin" / "glshade")
    r = subprocess.run([cli, "info", "cornell-box"], capture_output=True, text=True,
                       cwd=work, env=env)
    assert r.returncode == 0 and "models (8)" in r.stdout, r.stderr
    r = subprocess.run([cli, "doctor"], capture_output=True, text=True, cwd=work, env=env,
                       timeout=300)
    assert r.returncode == 0 and "GL tier" in r.stdout and "shadows exact" in r.stdout, \
        r.stdout + r.stderr
    for args, made in ((["render", "teapot.obj", "--shadows", "exact", "--opacity", "0.6",
                         "-o", "shadowed.png"], "shadowed.png"),
                       (["pathtrace", "cornell-box", "--spp", "2", "--size", "48x48", "-o",
                         "traced.png"], "traced.png")):
        r = subprocess.run([cli, *args], capture_output=True, text=True, cwd=work, env=env,
                           timeout=300)
        assert r.returncode == 0 and (work / made).stat().st_size > 0, r.stderr
    display = [] if os.environ.get("DISPLAY") else ["xvfb-run", "-a"]
    if display and shutil.which("xvfb-run") is None:
        pytest.fail("no display and no xvfb-run for the installed viewer (apt-get install "
                    "xvfb)", pytrace=False)
    r = subprocess.run([*display, cli, "view", "teapot.obj", "--hidden", "--frames", "3",
                        "--screenshot", "seen.png"], capture_output=True, text=True,
                       cwd=work, env=env, timeout=300)
    assert r.returncode == 0 and (work / "seen.png").stat().st_size > 0, r.stderr
