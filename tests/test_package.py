"""The package's shape: import cost, console script, and shaders in the wheel."""

import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

import glshade

ROOT = Path(__file__).resolve().parent.parent


PACKAGE = Path(glshade.__file__).parent

#: the layers, lowest first: a module may import its own layer and those below it. Each
#: chapter of the notes is one package (or module) at its public import path.
LAYERS = [
    {"_version", "atomic", "_callable", "interrupt", "_vec", "_srgb", "display", "errors",
     "modes",
     "options", "examples", "colormaps", "_paths"},
    {"parallel"},
    {"quaternion", "masspoint"},
    {"geometry"},
    {"brep"},
    {"patches"},
    {"solids"},
    {"octree"},
    {"scene"},
    {"io"},
    {"cpu", "hidden"},
    {"render"},
    {"pathtrace"},
    {"compare", "radiosity"},
    {"animate", "batch", "dataset"},
    {"viewer"},
    {"cli", "testing", "notebook", "__init__",
     "__main__"},
]
RANK = {name: i for i, layer in enumerate(LAYERS) for name in layer}
#: the import circles allowed: Mesh's methods that hand over to the modules built on Mesh
#: (``mesh.weld()`` -> merge, ``Mesh.from_trimesh`` -> trimesh_bridge), each a lazy import
#: inside the method with its reason (the facade trimesh uses too)
FACADE = {frozenset({"glshade.geometry.mesh", "glshade.geometry.merge"}),
          frozenset({"glshade.geometry.mesh", "glshade.geometry.trimesh_bridge"})}
#: GL-free packages: they never import moderngl, glfw or glcontext
GL_FREE = ["glshade", "glshade.geometry", "glshade.quaternion", "glshade.masspoint",
           "glshade.brep", "glshade.patches", "glshade.solids", "glshade.octree",
           "glshade.scene", "glshade.io", "glshade.viewer.controls",
           "glshade.cpu", "glshade.hidden", "glshade.compare", "glshade.animate",
           "glshade.batch", "glshade.parallel", "glshade.cli.parser", "glshade.pathtrace"]


@pytest.mark.parametrize("modules", GL_FREE)
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


def test_every_module_has_a_layer():
    for path in PACKAGE.rglob("*.py"):
        assert _part(path) in RANK, f"{path.relative_to(PACKAGE)} belongs to no layer"


def _module_name(path: Path) -> str:
    rel = path.relative_to(PACKAGE).with_suffix("")
    parts = ["glshade", *rel.parts]
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _module_imports(path: Path) -> set[str]:
    """The glshade modules that a module imports, lazy imports included (``from .x import
    y`` counts as ``x.y`` where y is a module, else as ``x``)."""
    import ast

    name = _module_name(path)
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[:len(base) - (node.level - 1)]
                target = ".".join([*base, *([node.module] if node.module else [])])
            else:
                target = node.module or ""
            if not target.startswith("glshade"):
                continue
            for alias in node.names:
                sub = f"{target}.{alias.name}"
                found.add(sub if _exists(sub) else target)
        elif isinstance(node, ast.Import):
            found.update(a.name for a in node.names if a.name.startswith("glshade."))
    found.discard(name)
    return {m for m in found if _exists(m)}


def _exists(module: str) -> bool:
    rel = Path(*module.split(".")[1:])
    return (PACKAGE / rel).with_suffix(".py").is_file() or (PACKAGE / rel / "__init__.py").is_file()


def test_no_import_circle_but_the_mesh_facade():
    """Strongly connected components of the module graph (lazy imports included): none but
    the documented facade pairs. (A package's __init__ importing its own modules, which
    import each other, is not a circle of the graph: edges go from importer to imported.)"""
    graph = {_module_name(p): _module_imports(p) for p in PACKAGE.rglob("*.py")}
    # an import of a package's module runs the package's __init__ first: follow it too
    for module in list(graph):
        parent = module.rpartition(".")[0]
        if parent.count(".") >= 1 and parent in graph and module != parent:
            graph[module] = graph[module] | set()  # (the edge parent -> module is its own)
    index, low, stack, on, circles = {}, {}, [], set(), []

    def visit(v):  # Tarjan, iteratively deep enough for this graph
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = set()
            while True:
                w = stack.pop()
                on.discard(w)
                component.add(w)
                if w == v:
                    break
            if len(component) > 1:
                circles.append(component)

    for v in sorted(graph):
        if v not in index:
            visit(v)
    unexplained = [sorted(c) for c in circles
                   if not all(frozenset(pair) in FACADE for pair in _pairs(c, graph))]
    assert unexplained == []


def _pairs(component, graph):
    return [(a, b) for a in component for b in graph[a] if b in component]


def _public_modules():
    import pkgutil

    for info in pkgutil.walk_packages([str(PACKAGE)], "glshade."):
        if not any(part.startswith("_") for part in info.name.split(".")[1:]):
            yield info.name


def _chapters() -> list[str]:
    """The public packages and top-level modules of glshade, from the files."""
    names = {p.stem if p.suffix == ".py" else p.name for p in PACKAGE.iterdir()
             if (p.suffix == ".py" or (p / "__init__.py").is_file())}
    return sorted(n for n in names if not n.startswith("_"))


@pytest.mark.parametrize("chapter", _chapters())
def test_every_chapter_is_an_attribute_of_glshade(chapter):
    """``glshade.<chapter>`` is the module ``import glshade.<chapter>`` gives, in a fresh
    interpreter where only ``import glshade`` ran (so the lazy names must find it)."""
    code = ("import glshade, importlib\n"
            f"value = glshade.{chapter}\n"
            f"assert value is importlib.import_module('glshade.{chapter}')\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr


def test_the_chapters_are_found():
    assert {"pathtrace", "patches", "solids", "radiosity", "notebook"} <= set(_chapters())


def test_every_exported_name_is_typed():
    """The TYPE_CHECKING block names exactly the exported names (so a type checker and an
    IDE see each one's real type), and each exported name loads."""
    import ast

    tree = ast.parse((PACKAGE / "__init__.py").read_text(encoding="utf-8"))
    block = next(n for n in tree.body if isinstance(n, ast.If)
                 and getattr(n.test, "id", None) == "TYPE_CHECKING")
    typed = {a.asname or a.name for n in block.body for a in n.names}
    exported = set(glshade.__all__) - {"__version__"}
    assert typed == exported
    assert all(getattr(glshade, name) is not None for name in exported)


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


@pytest.mark.parametrize("module", ["glshade", *sorted(_public_modules())])
def test_public_classes_and_functions_say_what_they_are(module):
    """Every class and function a module exports has a docstring (the API reference is made
    from them)."""
    import importlib
    import inspect

    mod = importlib.import_module(module)
    bare = []
    for name in getattr(mod, "__all__", []):
        obj = getattr(mod, name)
        if (inspect.isclass(obj) or inspect.isfunction(obj)) and not (obj.__doc__ or "").strip():
            bare.append(name)
    assert bare == []


def test_a_missing_test_extra_fails_in_ci_and_skips_elsewhere(monkeypatch):
    from tests.conftest import require

    monkeypatch.setenv("CI", "true")
    with pytest.raises(pytest.fail.Exception, match="missing in CI"):
        require("glshade_no_such_module", "a test extra")
    monkeypatch.delenv("CI")
    with pytest.raises(pytest.skip.Exception):
        require("glshade_no_such_module", "a test extra")
    assert require("numpy", "a dependency").__name__ == "numpy"


#: the longest a function may grow (lines, docstring included) before it is split
LONGEST = 80


def glsl_functions(source: str):
    """``(first line, lines, name)`` of each GLSL function defined in ``source``: from its
    signature (at the margin, wrapped over lines or not) to its closing brace at the margin;
    a prototype (a signature ending in ``;`` before any brace) is not a definition."""
    import re

    start = name = None
    opened = False
    for i, line in enumerate(source.splitlines(), start=1):
        found = re.match(r"^[a-z]\w*\s+(\w+)\s*\(", line)
        if start is None and found:
            start, name, opened = i, found.group(1), False
        if start is None:
            continue
        opened = opened or "{" in line
        if not opened and line.rstrip().endswith(";"):
            start = None  # (a prototype)
        elif opened and line.startswith("}"):
            yield start, i - start + 1, name
            start = None


def test_the_glsl_length_check_sees_wrapped_signatures():
    """The check's own parser: a signature over three lines counts from its first line; a
    one-line one too; a wrapped prototype is no function."""
    source = ("float wrapped(vec3 a,\n              vec3 b,\n              vec3 c) {\n"
              "    return 1.0;\n}\n"
              "vec3 declared(vec3 a,\n              vec3 b);\n"
              "void main() {\n    x = 1;\n    y = 2;\n}\n")
    assert list(glsl_functions(source)) == [(1, 5, "wrapped"), (8, 4, "main")]


def test_no_function_is_a_chapter():
    """Every Python function of glshade (its docstring aside) and every GLSL function of
    its shaders fits in LONGEST lines: past that, it holds parts that have names of their
    own."""
    import ast

    long = []
    for path in PACKAGE.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                lines = node.end_lineno - node.lineno + 1
                if ast.get_docstring(node) is not None:  # (its words are not its parts)
                    doc = node.body[0]
                    lines -= doc.end_lineno - doc.lineno + 1
                if lines > LONGEST:
                    long.append(f"{path.relative_to(PACKAGE)}:{node.lineno} {node.name} "
                                f"({lines} lines)")
    for path in (ROOT / "shaders").rglob("*"):
        if path.suffix == ".md" or not path.is_file():
            continue
        for start, lines, name in glsl_functions(path.read_text(encoding="utf-8")):
            if lines > LONGEST:
                long.append(f"shaders/{path.relative_to(ROOT / 'shaders')}:{start} {name} "
                            f"({lines} lines)")
    assert long == []


#: the most lines a shader file may have: past that it holds several concerns, each of which
#: can be an include of its own (the path tracer was one file of 606)
LONGEST_SHADER = 250


def test_no_shader_file_holds_several_concerns():
    """Every shader file (programs and includes) stays under LONGEST_SHADER lines."""
    long = [f"{p.relative_to(ROOT)} ({n} lines)" for p in sorted((ROOT / "shaders").rglob("*"))
            if p.is_file() and p.suffix != ".md"
            and (n := len(p.read_text(encoding="utf-8").splitlines())) > LONGEST_SHADER]
    assert long == []


def test_the_ray_triangle_test_is_written_once():
    """Moller-Trumbore (its first step, ``cross(d, e2)``) is in one shader file, which the
    path tracer and the shadow rays both include: one test, one way of judging a
    degenerate triangle."""
    import re

    step = re.compile(r"cross\(\s*d\s*,\s*e2\s*\)")
    files = [p.relative_to(ROOT / "shaders").as_posix()
             for p in sorted((ROOT / "shaders").rglob("*"))
             if p.is_file() and p.suffix != ".md" and step.search(p.read_text(encoding="utf-8"))]
    assert files == ["include/bvh_walk.glsl"]
    users = {p.name for p in (ROOT / "shaders").rglob("*.glsl")
             if '#include "bvh_walk.glsl"' in p.read_text(encoding="utf-8")}
    assert users == {"trace_scene.glsl", "shadow_trace.glsl"}


def test_uniforms_are_written_by_one_writer():
    """No module but render/programs.py (UniformWriter) sets a program member itself
    (``prog[name].value = ...`` or ``prog[name].write(...)``): the writer alone skips what a
    variant's compiler dropped, fits arrays and skips values already held."""
    import ast

    found = []
    for path in sorted((PACKAGE / "render").rglob("*.py")):
        if path.name == "programs.py":
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            target = None
            if isinstance(node, ast.Assign):
                target = node.targets[0]
                if not (isinstance(target, ast.Attribute) and target.attr == "value"):
                    continue
                target = target.value
            elif isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
                    and node.func.attr == "write":
                target = node.func.value
            if isinstance(target, ast.Subscript):
                found.append(f"{path.relative_to(PACKAGE)}:{node.lineno}")
    assert found == []
