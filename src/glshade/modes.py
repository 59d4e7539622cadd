"""The enums that name what a draw does: shading modes, outputs, back-face culling."""

from __future__ import annotations

import enum

from .errors import GeometryError

__all__ = ["ShadingMode", "Outputs", "parse_enum"]


def parse_enum(cls, value, what: str):
    """``cls(value)`` for a member or its (case-insensitive) value; a bad one lists the
    choices."""
    if isinstance(value, cls):
        return value
    try:
        return cls(str(value).lower())
    except ValueError:
        choices = ", ".join(m.value for m in cls)
        raise GeometryError(f"unknown {what} {value!r}; choose one of {choices}") from None


class ShadingMode(enum.Enum):
    """How a surface is shaded (the notes' three, a radiosity solution's display, and two
    debug views)."""

    FLAT = "flat"          # uniform shading: one intensity per polygon
    GOURAUD = "gouraud"    # intensities at the vertices, interpolated
    PHONG = "phong"        # normals interpolated, lit per pixel
    NORMALS = "normals"    # debug: world normal as colour
    DEPTH = "depth"        # debug: view depth as grey
    RADIOSITY = "radiosity"  # per-vertex radiosities (Model.vertex_colors), interpolated, unlit

    @classmethod
    def parse(cls, value) -> ShadingMode:
        """Accept a ShadingMode or its name; a bad name lists the choices."""
        return parse_enum(cls, value, "shading mode")

    @property
    def per_polygon(self) -> bool:
        """Whether the program needs vertices duplicated per triangle corner."""
        return self is ShadingMode.FLAT


class Outputs(enum.Flag):
    """What one draw produces besides the picture. Anything beyond COLOR is drawn into a
    target with integer id and depth buffers (never blended by an MSAA resolve)."""

    COLOR = enum.auto()
    DEPTH = enum.auto()      # distance along the view axis
    NORMAL = enum.auto()     # world-space unit normal
    FACE_ID = enum.auto()    # id of the source polygon
    ALL = COLOR | DEPTH | NORMAL | FACE_ID

    @property
    def auxiliary(self) -> bool:
        """Whether anything beyond colour is asked for."""
        return bool(self.value & ~Outputs.COLOR.value)
