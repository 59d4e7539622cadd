"""Where a data set's views come from: cameras spread evenly on a sphere around the scene
(a Fibonacci lattice, each looking at the scene's centre from a distance that frames its
bounds), or a scene file's key-framed path sampled evenly."""

from __future__ import annotations

import numpy as np

from ..errors import OptionError
from ..scene.camera import Camera

__all__ = ["sphere_cameras", "GOLDEN_ANGLE"]

#: the turn between successive points of a Fibonacci lattice (radians): pi (3 - sqrt 5)
GOLDEN_ANGLE = np.pi * (3 - np.sqrt(5))


def sphere_cameras(bounds, views: int, size: tuple[int, int], *,
                   margin: float = 1.1) -> list[Camera]:
    """``views`` cameras on a Fibonacci sphere around ``bounds``: directions at evenly
    spaced heights (y from near 1 to near -1) turned by the golden angle, so every part of
    the sphere is seen about as often; each camera looks at the box's centre, up along +y
    (near the poles, -z), framed to fit the box's bounding sphere.

    Parameters
    ----------
    bounds : array_like
        ``(2, 3)`` the scene's box (min and max corners), or anything with ``bounds``.
    views : int
        How many cameras, >= 1.
    size : (int, int)
        The images' width and height in pixels (the framing's aspect).
    margin : float
        How much larger than the bounding sphere the view is.
    """
    if isinstance(views, bool) or not isinstance(views, (int, np.integer)) or views < 1:
        raise OptionError(f"views must be a whole number >= 1, got {views!r}")
    box = np.asarray(getattr(bounds, "bounds", bounds), np.float64)
    centre = box.mean(0)
    radius = max(float(np.linalg.norm(box[1] - box[0])) / 2, 1e-9)
    k = np.arange(views) + 0.5
    y = 1 - 2 * k / views
    ring = np.sqrt(np.maximum(1 - y * y, 0))
    turn = GOLDEN_ANGLE * np.arange(views)
    directions = np.stack([ring * np.sin(turn), y, ring * np.cos(turn)], -1)
    aspect = size[0] / size[1]
    out = []
    for d in directions:
        up = (0.0, 1.0, 0.0) if abs(d[1]) < 0.99 else (0.0, 0.0, -1.0)
        camera = Camera.look_at(centre + 3 * radius * d, centre, up)
        out.append(camera.frame(box, aspect, margin))
    return out
