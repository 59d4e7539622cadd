"""The GPU half of the path tracer: the scene's tables (:mod:`glshade.pathtrace.pack`) in one
float texture, the program -- a fragment program (``shaders/pathtrace.frag``) or a compute
kernel (``shaders/pathtrace.comp``), one pass (``include/trace_integrator.glsl``) either way
-- and the accumulation targets it adds to pass after pass."""

from __future__ import annotations

from typing import Any

import numpy as np

from ...errors import EnvironmentFailure, OptionError
from ...modes import Accel, Kernel, LobeSampling, Sampler
from ...options import MAX_STREAMS, TraceOptions
from ...geometry.transforms import ray_uniforms
from ...solids.encoding import ROW, tree_data
from ...solids.tree import TIE
from .. import kernels
from ..base import GLResource
from ..data import NEAREST, data_texture
from ..film import LAYOUT_BLOCKS, film_layout, film_places
from ..programs import UniformWriter
from ..shaders import LOOP_BUDGET, LOOP_CAP, ShaderLibrary, assemble, compile_compute
from ..units import Binding, Unit
from .csg import csg_defines

__all__ = ["GpuPathTracer", "program_defines", "MAX_CONTROL_MODELS"]

#: texture units (render/units.py): the scene's tables, given rays, the solid's tree, the
#: seven targets, the hierarchy, each pixel's samples past the run's target (adaptive)
_DATA, _RAYS, _CSG, _TARGETS = Unit.TRACE_DATA, Unit.TRACE_RAYS, Unit.TRACE_CSG, \
    Unit.TRACE_TARGETS
_BVH, _EXTRA = Unit.TRACE_BVH, Unit.TRACE_EXTRA
#: the compute kernel's seven images (pathtrace.comp), in the targets' order
_IMAGE_NAMES = ("out_state0", "out_state1", "out_state2", "out_state3", "out_sum",
                "out_square", "out_hit")


def _kernel(context, asked: Kernel) -> Kernel:
    """The kernel a new tracer runs: the one asked for (compute needs GL 4.3), or for
    "auto" the one measured faster on this GL before (render/kernels.py), the fragment
    program where compute shaders are missing, else AUTO (measured at the first run)."""
    if asked is Kernel.COMPUTE:
        context.require(430, "kernel='compute' needs", "use kernel='fragment'")
    if asked is not Kernel.AUTO:
        return asked
    if not context.features.storage:
        return Kernel.FRAGMENT
    return kernels.chosen(context)


_TARGET_NAMES = ("u_state0", "u_state1", "u_state2", "u_state3", "u_acc0", "u_acc1", "u_acc2")


class GpuPathTracer(GLResource):
    """Path-trace ``scene`` (a :class:`glshade.pathtrace.TraceScene`, whose ``tables()``
    give the texels) at ``width x height`` as ``options`` say (a
    :class:`~glshade.pathtrace.TraceOptions`, checked where it was made: this pass only
    compiles it into its program): :meth:`run` makes every pixel finish ``samples`` more
    paths; :meth:`read` returns the sums. Each pixel traces its samples in order and sample
    k's random stream is seeded by (seed, pixel, k); a path in flight is kept between passes
    (shaders/pathtrace.frag), so one invocation's work stays under ``options.budget`` loop
    iterations (llvmpipe stops a shader at 65,535) and a pixel's k-th sample is the same
    however the work is grouped.

    Parameters
    ----------
    context : GLContext
        The context the GL objects live in.
    scene : TraceScene
        The scene's tables, lights and solids.
    width, height : int
        The picture's size in pixels.
    options : TraceOptions or None
        How paths are traced (None: the defaults); ``**changes`` replace its fields by name
        (checked as TraceOptions checks them).
    shaders : ShaderLibrary or None
        Where programs are compiled and kept (None: a library of its own).
    rays : ndarray or None
        ``(height, width, 2, 3)`` float: each pixel's own ray, origin then unit direction
        (world units), traced instead of the camera's (probes); None: a camera's.
    control : ndarray or None
        ``(M, 3)`` a control value for each of the scene's models in radiosity units
        (:func:`glshade.radiosity.control.radiosity_control`), used at Russian roulette.
    budget : int
        Loop iterations under which one invocation starts another bounce (``BUDGET``).
    **changes
        TraceOptions' fields, by name, laid over ``options``.
    """

    #: loop iterations under which an invocation starts another bounce (its own tuning, not
    #: the cap's: a bounce of a scene of 100k triangles costs a few hundred, so one begun
    #: just under this ends far below LOOP_BUDGET, where it would be reported as cut short)
    BUDGET = 8192
    # (the tuning below: each constant's measurement, and the benchmark that repeats it, in
    # docs/guide/speed.md's table of tuning constants)
    #: triangles up to which a ray tests every triangle, compiled into the program, rather
    #: than walk the hierarchy (``accel="auto"``)
    FLAT_LIMIT = 64
    #: emitting triangles up to which next-event estimation's choice among them is compiled
    #: in (their numbers as constants; above, a binary search through the table)
    EMITTERS_COMPILED = 16
    #: the most triangles ``accel="flat"`` compiles in (the compile grows faster than them)
    FLAT_MAX = 256
    #: with ``coherent``, a run goes in steps of this many samples, each ending with every
    #: pixel at the same sample: a block's pixels start their paths together again (they
    #: drift apart as their paths end at different bounces)
    SYNC = 16
    #: the targets hold the image in 8x8 blocks, this many a row (glshade.render.film)
    LAYOUT_BLOCKS = LAYOUT_BLOCKS
    #: passes without one more pixel finished before a run gives up (a pass moves every
    #: path on by at least one bounce; Russian roulette caps a path's odds of going on at
    #: 0.99, so thousands of passes without a pixel finishing mean nothing was drawn)
    STALL_PASSES = 10_000
    #: timed passes of each kernel when ``kernel="auto"`` measures (their best counts)
    MEASURE_ROUNDS = 3
    #: invocations a pass should have on a GPU (``streams=None``): about what an H100 holds
    #: at once (132 multiprocessors x 2,048 threads); a picture with fewer pixels shares
    #: each pixel's samples among several
    FILL_INVOCATIONS = 270_336

    def __init__(self, context, scene, width: int, height: int,
                 options: TraceOptions | None = None, *, shaders: ShaderLibrary | None = None,
                 rays: np.ndarray | None = None, control: np.ndarray | None = None,
                 budget: int = BUDGET, **changes):
        from ..target import check_fits, max_side

        self.width, self.height = int(width), int(height)
        #: how paths are traced (a TraceOptions)
        self.options = options = TraceOptions.of(options, **changes)
        #: invocations sharing each pixel's samples (TraceOptions.streams, decided here)
        self.streams = self._streams(context, options.streams)
        #: the targets' size (the image in blocks, a copy a stream: glshade.render.film)
        self.target_size, self._blocks = film_layout(self.width, self.height * self.streams,
                                                     self.LAYOUT_BLOCKS, max_side(context))
        # (the same budget as the renderer's: two sets of seven RGBA float targets a pixel)
        check_fits(context, *self.target_size, bytes_per_pixel=2 * 7 * 16 + 4,
                   image=(self.width, self.height))
        super().__init__(context)
        context.make_current()  # (its objects are made in its own context, whatever was last)
        ctx = context.ctx
        self.scene = scene
        if not 1 <= int(budget) <= LOOP_BUDGET:
            raise OptionError(f"budget must be 1 to {LOOP_BUDGET:,} loop iterations (the "
                              f"driver stops a shader at {LOOP_CAP:,}), got {budget!r}")
        self.max_depth, self.budget = options.max_depth, int(budget)
        self._shaders = shaders or self._keep(ShaderLibrary(context))
        self._put = UniformWriter().put
        compiled = self._choose(options.accel, scene)
        data, self.layout = scene.tables(compiled if self.accel is Accel.HYBRID else None)
        defines = self._defines(context, data, options, control)
        defines += self._solid(scene)
        self._rays = None
        if rays is not None:  # (H, W, 2, 3): each pixel's ray origin and unit direction
            texels = np.zeros((self.height, 2, self.width, 4), np.float32)
            texels[:, :, :, :3] = np.asarray(rays, np.float32).transpose(0, 2, 1, 3)
            self._rays = self._keep(data_texture(ctx, texels, self.width))
            defines += ("PROBES",)
        #: the program a pass runs: "fragment" or "compute" (TraceOptions.kernel; "auto"
        #: chosen when the first run measures both, kept per renderer and driver)
        self.kernel = _kernel(context, options.kernel)
        self._defines_used = defines
        self._programs: dict[Kernel, Any] = {}
        self.program = self._program(Kernel.COMPUTE if self.kernel is Kernel.COMPUTE
                                     else Kernel.FRAGMENT)
        width = self.layout["width"]
        self.texture = self._keep(data_texture(ctx, data, width))
        tree = self.layout["hierarchy"]
        if self.storage:  # (the walk's nodes, and the table's triangle rows, as buffers)
            first, n = self.layout["u_tris"], 3 * len(scene.triangles)
            self._walk = (self._keep(ctx.buffer(tree.tobytes())), self._keep(ctx.buffer(
                np.ascontiguousarray(data[first:first + n], "f4").tobytes())))
        else:  # (the walk's nodes as a texture; its triangles read from the table's)
            self._bvh = self._keep(ctx.texture((width, len(tree) // width), 4,
                                               tree.tobytes(), dtype="u4"))
            self._bvh.filter = (NEAREST, NEAREST)  # (a texel read whole)
        #: each image pixel's rows and columns in the targets, ``(S H, W)``: stream j's
        #: copies in rows j H to (j + 1) H, GL's order (glshade.render.film)
        self._where = film_places(self.width, self.height * self.streams, self._blocks)
        # two sets of the seven targets, read and written in turn
        size = self.target_size
        self._targets = [[self._keep(ctx.texture(size, 4, dtype="f4")) for _ in range(7)]
                         for _ in range(2)]
        self._fbos = [self._keep(ctx.framebuffer(t)) for t in self._targets]
        #: each pixel's samples past :attr:`samples` (``(H, W)``; adaptive sampling), and
        #: the same in the targets' layout, read by the program
        self.extra = np.zeros((self.height, self.width), np.int64)
        self._extra = self._keep(ctx.texture(size, 1, np.zeros(size[::-1], "f4").tobytes(),
                                             dtype="f4"))
        self._current = 0
        self._left = self._keep(self._shaders.compile("pathtrace.vert", "pathtrace_left.frag"))
        self._write(self._film_uniforms(), self._left)
        self._left_vao = self._keep(ctx.vertex_array(self._left, []))
        self._left_fbo = self._keep(ctx.simple_framebuffer(size, components=1))
        self._query = ctx.query(samples=True)  # (moderngl frees a query with its context)
        self.passes = 0
        self.samples = 0
        self.reset()

    def _streams(self, context, asked: int | None) -> int:
        """The streams a pixel's samples are shared among: ``asked``, else one on a
        software renderer (its few cores are filled by the pixels), else enough that the
        picture's copies make :attr:`FILL_INVOCATIONS`, at most ``MAX_STREAMS``."""
        if asked is not None:
            return asked
        if context.software:
            return 1
        pixels = self.width * self.height
        return int(min(MAX_STREAMS, max(1, -(-self.FILL_INVOCATIONS // pixels))))

    def _film_uniforms(self) -> dict:
        """Where a pixel's copies lie in the targets: what every program of the tracer
        that reads them needs (pixel_blocks.glsl)."""
        return {"u_blocks": self._blocks, "u_streams": self.streams,
                "u_size": (float(self.width), float(self.height))}

    def _solid(self, scene) -> tuple[str, ...]:
        """The scene's CSG solid (one at most): its tree's texture and uniforms kept, its
        defines returned (none without one)."""
        self._csg = None
        if not scene.solids:
            return ()
        solid, material = scene.solids[0]
        tree = tree_data(solid)
        self._csg = self._keep(data_texture(self.context.ctx, tree.texels, ROW))
        self._csg_values = {
            "u_csg": _CSG, "u_csg_material": material, **tree.offsets(),
            "u_csg_start": tree.nodes,  # (a path's rays start anywhere: always look)
            # the tie rule's length (solids/tree.py): a path's rays start in the scene
            "u_csg_tie": TIE * scene.size,
            "u_csg_kind_start": np.array(tree.kind_start, "i4")}
        return ("CSG_SOLID", *csg_defines(tree, blocks=False))

    def _check(self) -> None:
        """Not released, and this tracer's context current: with several contexts in one
        process (two tracers, a tracer beside a Renderer) GL calls go to the current one."""
        super()._check()
        self.context.make_current()

    def _program(self, kernel: Kernel):
        """The program of ``kernel`` (compiled once, its static uniforms written)."""
        found = self._programs.get(kernel)
        if found is None:
            if kernel is Kernel.COMPUTE:
                source, _ = assemble("pathtrace.comp", defines=self._defines_used)
                program = self._keep(compile_compute(self.context, source))
                vao = None
            else:
                program = self._keep(self._shaders.compile(
                    "pathtrace.vert", "pathtrace.frag", defines=self._defines_used))
                vao = self._keep(self.context.ctx.vertex_array(program, []))
            found = self._programs[kernel] = (program, vao)
            self._write(self._static_uniforms(), program)  # (this tracer's: they stay)
        return found[0]

    def _pass(self, kernel: Kernel) -> None:
        """One pass of ``kernel``: the read targets bound (the caller did), the others
        written -- as a framebuffer by the fragment program, as images by the kernel."""
        import moderngl

        program, vao = self._programs[kernel]
        if kernel is Kernel.COMPUTE:
            for i, tex in enumerate(self._targets[1 - self._current]):
                tex.bind_to_image(Binding.TRACE_IMAGES + i, read=False, write=True)
            w, h = self.target_size
            program.run(-(-w // 8), -(-h // 8), 1)
            self.context.ctx.memory_barrier()
        else:
            self._fbos[1 - self._current].use()
            vao.render(moderngl.TRIANGLES, vertices=3)

    def _measure(self) -> Kernel:
        """Time passes of each kernel here, in turn (one each to warm up, then the best of
        :attr:`MEASURE_ROUNDS` each: the choice is kept between processes, so one slow pass
        must not decide it), and keep the faster for this renderer and driver
        (:func:`glshade.render.kernels.keep`); the targets are cleared after."""
        import time

        took: dict = {}
        kinds = (Kernel.FRAGMENT, Kernel.COMPUTE)
        for kernel in kinds:
            self._program(kernel)
        for round_ in range(1 + self.MEASURE_ROUNDS):
            for kernel in kinds:
                self.reset()
                self._write({"u_target": 1.0, "u_cap": 1.0}, self._programs[kernel][0])
                for i, tex in enumerate(self._targets[self._current]):
                    tex.use(location=_TARGETS + i)
                self.context.ctx.finish()
                start = time.perf_counter()
                self._pass(kernel)
                self.context.ctx.finish()
                if round_:  # (the first round warms up)
                    took[kernel] = min(took.get(kernel, np.inf), time.perf_counter() - start)
        self.reset()
        chosen = min(took, key=lambda k: took[k])
        kernels.keep(self.context, chosen)
        return chosen

    def _defines(self, context, data: np.ndarray, options: TraceOptions,
                 control) -> tuple[str, ...]:
        """Decide :attr:`storage` and the control values, then the program's defines
        (:func:`program_defines`)."""
        #: whether the hierarchy's walk reads storage buffers (else texel fetches)
        self.storage = False
        if self.accel is not Accel.FLAT and self.layout["nodes"]:
            have = context.features.storage
            self.storage = have if options.storage is None else options.storage
            if self.storage and not have:
                context.require(430, "storage=True needs", "leave storage at None")
        self._control = _control(control, len(self.scene.names))
        return program_defines(self.scene, data, self.layout, self.accel, options,
                               storage=self.storage, controls=None if self._control is None
                               else MAX_CONTROL_MODELS, most_emitters=self.EMITTERS_COMPILED)

    def _choose(self, accel: Accel, scene) -> np.ndarray | None:
        """Check ``accel`` against ``scene``'s size, set :attr:`accel`; the triangles a
        hybrid compiles in (``(T,)`` bool) or None."""
        n = len(scene.triangles)
        if accel is Accel.FLAT and n > self.FLAT_MAX:
            raise OptionError(f"accel='flat' compiles the triangles into the program: at most "
                              f"{self.FLAT_MAX}, the scene has {n:,} (use accel='bvh')")
        small = scene.small_models(self.FLAT_LIMIT) if n else np.zeros(0, bool)
        if accel is Accel.AUTO:
            accel = Accel.FLAT if 0 < n <= self.FLAT_LIMIT else \
                Accel.HYBRID if small.any() else Accel.BVH
        if accel is Accel.HYBRID and not small.any():
            accel = Accel.BVH  # (no small model beside a large one: the hierarchy alone)
        #: how rays find triangles: "flat" (every one compiled in), "bvh" (the hierarchy)
        #: or "hybrid" (the small models compiled in, the hierarchy for the rest)
        self.accel = accel if n else Accel.BVH
        return small if self.accel is Accel.HYBRID else None

    def _write(self, values: dict, program=None) -> None:
        """``values`` into ``program`` (default the tracer's) through the one uniform
        writer (what a variant's compiler dropped is skipped; arrays fitted)."""
        prog = self.program if program is None else program
        for name, value in values.items():
            self._put(prog, name, value)

    def _static_uniforms(self) -> dict:
        """The uniforms that stay for this tracer's life: sizes, tables, lights, the solid."""
        values: dict = {**self._film_uniforms(),
                        "u_target_size": tuple(int(x) for x in self.target_size),
                        **{name: Binding.TRACE_IMAGES + i for i, name in enumerate(
                            _IMAGE_NAMES)},
                        "u_max_depth": int(self.max_depth or 0),
                        "u_eps": 1e-5 * self.scene.size, "u_budget": self.budget,
                        "u_data": _DATA, "u_bvh": _BVH, "u_rays": _RAYS,
                        "u_extra": _EXTRA,
                        **{name: _TARGETS + i for i, name in enumerate(_TARGET_NAMES)}}
        values.update((k, v) for k, v in self.layout.items() if k.startswith("u_"))
        if self._csg is not None:
            values.update(self._csg_values)
        if self._control is not None:
            values["u_control"] = self._control
        lights = self.scene.lights
        if len(lights):  # (arrays of LIGHTS entries: kind and position, irradiance, falloff)
            pos = np.ascontiguousarray(lights[:, [1, 2, 3, 0]], np.float32)
            values.update(u_light_pos=pos.tobytes(),
                          u_light_irr=np.ascontiguousarray(lights[:, 4:7], np.float32).tobytes(),
                          u_light_att=np.ascontiguousarray(lights[:, 7:10], np.float32).tobytes(),
                          u_light_spot=np.ascontiguousarray(lights[:, 10:14],
                                                            np.float32).tobytes(),
                          u_light_range=np.ascontiguousarray(lights[:, 14],
                                                             np.float32).tobytes())
        return values

    def reset(self) -> None:
        """Forget every sample (a new camera)."""
        self._check()
        for fbo in self._fbos:
            fbo.clear(0.0, 0.0, 0.0, 0.0)
        self.passes = self.samples = 0
        if self.extra.any():  # (a viewer resets at every camera move: upload only if needed)
            self._set_extra(np.zeros((self.height, self.width), np.int64))

    def _set_extra(self, extra: np.ndarray) -> None:
        self.extra = extra
        texels = np.zeros(self.target_size[::-1], np.float32)
        # (GL's rows: bottom first; each stream's copy holds the pixel's count)
        texels[self._where] = np.tile(extra[::-1], (self.streams, 1))
        self._extra.write(texels.tobytes())

    @property
    def counts(self) -> np.ndarray:
        """``(H, W)`` int64: the samples each pixel has finished."""
        return self.samples + self.extra

    def run(self, camera, samples: int = 1, seed: int = 0,
            counts: np.ndarray | None = None) -> int:
        """Make every pixel finish ``samples`` more paths seen from ``camera`` (None for
        given rays) -- or, ``counts`` ``(H, W)`` whole numbers, each pixel that many in all
        (none fewer than it has: adaptive sampling); the passes that took.

        Parameters
        ----------
        camera : Camera or None
            From where (None: the given rays).
        samples : int
            Paths a pixel to add.
        seed : int
            The random streams' seed.
        counts : ndarray or None
            ``(H, W)`` each pixel's samples in all, instead.
        """
        import moderngl

        self._check()
        ctx = self.context.ctx
        target = self.samples + int(samples)
        if counts is not None:
            counts = np.asarray(counts)
            if counts.shape != (self.height, self.width) or (counts < self.counts).any():
                raise OptionError(f"counts must be ({self.height}, {self.width}) samples, none "
                                  "fewer than a pixel has")
            target = int(counts.min())
            self._set_extra(counts.astype(np.int64) - target)
        values: dict = {"u_seed": int(seed) & 0xFFFFFFFF, "u_target": float(target)}
        if camera is not None:
            aspect = self.width / self.height
            values.update(ray_uniforms(camera.projection_matrix(aspect),
                                       camera.view_matrix()))
        if self.kernel is Kernel.AUTO:  # (first use on this GL: measure, then keep)
            self.kernel = self._measure()
            self.program = self._program(self.kernel)
        self._write(values)
        self._write({"u_acc0": _TARGETS, "u_extra": _EXTRA, "u_target": float(target)},
                    self._left)
        self._extra.use(location=_EXTRA)
        if self._csg is not None:
            self._csg.use(location=_CSG)
        self.texture.use(location=_DATA)
        if self.storage:
            for binding, buffer in zip((Binding.WALK_NODES, Binding.WALK_TRIANGLES),
                                       self._walk):
                buffer.bind_to_storage_buffer(binding)
        else:
            self._bvh.use(location=_BVH)
        if self._rays is not None:
            self._rays.use(location=_RAYS)
        ctx.viewport = (0, 0, *self.target_size)
        ctx.disable(moderngl.DEPTH_TEST | moderngl.CULL_FACE | moderngl.BLEND)
        passes = 0
        top = target + int(self.extra.max())
        # (blocks that share random numbers: in steps of SYNC samples, each ending with all
        # pixels at one sample; else one step)
        step = self.SYNC if self.options.coherent != (1, 1) else max(top - self.samples, 1)
        for cap in range(self.samples + step, top + step, step):
            for program in (self.program, self._left):
                self._put(program, "u_cap", float(min(cap, top)))
            fewest, stalled = None, 0
            while True:
                for i, tex in enumerate(self._targets[self._current]):
                    tex.use(location=_TARGETS + i)
                self._pass(self.kernel)
                self._current = 1 - self._current
                passes += 1
                left = self._unfinished()
                if not left:
                    break
                # (a pass always moves every path on: pixels that never finish mean the
                # GL drew nothing -- say so rather than loop for ever)
                stalled = stalled + 1 if fewest is not None and left >= fewest else 0
                fewest = left if fewest is None else min(fewest, left)
                if stalled > self.STALL_PASSES:
                    raise EnvironmentFailure(
                        f"the path tracer made no progress in {self.STALL_PASSES:,} passes "
                        f"({left:,} pixels unfinished): this GL ({self.context.detail}) "
                        "drew nothing into its targets")
        self.passes += passes
        self.samples = target
        return passes

    def _unfinished(self) -> int:
        """How many pixels have not finished the run's samples (an occlusion query)."""
        import moderngl

        self._targets[self._current][4].use(location=_TARGETS)
        self._left_fbo.use()
        with self._query:
            self._left_vao.render(moderngl.TRIANGLES, vertices=3)
        return int(self._query.samples)

    def show(self, fbo, exposure: float, srgb: bool = False) -> None:
        """Draw the picture so far (mean times ``exposure``, clipped) into ``fbo``, a
        framebuffer of this size (a window's): what the viewer's progressive mode shows.

        Parameters
        ----------
        fbo : moderngl.Framebuffer
            A framebuffer of this size.
        exposure : float
            The factor on the mean.
        srgb : bool
            Encode as sRGB.
        """
        import moderngl

        self._check()
        if getattr(self, "_show", None) is None:
            self._show = self._keep(self._shaders.compile("pathtrace.vert",
                                                          "pathtrace_show.frag"))
            self._show_vao = self._keep(self.context.ctx.vertex_array(self._show, []))
        fbo.use()
        ctx = self.context.ctx
        ctx.viewport = (0, 0, self.width, self.height)
        ctx.disable(moderngl.DEPTH_TEST | moderngl.BLEND)
        self._targets[self._current][4].use(location=Unit.TRACE_SHOW)
        self._write({"u_sum": Unit.TRACE_SHOW, **self._film_uniforms(),
                     "u_exposure": float(exposure), "u_srgb": bool(srgb)}, self._show)
        self._show_vao.render(moderngl.TRIANGLES, vertices=3)

    def _release_extra(self) -> None:
        self.context.rest()  # (never release the bound framebuffer)

    def sums(self) -> np.ndarray:
        """``(H, W, 4)`` float64, top row first: the samples' sum (RGB) and count (A) --
        :meth:`read`'s first array alone (one target read back, not three)."""
        self._check()
        return self._read(self._targets[self._current][4])

    def _read(self, tex) -> np.ndarray:
        """One target, each pixel's streams added, top row first."""
        w, h = self.target_size
        y, x = self._where
        a = np.frombuffer(tex.read(), np.float32).reshape(h, w, 4)[y, x]
        a = a.astype(np.float64).reshape(self.streams, self.height, self.width, 4)
        return a.sum(0)[::-1]

    def read(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(sum, square, hits): ``(H, W, 4)`` float64, top row first: the samples' sum
        (RGB) and count (A); the sum of their squares (RGB) and of first hits on an
        emitter (A); the count of camera rays that hit anything (R) and of bounces that
        came near the driver's loop limit (G) -- each the sum of the pixel's streams."""
        self._check()
        total, square, hits = (self._read(tex) for tex in self._targets[self._current][4:])
        return total, square, hits


def program_defines(scene, data: np.ndarray, layout: dict, accel: Accel,
                    options: TraceOptions, *, storage: bool, controls: int | None,
                    most_emitters: int) -> tuple[str, ...]:
    """The path tracer's program for one scene, as the defines that specialise
    ``shaders/pathtrace.frag`` -- its source made apart from any GL object, so what a scene
    and its options compile to can be read and tested without a context.

    Parameters
    ----------
    scene : TraceScene
        The scene (its triangles, emitters, lights, materials and shading normals).
    data : ndarray
        ``(N, 4)`` float32: the scene's tables (``scene.tables()``), whose triangle rows
        are compiled in where ``accel`` says.
    layout : dict
        Where each table starts in ``data`` (``scene.tables()``'s second value).
    accel : Accel
        How rays find triangles, as decided for this scene (not AUTO).
    options : TraceOptions
        How paths are traced.
    storage : bool
        Whether the hierarchy's walk reads storage buffers (GL 4.3).
    controls : int or None
        The rows of the control values' uniform array (None: no control variate): always
        MAX_CONTROL_MODELS, so the program's source is not the scene's model count.
    most_emitters : int
        Emitting triangles up to which next-event estimation's choice is compiled in.
    """
    # (the triangles compiled in: the table's first rows -- all of them, or the small
    # models' -- and the hierarchy for the rest)
    n_compiled = {Accel.FLAT: len(scene.triangles),
                  Accel.HYBRID: layout["compiled"]}.get(accel, 0)
    first = layout["u_tris"]
    defines: tuple[str, ...] = (f"DATA_WIDTH {layout['width']}",)
    if scene.shading is not None:
        defines += ("SMOOTH_NORMALS",)
    if n_compiled:
        defines += _flat_defines(data[first:first + 3 * n_compiled])
    if accel is not Accel.FLAT and layout["nodes"]:
        defines += ("HIERARCHY",) + (("GLSL_430", "STORAGE_WALK") if storage else ())
    defines += ("LOW_DISCREPANCY",) if options.sampler is Sampler.SOBOL else ()
    if 0 < len(scene.emitters) <= most_emitters:
        defines += (_emitter_pick(data, layout),)
    # (what the scene has no use for is compiled away: llvmpipe runs every branch)
    defines += (f"LIGHTS {len(scene.lights)}",) + (
        ("EMITTERS",) if len(scene.emitters) else ()) + (
        ("GLOSSY",) if (scene.materials[:, 3] > 0).any() else ()) + (
        ("PBR",) if (scene.materials[:, 10] > 0).any() else ()) + (
        ("ENVIRONMENT",) if scene.environment is not None else ()) + (
        ("VERTEX_COLORS",) if scene.colors is not None else ()) + (
        ("MAPS",) if scene.uvs is not None else ()) + (
        ("CUTOUTS",) if (scene.materials[:, 11] < 1).any() or (
            scene.maps is not None and (scene.maps[:, 4, 0] >= 0).any()) else ())
    defines += ("MIS",) if options.mis else ()
    defines += {LobeSampling.VISIBLE_NORMALS: (), LobeSampling.NORMALS: ("GGX_NORMALS",),
                LobeSampling.UNIFORM: ("LOBE_UNIFORM",)}[options.lobe_sampling]
    if options.coherent != (1, 1):
        defines += ("COHERENT_TILE uvec2({}u, {}u)".format(*options.coherent),)
    if controls is not None:
        defines += (f"CONTROL {controls}",)
    return defines


#: the most models a control variate covers (its values are a uniform array of this size
#: whatever the scene's model count: the program's source stays the same from scene to
#: scene, so a driver's shader cache serves them all)
MAX_CONTROL_MODELS = 256


def _control(values, models: int) -> np.ndarray | None:
    """``values`` (M, 3) as the program's ``u_control`` (float32, one row a model, zeros
    past M up to MAX_CONTROL_MODELS: one array size for every scene), or None; refused
    unless finite, at least 0 and at most one a model."""
    if values is None:
        return None
    a = np.asarray(values, np.float64)
    if a.ndim != 2 or a.shape[1] != 3 or len(a) > models or not np.isfinite(a).all() \
            or (a < 0).any():
        raise OptionError(f"control must be finite values >= 0, (M, 3) for at most the "
                          f"scene's {models} models, got shape {a.shape}")
    if models > MAX_CONTROL_MODELS:
        raise OptionError(f"a control variate covers at most {MAX_CONTROL_MODELS} models, the "
                          f"scene has {models}")
    out = np.zeros((MAX_CONTROL_MODELS, 3), np.float32)
    out[:len(a)] = a
    return out


def _flat_defines(rows: np.ndarray) -> tuple[str, ...]:
    """The defines that compile a small scene's triangles into the program
    (shaders/pathtrace.frag, FLAT_TRIANGLES): ``rows`` ``(3n, 4)`` float32, each
    triangle's p0, e1, e2 (the table's rows; the fourth column is not read), each written
    by :func:`_vec3`, so the constants are the table's exactly."""
    n = len(rows) // 3
    return (f"FLAT_TRIANGLES {n}", "FLAT_ROWS " + ",".join(_vec3(r[:3]) for r in rows),
            "FLAT_TESTS " + " ".join(f"FLAT_TEST({k})" for k in range(n)))


def _vec3(values) -> str:
    """A GLSL vec3 of float32 ``values``, written as their bits (exactly the table's)."""
    bits = np.asarray(values, np.float32).view(np.uint32)
    return "vec3(" + ",".join(f"uintBitsToFloat({b}u)" for b in bits.tolist()) + ")"


def _float(value) -> str:
    return f"uintBitsToFloat({int(np.float32(value).view(np.uint32))}u)"


def _emitter_pick(data: np.ndarray, layout: dict) -> str:
    """The define that compiles a few emitters' choice into the program
    (shaders/pathtrace.frag, pick_emitter): for each, its chance, area, rows, emission and
    triangle
    from the table, taken where ``r`` is past the cumulative chances before it (as the
    table's binary search picks: the first whose cumulative chance reaches r)."""
    emit = data[layout["u_emit"]:layout["u_emit"] + layout["u_n_emit"]]
    cdf = emit[:, 0].astype(np.float32)
    chance = cdf - np.concatenate([[np.float32(0)], cdf[:-1]]).astype(np.float32)
    out = []
    for i, row in enumerate(emit):
        k = int(np.float32(row[1]).view(np.int32))
        rows = data[layout["u_tris"] + 3 * k:layout["u_tris"] + 3 * k + 3]
        m = int(np.float32(rows[0, 3]).view(np.int32))
        e = data[layout["u_mats"] + 3 * m + 1, :3]
        sets = (f"p = {_float(chance[i])}; area = {_float(row[2])}; q0 = {_vec3(rows[0, :3])}; "
                f"q1 = {_vec3(rows[1, :3])}; q2 = {_vec3(rows[2, :3])}; e = {_vec3(e)}; "
                f"ek = {k};")
        out.append(sets if i == 0 else f"if ({_float(cdf[i - 1])} < r) {{ {sets} }}")
    return "EMITTER_PICK " + " ".join(out)
