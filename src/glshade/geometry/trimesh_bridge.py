"""The bridge to trimesh (the ``formats`` extra): meshes to and from ``trimesh.Trimesh``
and ``trimesh.Scene``; ``glshade.io`` reads every format trimesh reads (glTF/GLB, 3MF, ...)
through it. trimesh is never needed by the rest of glshade."""

from __future__ import annotations

import numpy as np

from ..errors import EnvironmentFailure, MeshFormatError
from .mesh import Mesh

__all__ = ["from_trimesh", "to_trimesh", "trimesh_formats", "trimesh_module", "trimesh_parts",
           "HINT"]

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
    with every node's transform applied (all its meshes joined, in the order of
    :func:`trimesh_parts`; or such a list itself), with their texture coordinates. (Their
    materials are the reader's: ``glshade.io.meshes``.)

    Parameters
    ----------
    tm : trimesh.Trimesh or trimesh.Scene
        The mesh or scene.
    name : str or None
        The mesh's name.
    """
    trimesh = trimesh_module()
    meshes = tm if isinstance(tm, list) else trimesh_parts(tm, name)
    if not all(isinstance(m, trimesh.Trimesh) for m in meshes):
        raise MeshFormatError(name or "<trimesh object>", f"holds a {type(tm).__name__}, not "
                              "a surface (a point cloud or a path has no faces)")
    vertices, faces, uvs, base = [], [], [], 0
    for m in meshes:
        vertices.append(np.asarray(m.vertices, np.float64))
        f = np.asarray(m.faces, np.int64)
        faces.append(f + base)
        uv = getattr(m.visual, "uv", None) if getattr(m.visual, "kind", None) == "texture" \
            else None
        uvs.append(None if uv is None or len(uv) != len(m.vertices) else
                   np.asarray(uv, np.float64)[f].reshape(-1, 2))
        base += len(m.vertices)
    textured = any(u is not None for u in uvs)
    out = Mesh(np.concatenate(vertices), np.concatenate(faces),
               name=name or meshes[0].metadata.get("name"),
               uv=np.concatenate([u if u is not None else np.zeros((3 * len(f), 2))
                                  for u, f in zip(uvs, faces)]) if textured else None)
    return out


def trimesh_parts(tm, name: str | None = None) -> list:
    """The triangle meshes a trimesh object holds, placed: itself, or a scene's dumped.

    Parameters
    ----------
    tm : trimesh.Trimesh or trimesh.Scene
        The mesh or scene.
    name : str or None
        The name its parts take.
    """
    trimesh = trimesh_module()
    if not isinstance(tm, trimesh.Scene):
        return [tm]
    meshes = [g for g in tm.dump() if isinstance(g, trimesh.Trimesh)]
    if not meshes:
        raise MeshFormatError(name or "<trimesh scene>", "the scene holds no triangle mesh")
    return meshes


def to_trimesh(mesh: Mesh):
    """A ``trimesh.Trimesh`` of the mesh's triangulation (polygons are split; trimesh only
    knows triangles), vertices kept as they are.

    Parameters
    ----------
    mesh : Mesh
        The mesh.
    """
    trimesh = trimesh_module()
    return trimesh.Trimesh(vertices=mesh.vertices.copy(), faces=mesh.triangles[0].copy(),
                           process=False, metadata={"name": mesh.name})
