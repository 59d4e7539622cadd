"""Polylines: paths, graphs, wireframes of one's own, vector fields -- lines with a width.

GL core profiles draw lines one pixel wide at most, so glshade builds wide lines as
geometry (``shaders/lines.geom``): every segment the exact shape of its width on screen at
any angle and depth -- a rectangle (``units="pixels"``), or the trapezoid of a band of
``width`` scene units facing the eye (``units="world"``: narrower far away) -- cut where
it meets its neighbours by the bisector of their angle (``joins="miter"``; a bevel where
the miter would reach past ``MITER_LIMIT`` half-widths) or rounded there by a disc
(``"round"``); its two ends cut square at the end point (``caps="butt"``) or rounded by a
half disc (``"round"``). Lines are depth-tested against everything drawn and show their
colour unlit (a line has no normal for the formula). Each segment is one id of
``Frame.face_id``, after the polygons, solid leaves and points.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import GeometryError, plain
from ..modes import LineCaps, LineJoins, LineUnits, choose
from .transforms import MAX_DRAWABLE_COORDINATE

__all__ = ["Polyline", "MITER_LIMIT"]

#: a miter joint longer than this many half-widths (from the joint to its tip) is
#: bevelled (SVG's default stroke-miterlimit, 4: joints sharper than 29 degrees)
MITER_LIMIT = 4.0


@dataclass(eq=False, init=False)
class Polyline:
    """One or more polylines with a width, drawn as geometry.

    Parameters
    ----------
    points : array_like or list of array_like
        ``(N, 3)`` the vertices of one polyline, or a list of such arrays (N >= 2 each),
        model coordinates.
    width : float
        The line's width (> 0): pixels, or scene units with ``units="world"``.
    colors : array_like or None
        ``(N, 3)`` (all polylines' vertices, in order) linear RGB in [0, 1], interpolated
        along each segment (None: the material's ``color``).
    units : LineUnits or str
        ``"pixels"`` (the same width at any depth) or ``"world"``.
    caps : LineCaps or str
        ``"butt"`` or ``"round"``: the ends.
    joins : LineJoins or str
        ``"miter"`` or ``"round"``: where two segments meet.
    name : str or None
        Its name.
    """

    vertices: NDArray[np.float64]
    offsets: NDArray[np.int64]
    width: float
    colors: NDArray[np.float64] | None
    units: LineUnits
    caps: LineCaps
    joins: LineJoins
    name: str | None

    def __init__(self, points, width: float = 2.0, colors: ArrayLike | None = None,
                 units: LineUnits | str = "pixels", caps: LineCaps | str = "butt",
                 joins: LineJoins | str = "miter", name: str | None = None):
        parts = list(points) if isinstance(points, (list, tuple)) and len(points) and \
            np.ndim(points[0]) == 2 else [points]
        arrays = []
        for i, part in enumerate(parts):
            label = "points" if len(parts) == 1 else f"points[{i}]"
            try:
                a = np.asarray(part, np.float64)
            except (TypeError, ValueError):
                raise GeometryError(f"{label} must be an (N, 3) array of numbers, got "
                                    f"{type(part).__name__}") from None
            if a.ndim != 2 or a.shape[1] != 3 or len(a) < 2:
                raise GeometryError(f"{label} must have shape (N, 3) with N >= 2 (a line "
                                    f"needs two points), got {a.shape}")
            bad = ~np.isfinite(a).all(1)
            if bad.any():
                k = int(np.flatnonzero(bad)[0])
                raise GeometryError(f"{label}[{k}] is not finite: {plain(a[k].tolist())}")
            arrays.append(a)
        self.vertices = np.concatenate(arrays)
        reach = float(np.abs(self.vertices).max())
        if reach > MAX_DRAWABLE_COORDINATE:
            raise GeometryError(f"points reach a coordinate of {reach:g}; the GPU draws up "
                                f"to {MAX_DRAWABLE_COORDINATE:g}: scale down")
        self.offsets = np.concatenate([[0], np.cumsum([len(a) for a in arrays])])
        try:
            self.width = float(width)
        except (TypeError, ValueError):
            raise GeometryError(f"width must be a number > 0, got {width!r}") from None
        if not (np.isfinite(self.width) and self.width > 0):
            raise GeometryError(f"width must be a finite number > 0, got {plain(self.width)}")
        self.units = choose(LineUnits, units, "units", GeometryError)
        self.caps = choose(LineCaps, caps, "caps", GeometryError)
        self.joins = choose(LineJoins, joins, "joins", GeometryError)
        self.colors = None
        if colors is not None:
            c = np.asarray(colors, np.float64)
            if c.shape != self.vertices.shape:
                raise GeometryError(f"colors must have shape {self.vertices.shape} (one a "
                                    f"vertex), got {c.shape}")
            outside = ~((c >= 0) & (c <= 1)).all(1)
            if outside.any():
                k = int(np.flatnonzero(outside)[0])
                raise GeometryError(f"colors must be linear RGB in [0, 1]; colors[{k}] is "
                                    f"{plain(c[k].tolist())}")
            self.colors = c
        self.name = name
        for held in (self.vertices, self.offsets, self.colors):
            if held is not None:
                held.flags.writeable = False

    def __repr__(self) -> str:
        unit = "px" if self.units is LineUnits.PIXELS else "units"
        return (f"<Polyline: {len(self.offsets) - 1} lines, {self.n_segments:,} segments, "
                f"{plain(self.width)} {unit} wide>")

    @property
    def n_segments(self) -> int:
        """How many segments (each one id of ``Frame.face_id``)."""
        return len(self.vertices) - (len(self.offsets) - 1)

    @property
    def segments(self) -> NDArray[np.uint32]:
        """``(S, 4)`` each segment's vertices as ``(before, start, end, after)`` -- GL's
        lines-with-adjacency order; ``before`` is ``start`` at a polyline's first segment
        and ``after`` is ``end`` at its last (no neighbour there: a cap)."""
        starts = np.concatenate([np.arange(a, b - 1) for a, b in
                                 zip(self.offsets[:-1], self.offsets[1:])])
        first = np.isin(starts, self.offsets[:-1])
        last = np.isin(starts + 2, self.offsets[1:])
        before = np.where(first, starts, starts - 1)
        after = np.where(last, starts + 1, starts + 2)
        return np.stack([before, starts, starts + 1, after], 1).astype(np.uint32)

    @property
    def bounds(self) -> NDArray[np.float64]:
        """``(2, 3)`` the box of the vertices (in world units grown by the farthest a
        miter's tip reaches)."""
        grow = MITER_LIMIT * self.width / 2 if self.units is LineUnits.WORLD else 0.0
        return np.stack([self.vertices.min(0) - grow, self.vertices.max(0) + grow])
