"""The example meshes and scene files, shipped in the wheel (the repository's ``assets/``
folder, mapped into it as ``glshade/examples``), so a pip-installed user can run every
example of the README and the docs.

    glshade.examples.names()               # ['cornell-box', 'csg-part', ..., 'teapot.obj', ...]
    glshade.examples.path("cornell-box")   # .../examples/scenes/cornell-box.toml
    glshade.examples.path("teapot.obj")    # .../examples/teapot.obj

On the command line an example is named the same way where a file is expected and no such
file exists: ``glshade radiosity cornell-box -o box.png``, ``glshade render teapot.obj``.
"""

from __future__ import annotations

import importlib.resources
from pathlib import Path

__all__ = ["folder", "names", "path", "resolve"]


def folder() -> Path:
    """The folder of the examples: package data in a wheel, the repository's ``assets/`` in
    an editable install."""
    packaged = Path(str(importlib.resources.files("glshade"))) / "examples"
    if packaged.is_dir():
        return packaged
    repo = Path(__file__).resolve().parents[2] / "assets"
    if repo.is_dir():
        return repo
    from .errors import EnvironmentFailure

    raise EnvironmentFailure(f"glshade's examples are missing: neither {packaged} nor {repo} "
                             "exists (a broken install? reinstall glshade)")


def _table() -> dict[str, Path]:
    root = folder()
    found = {p.stem: p for p in sorted((root / "scenes").glob("*.toml"))}
    found.update({p.name: p for p in sorted(root.iterdir())
                  if p.suffix.lower() in (".obj", ".off", ".ply", ".stl", ".glb", ".gltf")})
    return found


def names() -> list[str]:
    """Every example's name: scene files by their stem, meshes by their file name."""
    return sorted(_table())


def path(name: str) -> Path:
    """The file of the example ``name`` (a scene's stem, or a mesh's file name).

    Parameters
    ----------
    name : str
        The example's name (``glshade.examples.names()`` lists them).
    """
    from .errors import InputError

    table = _table()
    if name not in table:
        raise InputError(f"no example named {name!r}; the examples are "
                         f"{', '.join(sorted(table))}")
    return table[name]


def resolve(spec: str) -> str:
    """``spec`` itself when it names a file (or ``primitive:``, ``solid:``), else the example
    of that name when there is one: what the command line does with its inputs.

    Parameters
    ----------
    spec : str
        A file, a ``primitive:``/``solid:`` spec or an example's name.
    """
    if ":" in spec or "/" in spec or "\\" in spec or Path(spec).exists():
        return spec
    table = _table()
    return str(table[spec]) if spec in table else spec
