"""The shadow pass's G-buffer: the surface point each pixel of a draw sees, for the compute
passes that find each light's visibility there (shaders/include/gbuffer_point.glsl rebuilds
the point from its depth and the pixel's ray)."""

from __future__ import annotations

import numpy as np

from ...geometry.transforms import pixel_rays
from ..data import NEAREST
from ..units import Unit

__all__ = ["GBuffer", "bind_gbuffer"]


class GBuffer:
    """The draw's surface points: world normal (as (n + 1) / 2), polygon id + 1 (0
    background) and the view depth's bits, in textures the compute pass reads (drawn into
    like any target).

    Parameters
    ----------
    ctx : moderngl.Context
        The context.
    width, height : int
        The draw's size in pixels.
    rows_top_down : bool
        Whether the draw stores row 0 at the top.
    keep : callable
        Registers each GL object with its owner (released with it).
    """

    def __init__(self, ctx, width: int, height: int, rows_top_down: bool, keep):
        self.width, self.height, self.rows_top_down = width, height, rows_top_down
        size = (width, height)
        # the normals mode's colour is the world normal as (n + 1) / 2, 8 bits a component:
        # enough for a ray's start and a map's slope, a quarter of a float target's cost
        self.normal = keep(ctx.texture(size, 4, dtype="f1"))
        unread = keep(ctx.renderbuffer(size, 4, dtype="f1"))  # (the float normal: unused)
        self.face = keep(ctx.texture(size, 1, dtype="i4"))
        self.depth = keep(ctx.texture(size, 1, dtype="u4"))
        for t in (self.normal, self.face, self.depth):
            t.filter = (NEAREST, NEAREST)  # a pixel's own values, never blended
        self.zbuf = keep(ctx.depth_renderbuffer(size))
        self.fbo = keep(ctx.framebuffer([self.normal, unread, self.face, self.depth],
                                        self.zbuf))
        self.fbo_color = keep(ctx.framebuffer([self.normal], self.zbuf))

    def begin(self, background, outputs) -> None:
        """Bind and clear (everything to zero: background).

        Parameters
        ----------
        background : tuple
            Unused: the G-buffer has no colour.
        outputs : Outputs
            What the draw writes besides colour.
        """
        self.fbo.use()
        self.fbo.clear(0.0, 0.0, 0.0, 0.0, depth=1.0)

    def bind(self, outputs) -> None:
        """Bind without clearing.

        Parameters
        ----------
        outputs : Outputs
            What the draw writes besides colour.
        """
        self.fbo.use()

    def depth_source(self):
        return self.fbo_color

    def resolve(self, outputs) -> None:
        """Nothing: the G-buffer is single-sampled.

        Parameters
        ----------
        outputs : Outputs
            What the draw writes besides colour.
        """
        pass


def bind_gbuffer(put, prog, state, gbuf: GBuffer) -> None:
    """Bind the G-buffer and write what rebuilds its points
    (shaders/include/gbuffer_point.glsl), the viewport and the lights, for a compute program.

    Parameters
    ----------
    put
        the uniform writer's ``put(program, name, value)``.
    prog
        the compute program.
    state
        the draw's facts (its matrices, viewport, camera and lights).
    gbuf
        the G-buffer drawn for it.
    """
    gbuf.face.use(Unit.GBUFFER_FACE)
    gbuf.depth.use(Unit.GBUFFER_DEPTH)
    gbuf.normal.use(Unit.GBUFFER_NORMAL)
    inverse_view = np.linalg.inv(state.view)
    values = {"u_face_ids": Unit.GBUFFER_FACE, "u_depth_bits": Unit.GBUFFER_DEPTH,
              "u_normals": Unit.GBUFFER_NORMAL,
              **pixel_rays(state.proj, state.view, state.viewport),
              "u_eye": tuple(inverse_view[:3, 3]),
              "u_forward": tuple(-inverse_view[:3, 2]),
              "u_viewport": tuple(float(v) for v in state.viewport),
              "u_near": float(state.camera.planes()[0]),
              "u_light_count": len(state.lights)}
    for name, value in values.items():
        put(prog, name, value)
