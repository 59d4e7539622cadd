"""The bridge to trimesh (the ``formats`` extra): meshes to and from ``trimesh.Trimesh``
and ``trimesh.Scene``; ``glshade.io`` reads every format trimesh reads (glTF/GLB, 3MF, ...)
through it. trimesh is never needed by the rest of glshade."""

from __future__ import annotations

import numpy as np

from ..errors import EnvironmentFailure, MeshFormatError
from .mesh import Mesh

__all__ = ["from_trimesh", "to_trimesh", "trimesh_formats", "trimesh_module", "HINT"]

HINT = "pip install 'glshade[formats]'"


def trimesh_module():
    """trimesh, imported on first use, or an InputError saying how to install it."""
    try:
        import trimesh
    except ImportError:
        raise EnvironmentFailure(f"this needs trimesh: {HINT}") from None
    return trimesh


def trimesh_formats() -> tuple[str, ...]:
    """The file extensions trimesh can read here (empty when it is not installed)."""
    try:
        import trimesh
    except ImportError:
        return ()
    return tuple(sorted(trimesh.available_formats()))


def from_trimesh(tm, name: str | None = None) -> Mesh:
    """A glshade Mesh from a ``trimesh.Trimesh`` (triangles), or from a ``trimesh.Scene``
    with every node's transform applied (all its meshes joined)."""
    trimesh = trimesh_module()
    if isinstance(tm, trimesh.Scene):
        meshes = [g for g in tm.dump() if isinstance(g, trimesh.Trimesh)]
        if not meshes:
            raise MeshFormatError(name or "<trimesh scene>", "the scene holds no triangle mesh")
        tm = trimesh.util.concatenate(meshes)
    if not isinstance(tm, trimesh.Trimesh):
        raise MeshFormatError(name or "<trimesh object>", f"holds a {type(tm).__name__}, not "
                              "a surface (a point cloud or a path has no faces)")
    return Mesh(np.asarray(tm.vertices, np.float64), np.asarray(tm.faces, np.int64),
                name=name or tm.metadata.get("name"))


def to_trimesh(mesh: Mesh):
    """A ``trimesh.Trimesh`` of the mesh's triangulation (polygons are split; trimesh only
    knows triangles), vertices kept as they are."""
    trimesh = trimesh_module()
    return trimesh.Trimesh(vertices=mesh.vertices.copy(), faces=mesh.triangles[0].copy(),
                           process=False, metadata={"name": mesh.name})
