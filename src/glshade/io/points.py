"""Point sets from files: PLY vertex elements and OBJ ``v`` lines, as a
:class:`~glshade.geometry.points.PointCloud`.

Colours in these files are display values: 0-255 integers (PLY's ``uchar red``) or
fractions, sRGB-encoded as a scanner or MeshLab writes them; they are decoded to the linear
RGB glshade lights with (IEC 61966-2-1), so a point shows the colour it was stored with.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .._paths import file_fault
from ..errors import GeometryError, MeshFormatError
from ..geometry.points import PointCloud
from ..modes import PointStyle
from ..scene.texture import srgb_to_linear
from . import obj, ply

__all__ = ["load_points", "is_point_set", "POINT_FORMATS"]

#: the formats whose vertices load as points, each with ``read_points(path, data) -> dict``
_READERS = {"ply": ply, "obj": obj}
POINT_FORMATS = tuple(_READERS)


def is_point_set(path) -> bool:
    """Whether ``path`` is a PLY file with vertices and no faces, or an OBJ file with ``v``
    lines and no ``f`` lines: a point set, not a mesh (the command line draws it as points).

    Parameters
    ----------
    path : str or Path
        The file (False when unreadable: the mesh reader then says why).
    """
    path = Path(path)
    fmt = path.suffix.lstrip(".").lower()
    if fmt not in _READERS or file_fault(path) is not None:
        return False
    try:
        if fmt == "ply":
            with path.open("rb") as f:
                head = f.read(1 << 16)
            end = head.find(b"end_header")
            names = [line.split()[1] for line in head[:end].splitlines()
                     if line.startswith(b"element") and len(line.split()) > 1]
            return end > 0 and b"vertex" in names and b"face" not in names
        data = path.read_bytes()
    except OSError:
        return False
    lines = data.replace(b"\r", b"\n").replace(b"\t", b" ")
    return (lines.startswith(b"v ") or b"\nv " in lines) and \
        not (lines.startswith(b"f ") or b"\nf " in lines)


def load_points(path, format: str | None = None, *, radius: float | None = None,
                style: PointStyle | str = "sphere",
                pixel_size: float | None = None) -> PointCloud:
    """The points of a PLY file's vertex element or an OBJ file's ``v`` lines (faces, if
    any, ignored), with their normals (PLY ``nx ny nz``) and colours (PLY ``red green
    blue``, OBJ ``v x y z r g b``) where every point has one.

    Parameters
    ----------
    path : str or Path
        The file.
    format : str or None
        ``"ply"`` or ``"obj"`` (None: from the extension).
    radius : float or None
        Every point's radius, scene units (None: 1/200 of the box's diagonal -- a scan
        shows as a surface of dots, not a blob).
    style : PointStyle or str
        ``"sphere"``, ``"disc"`` (needs the file's normals) or ``"square"``.
    pixel_size : float or None
        A diameter on screen in pixels instead of a radius.

    Raises
    ------
    MeshFormatError
        The file is missing, unreadable or malformed, or its values cannot be points; the
        message names the path (and line) and says what was wrong.
    """
    path = Path(path)
    fault = file_fault(path)
    if fault is not None:
        raise MeshFormatError(path, fault.replace("not a file", "not a point file"))
    fmt = (format or path.suffix.lstrip(".")).lower()
    if fmt not in _READERS:
        raise MeshFormatError(path, f"unknown point format {fmt!r}; supported: "
                              f"{', '.join(POINT_FORMATS)}")
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise MeshFormatError(path, f"cannot read: {exc.strerror or exc}") from None
    if not data.strip():
        raise MeshFormatError(path, "the file is empty")
    found = _READERS[fmt].read_points(path, data)
    points, colors = found["points"], found["colors"]
    if colors is not None:
        colors = colors / 255.0 if found["integer_colors"] else colors
        if not (np.isfinite(colors).all() and (colors >= 0).all() and (colors <= 1).all()):
            raise MeshFormatError(path, "vertex colours must lie in 0-255 (integers) or "
                                  f"0-1, found {np.nanmin(colors):g} to {np.nanmax(colors):g}")
        colors = srgb_to_linear(colors)
    if radius is None and pixel_size is None:
        finite = points[np.isfinite(points).all(1)]
        span = float(np.linalg.norm(np.ptp(finite, 0))) if len(finite) else 0.0
        radius = span / 200 if span > 0 else 0.01
    try:
        return PointCloud(points, radius=radius if radius is not None else 0.01,
                          colors=colors, normals=found["normals"], style=style,
                          pixel_size=pixel_size, name=path.stem)
    except GeometryError as exc:
        raise MeshFormatError(path, str(exc)) from None
