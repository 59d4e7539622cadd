"""The polygon-edge overlay: each polygon's boundary (its Newell polygon, not the
triangulation) drawn as lines a few pixels wide, on top of the filled picture or alone
(``DrawOptions.edges`` / ``wireframe``).

Lines are widened into screen-aligned quads by a geometry shader (``edges.geom``): GL core
profiles promise no line width above 1, and a 1-pixel line vanishes on a large image, so the
width grows with the image (:func:`edge_width`). Whether an edge is seen is decided per
pixel (``edges.frag``): the surfaces' depth buffer is copied to a texture, and the pixel
holding the point of the edge's centre line decides -- nothing drawn there, or one of the
edge's own two faces (the depth lies on that face's plane within the pixel's square), or a
surface no nearer than the edge: seen; a nearer surface: hidden. No constant bias and no
neighbouring pixels (which, across a silhouette, see something else): it holds at any near
plane, with the camera inside the scene or out, convex edges and concave. They go to the
colour only: the auxiliary outputs (ids, depth, normals) stay the surfaces'.
"""

from __future__ import annotations

from typing import Any

import moderngl
import numpy as np

from ...geometry.transforms import gl_bytes
from ...modes import Outputs
from ..base import GLResource
from ..state import DrawState
from ..units import Unit
from . import Stage

__all__ = ["EdgePass", "edge_width", "EDGE_COLOR"]

#: the overlay's colour (linear RGB): dark, readable on every shading
EDGE_COLOR = (0.06, 0.06, 0.07)


def edge_width(width: int, height: int) -> float:
    """Line width in pixels for a ``width`` x ``height`` image: 1 pixel up to 400 pixels a
    side, then half a pixel more per 200 (1.5 at 512, 2.5 at 1024, 4.5 at 2048).

    Parameters
    ----------
    width, height : int
        The image's size in pixels.
    """
    side = min(int(width), int(height))
    return max(1.0, round(side / 400 * 2) / 2)


class EdgePass(GLResource, Stage):
    """The edge program and its drawing, for one Renderer (released with it): the
    pipeline's last stage, an overlay on top of every surface.

    Parameters
    ----------
    context
        the RenderContext drawn with.
    shaders
        its shader library.
    meshes
        the mesh pass (its GPU meshes' edge arrays and its uniform writer).
    """

    def __init__(self, context, shaders, meshes):
        super().__init__(context)
        self.shaders, self.meshes = shaders, meshes
        self._program: Any = None
        self._depth: Any = None   # (size, texture, framebuffer): the surfaces' depth

    def program(self):
        self._check()
        if self._program is None:
            self._program = self._keep(self.shaders.compile("edges.vert", "edges.frag",
                                                            geom="edges.geom"))
        return self._program

    def wanted(self, state: DrawState) -> bool:
        return bool(state.options.edges or state.options.wireframe)

    def draw(self, state: DrawState, id_base: int) -> int:
        """Draw the edges of the scene's visible meshes into the target's colour, in
        ``EDGE_COLOR`` (or, wireframe, each in its material's colour); the id base as it
        was (edges take no ids).

        Parameters
        ----------
        state : DrawState
            The draw.
        id_base : int
            The first polygon id free for this stage.
        """
        options = state.options
        models = [m for m in state.scene.models if state.drawn(m)]
        if not models:
            return id_base
        gpu_meshes = [(self.meshes.gpu_mesh(m.mesh), m.transform) for m in models]
        colors = [m.material.color for m in models] if options.wireframe else None
        prog = self.program()
        ctx = self.context.ctx
        hide = bool(state.options.depth_test)
        if hide:
            self._copy_depth(state.target)
        state.target.bind(Outputs.COLOR)
        put = self.meshes.uniforms.put
        x, y, w, h = state.viewport
        put(prog, "u_proj", gl_bytes(state.proj))
        put(prog, "u_inverse_proj", gl_bytes(np.linalg.inv(state.proj)))
        put(prog, "u_viewport_origin", (float(x), float(y)))
        put(prog, "u_viewport_size", (float(w), float(h)))
        put(prog, "u_edge_width", float(edge_width(w, h)))
        put(prog, "u_hide", int(hide))
        put(prog, "u_centre_depth", int(not state.target.samples))
        put(prog, "u_scene_depth", Unit.EDGE_DEPTH)
        ctx.disable(moderngl.CULL_FACE)
        ctx.disable(moderngl.DEPTH_TEST)  # (seen or not is edges.frag's judgement)
        for i, (gpu, model) in enumerate(gpu_meshes):
            normal_world, _ = self.meshes.normal_matrix(model, model.tobytes())
            put(prog, "u_model_view", gl_bytes(state.view @ model))
            put(prog, "u_normal_view", gl_bytes(state.view[:3, :3] @ normal_world))
            put(prog, "u_edge_color", tuple(float(c) for c in
                                            (colors[i] if colors is not None else EDGE_COLOR)))
            gpu.edge_array(prog).render(moderngl.LINES)
        if state.options.depth_test:
            ctx.enable(moderngl.DEPTH_TEST)
        return id_base

    def _copy_depth(self, target) -> None:
        """The surfaces' depth so far into a texture the edges read (resolved from MSAA by
        the copy), bound to its unit."""
        ctx = self.context.ctx
        source = target.depth_source()
        size = tuple(source.size)
        if self._depth is None or self._depth[0] != size:
            self._release_extra()
            texture = ctx.depth_texture(size)
            colour = ctx.renderbuffer(size, 4)
            self._depth = (size, texture, ctx.framebuffer([colour], texture), colour)
        ctx.copy_framebuffer(self._depth[2], source)
        self._depth[1].use(location=Unit.EDGE_DEPTH)

    def _release_extra(self) -> None:
        """The depth copy (remade when the target's size changes)."""
        if self._depth is not None:
            for obj in (self._depth[2], self._depth[3], self._depth[1]):
                obj.release()
            self._depth = None
