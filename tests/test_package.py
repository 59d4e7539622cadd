"""The package's shape: import cost, console script, and shaders in the wheel."""

import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

import glshade

ROOT = Path(__file__).resolve().parent.parent


PACKAGE = Path(glshade.__file__).parent

#: the layers, lowest first: a module may import its own layer and those below it
LAYERS = [
    {"_version", "_atomic", "_callable", "_interrupt", "errors", "modes", "options"},
    {"parallel"},
    {"geometry", "quaternion", "masspoint", "brep", "solids", "octree"},
    {"scene"},
    {"io"},
    {"cpu", "hidden"},
    {"render"},
    {"compare", "radiosity"},
    {"animate", "batch"},
    {"viewer"},
    {"cli", "testing", "pytest_plugin", "__init__", "__main__"},
]
RANK = {name: i for i, layer in enumerate(LAYERS) for name in layer}


@pytest.mark.parametrize("modules", ["glshade", "glshade.geometry", "glshade.scene",
                                     "glshade.io", "glshade.cpu", "glshade.compare",
                                     "glshade.animate", "glshade.batch", "glshade.parallel",
                                     "glshade.cli.parser"])
def test_gl_free_packages_load_no_gl(modules):
    code = (f"import sys, {modules}; "
            "bad = [m for m in ('moderngl', 'glfw', 'glcontext') if m in sys.modules]; "
            "print(bad); sys.exit(1 if bad else 0)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stdout + out.stderr


def _part(module_path: Path) -> str:
    rel = module_path.relative_to(PACKAGE)
    return rel.parts[0] if len(rel.parts) > 1 else rel.stem


def _imported_parts(path: Path):
    """The top-level parts of glshade that a module imports (lazy imports included)."""
    import ast

    here = path.relative_to(PACKAGE).parent.parts
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.level:
            base = here[:len(here) - (node.level - 1)] if node.level > 1 else here
            target = [*base, *(node.module.split(".") if node.module else [])]
            if target:
                yield target[0], node.lineno
            else:  # "from . import x" at the top level
                for alias in node.names:
                    yield alias.name, node.lineno
        elif isinstance(node, ast.ImportFrom) and (node.module or "").startswith("glshade."):
            yield node.module.split(".")[1], node.lineno


def test_imports_flow_one_way():
    wrong = []
    for path in sorted(PACKAGE.rglob("*.py")):
        source = _part(path)
        for target, line in _imported_parts(path):
            if target in RANK and RANK[target] > RANK[source]:
                wrong.append(f"{path.relative_to(PACKAGE)}:{line} ({source}) imports {target}")
    assert wrong == []


def test_every_module_has_a_layer_and_stays_small():
    for path in PACKAGE.rglob("*.py"):
        assert _part(path) in RANK, f"{path.relative_to(PACKAGE)} belongs to no layer"
        if path.name != "_teapot_data.py":  # (a data table)
            lines = len(path.read_text(encoding="utf-8").splitlines())
            assert lines <= 430, f"{path.relative_to(PACKAGE)}: {lines} lines (~400 at most)"


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
