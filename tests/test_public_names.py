"""Tests use glshade's public names only: a test that reaches a private name breaks when
the code is refactored without a change of behaviour, and says nothing a user can rely on.
"""

import ast
from pathlib import Path

TESTS = Path(__file__).resolve().parent


def _private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def private_imports(source: str, filename: str = "<test>") -> list[str]:
    """``file:line`` of each import of a private glshade name (a module or a name whose
    dotted path has a part starting with one underscore), lazy imports included."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[0] == "glshade":
            parts = node.module.split(".")[1:] + [a.name for a in node.names]
            if any(_private(p) for p in parts):
                found.append(f"{filename}:{node.lineno} from {node.module} import "
                             f"{', '.join(a.name for a in node.names)}")
        elif isinstance(node, ast.Import):
            for alias in node.names:
                parts = alias.name.split(".")
                if parts[0] == "glshade" and any(_private(p) for p in parts[1:]):
                    found.append(f"{filename}:{node.lineno} import {alias.name}")
    return found


def test_the_guard_sees_each_kind_of_private_import():
    """The guard itself: each way of reaching a private name is caught, public ones pass."""
    caught = ["from glshade._display import buffers_image",
              "from glshade.hidden._depth_sort import split",
              "from glshade.compare.comparison import _reference",
              "import glshade.render._context",
              "def f():\n    from glshade.render.passes.pathtrace import _layout"]
    passed = ["from glshade.display import buffers_image", "import glshade.render.context",
              "from glshade import __version__", "from tests.conftest import _helper",
              "import numpy._core"]
    assert all(private_imports(code) for code in caught)
    assert not any(private_imports(code) for code in passed)


def test_no_test_imports_a_private_glshade_name():
    found = [hit for path in sorted(TESTS.rglob("*.py")) if path != Path(__file__)
             for hit in private_imports(path.read_text(encoding="utf-8"),
                                        str(path.relative_to(TESTS.parent)))]
    assert found == []
