"""Lights, and the one rule for a scene without any: a white headlight at the eye.

The GPU programs, the numpy lighting twin and the command line all take their lights from
:func:`lights_for`, so a scene with no lights is lit the same way everywhere.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import SceneError, plain
from ..geometry.transforms import MAX_DRAWABLE_COORDINATE
from .material import color3, nonnegative

__all__ = ["PointLight", "DirectionalLight", "lights_for", "MAX_LIGHTS"]

MAX_LIGHTS = 8


@dataclass(frozen=True)
class PointLight:
    """A light at ``position`` (world). No distance attenuation by default (the notes'
    model); ``attenuation=(c, l, q)`` divides by ``c + l d + q d^2``. ``shadows=False``: the
    light reaches everything facing it even where a draw casts shadows.

    Parameters
    ----------
    position : tuple
        ``(3,)`` world position.
    color : tuple
        Linear RGB, each >= 0.
    intensity : float
        A factor on the colour, >= 0.
    attenuation : tuple
        ``(c, l, q)``: the light divided by ``c + l d + q d^2`` at distance d.
    shadows : bool
        Whether it casts shadows where a draw casts them.
    """

    position: tuple = (5.0, 5.0, 5.0)
    color: tuple = (1.0, 1.0, 1.0)
    intensity: float = 1.0
    attenuation: tuple = (1.0, 0.0, 0.0)
    shadows: bool = True

    def __post_init__(self):
        p = np.asarray(self.position, dtype=np.float64)
        if p.shape != (3,) or not np.isfinite(p).all():
            raise SceneError(f"light position must be 3 numbers, got {self.position!r}")
        if np.abs(p).max() > MAX_DRAWABLE_COORDINATE:
            # (the GPU's float32 squares the light's distance: beyond, it overflowed)
            raise SceneError(f"light position must be 3 numbers within "
                             f"{MAX_DRAWABLE_COORDINATE:g} of the origin (a light farther "
                             f"away is a DirectionalLight), got {plain(p)}")
        object.__setattr__(self, "position", tuple(p.tolist()))
        object.__setattr__(self, "color", color3(self.color, "light color"))
        object.__setattr__(self, "intensity", nonnegative(self.intensity, "light intensity"))
        att = color3(self.attenuation, "attenuation")
        if att == (0.0, 0.0, 0.0):
            raise SceneError("attenuation (c, l, q) must not be all zero")
        object.__setattr__(self, "attenuation", att)
        _check_shadows(self.shadows)

    def view_vector(self, view: NDArray[np.float64]) -> NDArray[np.float64]:
        """``[x, y, z, 1]``: the position in view space.

        Parameters
        ----------
        view : ndarray
            ``(4, 4)`` the world-to-view matrix.
        """
        x, y, z = view[:3, :3] @ self.position + view[:3, 3]
        return np.array([x, y, z, 1.0])


@dataclass(frozen=True)
class DirectionalLight:
    """A light infinitely far away. ``direction`` is the way the light travels, so the
    vector to the light is ``L = -direction``. ``shadows=False``: it casts none.

    Parameters
    ----------
    direction : tuple
        ``(3,)`` the way the light travels (world), non-zero.
    color : tuple
        Linear RGB, each >= 0.
    intensity : float
        A factor on the colour, >= 0.
    shadows : bool
        Whether it casts shadows where a draw casts them.
    """

    direction: tuple = (-1.0, -1.0, -1.0)
    color: tuple = (1.0, 1.0, 1.0)
    intensity: float = 1.0
    shadows: bool = True

    def __post_init__(self):
        d = np.asarray(self.direction, dtype=np.float64)
        if d.shape != (3,) or not np.isfinite(d).all() or not np.abs(d).max() > 0:
            raise SceneError(f"direction must be a non-zero 3-vector, got {self.direction!r}")
        d = d / np.abs(d).max()  # (scaled first: the length of (1e308, 1, 1) overflows)
        object.__setattr__(self, "direction", tuple((d / np.linalg.norm(d)).tolist()))
        object.__setattr__(self, "color", color3(self.color, "light color"))
        object.__setattr__(self, "intensity", nonnegative(self.intensity, "light intensity"))
        _check_shadows(self.shadows)

    attenuation = (1.0, 0.0, 0.0)

    def view_vector(self, view: NDArray[np.float64]) -> NDArray[np.float64]:
        """``[x, y, z, 0]``: the unit vector towards the light, in view space.

        Parameters
        ----------
        view : ndarray
            ``(4, 4)`` the world-to-view matrix.
        """
        x, y, z = view[:3, :3] @ self.direction
        return np.array([-x, -y, -z, 0.0])


def _check_shadows(value) -> None:
    if not isinstance(value, bool):
        raise SceneError(f"a light's shadows must be true or false, got {value!r}")


def lights_for(lights, camera) -> list:
    """The lights a draw uses: ``lights``, or -- when there are none -- the default, a white
    point light at the camera (a headlight: whatever faces the viewer is lit); from a camera
    beyond the coordinates a light may have, a light along its view, the point light's
    limit.

    Parameters
    ----------
    lights : list
        The scene's PointLights and DirectionalLights.
    camera : Camera
        The draw's camera (the headlight sits at its eye).
    """
    lights = list(lights)
    if lights:
        return lights
    eye = np.asarray(camera.position, np.float64)
    if np.abs(eye).max() > MAX_DRAWABLE_COORDINATE:  # (too far to light from: its limit)
        return [DirectionalLight(tuple(float(x) for x in camera.forward))]
    return [PointLight(tuple(float(x) for x in eye))]
