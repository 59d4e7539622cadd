"""The GL passes, one per kind of thing drawn or computed: each a :class:`GLResource` made
from a RenderContext, fed by the numpy of its chapter (``solids/encoding.py``,
``pathtrace/pack.py``, ...).

A frame is a pipeline: :func:`run` takes the GL context, the frozen
:class:`~glshade.render.state.DrawState` of the draw and a tuple of :class:`Stage` objects
-- the renderer's is shadows, meshes, patches, CSG solids, transparency, edges -- and drives
them with one protocol:

1. ``wanted(state)``: whether the stage has work in this draw;
2. ``prepare(state) -> state``: work before the target is bound (the shadow pass's
   G-buffer, maps or rays), returning the state with what the later stages need (uniforms);
3. ``draw(state, id_base) -> id_base``: draw into the bound target; ``id_base`` is the first
   polygon id still free (ids run on from one stage to the next);
4. ``finish(state)``: after every stage drew (counts read back, reports).

A stage owns its GL objects (``release()``, a :class:`~glshade.render.base.GLResource`).

No stage receives the renderer: what a stage needs from another (the mesh pass's drawing
routine, the opaque stages a G-buffer is drawn with) is handed to it when it is made.

- :mod:`.mesh`: the meshes (:class:`~.mesh.MeshPass`), the one routine that draws a model.
- :mod:`.shadows`: cast shadows, exact or by maps (:class:`~.shadows.ShadowPass`).
- :mod:`.patches`: patches tessellated by GL 4.0 shaders (:class:`~.patches.PatchPass`).
- :mod:`.csg`: CSG solids by ray casting (:class:`~.csg.CsgPass`).
- :mod:`.transparency`: transparent surfaces (:class:`~.transparency.TransparencyPass`).
- :mod:`.edges`: the edge overlay (:class:`~.edges.EdgePass`).
- :mod:`.hemicube`: radiosity's form factors (:class:`~.hemicube.Hemicube`; not a stage).
- :mod:`.pathtrace`: the path tracer's passes (:class:`~.pathtrace.GpuPathTracer`).
- :mod:`.labels`: the viewer's text bands (:class:`~.labels.LabelOverlay`).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import moderngl

if TYPE_CHECKING:
    from ..state import DrawState

__all__ = ["Stage", "run"]


class Stage:
    """One stage of a frame's pipeline; the defaults do nothing (a stage overrides what it
    takes part in)."""

    def wanted(self, state: DrawState) -> bool:
        """Whether this stage has work in ``state``'s draw.

        Parameters
        ----------
        state : DrawState
            The draw.
        """
        return True

    def prepare(self, state: DrawState) -> DrawState:
        """Work before the target is bound; the state the later stages see.

        Parameters
        ----------
        state : DrawState
            The draw.
        """
        return state

    def draw(self, state: DrawState, id_base: int) -> int:
        """Draw into the bound target; the first polygon id still free after this stage.

        Parameters
        ----------
        state : DrawState
            The draw.
        id_base : int
            The first polygon id free for this stage.
        """
        return id_base

    def finish(self, state: DrawState) -> None:
        """After every stage drew.

        Parameters
        ----------
        state : DrawState
            The draw.
        """

    def release(self) -> None:
        """Free the GL objects the stage made (a GLResource's, listed first in a stage's
        bases, is the one that runs)."""


def run(ctx: moderngl.Context, stages: Sequence[Stage], state: DrawState) -> DrawState:
    """Draw ``state``'s frame with ``stages``, in order: each prepares, the target is
    bound (cleared when ``state.clear``), each draws, each finishes; the target is resolved
    (MSAA) when it was cleared here. Returns the state the stages drew with.

    Parameters
    ----------
    ctx
        the moderngl context the stages draw with (current).
    stages
        the pipeline's stages, in drawing order.
    state
        the draw's facts (:meth:`DrawState.of`).
    """
    stages = [s for s in stages if s.wanted(state)]
    for stage in stages:
        state = stage.prepare(state)
    target, options = state.target, state.options
    if state.clear:
        target.begin(state.scene.background, options.outputs)
    else:
        target.bind(options.outputs)
    ctx.viewport = state.viewport
    if options.depth_test:
        ctx.enable(moderngl.DEPTH_TEST)
    else:
        ctx.disable(moderngl.DEPTH_TEST)
    id_base = 0
    for stage in stages:
        id_base = stage.draw(state, id_base)
    for stage in stages:
        stage.finish(state)
    ctx.disable(moderngl.CULL_FACE)
    ctx.front_face = "ccw"
    if state.clear:
        target.resolve(options.outputs)
    return state
