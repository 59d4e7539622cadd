"""What a command renders: a mesh file, a primitive or a scene file, with the command
line's options laid over the scene file's settings, which lie over the defaults of the
dataclasses (Material, Camera, DrawOptions, RenderSettings): each default lives in one
place."""

from __future__ import annotations

import contextlib
from dataclasses import dataclass, replace


import numpy as np

from ..errors import InputError, SettingError, UsageError
from ..io.meshes import load_source
from ..io.scenefile import RenderSettings
from ..modes import Backend
from ..options import DrawOptions, RenderConfig
from ..scene import Camera, CameraPath, Material, PointLight, Scene, default_camera
from .. import examples
from .arguments import RenderArgs

__all__ = ["Job", "load_job", "is_scene_file", "build_scene"]


def is_scene_file(spec: str) -> bool:
    """Whether a MESH argument names a scene file (``.toml``)."""
    return spec.lower().endswith(".toml")


@dataclass
class Job:
    """A scene and how to draw it, as a command resolved it."""

    scene: Scene
    camera: Camera
    settings: RenderSettings
    path: CameraPath | None = None

    @property
    def options(self) -> DrawOptions:
        return self.settings.options

    @property
    def size(self) -> tuple[int, int]:
        return self.settings.size

    def config(self, backend: Backend | str = Backend.AUTO) -> RenderConfig:
        """What the job's Renderer is built with: its size and samples, and ``backend``."""
        return RenderConfig(*self.size, samples=self.settings.samples,
                            backend=Backend.parse(backend))

    @property
    def polygons(self) -> int:
        return sum(m.mesh.n_faces for m in self.scene.models) + \
            sum(len(m.solid.leaves()) for m in self.scene.solids)

    @contextlib.contextmanager
    def explained(self):
        """Say where a setting the machine refuses came from: a scene file's line."""
        try:
            yield
        except SettingError as exc:
            where = self.settings.origin.get(exc.setting)
            if where is None:
                raise
            raise UsageError(f"{where}: {exc}") from None


def build_scene(mesh, args: RenderArgs, aspect: float, asset=None) -> tuple[Scene, Camera]:
    """A one-mesh scene and its camera from the render options (render, view, compare);
    ``asset``: the glTF file (:class:`~glshade.io.gltf.GltfFile`) the mesh came from, whose
    lights light it unless ``--light`` gives some, seen through its first camera unless
    ``--eye``, ``--target`` or ``--view`` places one."""
    scene = Scene(**args.given("background"))
    given = args.given("color", "ka", "kd", "ks", "shininess", "opacity")
    # (an OBJ's own materials, unless the command line gives one)
    own = bool(getattr(mesh, "material_groups", None)) and not given
    scene.add(mesh, None if own else Material.from_values(given), crease=args.crease)
    lens = {"fov_y": args.fov} if args.fov is not None else {}
    eye, target = args.eye, args.target
    if eye is not None or target is not None:  # (animate has neither: it turns round)
        eye = eye if eye is not None else (0.0, 0.0, 5.0)
        target = target if target is not None else tuple(scene.bounds.mean(0))
        camera = Camera.look_at(eye, target, **lens)  # (clip planes: from the scene)
    elif asset is not None and asset.cameras and args.view is None:
        camera = asset.cameras[0].camera.replace(**lens)
    else:
        camera = default_camera(scene.bounds, aspect, **lens)
    for position in args.light:  # none: the file's, else the default headlight
        scene.add_light(PointLight(position))
    if not args.light and asset is not None:
        for light in asset.lights:
            scene.add_light(light)
    return scene, camera


def _view(args: RenderArgs, camera: Camera, scene: Scene, aspect: float,
          pane: float, framed: bool) -> Camera:
    """``--view NAME`` (a named view, framed), ``--ortho`` (parallel projection, framed
    unless --eye gave the eye), both framed for a pane ``pane`` times as wide as the image
    is (view --compare: a third)."""
    aspect *= pane
    if args.view is not None and (args.eye is not None or args.target is not None):
        given = "--eye" if args.eye is not None else "--target"
        name = getattr(args.view, "value", args.view)
        raise UsageError(f"--view {name} frames its own camera; give --view or "
                         f"{given}, not both")
    if args.view is not None:
        lens = {"fov_y": args.fov} if args.fov is not None else {}
        camera = Camera.named(args.view, scene.bounds, aspect, **lens)
    if args.ortho:
        camera = camera.replace(projection="orthographic")
        if args.eye is None:
            camera = camera.frame(scene.bounds, aspect)
        else:
            b = scene.bounds
            camera = camera.replace(height=float(np.linalg.norm(b[1] - b[0])) * 1.1 *
                                    max(1.0, 1.0 / aspect))
    elif pane != 1.0 and framed and args.view is None and args.eye is None and \
            args.target is None:
        camera = camera.frame(scene.bounds, aspect)  # (the pane's aspect, not the window's)
    return camera


def load_job(args: RenderArgs, spec: str, defaults: RenderSettings | None = None,
             pane: float = 1.0) -> Job:
    """Resolve ``spec`` and ``args`` into a Job: command line > scene file > ``defaults``
    (a RenderSettings; the dataclass's own when None). A name that is no file but an
    example's (``cornell-box``, ``teapot.obj``) is that example."""
    spec = examples.resolve(spec)
    base = defaults or RenderSettings()
    time = args.time
    if is_scene_file(spec):
        from ..io.scenefile import load_scene

        sf = load_scene(spec)
        settings, scene, path = sf.settings, sf.scene, sf.path
        if time is not None and not path.start <= time <= path.end:
            import warnings

            side = "end" if time > path.end else "start"
            warnings.warn(f"--time {time:g} is outside {spec}'s camera path ({path.start:g} "
                          f"to {path.end:g} s): the view at its {side}", UserWarning,
                          stacklevel=2)
        camera = path.at(path.start if time is None else time)
    else:
        if time is not None:
            raise UsageError("--time needs a scene file (.toml) with a camera path")
        settings, path = base, None
        size = args.size or base.size
        asset = None
        if spec.lower().endswith((".gltf", ".glb")):  # (its lights and cameras too)
            from ..io.gltf import load_gltf

            asset = load_gltf(spec)
            mesh = asset.mesh
        else:
            mesh = load_source(spec)  # (its errors name the file and line)
        if args.tolerance is not None:
            from ..patches import PatchSurface, tessellate

            if not isinstance(mesh, PatchSurface):
                raise UsageError(f"--tolerance is for patches:NAME, not {spec}")
            mesh = tessellate(mesh, tolerance=args.tolerance).mesh
        try:
            scene, camera = build_scene(mesh, args, size[0] / size[1], asset)
        except InputError as exc:  # a mesh the options cannot place: say which mesh
            raise UsageError(f"{spec}: {exc}") from None
    if args.texture_filter is not None:
        scene.set_texture_filter(args.texture_filter)
    overrides = args.given("mode", "srgb", "edges")
    for option in ("shadows", "transparency"):  # (several methods: compare's alone)
        methods = getattr(args, option, None)
        if methods and len(methods) > 1 and not hasattr(args, "reference"):
            raise UsageError(f"--{option}: one method here, got {len(methods)} "
                             f"({','.join(m.value for m in methods)}): several are for compare")
        if methods:
            overrides[option] = methods[0]
    settings = replace(settings, options=settings.options.replace(**overrides))
    origin = dict(settings.origin)
    if args.size:
        settings.width, settings.height = args.size
        origin.pop("size", None)
    camera = _view(args, camera, scene, settings.width / settings.height, pane,
                   framed=not is_scene_file(spec))
    if args.samples is not None:
        settings.samples = args.samples
        origin.pop("samples", None)
    settings.origin = origin
    return Job(scene, camera, settings, path)
