"""What is drawn: meshes with materials and transforms, lights, ambient and background.

Plain data (numpy arrays), no GL handles: the renderer keeps the GPU copies.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .errors import GeometryError
from .geometry.mesh import Mesh
from .geometry.transforms import compose_transform

__all__ = ["Material", "PointLight", "DirectionalLight", "Model", "Scene", "MAX_LIGHTS"]

MAX_LIGHTS = 8


def _color(value, name) -> tuple[float, float, float]:
    c = np.asarray(value, dtype=np.float64)
    if c.shape == ():
        c = np.repeat(c, 3)
    if c.shape != (3,) or not np.isfinite(c).all() or (c < 0).any():
        raise GeometryError(f"{name} must be 3 non-negative numbers (r, g, b), got {value!r}")
    return tuple(float(x) for x in c)


def _nonneg(value, name) -> float:
    v = float(value)
    if not np.isfinite(v) or v < 0:
        raise GeometryError(f"{name} must be a non-negative number, got {value!r}")
    return v


@dataclass(frozen=True)
class Material:
    """The notes' reflection coefficients: ambient ``ka``, diffuse ``kd``, specular ``ks``
    and the specular exponent ``shininess`` (``n``). Ambient and diffuse multiply
    ``color``; specular takes the light's colour."""

    color: tuple = (0.8, 0.8, 0.8)
    ka: float = 0.2
    kd: float = 0.7
    ks: float = 0.3
    shininess: float = 32.0

    def __post_init__(self):
        object.__setattr__(self, "color", _color(self.color, "color"))
        for name in ("ka", "kd", "ks", "shininess"):
            object.__setattr__(self, name, _nonneg(getattr(self, name), name))


@dataclass(frozen=True)
class PointLight:
    """A light at ``position`` (world). No distance attenuation by default (the notes'
    model); ``attenuation=(c, l, q)`` divides by ``c + l d + q d^2``."""

    position: tuple = (5.0, 5.0, 5.0)
    color: tuple = (1.0, 1.0, 1.0)
    intensity: float = 1.0
    attenuation: tuple = (1.0, 0.0, 0.0)

    def __post_init__(self):
        p = np.asarray(self.position, dtype=np.float64)
        if p.shape != (3,) or not np.isfinite(p).all():
            raise GeometryError(f"light position must be 3 numbers, got {self.position!r}")
        object.__setattr__(self, "position", tuple(p.tolist()))
        object.__setattr__(self, "color", _color(self.color, "light color"))
        object.__setattr__(self, "intensity", _nonneg(self.intensity, "light intensity"))
        att = _color(self.attenuation, "attenuation")
        if att == (0.0, 0.0, 0.0):
            raise GeometryError("attenuation (c, l, q) must not be all zero")
        object.__setattr__(self, "attenuation", att)

    def view_vector(self, view: NDArray[np.float64]) -> NDArray[np.float64]:
        """``[x, y, z, 1]``: the position in view space."""
        return view @ np.append(self.position, 1.0)


@dataclass(frozen=True)
class DirectionalLight:
    """A light infinitely far away. ``direction`` is the way the light travels, so the
    vector to the light is ``L = -direction``."""

    direction: tuple = (-1.0, -1.0, -1.0)
    color: tuple = (1.0, 1.0, 1.0)
    intensity: float = 1.0

    def __post_init__(self):
        d = np.asarray(self.direction, dtype=np.float64)
        if d.shape != (3,) or not np.isfinite(d).all() or np.linalg.norm(d) == 0:
            raise GeometryError(f"direction must be a non-zero 3-vector, got {self.direction!r}")
        object.__setattr__(self, "direction", tuple((d / np.linalg.norm(d)).tolist()))
        object.__setattr__(self, "color", _color(self.color, "light color"))
        object.__setattr__(self, "intensity", _nonneg(self.intensity, "light intensity"))

    attenuation = (1.0, 0.0, 0.0)

    def view_vector(self, view: NDArray[np.float64]) -> NDArray[np.float64]:
        """``[x, y, z, 0]``: the unit vector towards the light, in view space."""
        return np.append(view[:3, :3] @ -np.asarray(self.direction), 0.0)


_model_ids = itertools.count()


@dataclass(eq=False)
class Model:
    """One mesh placed in a scene."""

    mesh: Mesh
    material: Material = field(default_factory=Material)
    transform: NDArray[np.float64] = field(default_factory=lambda: np.eye(4))
    name: str | None = None
    visible: bool = True


class Scene:
    """Meshes, lights, ambient intensity ``Ia`` and background colour.

    A scene with no lights is drawn with a default headlight: a white point light at the
    camera (so what faces the viewer is lit), documented here and in the README.
    """

    def __init__(self, ambient: ArrayLike = (1.0, 1.0, 1.0),
                 background: ArrayLike = (0.0, 0.0, 0.0, 1.0)):
        self.ambient = _color(ambient, "ambient")
        bg = np.asarray(background, dtype=np.float64)
        if bg.shape == (3,):
            bg = np.append(bg, 1.0)
        if bg.shape != (4,) or not np.isfinite(bg).all():
            raise GeometryError(f"background must be (r, g, b) or (r, g, b, a), got "
                                f"{background!r}")
        self.background = tuple(float(x) for x in bg)
        self.models: list[Model] = []
        self.lights: list = []

    def add(self, mesh: Mesh, material: Material | None = None, transform: ArrayLike | None = None,
            *, rotation: ArrayLike | None = None, translation: ArrayLike = (0, 0, 0),
            scale: ArrayLike = 1.0, name: str | None = None) -> Model:
        """Add a mesh. Place it with a 4x4 ``transform`` (column vectors), or with a
        quaternion ``rotation``, ``translation`` and ``scale`` (T R S)."""
        if not isinstance(mesh, Mesh):
            raise GeometryError(f"scene.add needs a Mesh, got {type(mesh).__name__}")
        if transform is not None:
            m = np.asarray(transform, dtype=np.float64)
            if m.shape != (4, 4) or not np.isfinite(m).all():
                raise GeometryError(f"transform must be a finite 4x4 matrix, got shape "
                                    f"{m.shape}")
        else:
            m = compose_transform(rotation, translation, scale)
        if abs(np.linalg.det(m[:3, :3])) < 1e-300:
            raise GeometryError("transform is singular (a zero scale?)")
        model = Model(mesh, material or Material(), m, name or mesh.name)
        self.models.append(model)
        return model

    def add_light(self, light) -> None:
        if not isinstance(light, (PointLight, DirectionalLight)):
            raise GeometryError(f"expected a PointLight or DirectionalLight, got {light!r}")
        if len(self.lights) >= MAX_LIGHTS:
            raise GeometryError(f"at most {MAX_LIGHTS} lights per scene")
        self.lights.append(light)

    def bounds(self) -> NDArray[np.float64]:
        """World bounding box ``(2, 3)`` of the visible models."""
        pts = []
        for m in self.models:
            if not m.visible or m.mesh.n_vertices == 0:
                continue
            b = m.mesh.bounds
            corners = np.array([[x, y, z] for x in b[:, 0] for y in b[:, 1] for z in b[:, 2]])
            pts.append(corners @ m.transform[:3, :3].T + m.transform[:3, 3])
        if not pts:
            return np.zeros((2, 3))
        p = np.vstack(pts)
        return np.stack([p.min(0), p.max(0)])
