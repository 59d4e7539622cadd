"""Read and write polygon meshes: Wavefront OBJ, OFF, PLY and STL, one module each.

Polygons are preserved (a quad stays a quad); STL, which only knows triangles, is welded
on load so that its topology is usable. Parsing is vectorized with numpy; a malformed file
raises :class:`~glshade.errors.MeshFormatError` naming the path, the line (or byte offset)
and what was wrong.
"""

from __future__ import annotations

import warnings
from pathlib import Path
from typing import Any

from ..atomic import atomic_write
from .._paths import file_fault
from ..errors import MeshFormatError
from ..geometry.mesh import Mesh
from ..geometry.trimesh_bridge import (
    HINT, from_trimesh, trimesh_formats, trimesh_module, trimesh_parts,
)
from . import obj, off, ply, stl

__all__ = ["load_mesh", "load_source", "save_mesh", "FORMATS"]

#: each format's module, with ``read(path, data) -> Mesh`` and ``write(mesh, file, binary)``
_MODULES = {"obj": obj, "off": off, "ply": ply, "stl": stl}
FORMATS = tuple(_MODULES)


def _format_of(path: Path, fmt: str | None, extra=()) -> str:
    fmt = (fmt or path.suffix.lstrip(".")).lower()
    if fmt not in FORMATS and fmt not in extra:
        more = (f"; through trimesh also {', '.join(sorted(set(extra) - set(FORMATS)))}"
                if extra else f" (and, with {HINT}, glTF/GLB, 3MF and more)")
        raise MeshFormatError(path, f"unknown mesh format {fmt!r}; supported: "
                              f"{', '.join(FORMATS)}{more}")
    return fmt


def load_mesh(path, format: str | None = None) -> Mesh:
    """Load a mesh from an OBJ, OFF, PLY or STL file (format from the extension); with
    the ``formats`` extra, also any format trimesh reads (glTF/GLB, 3MF, ...).

    Parameters
    ----------
    path : str or Path
        The file.
    format : str or None
        ``"obj"``, ``"off"``, ``"ply"``, ``"stl"`` ... (None: from the extension).

    Raises
    ------
    MeshFormatError
        The file is missing, unreadable or malformed; the message names the path and the
        line (or byte offset) and says what was wrong.
    """
    return read_mesh(Path(path), format)


def read_mesh(path: Path, format: str | None = None, extras_taken: bool = False) -> Mesh:
    """:func:`load_mesh`'s work; ``extras_taken``: a glTF's lights and cameras are read by
    the caller (:func:`~glshade.io.gltf.load_gltf`), so its warning does not name them."""
    fault = file_fault(path)
    if fault is not None:
        raise MeshFormatError(path, fault.replace("not a file", "not a mesh file"))
    native = (format or path.suffix.lstrip(".")).lower() in FORMATS
    # (trimesh is imported only for a format glshade does not read itself: it is slow to
    # import, and swallows a Ctrl-C that lands while it imports)
    fmt = _format_of(path, format, () if native else trimesh_formats())
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        raise MeshFormatError(path, "no such file") from None
    except IsADirectoryError:
        raise MeshFormatError(path, "is a directory, not a mesh file") from None
    except OSError as exc:
        raise MeshFormatError(path, f"cannot read: {exc.strerror or exc}") from None
    if not data.strip():
        raise MeshFormatError(path, "the file is empty")
    if fmt not in _MODULES:
        return load_with_trimesh(path, fmt, extras_taken)
    mesh = _MODULES[fmt].read(path, data)
    mesh.name = mesh.name or path.stem
    return mesh


def load_source(spec: str) -> Any:
    """A mesh from a ``primitive:NAME[:ARGS]`` spec or a file path (the command line's
    MESH argument); ``solid:TEXT`` gives a CSG solid (:mod:`glshade.solids.text`),
    ``patches:NAME`` or a ``.bpt`` file (the classic patch format) a
    :class:`~glshade.patches.PatchSurface`, a PLY or OBJ file of vertices alone a
    :class:`~glshade.geometry.points.PointCloud` (:func:`~glshade.io.points.load_points`).

    Parameters
    ----------
    spec : str
        A file path, ``primitive:NAME[:ARGS]``, ``solid:TEXT`` or ``patches:NAME``.
    """
    if spec.startswith("solid:"):
        from ..solids.text import parse_solid

        return parse_solid(spec[len("solid:"):], "solid")
    if spec.startswith("primitive:"):
        from ..geometry import primitives

        return primitives.from_spec(spec)
    if spec.startswith("patches:"):
        from .. import patches

        return patches.named(spec[len("patches:"):])
    from .points import is_point_set, load_points

    if is_point_set(spec):  # (a PLY or OBJ of vertices alone: a point cloud)
        return load_points(spec)
    if Path(spec).suffix.lower() == ".bpt":
        from ..patches import PatchSurface
        from ..patches.files import read_patches

        return PatchSurface(read_patches(spec), Path(spec).stem)
    return load_mesh(spec)


def save_mesh(mesh: Mesh, path, format: str | None = None, *, binary: bool = True) -> None:
    """Write ``mesh`` to ``path`` (atomically). PLY and STL are binary unless
    ``binary=False``; STL stores the triangulation. Coordinates keep full precision. An
    OBJ keeps texture coordinates and material parts, its materials written to an MTL
    file of the same name beside it (textures by their paths).

    Parameters
    ----------
    mesh : Mesh
        What to write.
    path : str or Path
        Where.
    format : str or None
        As :func:`load_mesh`.
    binary : bool
        PLY and STL: binary (else ASCII).
    """
    path = Path(path)
    fmt = _format_of(path, format)
    if fmt == "obj" and mesh.material_groups:
        from ..scene.material import Material
        from ..scene.pbr import PBRMaterial
        from .mtl import write_mtl

        library = path.with_suffix(".mtl")
        with atomic_write(library, "w") as text:
            write_mtl({k: m for k, m in mesh.materials.items()
                       if isinstance(m, (Material, PBRMaterial))}, text, library.parent)
        with atomic_write(path, "wb") as f:
            obj.write(mesh, f, binary, mtllib=library.name)
        return
    with atomic_write(path, "wb") as f:
        _MODULES[fmt].write(mesh, f, binary)


def load_with_trimesh(path: Path, fmt: str, extras_taken: bool = False) -> Mesh:
    """Read ``path`` through trimesh; any failure of its reader names the file."""
    trimesh = trimesh_module()
    try:
        loaded = trimesh.load(str(path), file_type=fmt, force=None)
    except Exception as exc:  # trimesh's readers raise anything on a bad file
        lines = [x for x in str(exc).strip().splitlines() if x.strip()]
        reason = lines[-1] if lines else type(exc).__name__
        raise MeshFormatError(path, f"trimesh could not read it as {fmt}: {reason}") from None
    parts = trimesh_parts(loaded, path.stem)
    if fmt in ("glb", "gltf"):
        from .gltf_json import gltf_unread

        unread = gltf_unread(path, extras_taken=extras_taken)
        if unread:
            warnings.warn(f"{path.name}: read and not drawn: {', '.join(unread)}",
                          UserWarning, stacklevel=4)
    # (a glTF's COLOR_0 is linear: trimesh scales it to bytes without a curve)
    mesh = from_trimesh(parts, name=path.stem, linear_colors=fmt in ("glb", "gltf"))
    from ..scene.describe import material_from_description

    # (the parts' materials, described by the bridge, made here: a glTF's metallic-roughness
    # ones PBRMaterials; what is read and not drawn, one warning naming it)
    mesh.materials = {name: material_from_description(d, f"{path.name}: {name}")
                      for name, d in mesh.materials.items()}
    return mesh
