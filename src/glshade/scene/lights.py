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

__all__ = ["PointLight", "DirectionalLight", "SpotLight", "lights_for", "MAX_LIGHTS"]

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
    range : float or None
        Where the light ends (KHR_lights_punctual's range): its light is multiplied by
        ``clamp(1 - (d / range)^4, 0, 1)^2``, glTF's window, in either lighting model; None:
        nowhere.
    """

    position: tuple = (5.0, 5.0, 5.0)
    color: tuple = (1.0, 1.0, 1.0)
    intensity: float = 1.0
    attenuation: tuple = (1.0, 0.0, 0.0)
    shadows: bool = True
    range: float | None = None

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
        object.__setattr__(self, "range", _check_range(self.range))

    def view_vector(self, view: NDArray[np.float64]) -> NDArray[np.float64]:
        """``[x, y, z, 1 / range]``: the position in view space, and the reciprocal of its
        range (0: none; lighting.glsl's window).

        Parameters
        ----------
        view : ndarray
            ``(4, 4)`` the world-to-view matrix.
        """
        x, y, z = view[:3, :3] @ self.position + view[:3, 3]
        return np.array([x, y, z, 1.0 / self.range if self.range else 0.0])

    def window(self, distance) -> np.ndarray:
        """KHR_lights_punctual's range window at ``distance``: 1 without a range.

        Parameters
        ----------
        distance : array_like
            Distances from the light.
        """
        return _window(self.range, distance)


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
    range = None  # (a directional light reaches everywhere)

    def window(self, distance) -> np.ndarray:
        """1: a directional light has no range.

        Parameters
        ----------
        distance : array_like
            Distances (ignored).
        """
        return np.ones(np.shape(distance))

    def view_vector(self, view: NDArray[np.float64]) -> NDArray[np.float64]:
        """``[x, y, z, 0]``: the unit vector towards the light, in view space.

        Parameters
        ----------
        view : ndarray
            ``(4, 4)`` the world-to-view matrix.
        """
        x, y, z = view[:3, :3] @ self.direction
        return np.array([-x, -y, -z, 0.0])


@dataclass(frozen=True)
class SpotLight:
    """A point light whose light leaves in a cone: KHR_lights_punctual's spot light. Full
    within ``inner_angle`` of ``direction``, none beyond ``outer_angle``, and between them
    a smooth falloff by the cosines: with ``s = clamp((cos a - cos outer) / (cos inner -
    cos outer), 0, 1)`` at angle ``a`` from the axis, the light is multiplied by ``s^2``
    (glTF's rule, which pyrender and three.js follow).

    The notes' model (:class:`~glshade.Material`) keeps its own rule for distance: none,
    unless ``attenuation=(c, l, q)`` asks, as for a :class:`PointLight`.

    Parameters
    ----------
    position : tuple
        ``(3,)`` world position.
    direction : tuple
        ``(3,)`` the way the cone points (world), non-zero.
    color : tuple
        Linear RGB, each >= 0.
    intensity : float
        A factor on the colour, >= 0.
    inner_angle : float
        Radians from the axis within which the light is full, in [0, outer_angle).
    outer_angle : float
        Radians from the axis beyond which there is none, in (0, pi/2].
    shadows : bool
        Whether it casts shadows where a draw casts them.
    attenuation : tuple
        ``(c, l, q)``: the light divided by ``c + l d + q d^2`` at distance d (the notes'
        model).
    range : float or None
        Where the light ends (KHR_lights_punctual's range), as for a :class:`PointLight`.
    """

    position: tuple = (0.0, 5.0, 0.0)
    direction: tuple = (0.0, -1.0, 0.0)
    color: tuple = (1.0, 1.0, 1.0)
    intensity: float = 1.0
    inner_angle: float = 0.0
    outer_angle: float = np.pi / 4
    shadows: bool = True
    attenuation: tuple = (1.0, 0.0, 0.0)
    range: float | None = None

    def __post_init__(self):
        point = PointLight(self.position, self.color, self.intensity, self.attenuation,
                           self.shadows, self.range)  # (the same checks, the same messages)
        for name in ("position", "color", "intensity", "attenuation", "range"):
            object.__setattr__(self, name, getattr(point, name))
        axis = DirectionalLight(self.direction).direction
        object.__setattr__(self, "direction", axis)
        inner, outer = float(self.inner_angle), float(self.outer_angle)
        if not (np.isfinite(outer) and 0 < outer <= np.pi / 2):
            raise SceneError(f"a spot light's outer_angle must be in (0, pi/2] radians, got "
                             f"{self.outer_angle!r}")
        if not (np.isfinite(inner) and 0 <= inner < outer):
            raise SceneError(f"a spot light's inner_angle must be in [0, outer_angle = "
                             f"{outer:g}) radians, got {self.inner_angle!r}")
        object.__setattr__(self, "inner_angle", inner)
        object.__setattr__(self, "outer_angle", outer)

    def cone(self) -> tuple[float, float]:
        """``(scale, offset)``: the falloff is ``clamp(cos(a) * scale + offset, 0, 1)^2``
        (KHR_lights_punctual's lightAngleScale and lightAngleOffset)."""
        scale = 1.0 / max(1e-3, np.cos(self.inner_angle) - np.cos(self.outer_angle))
        return float(scale), float(-np.cos(self.outer_angle) * scale)

    def falloff(self, points) -> np.ndarray:
        """The cone's factor at world ``points`` ``(..., 3)``: 1 within the inner cone, 0
        beyond the outer one.

        Parameters
        ----------
        points : array_like
            ``(..., 3)`` world positions.
        """
        to = np.asarray(points, np.float64) - self.position
        cos = (to @ np.asarray(self.direction)) / np.maximum(np.linalg.norm(to, axis=-1),
                                                               1e-300)
        scale, offset = self.cone()
        return np.clip(cos * scale + offset, 0.0, 1.0) ** 2

    # (a point light's place and range: the same view vector and window)
    view_vector = PointLight.view_vector
    window = PointLight.window

    def spot_vector(self, view: NDArray[np.float64]) -> NDArray[np.float64]:
        """``[sx, sy, sz, offset]``: the axis in view space times the cone's scale, and its
        offset (lighting.glsl's cone: ``clamp(dot(s, -L) + offset, 0, 1)^2``).

        Parameters
        ----------
        view : ndarray
            ``(4, 4)`` the world-to-view matrix.
        """
        scale, offset = self.cone()
        x, y, z = (view[:3, :3] @ self.direction) * scale
        return np.array([x, y, z, offset])


def _check_range(value) -> float | None:
    if value is None:
        return None
    r = float(value) if isinstance(value, (int, float, np.floating, np.integer)) and \
        not isinstance(value, bool) else float("nan")
    if not (np.isfinite(r) and r > 0):
        raise SceneError(f"a light's range must be a positive number (or None), got {value!r}")
    return r


def _window(range_: float | None, distance) -> np.ndarray:
    d = np.asarray(distance, np.float64)
    if not range_:
        return np.ones(d.shape)
    return np.clip(1.0 - (d / range_) ** 4, 0.0, 1.0) ** 2


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
