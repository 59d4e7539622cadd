"""glshade: classic shading (flat, Gouraud, Phong) on the GPU, headless or in a window.

Importing glshade touches no GL, no files and no environment variables, and loads nothing
heavy: each name below is imported on first use (``glshade.Renderer`` loads moderngl only
then), so ``import glshade`` and ``glshade --help`` are instant.
"""

from ._version import __version__

#: public name -> (module, attribute); attribute None: the module itself
_EXPORTS = {
    # geometry
    "Mesh": ("geometry.mesh", "Mesh"), "concatenate": ("geometry.merge", "concatenate"),
    "newell_normal": ("geometry.polygon", "newell_normal"),
    "polygon_area": ("geometry.polygon", "polygon_area"),
    "primitives": ("geometry.primitives", None), "quaternion": ("geometry.quaternion", None),
    "masspoint": ("geometry.masspoint", None), "brep": ("geometry.brep", None),
    "MassPoint": ("geometry.masspoint", "MassPoint"),
    "centroid": ("geometry.masspoint", "centroid"),
    # scene
    "Camera": ("scene.camera", "Camera"), "default_camera": ("scene.camera", "default_camera"),
    "CameraPath": ("scene.keyframes", "CameraPath"), "Keyframe": ("scene.keyframes", "Keyframe"),
    "Material": ("scene.material", "Material"), "PointLight": ("scene.lights", "PointLight"),
    "DirectionalLight": ("scene.lights", "DirectionalLight"), "Scene": ("scene.scene", "Scene"),
    # drawing options
    "ShadingMode": ("modes", "ShadingMode"), "Outputs": ("modes", "Outputs"),
    "DrawOptions": ("options", "DrawOptions"),
    # files
    "load_mesh": ("io.meshes", "load_mesh"), "save_mesh": ("io.meshes", "save_mesh"),
    "load_scene": ("io.scenefile", "load_scene"), "save_image": ("io.images", "save_image"),
    # rendering (GL)
    "Renderer": ("render.renderer", "Renderer"), "Frame": ("render.renderer", "Frame"),
    "create_context": ("render.context", "create_context"),
    "RenderContext": ("render.context", "RenderContext"),
    "Backend": ("render.context", "Backend"), "tune_malloc": ("render.context", "tune_malloc"),
    # comparing and animating
    "compare": ("compare.comparison", "compare"),
    "Comparison": ("compare.comparison", "Comparison"), "animate": ("animate.frames", "animate"),
    # errors
    **{name: ("errors", name) for name in (
        "GlshadeError", "InputError", "GeometryError", "MeshFormatError", "SceneFormatError",
        "TopologyError", "ContextError", "ShaderError", "ComparisonError", "RenderWarning")},
}

__all__ = ["__version__", *_EXPORTS]


def __getattr__(name):
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


def __dir__():
    return sorted(__all__)
