"""Exact surfaces that meshes approximate, as typed values that follow the mesh.

A sphere primitive remembers the sphere it was tessellated from, so a reference image can
ray-cast the true surface. ``Mesh.transformed`` and ``Mesh.flipped`` carry it along (an
ellipsoid is a transformed sphere; flipping turns its normals inward); operations that keep
the surface (welding, splitting creases) keep it unchanged.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import GeometryError
from .transforms import MAX_COORDINATE

__all__ = ["AnalyticSurface", "AnalyticSphere", "affine_matrix"]


def affine_matrix(matrix: ArrayLike, what: str = "matrix") -> NDArray[np.float64]:
    """A finite, nonsingular affine ``(4, 4)`` (a ``(3, 3)`` is widened); else a clear
    error.

    Parameters
    ----------
    matrix : array_like
        ``(4, 4)`` affine or ``(3, 3)`` linear.
    what : str
        What the matrix is, for the message.
    """
    try:
        m = np.asarray(matrix, dtype=np.float64)
    except (TypeError, ValueError):  # ragged, or not numbers
        raise GeometryError(f"{what} must be a 4x4 (or 3x3) array of numbers, got "
                            f"{matrix!r}") from None
    if m.shape == (3, 3):
        m = np.block([[m, np.zeros((3, 1))], [np.zeros((1, 3)), np.ones((1, 1))]])
    if m.shape != (4, 4):
        raise GeometryError(f"{what} must have shape (4, 4) or (3, 3), got {m.shape}")
    if not np.isfinite(m).all():
        raise GeometryError(f"{what} has a non-finite entry")
    if not np.allclose(m[3], (0, 0, 0, 1)):
        raise GeometryError(f"{what} must be affine (last row 0, 0, 0, 1), got {m[3].tolist()}")
    a = m[:3, :3]
    big = float(np.abs(a).max())
    if 0 < big < 1 / MAX_COORDINATE:
        raise GeometryError(f"{what} has entries no larger than {big:g}, too small to work "
                            f"with (its products underflow): keep its scale above "
                            f"{1 / MAX_COORDINATE:g}")
    if big > MAX_COORDINATE:
        raise GeometryError(f"{what} has an entry of {big:g}, too large to work with (its "
                            f"products overflow): keep its scale under {MAX_COORDINATE:g}")
    with np.errstate(all="ignore"):
        singular = big == 0 or not np.isfinite(np.linalg.cond(a / big)) or \
            np.linalg.cond(a / big) > 1e12
    if singular:
        raise GeometryError(f"{what} is singular or nearly (it flattens space: a zero scale, "
                            "or one tiny next to the others), so it cannot be inverted")
    return m


class AnalyticSurface:
    """What every exact surface offers: follow a transform or a flip, and meet rays."""

    def transformed(self, matrix: ArrayLike) -> AnalyticSurface:
        """This surface mapped by an affine matrix.

        Parameters
        ----------
        matrix : array_like
            ``(4, 4)`` affine, column vectors.
        """
        raise NotImplementedError

    def flipped(self) -> AnalyticSurface:
        raise NotImplementedError

    def intersect(self, origins, directions) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Nearest hit ``t (...,)`` (``inf`` on a miss) along ``origins + t directions`` with
        ``t > 0``, and the unit outward (or, when flipped, inward) normal there ``(..., 3)``.

        Parameters
        ----------
        origins, directions : array_like
            ``(..., 3)`` the rays.
        """
        raise NotImplementedError


@dataclass(frozen=True, eq=False)
class AnalyticSphere(AnalyticSurface):
    """The sphere of ``radius`` about the origin, mapped by the affine ``matrix`` (column
    vectors): an ellipsoid in general. ``inward`` normals after an odd number of flips.

    Parameters
    ----------
    radius : float
        The sphere's radius before the map.
    matrix : ndarray
        ``(4, 4)`` affine, column vectors.
    inward : bool
        Normals point inwards (a mirrored map).
    """

    radius: float = 1.0
    matrix: NDArray[np.float64] = field(default_factory=lambda: np.eye(4))
    inward: bool = False

    def __post_init__(self):
        r = float(self.radius)
        if not np.isfinite(r) or r <= 0:
            raise GeometryError(f"radius must be a positive number, got {self.radius!r}")
        object.__setattr__(self, "radius", r)
        m = affine_matrix(self.matrix, "the sphere's matrix")
        m.setflags(write=False)
        object.__setattr__(self, "matrix", m)

    def transformed(self, matrix: ArrayLike) -> AnalyticSphere:
        """This sphere mapped by an affine matrix.

        Parameters
        ----------
        matrix : array_like
            ``(4, 4)`` affine, column vectors.
        """
        m = affine_matrix(matrix)
        # a mirroring transform reverses the mesh's faces, which keeps the normals' sense
        return replace(self, matrix=m @ self.matrix)

    def flipped(self) -> AnalyticSphere:
        return replace(self, inward=not self.inward)

    def intersect(self, origins, directions):
        """Nearest hit ``t`` (``inf`` on a miss) along ``origins + t directions``, ``t >
        0``, and the unit normal there.

        Parameters
        ----------
        origins, directions : array_like
            ``(..., 3)`` the rays.
        """
        o = np.asarray(origins, dtype=np.float64)
        d = np.asarray(directions, dtype=np.float64)
        inv = np.linalg.inv(self.matrix)
        # the ray in the sphere's own space: o' + t d' (t is the same parameter)
        oo = o @ inv[:3, :3].T + inv[:3, 3]
        dd = d @ inv[:3, :3].T
        a = np.einsum("...i,...i", dd, dd)
        b = 2 * np.einsum("...i,...i", oo, dd)
        c = np.einsum("...i,...i", oo, oo) - self.radius**2
        disc = b * b - 4 * a * c
        hit = disc >= 0
        root = np.sqrt(np.where(hit, disc, 0))
        t_near = (-b - root) / (2 * a)
        t_far = (-b + root) / (2 * a)
        t = np.where(t_near > 0, t_near, t_far)  # from inside, the far wall
        hit &= t > 0
        t = np.where(hit, t, np.inf)
        p_obj = oo + np.where(hit, t, 0)[..., None] * dd
        n = p_obj @ inv[:3, :3]  # the inverse transpose applied to the normal
        n /= np.maximum(np.linalg.norm(n, axis=-1, keepdims=True), 1e-300)
        return t, -n if self.inward else n
