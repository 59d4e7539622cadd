"""Transparent surfaces (``Material.opacity`` below 1), drawn after the opaque ones.

- ``exact``: every transparent fragment that passes the opaque depth test joins its pixel's
  list (shaders/include/outputs.glsl): the pixel's first ``OIT_SLOTS`` fragments take slots
  of its own (a per-pixel atomic count), the rest a shared pool linked from the pixel's
  pool head (counts and heads: a storage buffer, two words a pixel); a full-viewport pass
  (shaders/oit_resolve.frag) sorts each list nearest first, keeps ``max_layers`` of it and
  composites "over" front to back onto a float copy of the opaque picture. A list longer
  than ``max_layers`` is counted (pixels, fragments) and reported; the pool grows and the
  capture runs again when a frame needs more room. Where no pixel has more fragments than
  its own slots, the resolve sorts just as many slots as the deepest pixel has (1, 2, 4 or
  8, flagged by the capture) in registers: llvmpipe runs every branch of a shader, so a
  resolve carrying the list walk costs a frame of depth one as much as one of depth eight.
  Where the GL has no storage buffers (OpenGL 4.1 core: every Mac), ``exact`` peels
  depth layers instead (:mod:`~glshade.render.passes.peeling`), until an occlusion query
  counts no fragment left: the same picture within one 8-bit step.
- ``weighted``: the same lists, resolved by McGuire and Bavoil's weighted blended estimate
  (order-free, approximate: for comparison).
- ``blend``: each surface blended "over" as it is drawn, in the scene's order (what a
  renderer without order independence shows).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ...errors import RenderWarning, warn_user
from ...modes import Outputs, Transparency
from ..base import GLResource
from ..data import NEAREST
from ..programs import OIT_SLOTS as SLOTS  # (a pixel's own slots; then a shared pool)
from ..programs import Role
from ..units import Binding, Unit
from . import Stage

__all__ = ["TransparencyPass", "TransparencyReport", "NODE_BYTES"]

#: bytes of one fragment in a list: colour (half floats), opacity, view depth, next
NODE_BYTES = 16
#: the pool's nodes at first, per pixel of the target (grown as frames need)
START_POOL_PER_PIXEL = 2


@dataclass(frozen=True)
class TransparencyReport:
    """What the last transparent draw kept and left out: ``fragments`` in the lists,
    ``pixels_over`` pixels with more than ``max_layers`` surfaces and the
    ``fragments_over`` left out there, ``cut_short`` pixels whose list walk hit the
    shader's step bound.

    Parameters
    ----------
    method : str
        The transparency method.
    fragments : int
        Fragments in the lists.
    max_layers : int
        The surfaces a pixel keeps.
    pixels_over : int
        Pixels with more surfaces than that.
    fragments_over : int
        The fragments left out there.
    cut_short : int
        Pixels whose list walk hit the shader's step bound.
    """

    method: str
    fragments: int = 0
    max_layers: int = 0
    pixels_over: int = 0
    fragments_over: int = 0
    cut_short: int = 0

    def __str__(self) -> str:
        if self.method == Transparency.BLEND.value:
            return "transparency: blended in drawing order"
        text = f"transparency {self.method}: {self.fragments:,} transparent fragments"
        if self.pixels_over:
            text += (f"; {self.pixels_over:,} pixels had more than {self.max_layers} layers "
                     f"({self.fragments_over:,} farther fragments left out)")
        return text


class TransparencyPass(GLResource, Stage):
    """A Renderer's fragment-list buffers and resolve programs: the stage that draws the
    transparent surfaces after every opaque one.

    Parameters
    ----------
    context
        the RenderContext drawn with.
    shaders
        its shader library.
    meshes
        the mesh pass, whose one drawing routine draws the surfaces (captured into the
        lists, or blended).
    """

    #: count and link a pixel's fragments through framebuffer fetch (no atomics: the GL
    #: keeps fragments in primitive order per pixel) where the GL has it and the target is a
    #: single-sampled offscreen one; else through storage-buffer atomics (faster: measured
    #: in docs/guide/speed.md)
    use_fetch = True

    def __init__(self, context, shaders, meshes):
        super().__init__(context)
        self.shaders, self.meshes = shaders, meshes
        self._put = meshes.uniforms.put  # (the one uniform writer, the meshes')
        self.drawn = False  # (some draw had transparent surfaces)
        ctx = context.ctx
        self._heads = None  # (size, the heads' buffer: the atomics path's)
        self._report = self._keep(ctx.buffer(reserve=16))  # (the resolve's four counts)
        self._nodes = None
        self._capacity = 0  # (the pool's nodes)
        self._slots = 0     # (the pixels' own slots)
        # the pool's nodes taken, then whether some pixel reached 2, 3, 5 fragments
        self._count = self._keep(ctx.buffer(reserve=16))
        self._programs: dict = {}
        self._behind = None  # (size, the opaque picture's copy)
        self._fetch: tuple | None = None  # (size, depth buffer, heads texture, fbos)
        self._has_fetch = context.features.framebuffer_fetch
        self._last = TransparencyReport(Transparency.EXACT.value)
        self._counted_in: tuple | None = None  # (the last lists' counts: texture or buffer)
        self._peeling = None  # (depth peeling's targets, where the GL has no storage buffers)
        self._peeled = 0

    def _heads_for(self, width: int, height: int):
        """The atomics path's per-pixel fragment counts and pool list heads (a storage
        buffer of two words a pixel, made once a size)."""
        if self._heads is None or self._heads[0] != (width, height):
            self._drop_heads()
            self._heads = ((width, height),
                           self.context.ctx.buffer(reserve=2 * width * height * 4))
        return self._heads[1]

    def _drop_heads(self) -> None:
        if self._heads is not None:
            self._count_fragments()  # (the last report's, before its lists go)
            self._heads[1].release()
            self._heads = None

    @property
    def compiled(self) -> tuple:
        """The keys of the resolve programs compiled so far: ``(method, layers, fetch,
        deepest)`` each (:meth:`_resolve_program`)."""
        return tuple(self._programs)

    @property
    def peeled(self) -> int:
        """The layers the last exact draw peeled (depth peeling, where the GL has no storage
        buffers); 0 where it kept fragment lists."""
        return self._peeled

    @property
    def counted_by_fetch(self) -> bool:
        """Whether the last exact draw counted its fragments through framebuffer fetch."""
        return self._fetch is not None

    @property
    def report(self) -> TransparencyReport:
        """What the last draw kept and left out; its ``fragments`` are summed from the
        lists' counts when first read (a readback that frames nobody asks about skip)."""
        self._count_fragments()
        return self._last

    def _count_fragments(self) -> None:
        """Sum the last draw's lists' counts into its report (once)."""
        if self._counted_in is not None:
            import moderngl

            heads, pixels = self._counted_in
            if isinstance(heads, moderngl.Buffer):
                counts = np.frombuffer(heads.read(size=4 * pixels), np.uint32)
            else:  # (the fetch capture's texture: count, pool head a pixel)
                counts = np.frombuffer(heads.read(), np.uint32)[0::2]
            self._last = replace(self._last, fragments=int(counts.sum(dtype=np.int64)))
            self._counted_in = None

    def _fetch_for(self, target):
        """The fetch capture's heads texture (count, pool head + 1 a pixel), a framebuffer of
        it with the target's depth buffer (the opaque depth test) and one that clears it
        alone; None where fetch cannot serve this target."""
        fbo = getattr(target, "fbo_draw_color", None)
        if not (self.use_fetch and self._has_fetch and fbo is not None
                and not getattr(target, "samples", 0)):
            return None
        depth, key = fbo.depth_attachment, (int(target.width), int(target.height))
        if self._fetch is None or self._fetch[0] != key or self._fetch[1] is not depth:
            self._drop_fetch()
            ctx = self.context.ctx
            tex = ctx.texture(key, 2, dtype="u4")
            tex.filter = (NEAREST, NEAREST)
            self._fetch = (key, depth, tex, ctx.framebuffer([tex], depth),
                           ctx.framebuffer([tex]))
        return self._fetch

    def _drop_fetch(self) -> None:
        if self._fetch is not None:
            self._count_fragments()  # (the last report's, before its lists go)
            for obj in self._fetch[:1:-1]:
                obj.release()
            self._fetch = None

    def _behind_for(self, target):
        """A single-sampled copy of the target's colour (its type) and its framebuffer,
        made once a size."""
        dtype = getattr(target, "color_dtype", "f1")
        key = (int(target.width), int(target.height), dtype)
        if self._behind is None or self._behind[0] != key:
            if self._behind is not None:
                self._behind[2].release()
                self._behind[1].release()
            ctx = self.context.ctx
            tex = ctx.texture(key[:2], 4, dtype=dtype)
            tex.filter = (NEAREST, NEAREST)
            self._behind = (key, tex, ctx.framebuffer([tex]))
        return self._behind[1], self._behind[2]

    def _room(self, slots: int, pool: int) -> None:
        """A node buffer of ``slots`` per-pixel slots, then a pool of at least ``pool``."""
        if slots != self._slots or pool > self._capacity:
            if self._nodes is not None:
                self._nodes.release()
            self._slots, self._capacity = int(slots), max(int(pool), self._capacity)
            self._nodes = self.context.ctx.buffer(
                reserve=(self._slots + self._capacity) * NODE_BYTES)

    def _resolve_program(self, method: Transparency, layers: int, fetch: bool, deepest: int):
        """The resolve for ``method``; ``deepest``: the most fragments a pixel has where all
        fit in its own slots (a power of two, up to OIT_SLOTS), else 0 (lists)."""
        if method is not Transparency.EXACT:
            deepest = 0
        key = (method, layers, fetch, deepest)
        prog = self._programs.get(key)
        if prog is None:
            defines = (f"MAX_LAYERS {layers}", f"OIT_SLOTS {SLOTS}") + (
                ("WEIGHTED",) if method is Transparency.WEIGHTED else ()) + (
                ("OIT_FETCH",) if fetch else ()) + (
                (f"SORTED_SLOTS {deepest}",) if deepest else ())
            prog = self._programs[key] = self.shaders.compile(
                "oit_resolve.vert", "oit_resolve.frag", defines=defines)
        return prog

    @staticmethod
    def _models(state) -> list:
        """The draw's transparent models (none in a wireframe draw)."""
        if state.options.wireframe:
            return []
        return [m for m in state.scene.models if state.drawn(m) and state.transparent(m)]

    def wanted(self, state) -> bool:
        return bool(self._models(state))

    def draw(self, state, id_base: int) -> int:
        """Draw the transparent models of ``state``'s draw over its opaque picture (their
        ids were counted by the mesh pass); the target bound again after.

        Parameters
        ----------
        state : DrawState
            The draw.
        id_base : int
            The first polygon id free for this stage.
        """
        self.drawn = True
        self._composite(state, self._models(state))
        state.target.bind(state.options.outputs)
        self.context.ctx.viewport = state.viewport
        return id_base

    def _composite(self, state, models) -> None:
        """Draw the transparent ``models`` of ``state``'s draw over its opaque picture."""
        import moderngl

        self._check()
        ctx = self.context.ctx
        options = state.options
        if options.transparency is Transparency.WEIGHTED:
            self.context.require(430, "transparency='weighted' keeps per-pixel fragment "
                                 "lists in storage buffers, which need",
                                 "use transparency='exact' (depth peeling here) or 'blend'")
        target = state.target
        if options.transparency is Transparency.EXACT and not self.context.features.storage:
            self._peel(state, models)
            return
        if options.transparency is Transparency.BLEND:
            target.bind(Outputs.COLOR)
            fbo = ctx.fbo  # (the target's, bound: its masks are GL's now)
            ctx.enable(moderngl.BLEND)
            # (the picture's alpha stays: the opaque pass's coverage)
            ctx.blend_func = (moderngl.SRC_ALPHA, moderngl.ONE_MINUS_SRC_ALPHA, moderngl.ZERO,
                              moderngl.ONE)
            fbo.depth_mask = False  # (tested against everything, written by nothing)
            fbo.use()  # (moderngl applies a framebuffer's masks when it is bound)
            try:
                self.meshes.draw_models(state, models, Role.BLEND)
            finally:
                fbo.depth_mask = True
                fbo.use()
                ctx.disable(moderngl.BLEND)
            self._last, self._counted_in = TransparencyReport(Transparency.BLEND.value), None
            return
        self._peeled = 0
        width, height = int(target.width), int(target.height)
        self._room(width * height * SLOTS, width * height * START_POOL_PER_PIXEL)
        layout = {"u_oit_width": width, "u_oit_pixels": width * height,
                  "u_oit_base": self._slots}
        fetch = self._fetch_for(target)
        heads = self._heads_for(width, height) if fetch is None else fetch[2]
        for _ in range(2):  # (a second time with room for every fragment, when short)
            self._capture(state, models, heads, fetch, layout)
            pooled, *deep = (int(v) for v in np.frombuffer(self._count.read(), np.uint32))
            if pooled <= self._capacity:
                break
            self._room(self._slots, int(pooled * 1.25) + 1024)
            layout["u_oit_base"] = self._slots
        # the most fragments a pixel has, rounded up to 1, 2, 4, 8 (0: some have more)
        deepest = 0 if pooled else 2 ** sum(deep)
        self._resolve(state, heads, layout, deepest)

    def _peel(self, state, models) -> None:
        """Exact transparency without storage buffers: depth peeling (peeling.py)."""
        if self._peeling is None:
            from .peeling import DepthPeeling

            self._peeling = DepthPeeling(self.context, self.shaders)
        self._drop_fetch()  # (no lists: counted_by_fetch says so)
        fragments, self._peeled, over, dropped = self._peeling.run(state, models, self.meshes,
                                                                   self._put)
        layers = state.options.max_layers
        self._last = TransparencyReport(Transparency.EXACT.value, fragments, layers, over,
                                        dropped, 0)
        self._counted_in = None
        if over:
            warn_user(f"{over:,} pixels had more than max_layers={layers} transparent "
                      f"surfaces: the nearest {layers} were composited, {dropped:,} "
                      "farther fragments left out (raise max_layers)", RenderWarning)

    def _capture(self, state, models, heads, fetch, layout: dict) -> None:
        """Draw the transparent ``models`` into their pixels' lists: counted through
        ``fetch`` (:meth:`_fetch_for`; ``heads`` its texture) when given, else through the
        ``heads`` buffer."""
        ctx = self.context.ctx
        self._count.clear()
        if fetch is None:
            heads.clear()
            state.target.bind(Outputs.COLOR)
            heads.bind_to_storage_buffer(Binding.OIT_HEADS)
            fbo = ctx.fbo  # (the target's, bound: its masks are GL's now)
            fbo.color_mask = (False, False, False, False)
        else:
            fetch[4].use()
            fetch[4].clear(0.0, 0.0, 0.0, 0.0)
            fbo = fetch[3]
        ctx.viewport = state.viewport
        self._nodes.bind_to_storage_buffer(Binding.OIT_NODES)
        self._count.bind_to_storage_buffer(Binding.OIT_COUNT)
        fbo.depth_mask = False
        fbo.use()  # (moderngl applies a framebuffer's masks when it is bound)
        try:
            self.meshes.draw_models(state, models, Role.CAPTURE if fetch is None else Role.FETCH,
                                    extra={"u_oit_capacity": self._capacity, **layout})
        finally:
            fbo.color_mask = (True, True, True, True)
            fbo.depth_mask = True
            fbo.use()
            state.target.bind(Outputs.COLOR)
        ctx.memory_barrier()

    def _resolve(self, state, heads, layout: dict, deepest: int) -> None:
        """Composite the lists (``heads``: the fetch capture's texture, or the buffer;
        ``deepest``: :meth:`_resolve_program`'s)."""
        import moderngl

        ctx = self.context.ctx
        options = state.options
        layers = options.max_layers
        fetch = not isinstance(heads, moderngl.Buffer)
        prog = self._resolve_program(options.transparency, layers, fetch, deepest)
        vao = ctx.vertex_array(prog, [])
        report = self._report
        report.clear()
        report.bind_to_storage_buffer(Binding.OIT_REPORT)
        if fetch:
            heads.use(Unit.OIT_HEADS)
            self._put(prog, "u_oit_heads", Unit.OIT_HEADS)
        else:
            heads.bind_to_storage_buffer(Binding.OIT_HEADS)
        self._nodes.bind_to_storage_buffer(Binding.OIT_NODES)
        for name, value in layout.items():  # (the fetch variant reads no buffer offsets)
            self._put(prog, name, value)
        target = state.target
        state.target.bind(Outputs.COLOR)
        # the opaque picture, read in float by the resolve: "over" it in one rounding (8-bit
        # blending would round the layers' colour and their transmittance apart)
        behind, behind_fbo = self._behind_for(target)
        ctx.copy_framebuffer(behind_fbo, ctx.fbo)  # (a multisampled picture: resolved)
        state.target.bind(Outputs.COLOR)
        behind.use(Unit.OIT_BEHIND)
        self._put(prog, "u_behind", Unit.OIT_BEHIND)
        ctx.viewport = state.viewport
        ctx.disable(moderngl.DEPTH_TEST)
        ctx.disable(moderngl.CULL_FACE)
        try:
            vao.render(moderngl.TRIANGLES, vertices=3)
        finally:
            if options.depth_test:
                ctx.enable(moderngl.DEPTH_TEST)
            vao.release()
        ctx.memory_barrier()
        rep = np.frombuffer(report.read(), np.uint32)
        over, dropped, short = int(rep[0]), int(rep[1]), int(rep[2])
        self._counted_in = (heads, int(target.width) * int(target.height))
        self._last = TransparencyReport(options.transparency.value, -1, layers, over,
                                         dropped, short)
        if over and options.transparency is Transparency.EXACT:
            warn_user(f"{over:,} pixels had more than max_layers={layers} transparent "
                          f"surfaces: the nearest {layers} were composited, {dropped:,} "
                          "farther fragments left out (raise max_layers)", RenderWarning)
        if short:
            warn_user(f"{short:,} pixels' transparent lists were longer than the "
                          "shader's step bound and composited in part", RenderWarning)

    def _release_extra(self) -> None:
        for p in self._programs.values():
            p.release()
        self._programs.clear()
        if self._peeling is not None:
            self._peeling.release()
            self._peeling = None
        self._drop_heads()
        self._drop_fetch()
        if self._behind is not None:
            self._behind[2].release()
            self._behind[1].release()
            self._behind = None
        if self._nodes is not None:
            self._nodes.release()
            self._nodes = None


