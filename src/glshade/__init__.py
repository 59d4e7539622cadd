"""glshade: classic shading (flat, Gouraud, Phong) on the GPU, headless or in a window.

Importing glshade touches no GL, no files and no environment variables; the renderer's
modules are loaded on first use.
"""

from ._version import __version__
from .animate import animate
from .compare import Comparison, compare
from .errors import (
    ComparisonError, ContextError, GeometryError, GlshadeError, InputError, MeshFormatError,
    SceneFormatError, ShaderError, TopologyError,
)
from .geometry import Mesh, brep, concatenate, masspoint, newell_normal, polygon_area
from .geometry import primitives, quaternion
from .geometry.masspoint import MassPoint, centroid
from .io import load_mesh, load_scene, save_image, save_mesh
from .modes import Outputs, ShadingMode
from .options import DrawOptions
from .scene import (
    Camera, CameraPath, DirectionalLight, Keyframe, Material, PointLight, Scene, default_camera,
)

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
    "default_camera", "save_image", "ShadingMode", "Outputs", "DrawOptions", "Scene", "Material",
    "PointLight", "DirectionalLight", "compare", "Comparison", "animate", "load_scene",
    "tune_malloc", "Renderer", "Frame", "create_context", "RenderContext", "Backend",
    "load_mesh", "save_mesh", "GlshadeError", "InputError", "GeometryError", "MeshFormatError",
    "SceneFormatError", "TopologyError", "ContextError", "ShaderError", "ComparisonError",
]
