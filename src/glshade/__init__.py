"""glshade: classic shading (flat, Gouraud, Phong) on the GPU, headless or in a window.

Importing glshade touches no GL, no files and no environment variables; the renderer's
modules are loaded on first use.
"""

from ._version import __version__
from .errors import (
    ComparisonError, ContextError, GeometryError, GlshadeError, MeshFormatError, ShaderError,
    TopologyError,
)
import sys as _sys

from .camera import Camera, default_camera
from .geometry import Mesh, concatenate, masspoint, newell_normal, polygon_area, primitives
from .geometry import brep, quaternion
from .geometry.masspoint import MassPoint, centroid
from .animate import animate
from .comparison import Comparison, compare
from .scenefile import load_scene
from .image import save_image
from .io import load_mesh, save_mesh
from .modes import ShadingMode
from .scene import DirectionalLight, Material, PointLight, Scene
from .keyframes import CameraPath, Keyframe

# ``import glshade.quaternion`` and ``glshade.masspoint`` name the geometry modules
_sys.modules[__name__ + ".quaternion"] = quaternion
_sys.modules[__name__ + ".masspoint"] = masspoint
_sys.modules[__name__ + ".brep"] = brep

_LAZY = {"Renderer": "renderer", "Frame": "renderer", "create_context": "context",
         "RenderContext": "context", "Backend": "context", "tune_malloc": "context"}


def __getattr__(name):
    """The GL parts load on first use, so ``import glshade`` never loads moderngl."""
    if name in _LAZY:
        import importlib

        module = importlib.import_module(f".render.{_LAZY[name]}", __name__)
        return getattr(module, name)
    raise AttributeError(f"module 'glshade' has no attribute {name!r}")

__all__ = [
    "__version__", "Mesh", "concatenate", "newell_normal", "polygon_area", "primitives",
    "quaternion", "masspoint", "brep", "MassPoint", "centroid", "Camera", "CameraPath", "Keyframe",
    "default_camera", "save_image", "ShadingMode", "Scene", "Material", "PointLight",
    "DirectionalLight", "compare", "Comparison", "animate", "load_scene", "tune_malloc",
    "Renderer", "Frame", "create_context", "RenderContext", "Backend",
    "load_mesh", "save_mesh", "GlshadeError", "GeometryError", "MeshFormatError",
    "TopologyError", "ContextError", "ShaderError", "ComparisonError",
]
