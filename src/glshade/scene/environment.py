"""Light from every direction at infinity: a constant colour, or an equirectangular
(latitude-longitude) image of radiance -- what modern assets are lit by, and what the path
tracer samples by importance. No GL.

The map's convention (one home; the tracer's GLSL, ``trace_environment.glsl``, reads it
so): a world direction ``d = (x, y, z)``, +y up, is the image's column ``u W`` and row
``v H`` with ``u = 0.5 + atan2(x, -z) / (2 pi)`` -- the middle column straight ahead of
the default camera, which looks down -z -- and ``v = acos(y) / pi``, row 0 the zenith.
``rotation`` turns the map about +y by that many radians (counter-clockwise seen from
above): a direction is looked up turned back by it."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import SceneError

__all__ = ["Environment"]

#: the image a constant colour is sampled as (the tracer's choice of direction is by this
#: grid's rows, each weighted by its solid angle: coarse is enough for one colour)
CONSTANT_GRID = (32, 16)


@dataclass(frozen=True, eq=False)
class Environment:
    """Radiance arriving from infinitely far away, in every direction: the sky.

    Parameters
    ----------
    image : array_like
        ``(3,)`` a constant linear RGB radiance, or ``(H, W, 3)`` an equirectangular image
        of linear radiance (W = 2 H is usual; the module's header gives the mapping).
    intensity : float
        A factor on it, >= 0.
    rotation : float
        Radians the map turns about +y.

    Examples
    --------
    >>> sky = Environment((0.6, 0.7, 0.9), intensity=1.5)
    >>> sky.radiance.shape
    (16, 32, 3)
    """

    image: ArrayLike
    intensity: float = 1.0
    rotation: float = 0.0
    #: whether it is one colour (``image`` was ``(3,)``)
    constant: bool = field(init=False, default=False)

    def __post_init__(self):
        a = np.asarray(self.image, dtype=np.float64)
        constant = a.shape == (3,)
        if constant:
            a = np.broadcast_to(a, (*CONSTANT_GRID[::-1], 3)).copy()
        if a.ndim != 3 or a.shape[2] != 3 or a.shape[0] < 1 or a.shape[1] < 1:
            raise SceneError(f"an environment is (r, g, b) or an (H, W, 3) image, got shape "
                             f"{np.shape(self.image)}")
        if not np.isfinite(a).all() or (a < 0).any():
            raise SceneError("an environment's radiance must be finite and >= 0")
        intensity = float(self.intensity)
        if not (math.isfinite(intensity) and intensity >= 0):
            raise SceneError(f"environment intensity must be >= 0, got {self.intensity!r}")
        rotation = float(self.rotation)
        if not math.isfinite(rotation):
            raise SceneError(f"environment rotation must be a finite angle, got "
                             f"{self.rotation!r}")
        a.setflags(write=False)
        object.__setattr__(self, "image", a)
        object.__setattr__(self, "intensity", intensity)
        object.__setattr__(self, "rotation", rotation)
        object.__setattr__(self, "constant", constant)

    @property
    def radiance(self) -> NDArray[np.float64]:
        """``(H, W, 3)`` the map's radiance, intensity applied."""
        return np.asarray(self.image) * self.intensity

    def __repr__(self) -> str:
        image = np.asarray(self.image)
        h, w, _ = image.shape
        what = (f"({', '.join(f'{x:g}' for x in image[0, 0])})" if self.constant
                else f"{w}x{h} image")
        return (f"Environment({what}, intensity={self.intensity:g}"
                f"{f', rotation={self.rotation:g}' if self.rotation else ''})")
