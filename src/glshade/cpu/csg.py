"""The numpy reference of the GPU's CSG pass: the same pixel rays (through pixel centres,
from the near plane), Roth's ray casting (:meth:`Solid.intersect`) in float64, and the
renderer's outputs -- view depth, world normal and id (the scene's mesh polygons first,
then each solid's leaves)."""

from __future__ import annotations

import numpy as np

from ..scene import Scene

__all__ = ["render_solids"]


def render_solids(scene: Scene, camera, size=(256, 256)):
    """``(depth (H, W), normal (H, W, 3), face_id (H, W))`` of the scene's solids alone
    (its meshes only count for the ids): inf, zero and -1 where no solid is hit.

    Parameters
    ----------
    scene : Scene
        Its solids are cast (its meshes count for the ids).
    camera : Camera
        From where.
    size : (int, int)
        Width and height.
    """
    from ..hidden.view import prepare

    width, height = size
    camera = camera.with_planes(scene.bounds)  # (as the renderer fits them)
    p = prepare(Scene(), camera, size)
    view = camera.view_matrix()
    inv = np.linalg.inv(view)  # the rays, from view space to the world's
    o = p.ray_origin @ inv[:3, :3].T + inv[:3, 3]
    d = p.ray_dir @ inv[:3, :3].T
    best = np.full(len(o), np.inf)
    normal = np.zeros((len(o), 3))
    face = np.full(len(o), -1, np.int64)
    base = sum(m.mesh.n_faces for m in scene.models)
    for model in scene.solids:
        if not model.visible:
            continue
        t, n, leaf = model.solid.intersect(o, d)
        hit = np.isfinite(t)
        point = o[hit] + t[hit, None] * d[hit]
        depth = np.full(len(o), np.inf)
        depth[hit] = -(point @ view[2, :3] + view[2, 3])
        nearer = (depth < best) & (depth <= camera.far)
        best[nearer], normal[nearer], face[nearer] = depth[nearer], n[nearer], \
            base + leaf[nearer]
        base += len(model.solid.leaves())
    # seen from inside the solid, the surface faces the eye (as the GPU shows it)
    facing = np.einsum("nd,nd->n", normal, d) > 0
    normal[facing] *= -1
    return (best.reshape(height, width), normal.reshape(height, width, 3),
            face.reshape(height, width))
