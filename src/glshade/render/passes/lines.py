"""Polylines on the GPU (:class:`~glshade.geometry.lines.Polyline`): the stage that draws
them after the points, into the same z-buffer.

One draw call a polyline model: ``GL_LINES_ADJACENCY`` over an index buffer of each
segment's (before, start, end, after) vertices, so the geometry stage (``lines.geom``) sees
the neighbours its joins are cut by and builds the segment's quad (``wide_lines.glsl``, the
edge overlay's construction too); the fragment stage (``lines.frag``) keeps the pixel
centres inside the exact shape. A model's buffers are uploaded once while its polyline
lives (render/arrays.py): 12 bytes a vertex (24 with colours) and 16 a segment.
"""

from __future__ import annotations


from ...geometry.lines import MITER_LIMIT, Polyline
from ...geometry.transforms import gl_bytes
from ...modes import LineCaps, LineJoins, LineUnits, ShadingMode
from ..arrays import GpuArrays, PerObject
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


def _gpu_lines(ctx, lines: Polyline) -> GpuArrays:
    """A polyline's GPU copy: its vertices (and colours) and each segment's four indices."""
    arrays = [("in_position", lines.vertices)]
    if lines.colors is not None:
        arrays.append(("in_color", lines.colors))
    return GpuArrays(ctx, arrays, lines.segments)


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
        self._lines = PerObject(lambda lines: _gpu_lines(context.ctx, lines))
        #: polyline models skipped by the last draw's frustum test
        self.culled = 0

    def gpu_lines(self, lines: Polyline) -> GpuArrays:
        """A polyline's GPU copy, uploaded once while it lives.

        Parameters
        ----------
        lines : Polyline
            The polylines.
        """
        self._check()
        return self._lines(lines)

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
        outside = state.outside(models)
        view, common = state.view, state.screen_uniforms()
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
            self.gpu_lines(lines).vertex_array(ctx, prog).render(
                moderngl.LINES_ADJACENCY, vertices=4 * lines.n_segments)
            id_base += model.n_polygons
        return id_base

    def _release_extra(self) -> None:
        self._lines.release()
        self._programs.clear()  # (the shader library owns and frees them)
