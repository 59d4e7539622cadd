"""Mass-points: points with mass, and vectors as mass-points of mass zero.

A mass-point is the pair ``(m P, m)``; ``m P`` alone has no meaning. The sum is the notes'
rule ``(m1 P1, m1) + (m2 P2, m2) = (m1 P1 + m2 P2, m1 + m2)``: the total mass sits at the
centre of mass. In quaternion terms ``(m P, m) = m O + m (P - O)``: the mass is the ``O``
part and ``m P`` the vector part (``to_quaternion``).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .errors import GeometryError

__all__ = ["MassPoint", "centroid", "mesh_center_of_mass"]


class MassPoint:
    """Arrays of mass-points: ``weighted (..., 3)`` = ``m P`` and ``mass (...)``.

    ``MassPoint(point, mass)`` needs ``mass != 0``; vectors are ``MassPoint.vector(v)``.

    Parameters
    ----------
    point : array_like
        ``(..., 3)`` positions (scene units).
    mass : array_like
        ``(...)`` masses, non-zero (broadcast against the points).
    """

    __slots__ = ("weighted", "mass")

    def __init__(self, point: ArrayLike, mass: ArrayLike = 1.0):
        p = np.asarray(point, dtype=np.float64)
        m = np.asarray(mass, dtype=np.float64)
        if p.shape[-1:] != (3,):
            raise GeometryError(f"point must have shape (..., 3), got {p.shape}")
        if np.any(m == 0):
            raise GeometryError("a mass-point needs a non-zero mass; use MassPoint.vector(v) "
                                "for a vector")
        shape = np.broadcast_shapes(p.shape[:-1], m.shape)
        self.mass = np.broadcast_to(m, shape).copy()
        self.weighted = np.broadcast_to(p * m[..., None], shape + (3,)).copy()

    @classmethod
    def _raw(cls, weighted, mass) -> MassPoint:
        obj = cls.__new__(cls)
        obj.weighted = np.asarray(weighted, dtype=np.float64)
        obj.mass = np.asarray(mass, dtype=np.float64)
        return obj

    @classmethod
    def vector(cls, v: ArrayLike) -> MassPoint:
        """Vectors as mass-points of mass zero: ``(v, 0)``.

        Parameters
        ----------
        v : array_like
            ``(..., 3)`` vectors.
        """
        v = np.asarray(v, dtype=np.float64)
        if v.shape[-1:] != (3,):
            raise GeometryError(f"vector must have shape (..., 3), got {v.shape}")
        return cls._raw(v.copy(), np.zeros(v.shape[:-1]))

    @property
    def point(self) -> NDArray[np.float64]:
        """``m P / m``: the affine point. An error for a vector (mass 0)."""
        if np.any(self.mass == 0):
            raise GeometryError("a vector (mass 0) has no point; read .weighted instead")
        return self.weighted / self.mass[..., None]

    @property
    def is_vector(self) -> NDArray[np.bool_]:
        return self.mass == 0

    def __add__(self, other: MassPoint) -> MassPoint:
        if not isinstance(other, MassPoint):
            return NotImplemented
        return MassPoint._raw(self.weighted + other.weighted, self.mass + other.mass)

    def __sub__(self, other: MassPoint) -> MassPoint:
        if not isinstance(other, MassPoint):
            return NotImplemented
        return MassPoint._raw(self.weighted - other.weighted, self.mass - other.mass)

    def __mul__(self, c: ArrayLike) -> MassPoint:
        """Scalar multiplication ``c (m P, m) = (c m P, c m)``: same point, c times the mass."""
        c = np.asarray(c, dtype=np.float64)
        return MassPoint._raw(self.weighted * c[..., None], self.mass * c)

    __rmul__ = __mul__

    def __neg__(self) -> MassPoint:
        return self * -1.0

    def sum(self, axis: int = 0) -> MassPoint:
        """Sum along an axis of the array of mass-points.

        Parameters
        ----------
        axis : int
            The axis of the array of mass-points to sum along.
        """
        return MassPoint._raw(self.weighted.sum(axis=axis), self.mass.sum(axis=axis))

    def to_quaternion(self) -> NDArray[np.float64]:
        """``(m P, m) = m O + m P``: ``[mPx, mPy, mPz, m]`` (scalar last)."""
        return np.concatenate([self.weighted, self.mass[..., None]], axis=-1)

    @classmethod
    def from_quaternion(cls, q: ArrayLike) -> MassPoint:
        """Inverse of :meth:`to_quaternion`: the ``O`` part is the mass.

        Parameters
        ----------
        q : array_like
            ``(..., 4)`` quaternions ``(x, y, z, w)``, w the mass.
        """
        q = np.asarray(q, dtype=np.float64)
        if q.shape[-1:] != (4,):
            raise GeometryError(f"q must have shape (..., 4), got {q.shape}")
        return cls._raw(q[..., :3].copy(), q[..., 3].copy())

    def __len__(self) -> int:
        return len(self.mass)

    def __getitem__(self, index) -> MassPoint:
        return MassPoint._raw(self.weighted[index], self.mass[index])

    def __repr__(self) -> str:
        if self.mass.ndim == 0:
            kind = "vector" if self.mass == 0 else f"point {self.point.tolist()}"
            return f"MassPoint({kind}, mass={float(self.mass)})"
        return f"MassPoint(array of {self.mass.shape})"


def centroid(points: ArrayLike, masses: ArrayLike | None = None) -> NDArray[np.float64]:
    """Centre of mass of points ``(n, 3)`` with masses ``(n,)`` (default equal): the point of
    the sum of the mass-points. Masses may be negative (a hole) but must not sum to zero.

    Parameters
    ----------
    points : array_like
        ``(n, 3)`` positions.
    masses : array_like or None
        ``(n,)`` masses (None: all 1).
    """
    p = np.asarray(points, dtype=np.float64)
    m = np.ones(len(p)) if masses is None else np.asarray(masses, dtype=np.float64)
    if p.ndim != 2 or p.shape[1] != 3 or m.shape != (len(p),):
        raise GeometryError(f"need points (n, 3) and masses (n,), got {p.shape} and {m.shape}")
    total = MassPoint._raw(p * m[:, None], m).sum()
    if total.mass == 0:
        raise GeometryError("the masses sum to zero: there is no centre of mass")
    return total.point


def mesh_center_of_mass(triangles, kind: str = "solid"):
    """Centre of mass ``(3,)`` of a Mesh or of triangles ``(T, 3, 3)``: of the solid they
    bound (``"solid"``: tetrahedra from the origin to each triangle, signed volumes as
    masses) or of the surface (``"surface"``: triangle centroids weighted by area).

    Parameters
    ----------
    triangles : Mesh or array_like
        A Mesh, or ``(T, 3, 3)`` triangles.
    kind : str
        ``"solid"`` or ``"surface"``.
    """
    if hasattr(triangles, "vertices") and hasattr(triangles, "triangles"):  # a Mesh
        triangles = triangles.vertices[triangles.triangles[0]]
    p = np.asarray(triangles, np.float64)
    if p.ndim != 3 or p.shape[1:] != (3, 3):
        raise GeometryError(f"need a Mesh or triangles of shape (T, 3, 3), got {p.shape}")
    if kind == "solid":
        mass = np.einsum("ij,ij->i", p[:, 0], np.cross(p[:, 1], p[:, 2])) / 6.0
        return centroid(p.sum(axis=1) / 4.0, mass)  # the origin is the 4th corner
    if kind == "surface":
        mass = 0.5 * np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1)
        return centroid(p.mean(axis=1), mass)
    raise GeometryError(f"kind must be 'solid' or 'surface', got {kind!r}")
