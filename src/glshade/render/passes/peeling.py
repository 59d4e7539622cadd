"""Depth peeling: exact transparency where the GL keeps no per-pixel lists (no storage
buffers: OpenGL 4.1 core, every Mac).

Each pass peels one layer -- at every pixel the nearest transparent fragment beyond the
layer peeled before and in front of the opaque surface -- and composites it under the
layers before it ("over" front to back), until a layer covers no pixel: as many passes as
the deepest pixel has layers, exact for any depth complexity. (The layer's depths are read
back and counted; an occlusion query cannot count them, since the renderer's own sample
query runs around the whole draw and GL runs one query of a kind at a time.) A layer takes
two draws of the transparent surfaces (shaders/include/outputs.glsl, OIT_PEEL): the first
(a program of its own, OIT_PEEL_DEPTH, unlit) finds its depth (each fragment left writes
its float32 depth into an R32F target blended by MIN), the second adds the colour of the
fragments at exactly that depth, premultiplied, to a float accumulation (colour,
transmittance) by blending. A full-viewport pass then puts the layers over a float copy of
the opaque picture: out = C + T behind, in one rounding -- what the fragment lists' resolve
computes, from the same colours and opacities.

The cost is a depth and a colour draw of every transparent surface a layer: quadratic in
the depth complexity (measured in benchmarks/transparency_bench.py: 8 layers over 512x512,
6.9x the lists' frame; 64 layers, 11x).

Past ``max_layers`` the depth passes go on, uncomposited, to count what was left out: the
pixels with more layers and the layers (fragments) they had beyond (the fragment lists'
report; fragments at exactly one depth of one pixel count as one).
"""

from __future__ import annotations

import numpy as np

from ...modes import Outputs
from ..data import NEAREST
from ..programs import Role
from ..units import Unit

__all__ = ["DepthPeeling"]

#: the depth before any layer (every fragment lies beyond it) and past every fragment
BEFORE_ALL, PAST_ALL = -1.0, 2.0


class DepthPeeling:
    """The targets of depth peeling at one size, and the pass that runs it.

    Parameters
    ----------
    context : RenderContext
        The context.
    shaders : ShaderLibrary
        Where the compositing program is compiled.
    """

    def __init__(self, context, shaders):
        self.context, self.shaders = context, shaders
        self._made: tuple | None = None
        self._program = None

    def _targets(self, width: int, height: int, color_dtype: str) -> dict:
        """Made once a size: two R32F depth targets (ping-pong), the accumulation, a copy of
        the opaque picture and its depth, and their framebuffers."""
        if self._made is None or self._made[0] != (width, height, color_dtype):
            self.release_targets()
            ctx = self.context.ctx
            size = (width, height)

            def tex(components, dtype):
                t = ctx.texture(size, components, dtype=dtype)
                t.filter = (NEAREST, NEAREST)
                return t

            near = [tex(1, "f4"), tex(1, "f4")]
            accum, behind = tex(4, "f4"), tex(4, color_dtype)
            opaque = ctx.depth_texture(size)
            opaque.compare_func = ""
            opaque.filter = (NEAREST, NEAREST)
            made = {"near": near, "near_fbo": [ctx.framebuffer([n]) for n in near],
                    "accum": accum, "accum_fbo": ctx.framebuffer([accum]),
                    "behind": behind, "opaque": opaque,
                    "behind_fbo": ctx.framebuffer([behind], opaque)}
            self._made = ((width, height, color_dtype), made)
        return self._made[1]

    def _composite_program(self):
        if self._program is None:
            self._program = self.shaders.compile("fullscreen.vert", "peel_composite.frag")
        return self._program

    def run(self, state, models, meshes, put) -> tuple[int, int, int, int]:
        """Peel ``models`` (the draw's transparent ones) over ``state``'s opaque picture,
        drawn by ``meshes``; ``put`` writes uniforms. Returns ``(fragments, layers peeled,
        pixels with more than max_layers, fragments left out there)``. The target is bound
        again (colour) after.

        Parameters
        ----------
        state : DrawState
            The draw.
        models : list
            Its transparent models.
        meshes : MeshPass
            The pass whose routine draws them.
        put : callable
            The uniform writer.
        """
        import moderngl

        ctx = self.context.ctx
        target = state.target
        width, height = int(target.width), int(target.height)
        t = self._targets(width, height, getattr(target, "color_dtype", "f1"))
        layers = state.options.max_layers
        target.bind(Outputs.COLOR)
        ctx.copy_framebuffer(t["behind_fbo"], ctx.fbo)  # (colour and depth, resolved)
        t["opaque"].use(Unit.PEEL_OPAQUE)
        t["accum_fbo"].use()
        t["accum_fbo"].clear(0.0, 0.0, 0.0, 1.0)
        # the layer before the first: every fragment lies beyond it
        t["near_fbo"][1].use()
        t["near_fbo"][1].clear(BEFORE_ALL, 0.0, 0.0, 0.0)
        fragments = peeled = pixels_over = left_out = 0
        ctx.disable(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
        ctx.enable(moderngl.BLEND)
        try:
            k = -1
            while True:
                k += 1
                before, near = t["near"][(k + 1) % 2], t["near"][k % 2]
                fbo = t["near_fbo"][k % 2]
                fbo.use()
                fbo.clear(PAST_ALL, 0.0, 0.0, 0.0)
                ctx.viewport = state.viewport
                ctx.blend_equation = moderngl.MIN
                before.use(Unit.PEEL_BEFORE)
                meshes.draw_models(state, models, Role.PEEL_DEPTH, extra=self._uniforms())
                # the pixels this layer covers (a query cannot count them: the renderer's
                # own sample count is running around the whole draw, and GL runs one query
                # of a kind at a time)
                depths = np.frombuffer(fbo.read(state.viewport, components=1, dtype="f4"),
                                       np.float32)
                left = int(np.count_nonzero(depths < PAST_ALL))
                if left == 0:
                    break
                if k >= layers:  # (past max_layers: counted, not composited)
                    pixels_over = pixels_over or left
                    left_out += left
                    continue
                fragments += left
                t["accum_fbo"].use()
                ctx.viewport = state.viewport
                ctx.blend_equation = moderngl.FUNC_ADD
                # under the layers before: C += T a c, T *= 1 - a
                ctx.blend_func = (moderngl.DST_ALPHA, moderngl.ONE, moderngl.ZERO,
                                  moderngl.ONE_MINUS_SRC_ALPHA)
                near.use(Unit.PEEL_NEAR)
                meshes.draw_models(state, models, Role.PEEL, extra=self._uniforms())
                peeled += 1
        finally:
            ctx.blend_equation = moderngl.FUNC_ADD
            ctx.blend_func = moderngl.DEFAULT_BLENDING
            ctx.disable(moderngl.BLEND)
        if peeled:
            self._composite(state, t, put)
        target.bind(state.options.outputs)
        return fragments + left_out, peeled, pixels_over, left_out

    @staticmethod
    def _uniforms() -> dict:
        return {"u_peel_before": Unit.PEEL_BEFORE, "u_peel_near": Unit.PEEL_NEAR,
                "u_peel_opaque": Unit.PEEL_OPAQUE}

    def _composite(self, state, t, put) -> None:
        """The layers over the opaque picture: C + T behind, the picture's alpha kept."""
        import moderngl

        ctx = self.context.ctx
        prog = self._composite_program()
        t["accum"].use(Unit.PEEL_ACCUM)
        t["behind"].use(Unit.OIT_BEHIND)
        put(prog, "u_accum", Unit.PEEL_ACCUM)
        put(prog, "u_behind", Unit.OIT_BEHIND)
        state.target.bind(Outputs.COLOR)
        ctx.viewport = state.viewport
        vao = ctx.vertex_array(prog, [])
        try:
            vao.render(moderngl.TRIANGLES, vertices=3)
        finally:
            vao.release()

    def release_targets(self) -> None:
        if self._made is not None:
            made = self._made[1]
            for obj in (*made["near_fbo"], made["accum_fbo"], made["behind_fbo"],
                        *made["near"], made["accum"], made["behind"], made["opaque"]):
                obj.release()
            self._made = None

    def release(self) -> None:
        self.release_targets()
        if self._program is not None:
            self._program.release()
            self._program = None
