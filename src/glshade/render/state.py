"""What one draw is, as one frozen value that every pass receives.

``Renderer.draw`` works out, once per draw, the camera's matrices, the lights, the program
variant, the uniforms every program shares, the target's viewport and orientation; each pass
(the meshes, the CSG solids) reads them from this value instead of from the renderer, so no
pass reaches into another object's state, and what a pass may depend on is written here.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..options import DrawOptions
from ..scene import Camera, Scene
from .programs import Variant

__all__ = ["DrawState"]


@dataclass(frozen=True, eq=False)
class DrawState:
    """One draw's facts.

    Attributes
    ----------
    scene, camera, options : what is drawn, from where, how.
    view : (4, 4) float64 world-to-view matrix (column vectors).
    proj : (4, 4) float64 projection, flipped in y for a top-row-first target.
    lights : the lights of the draw (the scene's, or the default headlight), in order.
    variant : the program variant's fields (mode, aux outputs, light kinds, sRGB,
        orthographic) that every program of the draw shares.
    frame_uniforms : ``(name, value)`` pairs every program of the draw takes (projection,
        lights in view space, depth range).
    viewport : ``(x, y, w, h)`` in the target's pixels.
    flip_rows : whether the target stores row 0 at the top (its winding is mirrored).
    target : what is drawn into (an OffscreenTarget, a window's; ``bind(outputs)``).
    """

    scene: Scene
    camera: Camera
    options: DrawOptions
    view: np.ndarray
    proj: np.ndarray
    lights: tuple
    variant: Variant
    frame_uniforms: tuple
    viewport: tuple[int, int, int, int]
    flip_rows: bool
    target: Any = None

    @property
    def view_proj(self) -> np.ndarray:
        """(4, 4) world-to-clip matrix."""
        return self.proj @ self.view
