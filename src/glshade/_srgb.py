"""The sRGB transfer curve (IEC 61966-2-1), both ways, in one place for every layer: the
texture and mesh readers decode with it, the trimesh bridge encodes and decodes colour
bytes, the CPU twin encodes its pictures."""

from __future__ import annotations

import numpy as np

__all__ = ["srgb_to_linear", "linear_to_srgb"]


def srgb_to_linear(c) -> np.ndarray:
    """sRGB-encoded values in [0, 1] to linear light, float64.

    Parameters
    ----------
    c : array_like
        sRGB-encoded values in [0, 1], any shape.
    """
    c = np.asarray(c, np.float64)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def linear_to_srgb(c) -> np.ndarray:
    """Linear values in [0, 1] to sRGB-encoded ones, float64 (clamped to [0, 1] first).

    Parameters
    ----------
    c : array_like
        Linear values, any shape.
    """
    c = np.clip(np.asarray(c, np.float64), 0.0, 1.0)
    return np.where(c > 0.0031308, 1.055 * c ** (1 / 2.4) - 0.055, 12.92 * c)
