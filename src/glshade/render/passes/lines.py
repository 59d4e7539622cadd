"""Polylines on the GPU (:class:`~glshade.geometry.lines.Polyline`): the stage that draws
them after the points, into the same z-buffer.

One draw call a polyline model: ``GL_LINES_ADJACENCY`` over an index buffer of each
segment's (before, start, end, after) vertices, so the geometry stage (``lines.geom``) sees
the neighbours its joins are cut by and builds the segment's quad (``wide_lines.glsl``, the
edge overlay's construction too); the fragment stage (``lines.frag``) keeps the pixel
centres inside the exact shape. A model's buffers are uploaded once while its polyline
lives: 12 bytes a vertex (24 with colours) and 16 a segment.
"""

from __future__ import annotations

import weakref
from typing import Any

import numpy as np

from ...geometry.lines import MITER_LIMIT, Polyline
from ...geometry.transforms import gl_bytes, outside_frustum
from ...modes import LineCaps, LineJoins, LineUnits, ShadingMode
from ..base import GLResource
from ..programs import ProgramKey, UniformWriter
from ..state import DrawState
from . import Stage

__all__ = ["LinePass", "line_defines"]


def line_defines(lines: Polyline) -> tuple[str, ...]:
    """The ``#define``s of the program that draws polylines like ``lines``.

    Parameters
    ----------
    lines : Polyline
        The polylines.
    """
    flags = (("LINE_WORLD", lines.units is LineUnits.WORLD),
             ("ROUND_CAPS", lines.caps is LineCaps.ROUND),
             ("ROUND_JOINS", lines.joins is LineJoins.ROUND),
             ("LINE_COLORS", lines.colors is not None))
    return (*(name for name, on in flags if on), f"MITER_LIMIT {MITER_LIMIT:.1f}")


class _GpuLines:
    """A polyline's vertex, colour and segment buffers and its vertex arrays."""

    def __init__(self, ctx, lines: Polyline):
        self.buffers = [("in_position", "3f", ctx.buffer(lines.vertices.astype("f4")))]
        if lines.colors is not None:
            self.buffers.append(("in_color", "3f", ctx.buffer(lines.colors.astype("f4"))))
        self.index = ctx.buffer(lines.segments)
        self.n = lines.n_segments
        self.nbytes = sum(b.size for _, _, b in self.buffers) + self.index.size
        self.vaos: dict[int, Any] = {}

    def vertex_array(self, ctx, prog):
        vao = self.vaos.get(id(prog))
        if vao is None:
            names = set(prog)
            vao = self.vaos[id(prog)] = ctx.vertex_array(
                prog, [(buf, fmt, name) for name, fmt, buf in self.buffers if name in names],
                index_buffer=self.index, index_element_size=4)
        return vao

    def release(self) -> None:
        for vao in self.vaos.values():
            vao.release()
        for _, _, buf in self.buffers:
            buf.release()
        self.index.release()
        self.vaos.clear()
        self.buffers = []


class LinePass(GLResource, Stage):
    """The polylines' programs, buffers and draws, for one Renderer.

    Parameters
    ----------
    context : RenderContext
        The context its GL objects live in.
    shaders : ShaderLibrary
        Where its programs are compiled.
    uniforms : UniformWriter
        The one uniform writer.
    """

    def __init__(self, context, shaders, uniforms: UniformWriter):
        super().__init__(context)
        self.shaders, self.uniforms = shaders, uniforms
        self._programs: dict = {}
        self._lines: dict[int, tuple] = {}
        #: polyline models skipped by the last draw's frustum test
        self.culled = 0

    def gpu_lines(self, lines: Polyline) -> _GpuLines:
        """A polyline's GPU copy, uploaded once while it lives.

        Parameters
        ----------
        lines : Polyline
            The polylines.
        """
        self._check()
        for key in [k for k, v in self._lines.items() if v[0]() is None]:
            self._lines.pop(key)[1].release()
        found = self._lines.get(id(lines))
        if found is None or found[0]() is not lines:
            if found is not None:
                found[1].release()
            found = self._lines[id(lines)] = (weakref.ref(lines),
                                              _GpuLines(self.context.ctx, lines))
        return found[1]

    def program(self, key: ProgramKey, lines: Polyline):
        """The program of a variant for polylines like ``lines``.

        Parameters
        ----------
        key : ProgramKey
            The variant.
        lines : Polyline
            Polylines of the units, caps, joins and colours wanted.
        """
        self._check()
        wanted = line_defines(lines)
        found = self._programs.get((key, wanted))
        if found is None:
            mode = {ShadingMode.NORMALS: ("SHOW_NORMALS",),
                    ShadingMode.DEPTH: ("SHOW_DEPTH",)}.get(key.mode, ())
            found = self._programs[(key, wanted)] = self.shaders.compile(
                "lines.vert", "lines.frag", defines=(*key.defines(), *wanted, *mode),
                geom="lines.geom")
        return found

    def wanted(self, state: DrawState) -> bool:
        return bool(state.scene.lines)

    def draw(self, state: DrawState, id_base: int) -> int:
        """Draw the scene's visible polylines (their ids, a segment each, follow from
        ``id_base``); the id base after them.

        Parameters
        ----------
        state : DrawState
            The draw.
        id_base : int
            The first polygon id free for this stage.
        """
        import moderngl

        self._check()
        ctx, put = self.context.ctx, self.uniforms.put
        models = state.scene.lines
        self.culled = 0
        outside = outside_frustum(state.view_proj, np.stack([m.corners for m in models])) \
            if state.options.frustum_cull and len(models) > 1 else np.zeros(len(models), bool)
        view, viewport = state.view, state.viewport
        common = {"u_inverse_proj": gl_bytes(np.linalg.inv(state.proj)),
                  "u_camera_to_world": gl_bytes(np.linalg.inv(view)),
                  "u_viewport_origin": (float(viewport[0]), float(viewport[1])),
                  "u_viewport_size": (float(viewport[2]), float(viewport[3]))}
        ctx.disable(moderngl.CULL_FACE)
        for index, model in enumerate(models):
            if not model.visible or outside[index]:
                self.culled += bool(model.visible)
                id_base += model.n_polygons
                continue
            lines = model.lines
            prog = self.program(ProgramKey.of(state.variant, two_sided=False), lines)
            for name, value in state.frame_uniforms:
                put(prog, name, value)
            world = lines.units is LineUnits.WORLD
            values = {**common, "u_model_view": gl_bytes(view @ model.transform),
                      "u_half_width": lines.width / 2 * (model.scale if world else 1.0),
                      "u_line_color": tuple(float(x) for x in model.material.color),
                      "u_face_id_base": id_base}
            for name, value in values.items():
                put(prog, name, value)
            gpu = self.gpu_lines(lines)
            gpu.vertex_array(ctx, prog).render(moderngl.LINES_ADJACENCY, vertices=4 * gpu.n)
            id_base += model.n_polygons
        return id_base

    def _release_extra(self) -> None:
        for _, gpu in self._lines.values():
            gpu.release()
        self._lines.clear()
        self._programs.clear()  # (the shader library owns and frees them)
