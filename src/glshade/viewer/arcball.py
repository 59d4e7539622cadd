"""Shoemake's arcball, as the viewer's rotation control (pure numpy, no window needed).

A window point is lifted onto a unit sphere centred in the window (points outside it onto
its rim). A drag from ``p0`` to ``p1`` is the rotation taking ``p0`` to ``p1`` about
``p0 x p1``, so dragging from the centre to the rim turns by 90 degrees about the axis
perpendicular to the drag. Rotations are unit quaternions (scalar last), in view space.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .. import quaternion as quat

__all__ = ["sphere_point", "drag_rotation", "Arcball"]


def sphere_point(x: float, y: float, width: float, height: float) -> NDArray[np.float64]:
    """The point on the arcball under window position (x, y) (pixels, y down), in view
    space: x right, y up, z towards the viewer.

    Parameters
    ----------
    x, y : float
        The position in pixels, y down.
    width, height : float
        The window's size.
    """
    r = min(width, height) / 2.0
    px = (x - width / 2.0) / r
    py = (height / 2.0 - y) / r
    d2 = px * px + py * py
    if d2 <= 1.0:
        return np.array([px, py, np.sqrt(1.0 - d2)])
    d = np.sqrt(d2)
    return np.array([px / d, py / d, 0.0])


def drag_rotation(p0: NDArray[np.float64], p1: NDArray[np.float64]) -> NDArray[np.float64]:
    """Unit quaternion rotating unit vector ``p0`` onto ``p1`` (the shorter way):
    ``normalize([p0 x p1, 1 + p0.p1])``, the half-way quaternion.

    Parameters
    ----------
    p0, p1 : ndarray
        ``(3,)`` unit vectors: where the drag started and where it is.
    """
    c = 1.0 + float(np.dot(p0, p1))
    if c < 1e-12:  # opposite points: any perpendicular axis
        axis = np.cross(p0, [1.0, 0.0, 0.0])
        if np.linalg.norm(axis) < 1e-6:
            axis = np.cross(p0, [0.0, 1.0, 0.0])
        return quat.from_axis_angle(axis, np.pi)
    return quat.normalize(np.append(np.cross(p0, p1), c))


class Arcball:
    """Accumulates a drag: ``begin`` at the press, ``drag`` at each move returns the
    rotation since the press (view space, unit).

    Parameters
    ----------
    width, height : float
        The window's size in pixels.
    """

    def __init__(self, width: float, height: float):
        self.resize(width, height)
        self._start: np.ndarray | None = None

    def resize(self, width: float, height: float) -> None:
        """The window's new size.

        Parameters
        ----------
        width, height : float
            In pixels.
        """
        self.width, self.height = float(width), float(height)

    def begin(self, x: float, y: float) -> None:
        """A drag starts at (x, y).

        Parameters
        ----------
        x, y : float
            The position in pixels, y down.
        """
        self._start = sphere_point(x, y, self.width, self.height)

    @property
    def active(self) -> bool:
        return self._start is not None

    def drag(self, x: float, y: float) -> NDArray[np.float64]:
        """The rotation since the press (view space, a unit quaternion).

        Parameters
        ----------
        x, y : float
            The position in pixels, y down.
        """
        if self._start is None:
            return quat.identity()
        return drag_rotation(self._start, sphere_point(x, y, self.width, self.height))

    def end(self) -> None:
        self._start = None
