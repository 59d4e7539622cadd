"""glshade: classic shading (flat, Gouraud, Phong) on the GPU, headless or in a window.

Importing glshade touches no GL, no files and no environment variables; the renderer's
modules are loaded on first use.
"""

from ._version import __version__
from .errors import (
    ContextError, GeometryError, GlshadeError, MeshFormatError, ShaderError, TopologyError,
)
import sys as _sys

from .camera import Camera
from .geometry import Mesh, concatenate, masspoint, newell_normal, polygon_area, primitives
from .geometry import quaternion
from .geometry.masspoint import MassPoint, centroid
from .io import load_mesh, save_mesh
from .keyframes import CameraPath, Keyframe

# ``import glshade.quaternion`` and ``glshade.masspoint`` name the geometry modules
_sys.modules[__name__ + ".quaternion"] = quaternion
_sys.modules[__name__ + ".masspoint"] = masspoint

__all__ = [
    "__version__", "Mesh", "concatenate", "newell_normal", "polygon_area", "primitives",
    "quaternion", "masspoint", "MassPoint", "centroid", "Camera", "CameraPath", "Keyframe",
    "load_mesh", "save_mesh", "GlshadeError", "GeometryError", "MeshFormatError",
    "TopologyError", "ContextError", "ShaderError",
]
