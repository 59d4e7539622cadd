"""The Renderer: draws a Scene seen by a Camera with DrawOptions, headless or into a window.

``Renderer.draw(target, scene, camera, options)`` is the one drawing path; ``render`` and
``render_frame`` draw into the renderer's own offscreen target and read it back.

Meshes are uploaded once per Renderer and cached (the cache follows the scene: a mesh that
is garbage-collected loses its GPU copy at the next frame). A new camera only changes
uniforms; buffers are never re-uploaded per frame.
"""

from __future__ import annotations

from typing import Any

import math
import warnings
from collections.abc import Iterable, Iterator, Sized
from dataclasses import dataclass

import numpy as np

from ..errors import (
    EnvironmentFailure, GlshadeError, InputError, OptionError, RenderWarning, SceneError,
    UsageError,
)
from ..interrupt import held
from ..modes import Backend, Outputs, ShadingMode, Shadows, Transparency
from ..options import DrawOptions, RenderConfig
from ..scene import MAX_LIGHTS, Camera, Scene
from ..scene.camera import MAX_PLANE_RATIO
from .context import RenderContext, check_gpu, create_context
from .diagnostics import why_blank
from .passes import Stage, run
from .passes.csg import CsgPass
from .passes.edges import EdgePass
from .passes.environment import EnvironmentPass
from .passes.mesh import MeshPass
from .passes.patches import PatchPass
from .passes.lines import LinePass
from .passes.points import PointPass
from .passes.shadows import ShadowPass
from .passes.transparency import TransparencyPass
from .programs import MaterialUniforms, UniformWriter
from .shaders import ShaderLibrary
from .state import SHADOWED_MODES, DrawState, sees_through
from .target import OffscreenTarget, check_fits

__all__ = ["Renderer", "Frame", "Pick", "Culled", "MAX_CAMERA_REACH", "SHADOWED_MODES"]


#: how far a camera may be from the origin or its scene: its projection's depth term is
#: about 100 times its reach, and the matrices go to the GPU as 32-bit floats (largest
#: 3.4e38) -- a camera at 3.4e36 overflowed them (the numeric sweep found it)
MAX_CAMERA_REACH = 1e32


@dataclass(frozen=True)
class Culled:
    """What the last draw skipped as wholly outside the view (:attr:`Renderer.culled`):
    meshes and instances, and big meshes' and point clouds' spatial chunks -- never a
    pixel it would have drawn.

    Parameters
    ----------
    models : int
        Meshes (and instances of a group) wholly outside the view, not drawn.
    chunks : int
        Big meshes' chunks outside it (``DrawOptions.frustum_cull``).
    point_chunks : int
        Point clouds' chunks outside it.
    """

    models: int
    chunks: int
    point_chunks: int


@dataclass(frozen=True)
class Pick:
    """What a pixel shows (:meth:`Renderer.pick`): ``face_id`` (as :class:`Frame` numbers
    polygons: the scene's mesh polygons in order, then its solids' leaves), the world
    ``point (3,)``, the unit world ``normal (3,)`` and the view ``depth``.

    Parameters
    ----------
    face_id : int
        The polygon's id.
    point : ndarray
        ``(3,)`` the world point (scene units).
    normal : ndarray
        ``(3,)`` the unit world normal.
    depth : float
        Distance along the view axis (scene units).
    """

    face_id: int
    point: np.ndarray
    normal: np.ndarray
    depth: float

    def __str__(self) -> str:
        p, n = (", ".join(f"{v:.4g}" for v in a) for a in (self.point, self.normal))
        return f"polygon {self.face_id} at ({p}), normal ({n}), depth {self.depth:.4g}"


@dataclass
class Frame:
    """What one pass produces (row 0 at the top); outputs not asked for are None.

    Parameters
    ----------
    color : ndarray
        ``(H, W, 4)`` uint8 (float32 with ``color_dtype="f4"``), linear unless ``srgb``.
    depth : ndarray or None
        ``(H, W)`` float32 distance along the view axis in scene units; ``inf`` where
        nothing was drawn.
    normal : ndarray or None
        ``(H, W, 3)`` float32 world-space unit normal (zero where nothing was drawn).
    face_id : ndarray or None
        ``(H, W)`` int32 id of the source polygon (not the triangle); -1 for background;
        with several models, ids continue from one model to the next in scene order.
    visibility : ndarray or None
        ``(H, W, L)`` float32, a draw with shadows: how much of each of its L lights
        reaches the surface point each pixel centre sees (1 seen, 0 hidden; a shadow map's
        PCF gives fractions; 1 on the background).
    instance : ndarray or None
        ``(H, W)`` int32 the ``instance_id`` of the model whose surface the pixel centre
        sees (0: background) -- exact like the polygon ids, never a blend, the same with
        any MSAA; a transparent surface does not own the pixel (what lies behind it does).
    semantic : ndarray or None
        ``(H, W)`` int32 that model's class id (:attr:`Scene.labels`; 0: background).
    camera : Camera or None
        The camera the frame was drawn with (its clip planes fitted to the scene).
    """

    color: np.ndarray
    depth: np.ndarray | None = None
    normal: np.ndarray | None = None
    face_id: np.ndarray | None = None
    visibility: np.ndarray | None = None
    instance: np.ndarray | None = None
    semantic: np.ndarray | None = None
    camera: Camera | None = None

    def points(self, space: str = "world") -> np.ndarray:
        """``(H, W, 3)`` float32: the surface point each pixel centre sees, NaN where
        nothing was drawn -- the depth unprojected through the frame's camera (its pixel's
        ray from :meth:`Camera.rays`, as far along the view axis as the depth says).

        Parameters
        ----------
        space : str
            ``"world"`` (scene units, world axes) or ``"camera"`` (OpenCV's axes: x right,
            y down, z forward -- z is the pixel's depth).
        """
        if space not in ("world", "camera"):
            raise OptionError(f"space must be 'world' or 'camera', got {space!r}")
        if self.depth is None or self.camera is None:
            raise OptionError("points need the frame's depth and camera: draw it with "
                              "outputs including Outputs.DEPTH")
        h, w = self.depth.shape
        origin, ray = self.camera.rays((w, h))
        depth = np.where(np.isfinite(self.depth), self.depth, np.nan).astype(np.float64)
        along = depth / (ray @ self.camera.forward)  # (depth is along the view axis)
        world = origin + ray * along[..., None]
        if space == "world":
            return world.astype(np.float32)
        from ..scene.intrinsics import GL_FROM_CV

        R = GL_FROM_CV @ self.camera.rotation.T  # (world to OpenCV's camera axes)
        return ((world - self.camera.position) @ R.T).astype(np.float32)

    def __repr__(self) -> str:
        h, w = self.color.shape[:2]
        outputs = [n for n in ("color", "depth", "normal", "face_id", "instance", "semantic")
                   if getattr(self, n) is not None]
        drawn = "" if self.face_id is None else \
            f"; {int((self.face_id >= 0).sum()):,} pixels drawn"
        return f"<Frame {w}x{h}: {', '.join(outputs)}{drawn}>"

    def _repr_html_(self) -> str:
        """In a notebook: its buffers side by side (colour, depth, normals, ids)."""
        from ..display import buffers_image, facts_html

        facts = []
        if self.depth is not None and np.isfinite(self.depth).any():
            d = self.depth[np.isfinite(self.depth)]
            facts.append(f"depth {float(d.min()):.4g} .. {float(d.max()):.4g}")
        if self.face_id is not None:
            facts.append(f"{len(np.unique(self.face_id[self.face_id >= 0])):,} polygons seen")
        return facts_html(repr(self), facts, buffers_image(self))


def _blends(options: DrawOptions, scene: Scene) -> bool:
    """Whether the draw blends transparent surfaces in drawing order (``transparency=
    "blend"``): then its colour is drawn into a float target and rounded once at the end --
    each layer rounded to 8 bits would lose up to half a level a layer (32 layers of
    opacity 0.2 gave 253 where 1 - 0.8^32 is 254.8)."""
    return options.transparency is Transparency.BLEND and sees_through(options, scene)


def _to_u8(color: np.ndarray) -> np.ndarray:
    """Float colour as an 8-bit target stores it: clipped to [0, 1], rounded to 1/255."""
    return (np.clip(color, 0.0, 1.0) * 255 + 0.5).astype(np.uint8)


def _id_pass(options: DrawOptions, scene: Scene) -> DrawOptions:
    """The options of a multisampled frame's single-sampled pass for its ids and depth: the
    same, or -- where the frame asks no normals and nothing the mode decides shows in the
    ids (shadows read back, wireframe, transparent surfaces, GPU patches) -- the depth
    mode's, whose fragments only write what they are (the colour is thrown away): the same
    ids and depth for less shading (the pass alone 1.25x as fast as Phong's, a frame 1.09x
    at MSAA 4: benchmarks/dataset_bench.py)."""
    cheap = (not options.outputs & Outputs.NORMAL and options.shadows is Shadows.OFF
             and not options.wireframe and not scene.patch_models
             and not sees_through(options, scene))
    return options.replace(mode=ShadingMode.DEPTH, edges=False) if cheap else options


#: frames :meth:`Renderer.render_many` draws ahead of the one it reads back, each into
#: targets of its own: the driver takes in frame k+1's triangles while it fills frame k's
#: pixels (llvmpipe bins in the calling thread and rasterises in its own threads: at
#: 640x480 without MSAA 51 frames/s one at a time, 65 four ahead, 69 eight ahead here;
#: benchmarks/dataset_bench.py) -- as many as AHEAD_BYTES of targets hold
FRAMES_AHEAD = 8
AHEAD_BYTES = 256 << 20
#: bytes a pixel sample of an offscreen target takes: colour (up to float 4x4), normal
#: (4x4), polygon id, depth and z (4 each)
TARGET_BYTES = 44


@dataclass
class _Drawn:
    """A frame drawn and not yet read back: its colour's target and the target of its
    other outputs (the same without MSAA), the draw whose covered samples were counted and
    the draw the other outputs came from, what was asked."""

    color_target: OffscreenTarget
    target: OffscreenTarget
    counted: DrawState
    state: DrawState
    options: DrawOptions
    want: Outputs
    blends: bool
    slot: int


class Renderer:
    """Renders scenes into images of ``width`` x ``height`` pixels.

    On a software rasterizer Phong programs take the lighting constants as flat varyings
    for models with large triangles (``flat_constants``): faster there, the same pictures.

    Parameters
    ----------
    width, height : int
        Image size in pixels.
    samples : int
        MSAA samples (0 = off; the id, depth and normal outputs are exact either way).
    backend : Backend or str
        ``"auto"`` (EGL, then OSMesa), ``"egl"`` or ``"osmesa"``; ``GLSHADE_BACKEND``
        overrides ``"auto"``.
    device : int or None
        EGL device index, for machines with several GPUs.
    context : RenderContext or None
        An existing context to draw with (not released by ``close()``).
    config : RenderConfig or None
        All of the above but the context as one value (``Renderer(config=c)``; then the
        other arguments are not given).
    require_gpu : bool or None
        Refuse a software rasterizer (llvmpipe and the like) with one line naming it and
        the usual cause, :class:`~glshade.errors.NoGpuError` (None:
        ``GLSHADE_REQUIRE_GPU``, which ``--require-gpu`` sets).
    """

    def __init__(self, width: int = 512, height: int = 512, samples: int = 4,
                 backend: Backend | str = "auto", device: int | None = None,
                 context: RenderContext | None = None, *, config: RenderConfig | None = None,
                 require_gpu: bool | None = None):
        if config is None:
            config = RenderConfig(width, height, samples, Backend.parse(backend), device,
                                  require_gpu)
        elif (width, height, samples, backend, device) != (512, 512, 4, "auto", None):
            raise UsageError("give a Renderer either a config or width, height, samples, "
                             "backend and device, not both")
        elif require_gpu is not None:
            config = config.replace(require_gpu=require_gpu)
        self.config = config
        self._owns_context = context is None
        self.context = context or create_context(config.backend, config.device,
                                                 require_gpu=config.require_gpu)
        if context is not None:  # (a context of the caller's: refused, never released)
            check_gpu(context, config.require_gpu, release=False)
        self.ctx = self.context.ctx
        # (with several contexts in a process, the GL objects made here must go to this one)
        self.context.make_current()
        try:
            check_fits(self.context, config.width, config.height, config.samples)
        except InputError:
            if self._owns_context:
                self.context.release()
            raise
        self.width, self.height, self.samples = config.width, config.height, config.samples
        self.shaders = ShaderLibrary(self.context)
        uniforms, materials = UniformWriter(), MaterialUniforms()
        # (flat constants: shaders/include/constants.glsl; per model:
        # programs.FLAT_CONSTANTS_PIXELS)
        self.meshes = MeshPass(self.context, self.shaders, uniforms, materials,
                               flat_constants=self.context.software)
        self.csg = CsgPass(self.context, self.shaders, uniforms, materials)
        self.patches = PatchPass(self.context, self.shaders, self.meshes)
        self.points = PointPass(self.context, self.shaders, uniforms)
        self.lines = LinePass(self.context, self.shaders, uniforms)
        #: the stages that draw opaque surfaces (a shadow pass's G-buffer is drawn with them)
        opaque = (self.meshes, self.patches, self.csg, self.points, self.lines)
        self.shadows = ShadowPass(self.context, self.shaders, opaque)
        self.transparent = TransparencyPass(self.context, self.shaders, self.meshes)
        self.edges = EdgePass(self.context, self.shaders, self.meshes)
        self.environment = EnvironmentPass(self.context, self.shaders, uniforms)
        #: a frame's pipeline, in drawing order (render/passes/__init__.py: the protocol)
        self.stages: tuple[Stage, ...] = (self.environment, self.shadows, *opaque,
                                          self.transparent, self.edges)
        self._uniforms = uniforms
        self._targets: dict[str, OffscreenTarget] = {}
        self._queries: dict[int, Any] = {}  # a sample-counting query per target slot
        self._warned: set[int] = set()  # scenes told that the radiosity mode needs a solve
        self.closed = False

    # ------------------------------------------------------------------ lifecycle
    @property
    def backend(self) -> str:
        return self.context.backend.value

    def close(self) -> None:
        """Free every GL object this Renderer made (and its context, if it made it)."""
        if self.closed:
            return
        if not self.context.released:
            self.context.make_current()
        for t in self._targets.values():
            t.release()
        for stage in reversed(self.stages):
            stage.release()
        self.shaders.release()  # (moderngl's Query has no release: its context frees it)
        self._uniforms.forget()
        self._targets.clear()
        if self._owns_context:
            self.context.release()
        self.closed = True

    def __enter__(self) -> Renderer:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def _check(self) -> None:
        if self.closed:
            raise GlshadeError("this Renderer was closed; make a new one")

    # ------------------------------------------------------------------ caches
    def _target(self, color_dtype: str, samples: int | None = None,
                slot: int = 0, size: tuple[int, int] | None = None) -> OffscreenTarget:
        """The offscreen target of this colour type and sample count; ``slot`` > 0: one of
        the targets :meth:`render_many` draws frames ahead into (kept apart from slot 0,
        which every other read uses, so a pending frame survives a call between yields);
        ``size``: another than the renderer's (an annotation's whole projection)."""
        self._check()
        self.context.make_current()
        samples = self.samples if samples is None else samples
        w, h = size or (self.width, self.height)
        key = f"{color_dtype}/{samples}/{slot}" + (f"/{w}x{h}" if size else "")
        t = self._targets.get(key)
        if t is None:
            try:
                t = OffscreenTarget(self.context, w, h, samples, color_dtype)
            except GlshadeError:
                raise
            except Exception as exc:  # the driver's refusal (out of memory, incomplete)
                raise EnvironmentFailure(f"this GL could not make a {self.width}x"
                                         f"{self.height} framebuffer with {self.samples} "
                                         f"samples: {exc}") from None
            self._targets[key] = t
        return t

    @property
    def cached_meshes(self) -> int:
        """How many meshes have a GPU copy (uploaded once, dropped with their mesh)."""
        return self.meshes.cached

    @property
    def flat_constants(self) -> bool:
        """Phong programs take the lighting constants as flat varyings for models with
        large triangles (on by default on a software rasterizer: faster, the same
        pictures)."""
        return self.meshes.flat_constants

    @flat_constants.setter
    def flat_constants(self, on: bool) -> None:
        self.meshes.flat_constants = bool(on)

    # ------------------------------------------------------------------ drawing
    def draw(self, target, scene: Scene, camera: Camera, options: DrawOptions | None = None,
             *, viewport=None, clear: bool = True, read_visibility: bool = False) -> DrawState:
        """Draw ``scene`` into ``target`` -- the renderer's offscreen target, a window's
        framebuffer (the viewer) or any object with its ``begin/bind/resolve`` -- optionally
        into a ``viewport`` ``(x, y, w, h)`` without clearing (GL's: a window's origin is
        its bottom left; an offscreen target, stored top row first, counts from the top).
        The one drawing path: every picture glshade makes comes through here.

        Parameters
        ----------
        target
            what is drawn into.
        scene, camera
            what is drawn and from where.
        options
            :class:`~glshade.DrawOptions` or a shading mode's name.
        viewport
            ``(x, y, w, h)`` in the target's pixels; the whole target when None.
        clear
            clear the target first (and resolve it after).
        read_visibility
            the caller reads each light's visibility back afterwards (:attr:`shadows`'
            ``read()``): shadows go through a G-buffer.

        Returns
        -------
        DrawState
            The draw's facts, every decision the stages acted on among them.
        """
        self._check()
        options = DrawOptions.of(options)
        camera = self._checked(scene, camera, options)
        self.context.make_current()
        self.meshes.sync()
        state = DrawState.of(target, scene, camera, options, viewport,
                             read_visibility=read_visibility, clear=clear,
                             traced_forward=self.context.features.storage)
        # the pipeline: shadows -> meshes -> patches -> CSG solids -> point clouds ->
        # polylines -> transparency -> edges
        return run(self.ctx, self.stages, state)

    @property
    def transparency(self):
        """What the last draw with transparent surfaces composited and left out (a
        :class:`~glshade.render.passes.transparency.TransparencyReport`), or None."""
        return self.transparent.report if self.transparent.drawn else None

    @property
    def culled(self) -> Culled:
        """What the last draw skipped as outside the view (:class:`Culled`)."""
        return Culled(int(self.meshes.culled), int(self.meshes.culled_chunks),
                      int(self.points.culled_chunks))

    @property
    def shadow_pass(self):
        """The last shadowed draw's pass (its ``undecided`` rays, its ``maps``), or None."""
        return self.shadows if self.shadows.drawn else None

    def _checked(self, scene, camera, options: DrawOptions) -> Camera:
        """The camera a draw uses (planes fitted to the scene), after the checks every draw
        makes of what it was given."""
        if not isinstance(scene, Scene):
            raise OptionError(f"expected a Scene, got {type(scene).__name__}")
        if not isinstance(camera, Camera):
            raise OptionError(f"expected a Camera, got {type(camera).__name__}")
        camera = camera.with_planes(scene.bounds)  # (planes not given: fitted to the scene)
        if options.mode is ShadingMode.RADIOSITY:
            self._warn_unsolved(scene)
        near, far = camera.planes()
        reach = max(far, math.hypot(*camera.position))
        if not reach <= MAX_CAMERA_REACH:  # (a far camera that sees nothing is just blank)
            raise SceneError(f"the camera is {reach:.3g} from the origin or its scene, too "
                             f"far to compute its projection (at most {MAX_CAMERA_REACH:g}): "
                             "move it closer")
        if far > MAX_PLANE_RATIO * near and camera.projection == "perspective":
            warnings.warn(f"the near plane ({near:.3g}) is {far / near:.3g} times nearer than "
                          f"the far plane ({far:.3g}): past {MAX_PLANE_RATIO:.0e} the depth "
                          "buffer cannot order surfaces and drops some; raise the near "
                          "plane or lower the far one", RenderWarning, stacklevel=3)
        if len(scene.lights) > MAX_LIGHTS:
            raise SceneError(f"at most {MAX_LIGHTS} lights per draw, the scene has "
                                f"{len(scene.lights)}")
        return camera

    def _warn_unsolved(self, scene: Scene) -> None:
        """The radiosity mode shows solved radiosities; say so, once per scene, when the
        scene has none (it would show only emitters and the ambient term: nearly black)."""
        unsolved = [m for m in scene.models if m.visible and m.vertex_colors is None]
        if not unsolved or id(scene) in self._warned:
            return
        self._warned.add(id(scene))
        warnings.warn("the radiosity mode shows a solved scene's radiosities, and this one "
                      f"has none (unsolved models: {len(unsolved)}; only emitters and the "
                      "ambient term show); solve it first: glshade radiosity SCENE.toml -o "
                      "out.png, or glshade.radiosity.solve(scene).scene()",
                      UserWarning, stacklevel=4)

    def _counted_draw(self, target, scene: Scene, camera: Camera, options,
                      read_visibility: bool = False, slot: int = 0) -> DrawState:
        """Draw, counting the samples that pass the depth test (:meth:`_check_covered`
        reads the count: a render that covers no pixel is almost always a mistake)."""
        query = self._queries.get(slot)
        if query is None:
            self.context.make_current()
            query = self._queries[slot] = self.ctx.query(samples=True)
        with query:
            return self.draw(target, scene, camera, options, read_visibility=read_visibility)

    def _check_covered(self, scene: Scene, state: DrawState, options, slot: int = 0,
                       stacklevel: int = 4) -> None:
        """Report a draw that covered no pixel (RenderWarning) with its cause. Reading the
        count waits for the draw: callers read it with the frame's pixels."""
        if self._queries[slot].samples == 0:
            warnings.warn(why_blank(scene, state.camera.with_planes(scene.bounds),
                                    options.cull), RenderWarning, stacklevel=stacklevel)

    def render(self, scene: Scene, camera: Camera, options=None, **changes) -> np.ndarray:
        """The colour image ``(H, W, 4) uint8``, row 0 at the top.

        ``options``: DrawOptions or a shading mode's name; ``changes`` override single
        options (``mode="flat"``, ``depth_test=False``, ``cull=True``, ``srgb=True`` ...).

        Parameters
        ----------
        scene : Scene
            What to draw.
        camera : Camera
            From where.
        options : DrawOptions, ShadingMode, str or None
            How (None: the defaults, Phong).
        **changes
            Single options replaced, by name.
        """
        options = DrawOptions.of(options, **changes)
        if options.outputs is not Outputs.COLOR:
            options = options.replace(outputs=Outputs.COLOR)
        with held():  # (a Ctrl-C waits for the frame: never mid-way through the driver's work)
            blends = _blends(options, scene)
            target = self._target("f4" if blends else "f1")
            state = self._counted_draw(target, scene, camera, options)
            self._check_covered(scene, state, options)
            return _to_u8(target.read_color()) if blends else target.read_color()

    def render_frame(self, scene: Scene, camera: Camera, options=None, *,
                     outputs: Outputs = Outputs.ALL, color_dtype: str = "u1",
                     **changes) -> Frame:
        """Colour and the ``outputs`` asked for (depth, world normals, polygon ids).
        ``color_dtype="f4"`` returns unquantised float colour, for tests of the formula.

        The auxiliary outputs are exact whatever the renderer's MSAA samples: each pixel's
        id, depth and unit normal are those of the surface its centre sees (zero normal,
        ``inf`` depth and id -1 where nothing is drawn), never a blend of a silhouette's
        samples. Without MSAA they come from the colour's own pass (several render
        targets); with it, from a second, single-sampled pass of the same draw.

        Parameters
        ----------
        scene : Scene
            What to draw.
        camera : Camera
            From where.
        options : DrawOptions, ShadingMode, str or None
            How (None: the defaults, Phong).
        outputs : Outputs
            The buffers to read back (flags: COLOR, DEPTH, NORMAL, FACE_ID ...).
        color_dtype : str
            ``"u1"`` (uint8) or ``"f4"`` (float32, unquantised).
        **changes
            Single options replaced, by name.
        """
        options, blends = self._frame_options(scene, options, changes, outputs, color_dtype)
        with held():  # (a Ctrl-C waits for the frame: never mid-way through the driver's work)
            return self._read_frame(scene, self._draw_frame(scene, camera, options, blends,
                                                            color_dtype))

    def _frame_options(self, scene: Scene, options, changes: dict, outputs: Outputs,
                       color_dtype: str) -> tuple[DrawOptions, bool]:
        """A frame's options (the polygon ids drawn where instance or class ids are asked
        for: those are looked up from them) and whether it blends in a float target."""
        if color_dtype not in ("u1", "f4"):
            raise OptionError(f"color_dtype must be 'u1' or 'f4', got {color_dtype!r}")
        options = DrawOptions.of(options, **changes).replace(outputs=outputs | Outputs.COLOR)
        blends = color_dtype == "u1" and _blends(options, scene)
        return options, blends

    def _draw_frame(self, scene: Scene, camera: Camera, options: DrawOptions, blends: bool,
                    color_dtype: str, slot: int = 0) -> _Drawn:
        """Draw a frame into the targets of ``slot`` without reading anything back (the
        read, :meth:`_read_frame`, is what waits for the driver)."""
        dtype = "f1" if color_dtype == "u1" and not blends else "f4"
        want = options.outputs
        if want & (Outputs.INSTANCE | Outputs.SEMANTIC):
            options = options.replace(outputs=want | Outputs.FACE_ID)
        target = self._target(dtype, slot=slot)
        if self.samples and want.auxiliary:  # colour multisampled, the rest exact
            drawn = self._counted_draw(target, scene, camera,
                                       options.replace(outputs=Outputs.COLOR), True, slot)
            aux = self._target(dtype, samples=0, slot=slot)
            state = self.draw(aux, scene, camera, _id_pass(options, scene),
                              read_visibility=True)
            return _Drawn(target, aux, drawn, state, options, want, blends, slot)
        state = self._counted_draw(target, scene, camera, options, True, slot)
        return _Drawn(target, target, state, state, options, want, blends, slot)

    def _read_frame(self, scene: Scene, drawn: _Drawn) -> Frame:
        """Read a drawn frame's buffers back: the outputs it asked for."""
        self.context.make_current()
        self._check_covered(scene, drawn.counted, drawn.options, drawn.slot, stacklevel=5)
        color = drawn.color_target.read_color()
        if drawn.blends:
            color = _to_u8(color)
        want, target = drawn.want, drawn.target
        ids = want & (Outputs.INSTANCE | Outputs.SEMANTIC)
        face_id = target.read_face_id() if want & Outputs.FACE_ID or ids else None
        instance = semantic = None
        if ids:
            assert face_id is not None  # (drawn for them)
            instances, classes = scene.id_tables()
            if want & Outputs.INSTANCE:
                instance = instances[face_id + 1]
            if want & Outputs.SEMANTIC:
                semantic = classes[face_id + 1]
        state = drawn.state
        return Frame(color,
                     target.read_depth() if want & Outputs.DEPTH else None,
                     target.read_normal() if want & Outputs.NORMAL else None,
                     face_id if want & Outputs.FACE_ID else None,
                     self.shadows.read() if state.read_visibility else None,
                     instance, semantic, state.camera)

    def pick(self, scene: Scene, camera: Camera, x: float, y: float,
             options=None) -> Pick | None:
        """What is under pixel ``(x, y)`` of this renderer's image (x right, y down, in
        pixels; the pixel whose centre is nearest): the polygon id (as ``Frame.face_id``
        numbers them), the world point, the world normal and the view depth -- read from
        the id, depth and normal buffers of one draw. None where the pixel shows background.
        The normal is the polygon's own (a flat draw) unless ``options`` say another mode
        (Phong's: the interpolated normal there).

        Parameters
        ----------
        scene : Scene
            What is drawn.
        camera : Camera
            From where.
        x, y : float
            The pixel, x right and y down from the top-left corner, in pixels.
        options : DrawOptions, ShadingMode, str or None
            How it is drawn (None: flat, so the normal is the polygon's).
        """
        try:
            fx, fy = float(x), float(y)
        except (TypeError, ValueError):
            raise OptionError(f"a pixel is two numbers (x, y), got ({x!r}, {y!r})") from None
        if not (math.isfinite(fx) and math.isfinite(fy)):
            raise OptionError(f"a pixel is two finite numbers, got ({fx:g}, {fy:g})")
        px, py = math.floor(fx), math.floor(fy)
        if not (0 <= px < self.width and 0 <= py < self.height):
            raise OptionError(f"pixel ({fx:g}, {fy:g}) is outside the {self.width}x"
                              f"{self.height} image")
        o = DrawOptions.of(options if options is not None else ShadingMode.FLAT)
        frame = self.render_frame(scene, camera, o, outputs=Outputs.ALL)
        assert frame.face_id is not None and frame.depth is not None
        assert frame.normal is not None
        face = int(frame.face_id[py, px])
        if face < 0:
            return None
        depth = float(frame.depth[py, px])
        # the pixel centre's ray (Camera's one convention) to the depth drawn there, a
        # distance along the view axis
        eye, ray = camera.rays_through((self.width, self.height), px + 0.5, py + 0.5)
        p_world = eye + ray * (depth / float(ray @ camera.forward))
        return Pick(face, p_world, np.asarray(frame.normal[py, px], np.float64), depth)

    def render_ids(self, scene: Scene, camera: Camera, options=None) -> np.ndarray:
        """``(H, W)`` int32 polygon ids (-1: background), exact at pixel centres as
        ``Frame.face_id``, drawn once, single-sampled, with the cheapest program that gives
        the same ids (its colour is not read): masks in bulk.

        Parameters
        ----------
        scene : Scene
            What to draw.
        camera : Camera
            From where.
        options : DrawOptions, ShadingMode, str or None
            How (what changes ids: culling, wireframe, transparency).
        """
        return self._ids(scene, camera, options)

    def _ids(self, scene: Scene, camera: Camera, options=None,
             size: tuple[int, int] | None = None) -> np.ndarray:
        """:meth:`render_ids`, into a target of ``size`` (None: the renderer's)."""
        options = DrawOptions.of(options).replace(outputs=Outputs.COLOR | Outputs.FACE_ID)
        with held():
            target = self._target("f1", samples=0, size=size)
            self.draw(target, scene, camera, _id_pass(options, scene))
            return target.read_face_id()

    def annotate(self, scene: Scene, camera: Camera, options=None, *,
                 view: Frame | None = None) -> list:
        """Per-object ground truth for one view, by BOP's names
        (:class:`~glshade.render.annotate.Annotation`: ``instance_id``, ``label``,
        ``obj_id``, ``cam_R_m2c``, ``cam_t_m2c``, ``mask`` drawn alone, ``mask_visib``, pixel
        counts, ``visib_fract``, ``bbox_obj``, ``bbox_visib``), one for each object the
        camera sees any of when drawn alone, in instance order. The view's instance mask is
        one draw; an object's full mask is its visible one where no other object's screen
        box meets its own, else drawn with only the objects of its batch shown (objects
        whose boxes do not meet: :func:`glshade.render.annotate.plan`).

        Parameters
        ----------
        scene : Scene
            The objects (labelled by :meth:`Scene.add`'s ``label``).
        camera : Camera
            The view.
        options : DrawOptions, ShadingMode, str or None
            How the scene is drawn (culling and wireframe change what is seen).
        view : Frame or None
            This view's frame with its instance ids, if drawn already (None: drawn here).
        """
        from . import annotate

        if view is None or view.instance is None or view.depth is None:
            view = self.render_frame(scene, camera, options,
                                     outputs=Outputs.INSTANCE | Outputs.DEPTH)
        assert view.instance is not None and view.depth is not None
        camera = camera.with_planes(scene.bounds)
        models = annotate.objects(scene)
        size = (self.width, self.height)
        alone, batches, window = annotate.plan(models, camera, size)
        full = {k: (window[k], view.instance[window[k]] == k) for k in alone}
        every: list[Any] = scene.every_model
        shown = [m.visible for m in every]
        instances, _ = scene.id_tables()
        try:  # (each batch drawn with only its objects shown; all shown again after)
            for batch in batches:
                members = {id(m) for k in batch for m in models[k]}
                for m in every:
                    m.visible = id(m) in members
                ids = self.render_ids(scene, camera, options)
                full.update({k: (window[k], instances[ids[window[k]] + 1] == k)
                             for k in batch})
            whole = self._whole_projections(scene, camera, options, models, full,
                                            annotate.crossing(models, camera, size))
        finally:
            for m, was in zip(every, shown):
                m.visible = was
        return annotate.records(scene, camera, models, view.instance, view.depth, full,
                                whole)

    def _whole_projections(self, scene, camera, options, models, full, crossing) -> dict:
        """For each object of ``crossing`` (whose screen box leaves the image) that is in
        view: its pixels over its whole projection and their box, as BOP's toolkit counts
        them -- the object drawn alone into an image three times as wide and high with the
        view's in its middle (the same pixels, the principal point moved by W and H).
        Perspective cameras only (an orthographic view keeps its in-image count)."""
        from ..modes import Projection
        from . import annotate

        if camera.projection is not Projection.PERSPECTIVE:
            return {}
        w, h = self.width, self.height
        K, R, t = camera.to_opencv((w, h))
        K = K.copy()
        K[0, 2] += w
        K[1, 2] += h
        # (the view's clip planes, fitted to the whole scene: the bounds of what is shown
        # now would cut the object)
        wide = Camera.from_opencv(K, R, t, (3 * w, 3 * h), near=camera.near, far=camera.far)
        instances, _ = scene.id_tables()
        out = {}
        for k in crossing:
            if k not in full or not full[k][1].any():
                continue
            members = {id(m) for m in models[k]}
            for m in scene.every_model:
                m.visible = id(m) in members
            mask = instances[self._ids(scene, wide, options, size=(3 * w, 3 * h)) + 1] == k
            out[k] = (int(mask.sum()), annotate.shifted_box(annotate.bbox(mask), -w, -h))
        return out

    def render_depth(self, scene: Scene, camera: Camera, **changes) -> np.ndarray:
        """``(H, W) float32``: distance along the view axis, ``inf`` where nothing was drawn.

        Parameters
        ----------
        scene : Scene
            What to draw.
        camera : Camera
            From where.
        **changes
            Single options replaced, by name.
        """
        depth = self.render_frame(scene, camera, "depth", outputs=Outputs.DEPTH,
                                  **changes).depth
        assert depth is not None  # (asked for)
        return depth

    def render_many(self, scene: Scene, cameras: Iterable[Camera], options=None, *,
                    outputs: Outputs = Outputs.COLOR, **changes) -> Iterator[Frame]:
        """Frames for a sequence of cameras, each equal to :meth:`render_frame`'s for its
        camera (the outputs not asked for None); meshes are uploaded and programs compiled
        once, and only the outputs asked for are read back.

        Parameters
        ----------
        scene : Scene
            What to draw.
        cameras : iterable of Camera
            From where, in turn.
        options : DrawOptions, ShadingMode, str or None
            How (None: the defaults, Phong).
        outputs : Outputs
            The buffers to read back (COLOR is always read).
        **changes
            Single options replaced, by name.
        """
        options, blends = self._frame_options(scene, options, changes, outputs, "u1")
        ahead = self._frames_ahead(options)
        if isinstance(cameras, Sized):  # (no targets for frames that will not come)
            ahead = max(1, min(ahead, len(cameras)))
        pending: list[_Drawn] = []
        try:
            try:
                for camera in cameras:
                    with held():
                        pending.append(self._draw_frame(  # (one at a time: slot 0's target)
                            scene, camera, options, blends, "u1",
                            len(pending) + 1 if ahead > 1 else 0))
                    if len(pending) == ahead:  # (read as a group: reading frame k while
                        yield from self._read_all(scene, pending)  # k+1 is drawn waits)
            except Exception:  # (a bad camera: the frames before it first, as one at a time)
                yield from self._read_all(scene, pending)
                raise
            yield from self._read_all(scene, pending)
        finally:  # (the targets drawn ahead into are big: not kept past the run)
            for key in [k for k in self._targets if not k.endswith("/0")]:
                if not self.closed:
                    self.context.make_current()
                    self._targets.pop(key).release()

    def _read_all(self, scene: Scene, pending: list[_Drawn]) -> Iterator[Frame]:
        """The pending frames read back in order (the list emptied)."""
        frames = []
        with held():
            for drawn in pending:
                frames.append(self._read_frame(scene, drawn))
        pending.clear()
        yield from frames

    def _frames_ahead(self, options: DrawOptions) -> int:
        """How many frames :meth:`render_many` draws before reading the first back: up to
        FRAMES_AHEAD, as many as AHEAD_BYTES of targets hold; one where a frame reads
        buffers every draw shares (the shadows' visibility)."""
        if options.shadows is not Shadows.OFF:
            return 1
        # (a slot's targets: with MSAA the multisampled one, its resolved copy and the
        # single-sampled one of the ids; without, one)
        per_slot = self.width * self.height * TARGET_BYTES * (
            self.samples + 2 if self.samples else 1)
        return max(1, min(FRAMES_AHEAD, AHEAD_BYTES // per_slot))

    def info(self) -> dict:
        return self.context.info
