"""Why a render came out blank: what the scene's data can tell."""

from __future__ import annotations

import numpy as np

from ..modes import Culling
from ..scene import Camera, Scene

__all__ = ["why_blank"]


def why_blank(scene: Scene, camera: Camera, cull: Culling = Culling.AUTO) -> str:
    """Why a render of ``scene`` covers no pixel, as far as the data can tell (``cull``: the
    draw's back-face culling).

    Parameters
    ----------
    scene : Scene
        What was drawn.
    camera : Camera
        From where.
    cull : Culling
        The draw's back-face culling.
    """
    drawn = [m for m in scene.models if m.visible and len(m.mesh.triangles[0])]
    solids = [s for s in scene.solids if s.visible]
    clouds = [c for c in scene.clouds if c.visible]
    if clouds and not drawn and not solids:
        return ("the render is blank: no point of the clouds lies in the camera's view "
                "(between its near and far planes, inside its field of view)")
    empty = [s for s in solids if (b := s.solid.bounds) is not None and np.prod(b[1] - b[0]) == 0]
    if solids and len(empty) == len(solids) and not drawn:
        names = ", ".join(str(s.name) for s in empty)
        return (f"the render is blank: the solid ({names}) is empty -- an intersection of "
                "parts that do not meet")
    if not drawn and not solids:
        return "the render is blank: the scene has nothing to draw (no visible mesh with faces)"
    if not drawn:
        return ("the render is blank: no solid surface lies in the camera's view (or the "
                "solids are empty: parts of an intersection that do not meet)")
    if not clouds and all(len(m.mesh.degenerate_faces) == m.mesh.n_faces for m in drawn):
        return ("the render is blank: every face has zero area (identical or collinear "
                "vertices)")
    b = scene.bounds
    extent = float(np.linalg.norm(b[1] - b[0]))
    distance = float(np.linalg.norm(b.mean(axis=0) - camera.position))
    if extent < 1e-6 * max(distance, 1e-300):
        return (f"the render is blank: the scene is {extent:.3g} across, seen from "
                f"{distance:.3g} away -- smaller than a pixel (frame it, or scale it up)")
    if Culling.parse(cull) is Culling.ON:  # from inside (or cut by the near plane): all back
        view = camera.view_matrix()
        for m in drawn:
            if (m.corners @ view[2, :3] + view[2, 3] >= -camera.planes(b)[0]).any():
                return ("the render is blank: back faces are culled (cull=True) and the "
                        "camera may be inside a mesh, where every face turns its back to it "
                        "(use cull='auto' or False)")
    return ("the render is blank: no part of the scene lies in the camera's view (between "
            "its near and far planes, inside its field of view)")
