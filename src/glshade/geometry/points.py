"""Point clouds: scans, samples, particle states -- points with a size, drawn without a mesh.

A :class:`PointCloud` is plain data (numpy), checked once when made. Its points are drawn
by the GPU as spheres ray cast per pixel (exact depth and normals, so they meet meshes in
the z-buffer where the surfaces really cross), as discs oriented by their normals, or as
screen-aligned squares, the cheap style for millions (``glshade.modes.PointStyle``). Each
point is one id of ``Frame.face_id``, numbered after the polygons (as solids' leaves are).

Sizes are radii in world units, one for all or one a point, or ``pixel_size``: a diameter
on screen, the same at every depth (a sphere's radius is then what that diameter is at its
centre's depth).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import GeometryError, plain
from ..modes import PointStyle, choose
from .transforms import MAX_DRAWABLE_COORDINATE

__all__ = ["PointCloud"]


def _array(values, name: str, n: int | None, width: int | None) -> NDArray[np.float64]:
    """``values`` as finite float64 ``(n, width)`` (``(n,)`` when width is None), else a
    GeometryError naming ``name`` and the first bad entry."""
    try:
        a = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise GeometryError(f"{name} must be an array of numbers, got "
                            f"{type(values).__name__}") from None
    want = (n if n is not None else "N",) + ((width,) if width else ())
    shape_ok = a.ndim == len(want) and (width is None or a.shape[-1] == width) and \
        (n is None or a.shape[0] == n)
    if not shape_ok:
        raise GeometryError(f"{name} must have shape ({', '.join(map(str, want))}), got "
                            f"{a.shape}")
    bad = ~np.isfinite(a) if a.ndim == 1 else ~np.isfinite(a).all(1)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise GeometryError(f"{name}[{i}] is not finite: {plain(a[i].tolist())} "
                            f"({int(bad.sum())} of {len(a)} such)")
    return a


@dataclass(eq=False)
class PointCloud:
    """Points drawn with a size: spheres, oriented discs or screen squares.

    Parameters
    ----------
    points : array_like
        ``(N, 3)`` positions, model coordinates (scene units).
    radius : float
        Every point's radius in scene units (> 0), unless ``radii`` or ``pixel_size``.
    radii : array_like or None
        ``(N,)`` each point's radius in scene units (> 0).
    colors : array_like or None
        ``(N, 3)`` linear RGB in [0, 1], each point's colour in place of its material's
        ``color`` (the material's ``ka``, ``kd`` and specular still apply).
    normals : array_like or None
        ``(N, 3)`` each point's normal (any length but 0): a disc's orientation, a square's
        lit normal. Needed by ``style="disc"``.
    style : PointStyle or str
        ``"sphere"`` (default), ``"disc"`` or ``"square"``.
    pixel_size : float or None
        A diameter in pixels (> 0), the same at every depth, instead of world radii.
    name : str or None
        Its name.
    """

    points: NDArray[np.float64]
    radius: float = 0.01
    radii: NDArray[np.float64] | None = None
    colors: NDArray[np.float64] | None = None
    normals: NDArray[np.float64] | None = None
    style: PointStyle = PointStyle.SPHERE
    pixel_size: float | None = None
    name: str | None = None
    _bounds: NDArray[np.float64] | None = field(default=None, repr=False)

    def __init__(self, points: ArrayLike, radius: float = 0.01, radii: ArrayLike | None = None,
                 colors: ArrayLike | None = None, normals: ArrayLike | None = None,
                 style: PointStyle | str = "sphere", pixel_size: float | None = None,
                 name: str | None = None):
        self.points = _array(points, "points", None, 3)
        n = len(self.points)
        if n == 0:
            raise GeometryError("a point cloud needs at least one point, got 0")
        reach = float(np.abs(self.points).max())
        if reach > MAX_DRAWABLE_COORDINATE:
            raise GeometryError(f"points reach a coordinate of {reach:g}; the GPU draws up "
                                f"to {MAX_DRAWABLE_COORDINATE:g}: scale down")
        self.style = choose(PointStyle, style, "style", GeometryError)
        if pixel_size is not None and radii is not None:
            raise GeometryError("give radii (world units) or pixel_size (screen), not both")
        self.radius = _positive(radius, "radius")
        self.radii = None
        if radii is not None:
            self.radii = _array(radii, "radii", n, None)
            if not (self.radii > 0).all():
                i = int(np.flatnonzero(~(self.radii > 0))[0])
                raise GeometryError(f"radii must be > 0 (scene units); radii[{i}] is "
                                    f"{plain(self.radii[i])}")
        self.pixel_size = None if pixel_size is None else _positive(pixel_size, "pixel_size")
        self.colors = None
        if colors is not None:
            self.colors = _array(colors, "colors", n, 3)
            outside = ~((self.colors >= 0) & (self.colors <= 1)).all(1)
            if outside.any():
                i = int(np.flatnonzero(outside)[0])
                raise GeometryError(f"colors must be linear RGB in [0, 1]; colors[{i}] is "
                                    f"{plain(self.colors[i].tolist())}")
        self.normals = None
        if normals is not None:
            nrm = _array(normals, "normals", n, 3)
            length = np.linalg.norm(nrm, axis=1)
            if not (length > 0).all():
                i = int(np.flatnonzero(~(length > 0))[0])
                raise GeometryError(f"normals[{i}] has length 0: a point's normal needs a "
                                    "direction")
            self.normals = nrm / length[:, None]
        if self.style is PointStyle.DISC and self.normals is None:
            raise GeometryError("style='disc' orients each disc by its normal: give normals "
                                "(N, 3)")
        self.name = name
        self._bounds = None
        for a in (self.points, self.radii, self.colors, self.normals):
            if a is not None:
                a.flags.writeable = False

    def __len__(self) -> int:
        return len(self.points)

    def __repr__(self) -> str:
        size = (f"{plain(self.pixel_size)} px" if self.pixel_size is not None else
                "radii" if self.radii is not None else f"radius {plain(self.radius)}")
        return f"<PointCloud: {len(self):,} points, {self.style.value}, {size}>"

    @property
    def n_points(self) -> int:
        """How many points (each one id of ``Frame.face_id``)."""
        return len(self.points)

    @property
    def bounds(self) -> NDArray[np.float64]:
        """``(2, 3)`` the box of the points grown by their radii (by nothing with
        ``pixel_size``: a size on screen has none in the world)."""
        if self._bounds is None:
            grow = 0.0 if self.pixel_size is not None else (
                self.radii[:, None] if self.radii is not None else self.radius)
            self._bounds = np.stack([(self.points - grow).min(0), (self.points + grow).max(0)])
        return self._bounds

    def arrays(self) -> list[tuple[str, NDArray[np.float32]]]:
        """The per-point arrays a draw uploads, float32, by their vertex-shader names:
        positions, and radii, colours and normals where the cloud has them."""
        named = [("in_position", self.points), ("in_radius", self.radii),
                 ("in_color", self.colors), ("in_normal", self.normals)]
        return [(name, np.ascontiguousarray(a, np.float32)) for name, a in named
                if a is not None]

    def world_radii(self) -> NDArray[np.float64]:
        """``(N,)`` each point's radius in model units (``radius`` repeated where no radii;
        zeros with ``pixel_size``)."""
        if self.pixel_size is not None:
            return np.zeros(len(self))
        return self.radii if self.radii is not None else np.full(len(self), self.radius)


def _positive(value, name: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise GeometryError(f"{name} must be a number > 0, got {value!r}") from None
    if not (np.isfinite(v) and v > 0):
        raise GeometryError(f"{name} must be a finite number > 0, got {plain(v)}")
    return v
