"""The package's shape: import cost, console script, and shaders in the wheel."""

import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

import glshade

ROOT = Path(__file__).resolve().parent.parent


def test_geometry_import_loads_no_gl():
    code = ("import sys, glshade, glshade.geometry, glshade.io; "
            "bad = [m for m in ('moderngl', 'glfw', 'glcontext') if m in sys.modules]; "
            "print(bad); sys.exit(1 if bad else 0)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stdout + out.stderr


def test_version_command():
    out = subprocess.run([sys.executable, "-m", "glshade", "--version"], capture_output=True,
                         text=True)
    assert out.returncode == 0
    assert out.stdout.strip() == f"glshade {glshade.__version__}"


@pytest.mark.slow
def test_wheel_contains_shaders(tmp_path):
    out = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q",
         "-w", str(tmp_path), str(ROOT)], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    wheel = next(tmp_path.glob("glshade-*.whl"))
    names = zipfile.ZipFile(wheel).namelist()
    shaders = sorted(n for n in names if n.startswith("glshade/shaders/"))
    on_disk = sorted("glshade/shaders/" + p.relative_to(ROOT / "shaders").as_posix()
                     for p in (ROOT / "shaders").rglob("*") if p.is_file())
    assert on_disk and shaders == on_disk
    assert "glshade/py.typed" in names
