"""The public API's docstrings say what each parameter is: every function, class and
public method that any public module of glshade defines (the command line's aside: its
interface is the command, docs/guide/cli.md) has a
numpydoc ``Parameters`` section naming each of its parameters, and no other (the docs
build renders them)."""

import enum
import importlib
import inspect
import pkgutil
import re
import types

import pytest

import glshade
from glshade import pathtrace


FRONT = [(n, getattr(glshade, n)) for n in glshade.__all__
         if not n.startswith("__") and not isinstance(getattr(glshade, n), types.ModuleType)]
FRONT += [(f"pathtrace.{n}", getattr(pathtrace, n)) for n in pathtrace.__all__]


def _public_modules() -> list:
    """Every public module of glshade but the command line's (``glshade.cli`` is the
    command line, documented in docs/guide/cli.md, not a Python API)."""
    names = [m.name for m in pkgutil.walk_packages(glshade.__path__, "glshade.")
             if not any(part.startswith("_") for part in m.name.split(".")[1:])
             and not m.name.startswith("glshade.cli")]
    return [importlib.import_module(n) for n in names]


#: every public module's own names (those it defines, not those it re-exports)
FRONT += [(f"{m.__name__}.{n}", getattr(m, n)) for m in _public_modules()
          for n in getattr(m, "__all__", ())
          if getattr(getattr(m, n), "__module__", m.__name__) == m.__name__]


def _callables():
    for name, obj in FRONT:
        if inspect.isclass(obj) and issubclass(obj, BaseException):
            continue  # (an error's one parameter is its message)
        if inspect.isfunction(obj):
            yield name, obj
        elif inspect.isclass(obj):
            if not issubclass(obj, enum.Enum):
                yield name, obj
            for key, value in vars(obj).items():
                if key.startswith("_"):
                    continue
                if isinstance(value, (classmethod, staticmethod)):
                    value = value.__func__
                if inspect.isfunction(value):
                    yield f"{name}.{key}", value


def documented(doc: str) -> set:
    """The names a numpydoc Parameters section lists (``a, b : type`` lines, ``**kw``)."""
    found = re.search(r"^(?:Parameters|Attributes)\n-+\n(.*?)(?:\n\n[A-Z][A-Za-z ]+\n-+\n|\Z)",
                      doc, re.S | re.M)  # (a dataclass may list its fields as Attributes)
    if found is None:
        return set()
    names = set()
    entry = re.compile(r"^(\*{0,2}\w+(?:, \*{0,2}\w+)*)(?: : .*)?$")
    for line in found.group(1).splitlines():
        match = entry.match(line)
        if match:
            names.update(part.strip().lstrip("*") for part in match.group(1).split(","))
    return names


def test_the_section_reader():
    doc = ("Say.\n\nParameters\n----------\nx, y : float\n    The point.\n**changes\n"
           "    More.\n\nReturns\n-------\nfloat\n    Not a parameter.\n")
    assert documented(doc) == {"x", "y", "changes"}


CASES = list(_callables())


@pytest.mark.parametrize("name, obj", CASES, ids=[c[0] for c in CASES])
def test_every_parameter_is_documented(name, obj):
    params = list(inspect.signature(obj).parameters)
    if "." in obj.__qualname__ and params and params[0] in ("self", "cls"):
        params = params[1:]  # (a method's own object; a function's cls is a parameter)
    wanted = {p for p in params if not p.startswith("_")}  # (a dataclass's private field)
    if not wanted:
        return
    assert documented(inspect.getdoc(obj) or "") == wanted
