"""The exceptions glshade raises.

Every message says what was expected, what arrived and, where there is one, the fix.
Expected user errors (bad files, bad arguments, no GL) are subclasses of
:class:`GlshadeError`, so a command line tool can report them in one line.
"""

from __future__ import annotations

__all__ = [
    "GlshadeError",
    "GeometryError",
    "MeshFormatError",
    "TopologyError",
    "ContextError",
    "ShaderError",
    "ComparisonError",
]


class GlshadeError(Exception):
    """Base class of every error glshade raises on purpose."""


class GeometryError(GlshadeError, ValueError):
    """Bad shapes, indices or values handed to the geometry code."""


class MeshFormatError(GlshadeError, ValueError):
    """A mesh file that cannot be read: names the path, the line (or byte) and the fault."""

    def __init__(self, path, message: str, line: int | None = None, byte: int | None = None):
        self.path = str(path)
        self.line = line
        self.byte = byte
        self.reason = message
        where = self.path
        if line is not None:
            where += f":{line}"
        elif byte is not None:
            where += f" (byte {byte})"
        super().__init__(f"{where}: {message}")


class TopologyError(GeometryError):
    """Invalid topology (non-manifold edges, inconsistent orientation, ...)."""


class ContextError(GlshadeError, RuntimeError):
    """No OpenGL context could be made: says which backends were tried and why each failed."""


class ShaderError(GlshadeError, RuntimeError):
    """A GLSL program failed to compile or link: names the file, the line and the driver's text."""


class ComparisonError(GlshadeError, ValueError):
    """A comparison that cannot be made: no analytic surface, a reference of another size."""
