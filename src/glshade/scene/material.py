"""A surface's reflection coefficients (the notes' ka, kd, ks, n), and the checked colour
and number values that scene data is made of."""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from ..errors import SceneError

__all__ = ["Material", "color3", "nonnegative"]


def color3(value, name) -> tuple[float, float, float]:
    """An RGB triple of finite numbers in [0, 1], or a SceneError naming ``name``."""
    c = np.asarray(value, dtype=np.float64)
    if c.shape == ():
        c = np.repeat(c, 3)
    if c.shape != (3,) or not np.isfinite(c).all() or (c < 0).any():
        raise SceneError(f"{name} must be 3 non-negative numbers (r, g, b), got {value!r}")
    return float(c[0]), float(c[1]), float(c[2])


def nonnegative(value, name) -> float:
    """A finite number >= 0, or a SceneError naming ``name``."""
    v = float(value)
    if not np.isfinite(v) or v < 0:
        raise SceneError(f"{name} must be a non-negative number, got {value!r}")
    return v


@dataclass(frozen=True)
class Material:
    """The notes' reflection coefficients: ambient ``ka``, diffuse ``kd``, specular ``ks``
    and the specular exponent ``shininess`` (``n``). Ambient and diffuse multiply
    ``color``; specular takes the light's colour.

    For radiosity (diffuse surfaces only): ``emission`` E, the radiosity a surface gives
    off by itself (RGB, any non-negative size), and ``reflectance`` the notes' rho_d
    (RGB, each in [0, 1]); without it, rho_d = kd * color.

    ``opacity`` in [0, 1]: below 1 the surface is transparent, composited "over" what lies
    behind it (:class:`~glshade.DrawOptions` ``transparency``) after the opaque ones."""

    color: tuple = (0.8, 0.8, 0.8)
    ka: float = 0.2
    kd: float = 0.7
    ks: float = 0.3
    shininess: float = 32.0
    emission: tuple = (0.0, 0.0, 0.0)
    reflectance: tuple | None = None
    opacity: float = 1.0

    def __post_init__(self):
        object.__setattr__(self, "color", color3(self.color, "color"))
        for name in ("ka", "kd", "ks", "shininess"):
            object.__setattr__(self, name, nonnegative(getattr(self, name), name))
        object.__setattr__(self, "emission", color3(self.emission, "emission"))
        opacity = nonnegative(self.opacity, "opacity")
        if opacity > 1:
            raise SceneError(f"opacity must be in [0, 1] (1: opaque), got {opacity:g}")
        object.__setattr__(self, "opacity", opacity)
        if self.reflectance is not None:
            rho = color3(self.reflectance, "reflectance")
            if max(rho) > 1:
                raise SceneError(f"reflectance must be 3 numbers in [0, 1] (a surface "
                                    f"reflects at most what it receives), got {rho}")
            object.__setattr__(self, "reflectance", rho)

    @property
    def rho(self) -> tuple[float, float, float]:
        """The diffuse reflectance rho_d (RGB) radiosity uses."""
        if self.reflectance is not None:
            return self.reflectance
        return tuple(self.kd * c for c in self.color)

    @property
    def transparent(self) -> bool:
        return self.opacity < 1.0

    @classmethod
    def from_values(cls, values: dict) -> Material:
        """A Material from whichever of its fields ``values`` gives; the rest keep the
        dataclass defaults (the one place material defaults live)."""
        names = {f.name for f in fields(cls)}
        return cls(**{k: v for k, v in values.items() if k in names and v is not None})
