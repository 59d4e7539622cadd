"""A surface's reflection coefficients (the notes' ka, kd, ks, n), and the checked colour
and number values that scene data is made of."""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from ..errors import GeometryError

__all__ = ["Material", "color3", "nonnegative"]


def color3(value, name) -> tuple[float, float, float]:
    c = np.asarray(value, dtype=np.float64)
    if c.shape == ():
        c = np.repeat(c, 3)
    if c.shape != (3,) or not np.isfinite(c).all() or (c < 0).any():
        raise GeometryError(f"{name} must be 3 non-negative numbers (r, g, b), got {value!r}")
    return tuple(float(x) for x in c)


def nonnegative(value, name) -> float:
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
        object.__setattr__(self, "color", color3(self.color, "color"))
        for name in ("ka", "kd", "ks", "shininess"):
            object.__setattr__(self, name, nonnegative(getattr(self, name), name))


    @classmethod
    def from_values(cls, values: dict) -> Material:
        """A Material from whichever of its fields ``values`` gives; the rest keep the
        dataclass defaults (the one place material defaults live)."""
        names = {f.name for f in fields(cls)}
        return cls(**{k: v for k, v in values.items() if k in names and v is not None})
