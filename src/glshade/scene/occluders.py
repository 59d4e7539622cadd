"""What casts shadows: a scene's visible surfaces as world triangles, each with the polygon id
the renderer gives its polygon (so a point on a planar polygon can skip it). Pure numpy; the
shadow pass builds its BVH and its shadow maps from these."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Occluders", "occluders"]


@dataclass(frozen=True)
class Occluders:
    """What casts shadows: the scene's opaque triangles in the world, each with its
    polygon, and every mesh polygon's normal.

    Parameters
    ----------
    triangles : ndarray
        ``(T, 3, 3)`` float64 world positions.
    polygon : ndarray
        ``(T,)`` int64: the id of the mesh polygon each comes from, as
        :class:`~glshade.Frame` numbers them, or -1 (a tessellated patch's triangle: a
        curved patch may shade itself, so none is skipped).
    normals : ndarray
        ``(P, 3)`` the world unit normal of every mesh polygon by that id (zero for a
        hidden model's): the surface's own side for a ray's start.
    """

    triangles: np.ndarray
    polygon: np.ndarray
    normals: np.ndarray

    def __len__(self) -> int:
        return len(self.triangles)

    @property
    def bounds(self) -> np.ndarray:
        """``(2, 3)``: their box (zeros when there are none)."""
        if not len(self.triangles):
            return np.zeros((2, 3))
        p = self.triangles.reshape(-1, 3)
        return np.stack([p.min(0), p.max(0)])


def occluders(scene) -> Occluders:
    """The triangles of ``scene``'s visible opaque meshes and patch models (at their level),
    with zero-area triangles left out (no ray can hit them); transparent meshes cast none.

    Parameters
    ----------
    scene : Scene
        The scene whose opaque surfaces cast shadows.
    """
    tris, ids, normals = [], [], []
    base = 0
    for model in scene.models:
        mesh = model.mesh
        t, face = mesh.triangles
        n = np.zeros((mesh.n_faces, 3))
        if model.visible and len(t) and not model.transparent:  # (opaque only)
            m = model.transform
            v = mesh.vertices @ m[:3, :3].T + m[:3, 3]
            tris.append(v[t])
            ids.append(base + face)
            n = mesh.newell_normals @ np.linalg.inv(m[:3, :3])  # (the inverse transpose)
            length = np.linalg.norm(n, axis=1, keepdims=True)
            n = np.divide(n, length, out=np.zeros_like(n), where=length > 0)
        normals.append(n)
        base += mesh.n_faces
    if scene.patch_models:  # (the GPU tessellates them on the same grid)
        from ..patches import tessellate

        for p in scene.patch_models:
            if not p.visible:
                continue
            mesh = tessellate(p.patches, level=p.level).mesh
            t, _ = mesh.triangles
            v = mesh.vertices @ p.transform[:3, :3].T + p.transform[:3, 3]
            tris.append(v[t])
            ids.append(np.full(len(t), -1))
    normal = np.concatenate(normals) if normals else np.zeros((0, 3))
    if not tris:
        return Occluders(np.zeros((0, 3, 3)), np.zeros(0, np.int64), normal)
    triangles = np.concatenate(tris).astype(np.float64)
    polygon = np.concatenate(ids).astype(np.int64)
    area2 = np.linalg.norm(np.cross(triangles[:, 1] - triangles[:, 0],
                                    triangles[:, 2] - triangles[:, 0]), axis=1)
    keep = np.isfinite(triangles).all((1, 2)) & (area2 > 0)
    return Occluders(triangles[keep], polygon[keep], normal)
