"""glshade: classic shading (flat, Gouraud, Phong) on the GPU, headless or in a window.

Importing glshade touches no GL, no files and no environment variables, and loads nothing
heavy: each name below is imported on first use (``glshade.Renderer`` loads moderngl only
then), so ``import glshade`` and ``glshade --help`` are instant.
"""

import sys

from ._version import __version__

#: (typing's own constant, without importing typing: ``python -m glshade`` imports this
#: package before the command can catch a Ctrl-C, and importing typing was most of that
#: window; type checkers read any name TYPE_CHECKING as true)
TYPE_CHECKING = False

#: public name -> (module, attribute); attribute None: the module itself. The names are
#: typed for checkers and IDEs by the TYPE_CHECKING imports below (a test keeps both equal).
_EXPORTS = {
    # the notes' algebra and chapters, and every other package and public module: each
    # ``glshade.<name>`` is the module (a test imports them all this way, fresh)
    **{name: (name, None) for name in (
        "quaternion", "masspoint", "brep", "solids", "octree", "hidden", "radiosity",
        "patches", "pathtrace", "dataset", "scene", "io", "render", "cpu", "batch",
        "parallel",
        "viewer", "notebook", "testing", "examples", "modes",
        "options", "errors", "atomic", "interrupt", "cli", "colormaps", "display")},
    "MassPoint": ("masspoint", "MassPoint"), "centroid": ("masspoint", "centroid"),
    # the mesh kernel
    "geometry": ("geometry", None),
    "Mesh": ("geometry.mesh", "Mesh"), "concatenate": ("geometry.merge", "concatenate"),
    "PointCloud": ("geometry.points", "PointCloud"), "Polyline": ("geometry.lines", "Polyline"),
    "newell_normal": ("geometry.polygon", "newell_normal"),
    "polygon_area": ("geometry.polygon", "polygon_area"),
    # scene
    "Camera": ("scene.camera", "Camera"), "default_camera": ("scene.camera", "default_camera"),
    "CameraPath": ("scene.keyframes", "CameraPath"), "Keyframe": ("scene.keyframes", "Keyframe"),
    "Material": ("scene.material", "Material"), "PointLight": ("scene.lights", "PointLight"),
    "Texture": ("scene.texture", "Texture"),
    "DirectionalLight": ("scene.lights", "DirectionalLight"), "Scene": ("scene.scene", "Scene"),
    "SpotLight": ("scene.lights", "SpotLight"), "PBRMaterial": ("scene.pbr", "PBRMaterial"),
    "Environment": ("scene.environment", "Environment"),
    "LightingModel": ("modes", "LightingModel"),
    # drawing options
    "ShadingMode": ("modes", "ShadingMode"), "Outputs": ("modes", "Outputs"),
    "Culling": ("modes", "Culling"), "Projection": ("modes", "Projection"),
    "Shadows": ("modes", "Shadows"), "Transparency": ("modes", "Transparency"),
    "DrawOptions": ("options", "DrawOptions"), "RenderConfig": ("options", "RenderConfig"),
    # files
    "load_mesh": ("io.meshes", "load_mesh"), "save_mesh": ("io.meshes", "save_mesh"),
    "load_scene": ("io.scenefile", "load_scene"), "save_image": ("io.images", "save_image"),
    "load_points": ("io.points", "load_points"), "load_gltf": ("io.gltf", "load_gltf"),
    # rendering (GL)
    "Renderer": ("render.renderer", "Renderer"), "Frame": ("render.renderer", "Frame"),
    "Pick": ("render.renderer", "Pick"), "View": ("scene.camera", "View"),
    "create_context": ("render.context", "create_context"),
    "RenderContext": ("render.context", "RenderContext"),
    "Backend": ("render.context", "Backend"), "tune_malloc": ("render.context", "tune_malloc"),
    # comparing and animating
    "compare": ("compare", None),  # (callable packages: glshade.compare(...) is the function)
    "Comparison": ("compare.comparison", "Comparison"), "animate": ("animate", None),
    # notebooks
    "show": ("notebook.display", "show"),
    # errors
    **{name: ("errors", name) for name in (
        "GlshadeError", "InputError", "EnvironmentFailure", "NoGpuError", "GeometryError",
        "OptionError",
        "SceneError", "MeshFormatError", "SceneFormatError", "TopologyError", "ContextError",
        "DisplayError", "ShaderError", "ComparisonError", "RenderWarning")},
}

__all__ = ["__version__", *_EXPORTS]

if TYPE_CHECKING:  # what the lazy names are, for type checkers (never run)
    from . import (atomic, batch, brep, cli, colormaps, cpu, dataset, display, errors,
                   examples,
                   geometry, hidden,
                   interrupt, io, masspoint, modes, notebook, octree, options,
                   parallel, patches, pathtrace, quaternion, radiosity, render, scene,
                   solids, testing, viewer)
    from .compare.comparison import Comparison, compare
    from .animate.frames import animate
    from .notebook.display import show
    from .errors import (ComparisonError, ContextError, DisplayError, EnvironmentFailure,
                         NoGpuError,
                         GeometryError, GlshadeError, InputError, MeshFormatError,
                         OptionError, RenderWarning, SceneError, SceneFormatError,
                         ShaderError, TopologyError)
    from .geometry.merge import concatenate
    from .geometry.mesh import Mesh
    from .geometry.lines import Polyline
    from .geometry.points import PointCloud
    from .geometry.polygon import newell_normal, polygon_area
    from .io.gltf import load_gltf
    from .io.images import save_image
    from .io.meshes import load_mesh, save_mesh
    from .io.points import load_points
    from .io.scenefile import load_scene
    from .masspoint import MassPoint, centroid
    from .modes import Culling, Outputs, Projection, ShadingMode, Shadows, Transparency
    from .options import DrawOptions, RenderConfig
    from .render.context import Backend, RenderContext, create_context, tune_malloc
    from .render.renderer import Frame, Pick, Renderer
    from .scene.camera import Camera, View, default_camera
    from .scene.keyframes import CameraPath, Keyframe
    from .modes import LightingModel
    from .scene.lights import DirectionalLight, PointLight, SpotLight
    from .scene.pbr import PBRMaterial
    from .scene.environment import Environment
    from .scene.material import Material
    from .scene.scene import Scene
    from .scene.texture import Texture


if "IPython" in sys.modules:  # (in a notebook: objects' reprs draw their thumbnails)
    from .notebook import display as _display_hook  # noqa: F401


def __getattr__(name: str):
    """Load a public name on first use (and keep it, so the next use is a plain lookup)."""
    try:
        module, attribute = _EXPORTS[name]
    except KeyError:
        raise AttributeError(f"module 'glshade' has no attribute {name!r}") from None
    import importlib

    value = importlib.import_module(f"{__name__}.{module}")
    if attribute is not None:
        value = getattr(value, attribute)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(__all__)
