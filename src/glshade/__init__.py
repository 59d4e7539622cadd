"""glshade: classic shading (flat, Gouraud, Phong) on the GPU, headless or in a window.

Importing glshade touches no GL, no files and no environment variables; the renderer's
modules are loaded on first use.
"""

from ._version import __version__
from .errors import (
    ContextError, GeometryError, GlshadeError, MeshFormatError, ShaderError, TopologyError,
)
from .geometry import Mesh, concatenate, newell_normal, polygon_area, primitives
from .io import load_mesh, save_mesh

__all__ = [
    "__version__", "Mesh", "concatenate", "newell_normal", "polygon_area", "primitives",
    "load_mesh", "save_mesh", "GlshadeError", "GeometryError", "MeshFormatError",
    "TopologyError", "ContextError", "ShaderError",
]
