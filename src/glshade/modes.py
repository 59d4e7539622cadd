"""Shading modes and the one table mapping each to its GLSL program."""

from __future__ import annotations

import enum

from .errors import GeometryError

__all__ = ["ShadingMode", "PROGRAMS"]


class ShadingMode(enum.Enum):
    """How a surface is shaded (the notes' three, and two debug views)."""

    FLAT = "flat"          # uniform shading: one intensity per polygon
    GOURAUD = "gouraud"    # intensities at the vertices, interpolated
    PHONG = "phong"        # normals interpolated, lit per pixel
    NORMALS = "normals"    # debug: world normal as colour
    DEPTH = "depth"        # debug: view depth as grey

    @classmethod
    def parse(cls, value) -> ShadingMode:
        """Accept a ShadingMode or its name; a bad name lists the choices."""
        if isinstance(value, cls):
            return value
        try:
            return cls(str(value).lower())
        except ValueError:
            choices = ", ".join(m.value for m in cls)
            raise GeometryError(f"unknown shading mode {value!r}; choose one of {choices}") \
                from None

    @property
    def per_polygon(self) -> bool:
        """Whether the program needs vertices duplicated per triangle corner."""
        return self is ShadingMode.FLAT


#: program of each mode: (vertex shader file, fragment shader file) under shaders/
PROGRAMS = {
    ShadingMode.FLAT: ("flat.vert", "flat.frag"),
    ShadingMode.GOURAUD: ("gouraud.vert", "gouraud.frag"),
    ShadingMode.PHONG: ("smooth.vert", "phong.frag"),
    ShadingMode.NORMALS: ("smooth.vert", "normals.frag"),
    ShadingMode.DEPTH: ("smooth.vert", "depth.frag"),
}
