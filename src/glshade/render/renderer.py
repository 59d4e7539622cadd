"""The Renderer: draws a Scene seen by a Camera with DrawOptions, headless or into a window.

``Renderer.draw(target, scene, camera, options)`` is the one drawing path; ``render`` and
``render_frame`` draw into the renderer's own offscreen target and read it back.

Meshes are uploaded once per Renderer and cached (the cache follows the scene: a mesh that
is garbage-collected loses its GPU copy at the next frame). A new camera only changes
uniforms; buffers are never re-uploaded per frame.
"""

from __future__ import annotations

from typing import Any

import dataclasses
import math
import warnings
import weakref
from collections.abc import Iterable, Iterator
from dataclasses import dataclass

import moderngl
import numpy as np

from ..errors import (
    EnvironmentFailure, GlshadeError, InputError, RenderWarning, SettingError,
    OptionError, SceneError, UsageError,
)
from ..interrupt import held
from ..geometry.transforms import box_corners, gl_bytes
from ..modes import Backend, Culling, Outputs, Projection, ShadingMode, Shadows
from ..options import DrawOptions, RenderConfig
from ..scene import MAX_LIGHTS, Camera, Scene
from ..scene.camera import MAX_PLANE_RATIO
from .context import RenderContext, create_context
from .gpu_mesh import GpuMesh
from .programs import (
    FLAT_CONSTANTS_PIXELS, TEXTURED_MODES, MaterialUniforms, ProgramKey, UniformWriter,
    Variant,
    flat_constants_fit, light_kind,
)
from .shaders import ShaderLibrary
from .state import DrawState
from .textures import TextureCache
from .passes.csg import CsgPass
from .passes.edges import EdgePass
from .diagnostics import why_blank
from .target import OffscreenTarget

__all__ = ["Renderer", "Frame", "Pick", "MAX_CAMERA_REACH", "SHADOWED_MODES"]

#: the modes whose lights a shadow hides (the others show no light: normals, depth,
#: radiosity's solved values)
SHADOWED_MODES = (ShadingMode.FLAT, ShadingMode.GOURAUD, ShadingMode.PHONG)
#: the texture unit of a shadowed draw's visibility array (shaders/include/shadow_mask.glsl)
SHADOW_UNIT = 6
#: the first texture unit of a forward map-shadowed draw's maps (a light each, up to 8)
MAP_FORWARD_UNIT = 16

#: how far a camera may be from the origin or its scene (beyond, the view and projection
#: matrices overflow float64 products)
MAX_CAMERA_REACH = 1e150


@dataclass(frozen=True)
class Pick:
    """What a pixel shows (:meth:`Renderer.pick`): ``face_id`` (as :class:`Frame` numbers
    polygons: the scene's mesh polygons in order, then its solids' leaves), the world
    ``point (3,)``, the unit world ``normal (3,)`` and the view ``depth``."""

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

    color : (H, W, 4) uint8 (float32 with ``color_dtype="f4"``), linear unless ``srgb``.
    depth : (H, W) float32 distance along the view axis; ``inf`` where nothing was drawn.
    normal : (H, W, 3) float32 world-space unit normal (zero where nothing was drawn).
    face_id : (H, W) int32 id of the source polygon (not the triangle); -1 for background;
    with several models, ids continue from one model to the next in scene order.
    visibility : (H, W, L) float32, a draw with shadows: how much of each of its L lights
    reaches the surface point each pixel centre sees (1 seen, 0 hidden; a shadow map's PCF
    gives fractions; 1 on the background).
    """

    color: np.ndarray
    depth: np.ndarray | None = None
    normal: np.ndarray | None = None
    face_id: np.ndarray | None = None
    visibility: np.ndarray | None = None

    def __repr__(self) -> str:
        h, w = self.color.shape[:2]
        outputs = [n for n in ("color", "depth", "normal", "face_id")
                   if getattr(self, n) is not None]
        drawn = "" if self.face_id is None else \
            f"; {int((self.face_id >= 0).sum()):,} pixels drawn"
        return f"<Frame {w}x{h}: {', '.join(outputs)}{drawn}>"

    def _repr_html_(self) -> str:
        """In a notebook: its buffers side by side (colour, depth, normals, ids)."""
        from .._display import buffers_image, facts_html

        facts = []
        if self.depth is not None and np.isfinite(self.depth).any():
            d = self.depth[np.isfinite(self.depth)]
            facts.append(f"depth {float(d.min()):.4g} .. {float(d.max()):.4g}")
        if self.face_id is not None:
            facts.append(f"{len(np.unique(self.face_id[self.face_id >= 0])):,} polygons seen")
        return facts_html(repr(self), facts, buffers_image(self))


_FLIP_Y = np.diag([1.0, -1.0, 1.0, 1.0])

#: bytes per pixel and sample of an offscreen target: colour (up to 16 as float), normal
#: (16), polygon id (4), view depth (4) and the z-buffer (4)
_BYTES_PER_SAMPLE = 44


def check_fits(context, width: int, height: int, samples: int = 0,
               bytes_per_pixel: int = 0) -> None:
    """Refuse, up front and by name, what this GL cannot make: MSAA sample counts it lacks,
    images wider than its framebuffers, and (on a software renderer, which draws in main
    memory) images larger than the machine's memory."""
    import os

    info = context.ctx.info
    max_samples = context.ctx.max_samples
    if samples and (samples > max_samples or samples & (samples - 1)):
        counts = ", ".join(str(2**i) for i in range(int(np.log2(max(max_samples, 1))) + 1))
        raise SettingError("samples", f"samples must be 0 (off) or one of {counts} on this "
                                      f"GL ({context.detail}), got {samples}")
    side = min(int(info.get("GL_MAX_RENDERBUFFER_SIZE") or 16384),
               *[int(x) for x in (info.get("GL_MAX_VIEWPORT_DIMS") or (16384, 16384))])
    if max(width, height) > side:
        raise SettingError("size", f"an image of {width}x{height} is larger than this GL's "
                                   f"largest framebuffer, {side} pixels a side "
                                   f"({context.detail})")
    need = width * height * (bytes_per_pixel or
                             _BYTES_PER_SAMPLE * (samples + 1 if samples else 1))
    software = context.software
    try:
        memory = os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError, AttributeError):
        memory = 0
    if software and memory and need > memory // 3:
        what = f"with {samples} samples " if not bytes_per_pixel else ""
        raise SettingError("size", f"an image of {width}x{height} {what}"
                                   f"needs about {need / 2**30:.1f} GiB of framebuffers; this "
                                   "software renderer draws in main memory "
                                   f"({memory / 2**30:.0f} GiB): ask for fewer pixels or "
                                   "samples")


def _mat3(m: np.ndarray) -> bytes:
    return np.ascontiguousarray(np.asarray(m, dtype=np.float32).T).tobytes()


class Renderer:
    """Renders scenes into images of ``width`` x ``height`` pixels.

    Parameters
    ----------
    width, height : image size in pixels.
    samples : MSAA samples (0 = off; exact per-pixel comparisons use 0).
    backend : "auto" (EGL, then OSMesa), "egl" or "osmesa"; ``GLSHADE_BACKEND`` overrides
        "auto".
    device : EGL device index, for machines with several GPUs.
    context : an existing RenderContext to draw with (not released by ``close()``).
    config : all of the above but the context as one :class:`~glshade.RenderConfig`
        (``Renderer(config=c)``; then the other arguments are not given).

    ``flat_constants`` (on by default on a software rasterizer) lets Phong programs take the
    lighting constants as flat varyings for models with large triangles: faster there, the
    same pictures.
    """

    def __init__(self, width: int = 512, height: int = 512, samples: int = 4,
                 backend: Backend | str = "auto", device: int | None = None,
                 context: RenderContext | None = None, *, config: RenderConfig | None = None):
        if config is None:
            config = RenderConfig(width, height, samples, Backend.parse(backend), device)
        elif (width, height, samples, backend, device) != (512, 512, 4, "auto", None):
            raise UsageError("give a Renderer either a config or width, height, samples, "
                             "backend and device, not both")
        self.config = config
        self._owns_context = context is None
        self.context = context or create_context(config.backend, config.device)
        self.ctx = self.context.ctx
        try:
            check_fits(self.context, config.width, config.height, config.samples)
        except InputError:
            if self._owns_context:
                self.context.release()
            raise
        self.width, self.height, self.samples = config.width, config.height, config.samples
        self.shaders = ShaderLibrary(self.context)
        self._uniforms = UniformWriter()
        self._materials = MaterialUniforms()
        self._csg = CsgPass(self.context, self.shaders, self._uniforms, self._materials)
        self._edges = EdgePass(self.context, self.shaders, self._uniforms, self._gpu_mesh)
        self._patches: Any = None  # (a PatchPass, made for the first GPU patch model)
        self._shadow_pass: Any = None  # (a ShadowPass, made for the first shadowed draw)
        self._oit: Any = None  # (a TransparencyPass, made for the first transparent surface)
        self._textures: Any = None  # (a TextureCache, made for the first textured draw)
        self._meshes: dict[int, tuple[weakref.ref, GpuMesh]] = {}
        self._targets: dict[str, OffscreenTarget] = {}
        self._query: Any = None
        self._normal_cache: dict[bytes, tuple[np.ndarray, bool]] = {}
        self._programs: dict[tuple, Any] = {}
        self._model_state: dict[int, tuple] = {}  # per program: the model uniforms it holds
        self._warned: set[int] = set()  # scenes told that the radiosity mode needs a solve
        self._visibility_wanted = False  # (render_frame: shadows through a G-buffer)
        # (shaders/include/constants.glsl; per model: programs.FLAT_CONSTANTS_PIXELS)
        self.flat_constants = self.context.software
        self._max_varyings = int(self.ctx.info.get("GL_MAX_VARYING_VECTORS") or 15)
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
        for _, gpu in self._meshes.values():
            gpu.release()
        for t in self._targets.values():
            t.release()
        self._csg.release()
        self._edges.release()
        if self._patches is not None:
            self._patches.release()
        if self._shadow_pass is not None:
            self._shadow_pass.release()
        if self._textures is not None:
            self._textures.release()
        if self._oit is not None:
            self._oit.release()
        self.shaders.release()  # (moderngl's Query has no release: its context frees it)
        self._uniforms.forget()
        self._programs.clear()
        self._model_state.clear()
        self._meshes.clear()
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
    def _target(self, color_dtype: str, samples: int | None = None) -> OffscreenTarget:
        self._check()
        self.context.make_current()
        samples = self.samples if samples is None else samples
        key = f"{color_dtype}/{samples}"
        t = self._targets.get(key)
        if t is None:
            try:
                t = OffscreenTarget(self.context, self.width, self.height, samples,
                                    color_dtype)
            except GlshadeError:
                raise
            except Exception as exc:  # the driver's refusal (out of memory, incomplete)
                raise EnvironmentFailure(f"this GL could not make a {self.width}x"
                                         f"{self.height} framebuffer with {self.samples} "
                                         f"samples: {exc}") from None
            self._targets[key] = t
        return t

    def _gpu_mesh(self, mesh) -> GpuMesh:
        entry = self._meshes.get(id(mesh))
        if entry is not None and entry[0]() is mesh:
            return entry[1]
        if entry is not None:  # the id was reused by a new object
            entry[1].release()
        gpu = GpuMesh(self.context, mesh)
        self._meshes[id(mesh)] = (weakref.ref(mesh), gpu)
        return gpu

    def _sync(self, scene: Scene) -> None:
        """Drop GPU copies of meshes that no longer exist (no GL work in finalizers)."""
        dead = [k for k, (ref, _) in self._meshes.items() if ref() is None]
        for k in dead:
            self._meshes.pop(k)[1].release()

    @property
    def cached_meshes(self) -> int:
        return len(self._meshes)

    # ------------------------------------------------------------------ drawing
    def draw(self, target, scene: Scene, camera: Camera, options: DrawOptions | None = None,
             *, viewport=None, clear: bool = True) -> None:
        """Draw ``scene`` into ``target`` -- the renderer's offscreen target, a window's
        framebuffer (the viewer) or any object with its ``begin/bind/resolve`` -- optionally
        into a ``viewport`` ``(x, y, w, h)`` without clearing (GL's: a window's origin is
        its bottom left; an offscreen target, stored top row first, counts from the top).
        The one drawing path: every picture glshade makes comes through here."""
        self._check()
        options = DrawOptions.of(options)
        camera = self._checked(scene, camera, options)
        self.context.make_current()
        self._sync(scene)
        state = self._state(target, scene, camera, options, viewport)
        ctx = self.ctx
        visibility = self._shadows_of(state)
        if isinstance(visibility, dict):  # (maps looked up as the programs shade)
            state = dataclasses.replace(
                state, frame_uniforms=state.frame_uniforms + tuple(visibility.items()))
            visibility = None
        if clear:
            target.begin(scene.background, options.outputs)
        else:
            target.bind(options.outputs)
        ctx.viewport = state.viewport
        if options.depth_test:
            ctx.enable(moderngl.DEPTH_TEST)
        else:
            ctx.disable(moderngl.DEPTH_TEST)
        if visibility is not None:
            visibility.use(SHADOW_UNIT)
        id_base = self._draw_meshes(state)
        passes: list = []
        if scene.patch_models and not options.wireframe:  # tessellated here, by the GPU
            if self._patches is None:
                from .passes.patches import PatchPass

                self._patches = PatchPass(self.context, self.shaders, self._uniforms,
                                          self._materials, self._normal_matrix)
            passes.append(self._patches)
        if scene.solids and not options.wireframe:  # CSG, ray cast into the same z-buffer
            passes.append(self._csg)
        for p in passes:  # (one signature: the draw's facts, the first free polygon id)
            id_base = p.draw(state, id_base)
        clear_of = [m for m in scene.models if m.visible and len(m.mesh.triangles[0]) and
                    not options.wireframe and self._transparent(m, options)]
        if clear_of:  # (after every opaque surface: what they show through)
            self._transparency_pass().draw(self, state, clear_of)
            target.bind(options.outputs)
            ctx.viewport = state.viewport
        id_base = self._edges.draw(state, id_base)  # (the overlay: when asked for, on top)
        if state.variant.forward == "rays":  # (the rays that ran out, reported)
            self._shadow_pass.forward_done()
        ctx.disable(moderngl.CULL_FACE)
        ctx.front_face = "ccw"
        if clear:
            target.resolve(options.outputs)

    def _shadows_of(self, state: DrawState):
        """The visibility of each light at each pixel (a texture array), when the draw casts
        shadows: the shadow pass draws the scene's surface points first, then traces or
        looks up each light (render/passes/shadows.py); or, for a draw whose programs find
        it themselves as they shade (``variant.forward``), the uniforms they take."""
        if not state.variant.shadows:
            return None
        # (compute shaders, storage buffers, sampler arrays)
        self.context.require(430, f"shadows={state.options.shadows.value!r} needs",
                             "use shadows='off'")
        if self._shadow_pass is None:
            from .passes.shadows import ShadowPass

            self._shadow_pass = ShadowPass(self.context, self.shaders)
        if state.variant.forward:
            return self._shadow_pass.forward(state, MAP_FORWARD_UNIT)
        return self._shadow_pass.prepare(self, state)

    def _transparency_pass(self):
        if self._oit is None:
            from .passes.transparency import TransparencyPass

            self._oit = TransparencyPass(self.context, self.shaders)
        return self._oit

    @property
    def transparency(self):
        """What the last draw with transparent surfaces composited and left out (a
        :class:`~glshade.render.passes.transparency.TransparencyReport`), or None."""
        return None if self._oit is None else self._oit.report

    @property
    def shadow_pass(self):
        """The last shadowed draw's pass (its ``undecided`` rays, its ``maps``), or None."""
        return self._shadow_pass

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

    def _state(self, target, scene: Scene, camera: Camera, options: DrawOptions,
               viewport) -> DrawState:
        """The frozen facts of one draw (matrices, lights, variant, shared uniforms)."""
        view = camera.view_matrix()
        vx, vy, vw, vh = viewport or (0, 0, target.width, target.height)
        proj = camera.projection_matrix(vw / vh)
        flip_rows = getattr(target, "rows_top_down", False)
        if flip_rows:  # image row 0 first in memory; this mirrors the winding on screen
            proj = _FLIP_Y @ proj
        lights = tuple(scene.lights_for(camera))
        shadows = options.shadows is not Shadows.OFF and options.mode in SHADOWED_MODES \
            and not options.wireframe
        # shadows found by the programs as they shade (maps looked up, rays traced), unless
        # the frame reads the visibility back (render_frame: Frame.visibility) or a CSG solid
        # casts (its rays are a compute pass's) -- then through a G-buffer
        forward = ""
        if shadows and not self._visibility_wanted:
            if options.shadows is Shadows.MAP:
                forward = "maps"
            elif not scene.solids:
                forward = "rays"
        variant = Variant(options.mode, options.outputs.auxiliary,
                          tuple(light_kind(x) for x in lights), options.srgb,
                          camera.projection is Projection.ORTHOGRAPHIC, shadows, forward)
        frame = self._frame_uniforms(scene, camera, lights, view, proj, options.mode)
        if shadows and not forward:
            frame.append(("u_visibility", SHADOW_UNIT))
        return DrawState(scene, camera, options, view, proj, lights, variant, tuple(frame),
                         (vx, vy, vw, vh), flip_rows, target)

    def _draw_meshes(self, state: DrawState) -> int:
        """Draw the scene's visible opaque meshes; the polygon id after theirs (transparent
        ones keep their ids: they are drawn later, by the transparency pass)."""
        scene, options = state.scene, state.options
        prepared: set[int] = set()
        id_base = 0
        for model in scene.models:
            if not model.visible or len(model.mesh.triangles[0]) == 0:
                id_base += model.mesh.n_faces
                continue
            gpu = self._gpu_mesh(model.mesh)
            if not options.wireframe and not self._transparent(model, options):
                self._draw_model(state, model, gpu, id_base, prepared)
            id_base += gpu.n_polygons
        return id_base

    @staticmethod
    def _transparent(model, options) -> bool:
        """Whether a model is drawn by the transparency pass (not in the debug modes, whose
        colours are values to read, not surfaces to see through)."""
        return model.material.transparent and options.mode in SHADOWED_MODES + (
            ShadingMode.RADIOSITY,)

    def _draw_models(self, state: DrawState, models, oit: str = "",
                     extra: dict | None = None) -> None:
        """Draw ``models`` (the transparency pass's: ``oit`` "capture", "fetch" or
        "blend")."""
        prepared: set[int] = set()
        for model in models:
            self._draw_model(state, model, self._gpu_mesh(model.mesh), 0, prepared, oit,
                             extra)

    def _draw_model(self, state: DrawState, model, gpu, id_base: int, prepared: set,
                    oit: str = "", extra: dict | None = None) -> None:
        """One model's draw call, with the uniforms its program does not hold yet."""
        ctx, put = self.ctx, self._uniforms.put
        scene, options, view, lights = state.scene, state.options, state.view, state.lights
        near = state.camera.planes()[0]
        pixels = state.viewport[2] * state.viewport[3]
        m = model.transform
        model_view = view @ m
        cull = options.cull is Culling.ON or (
            options.cull is Culling.AUTO and gpu.closed
            and gpu.beyond(model_view, near) and not oit)  # (seen from outside)
        flat = self.flat_constants and gpu.n_triangles * FLAT_CONSTANTS_PIXELS <= pixels
        textured = (gpu.textured and bool(model.material.textures)
                    and options.mode in TEXTURED_MODES)
        prog = self._program(state.variant, not cull, flat, oit, textured)
        if id(prog) not in prepared:  # the frame's uniforms, once per program used
            for name, value in state.frame_uniforms:
                put(prog, name, value)
            for name, value in (extra or {}).items():
                put(prog, name, value)
            prepared.add(id(prog))
        transform = m.tobytes()
        normal_world, mirrored = self._normal_matrix(m, transform)
        # (the view is rigid: its inverse transpose is itself)
        put(prog, "u_normal_view", _mat3(view[:3, :3] @ normal_world))
        put(prog, "u_model_view", gl_bytes(model_view))
        held = (transform, id_base, model.material, lights, scene.ambient)
        if self._model_state.get(id(prog)) != held:  # else all of it is in place
            put(prog, "u_normal_world", _mat3(normal_world))
            put(prog, "u_face_id_base", id_base)
            put(prog, "u_opacity", float(model.material.opacity))
            for name, value in self._materials(model.material, lights, scene.ambient):
                put(prog, name, value)
            self._model_state[id(prog)] = held
        ctx.front_face = "cw" if mirrored != state.flip_rows else "ccw"
        if cull:
            ctx.enable(moderngl.CULL_FACE)
            ctx.cull_face = "back"
        else:
            ctx.disable(moderngl.CULL_FACE)
        if textured:
            if self._textures is None:
                self._textures = TextureCache(self.context)
            self._textures.bind(model.material, put, prog)
        if options.mode is ShadingMode.RADIOSITY:
            vao = gpu.color_array(prog, model.display_colors(scene.ambient))
        else:
            vao = gpu.vertex_array(prog, options.mode)
        vao.render(moderngl.TRIANGLES)

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

    def _normal_matrix(self, model: np.ndarray, key: bytes) -> tuple[np.ndarray, bool]:
        """Inverse transpose of a model matrix's 3x3 part, and whether it mirrors (its
        faces then wind the other way), cached per transform (``key``: its bytes)."""
        found = self._normal_cache.get(key)
        if found is None:
            if len(self._normal_cache) > 4096:
                self._normal_cache.clear()
            found = self._normal_cache[key] = (np.linalg.inv(model[:3, :3]).T,
                                               bool(np.linalg.det(model[:3, :3]) < 0))
        return found

    def _program(self, variant: Variant, two_sided: bool, flat: bool = False, oit: str = "",
                 textured: bool = False):
        """The compiled program of a variant (mode, aux, light kinds, srgb, orthographic),
        with flat lighting constants if asked for and they fit; ``oit``: a transparent
        surface's ("capture" into fragment lists, or "blend"); ``textured``: its material's
        maps sampled."""
        found = (variant, two_sided, flat, oit, textured)
        program = self._programs.get(found)
        if program is None:
            world = (variant.aux or (bool(variant.forward) and variant.shadows)) and not oit
            flat = flat and flat_constants_fit(variant.mode, world, variant.lights,
                                               self._max_varyings, textured)
            key = ProgramKey.of(variant, two_sided=two_sided, flat_constants=flat, oit=oit,
                                textured=textured)
            program = self._programs[found] = self.shaders.program(key)
        return program

    @staticmethod
    def _frame_uniforms(scene, camera, lights, view, proj, mode) -> list:
        """The uniforms every program of one draw shares: matrices, lights, ambient."""
        # (only as many entries as lights: a program's arrays are cut to what it uses)
        pos = np.array([light.view_vector(view) for light in lights], dtype="f4")
        att = np.array([light.attenuation for light in lights], dtype="f4")
        out: list[tuple[str, Any]] = [
            ("u_proj", gl_bytes(proj)), ("u_light_pos_view", pos.tobytes()),
            ("u_light_attenuation", att.tobytes())]
        if mode is ShadingMode.DEPTH:
            corners = box_corners(scene.bounds)
            d = -(corners @ view[:3, :3].T + view[:3, 3])[:, 2]
            planes = camera.planes()
            near, far = max(planes[0], d.min()), min(planes[1], d.max())
            out.append(("u_depth_range", (float(near), float(max(far, near + 1e-6)))))
        return out

    def _counted_draw(self, target, scene: Scene, camera: Camera, options) -> None:
        """Draw, counting the samples that pass the depth test: a render that covers no
        pixel is almost always a mistake, so it is reported (RenderWarning) with its cause."""
        if self._query is None:
            self.context.make_current()
            self._query = self.ctx.query(samples=True)
        with self._query:
            self.draw(target, scene, camera, options)
        if self._query.samples == 0:
            warnings.warn(why_blank(scene, camera.with_planes(scene.bounds), options.cull),
                          RenderWarning, stacklevel=3)

    def render(self, scene: Scene, camera: Camera, options=None, **changes) -> np.ndarray:
        """The colour image ``(H, W, 4) uint8``, row 0 at the top.

        ``options``: DrawOptions or a shading mode's name; ``changes`` override single
        options (``mode="flat"``, ``depth_test=False``, ``cull=True``, ``srgb=True`` ...).
        """
        options = DrawOptions.of(options, **changes)
        if options.outputs is not Outputs.COLOR:
            options = options.replace(outputs=Outputs.COLOR)
        with held():  # (a Ctrl-C waits for the frame: never mid-way through the driver's work)
            target = self._target("f1")
            self._counted_draw(target, scene, camera, options)
            return target.read_color()

    def render_frame(self, scene: Scene, camera: Camera, options=None, *,
                     outputs: Outputs = Outputs.ALL, color_dtype: str = "u1",
                     **changes) -> Frame:
        """Colour and the ``outputs`` asked for (depth, world normals, polygon ids).
        ``color_dtype="f4"`` returns unquantised float colour, for tests of the formula.

        The auxiliary outputs are exact whatever the renderer's MSAA samples: each pixel's
        id, depth and unit normal are those of the surface its centre sees (zero normal,
        ``inf`` depth and id -1 where nothing is drawn), never a blend of a silhouette's
        samples. Without MSAA they come from the colour's own pass (several render
        targets); with it, from a second, single-sampled pass of the same draw."""
        if color_dtype not in ("u1", "f4"):
            raise OptionError(f"color_dtype must be 'u1' or 'f4', got {color_dtype!r}")
        options = DrawOptions.of(options, **changes).replace(outputs=outputs | Outputs.COLOR)
        dtype = "f1" if color_dtype == "u1" else "f4"
        want = options.outputs
        self._visibility_wanted = True
        try:
            return self._frame(options, dtype, want, scene, camera)
        finally:
            self._visibility_wanted = False

    def _frame(self, options, dtype, want, scene, camera) -> Frame:
        """render_frame's draws and reads."""
        with held():  # (a Ctrl-C waits for the frame: never mid-way through the driver's work)
            target = self._target(dtype)
            if self.samples and want.auxiliary:  # colour multisampled, the rest exact
                self._counted_draw(target, scene, camera,
                                   options.replace(outputs=Outputs.COLOR))
                color = target.read_color()
                target = self._target(dtype, samples=0)
                self.draw(target, scene, camera, options)
            else:
                self._counted_draw(target, scene, camera, options)
                color = target.read_color()
            shadowed = options.shadows is not Shadows.OFF and options.mode in SHADOWED_MODES
            return Frame(color,
                         target.read_depth() if want & Outputs.DEPTH else None,
                         target.read_normal() if want & Outputs.NORMAL else None,
                         target.read_face_id() if want & Outputs.FACE_ID else None,
                         self._shadow_pass.read() if shadowed else None)

    def pick(self, scene: Scene, camera: Camera, x: float, y: float,
             options=None) -> Pick | None:
        """What is under pixel ``(x, y)`` of this renderer's image (x right, y down, in
        pixels; the pixel whose centre is nearest): the polygon id (as ``Frame.face_id``
        numbers them), the world point, the world normal and the view depth -- read from
        the id, depth and normal buffers of one draw. None where the pixel shows background.
        The normal is the polygon's own (a flat draw) unless ``options`` say another mode
        (Phong's: the interpolated normal there)."""
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
        # the pixel centre's ray, in view space, to the depth drawn there
        ndc_x = 2 * (px + 0.5) / self.width - 1
        ndc_y = 1 - 2 * (py + 0.5) / self.height
        aspect = self.width / self.height
        if camera.projection is Projection.PERSPECTIVE:
            t = np.tan(np.radians(camera.fov_y) / 2)
            p_view = np.array([ndc_x * t * aspect * depth, ndc_y * t * depth, -depth])
        else:
            half = camera.height / 2
            p_view = np.array([ndc_x * half * aspect, ndc_y * half, -depth])
        p_world = camera.rotation @ p_view + camera.position
        return Pick(face, p_world, np.asarray(frame.normal[py, px], np.float64), depth)

    def render_depth(self, scene: Scene, camera: Camera, **changes) -> np.ndarray:
        """``(H, W) float32``: distance along the view axis, ``inf`` where nothing was drawn."""
        depth = self.render_frame(scene, camera, "depth", outputs=Outputs.DEPTH,
                                  **changes).depth
        assert depth is not None  # (asked for)
        return depth

    def render_many(self, scene: Scene, cameras: Iterable[Camera], options=None,
                    **changes) -> Iterator[np.ndarray]:
        """Stream colour images for a sequence of cameras; meshes are uploaded once."""
        for camera in cameras:
            yield self.render(scene, camera, options, **changes)

    def info(self) -> dict:
        return self.context.info
