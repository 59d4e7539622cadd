"""Patches tessellated on the GPU (GL 4.0 tessellation shaders), drawn by the renderer beside
meshes: each patch's control points, as mass-points, in one buffer; ``patch.tesc`` sets one
uniform level for every patch (so shared edges get the same samples: no cracks) and
``patch.tese`` evaluates the surface and its exact normal at each generated vertex, then does
the mode's vertex work (the same include files smooth.vert and gouraud.vert use), so the
pictures are the CPU tessellation's at the same level. The CPU path stays the default: on a
software rasterizer the tessellator costs more than the triangles it saves uploading."""

from __future__ import annotations

from typing import Any

import numpy as np

from ...errors import SceneError
from ...modes import ShadingMode
from ..base import GLResource
from ..programs import ProgramKey
from . import Stage

__all__ = ["PatchPass", "GPU_MODES"]

#: tessellated vertices one draw may make: llvmpipe silently drops patches past about 64k
#: (the teapot at level 48 lost its lid and spout), so larger jobs are drawn in batches
DRAW_VERTICES = 32768
#: the modes a GPU-tessellated patch model draws in (flat needs a polygon's normal, which a
#: generated triangle does not have; radiosity needs vertex colours)
GPU_MODES = (ShadingMode.GOURAUD, ShadingMode.PHONG, ShadingMode.NORMALS, ShadingMode.DEPTH)


class PatchPass(GLResource, Stage):
    """Programs and control-point buffers of GPU-tessellated patch models, for one
    Renderer: the stage that draws them beside the meshes.

    Parameters
    ----------
    context
        the RenderContext drawn with.
    shaders
        its shader library.
    meshes
        the mesh pass (its uniform writer, material cache and normal matrices).
    """

    def __init__(self, context, shaders, meshes):
        super().__init__(context)
        self.shaders, self.meshes = shaders, meshes
        self.uniforms, self.materials = meshes.uniforms, meshes.materials
        self._programs: dict = {}
        self._buffers: dict[int, Any] = {}

    def program(self, key: ProgramKey, degree: tuple[int, int]):
        """The program of a variant for patches of ``degree`` (m, n).

        Parameters
        ----------
        key : ProgramKey
            The variant.
        degree : (int, int)
            The patches' degree (m, n).
        """
        from ..shaders import PROGRAMS

        found = self._programs.get((key, degree))
        if found is None:
            m, n = degree
            defines = (*key.defines(), f"DEGREE_U {m}", f"DEGREE_V {n}",
                       f"PATCH_POINTS {(m + 1) * (n + 1)}", "PATCH_IDS")
            if key.mode is ShadingMode.GOURAUD:
                defines += ("GOURAUD_STAGE",)
            frag = PROGRAMS[key.mode][1]
            found = self._programs[(key, degree)] = self.shaders.compile(
                "patch.vert", frag, defines=defines, tess=("patch.tesc", "patch.tese"))
        return found

    def vertex_array(self, model, program):
        """The VAO of a model's control points with ``program`` (made once per pair).

        Parameters
        ----------
        model : PatchModel
            The model.
        program : moderngl.Program
            Its program.
        """
        ctx = self.context.ctx
        found = self._buffers.get(id(model))
        if found is None or found[0] is not model.patches:
            if found is not None:
                for obj in (*found[2].values(), found[1]):
                    obj.release()
            h = model.patches.homogeneous.reshape(-1, 4).astype("f4")
            found = self._buffers[id(model)] = (model.patches, ctx.buffer(h.tobytes()), {})
        vaos = found[2]
        vao = vaos.get(id(program))
        if vao is None:
            vao = vaos[id(program)] = ctx.vertex_array(program, [(found[1], "4f",
                                                                  "in_control")])
        return vao

    def wanted(self, state) -> bool:
        """Whether the draw has patch models to draw.

        Parameters
        ----------
        state : DrawState
            The draw.
        """
        return bool(state.scene.patch_models) and not state.options.wireframe

    def draw(self, state, id_base: int) -> int:
        """Draw the scene's visible patch models (their ids, one per patch, follow from
        ``id_base``); return the id base after them.

        Parameters
        ----------
        state : DrawState
            The draw.
        id_base : int
            The first polygon id free for the patches.
        """
        import moderngl

        from ...geometry.transforms import gl_bytes

        self._check()
        ctx = self.context.ctx
        self.context.require(400, "GPU tessellation needs", "tessellate on the CPU "
                             "(tessellation='cpu')")
        mode = state.options.mode
        if mode not in GPU_MODES:
            raise SceneError(f"a GPU-tessellated patch model draws in "
                             f"{', '.join(m.value for m in GPU_MODES)}; the {mode.value} mode "
                             "needs its CPU tessellation (tessellation='cpu')")
        put = self.uniforms.put
        view3 = state.view[:3, :3]
        for model in state.scene.patch_models:
            if not model.visible:
                id_base += len(model.patches)
                continue
            key = ProgramKey.of(state.variant, two_sided=True)
            prog = self.program(key, model.patches.degree)
            for name, value in state.frame_uniforms:
                put(prog, name, value)
            m = model.transform
            normal_world, mirrored = self.meshes.normal_matrix(m, m.tobytes())
            put(prog, "u_normal_view", np.ascontiguousarray(
                (view3 @ normal_world).T, "f4").tobytes())
            put(prog, "u_normal_world", np.ascontiguousarray(normal_world.T, "f4").tobytes())
            put(prog, "u_model_view", gl_bytes(state.view @ m))
            put(prog, "u_level", float(model.level))
            for name, value in self.materials(model.material, state.lights,
                                              state.scene.ambient):
                put(prog, name, value)
            ctx.front_face = "cw" if mirrored != state.flip_rows else "ccw"
            ctx.disable(moderngl.CULL_FACE)
            points = int(np.prod(np.add(model.patches.degree, 1)))
            ctx.patch_vertices = points
            vao = self.vertex_array(model, prog)
            batch = max(1, DRAW_VERTICES // (model.level + 1) ** 2)
            for first in range(0, len(model.patches), batch):
                count = min(batch, len(model.patches) - first)
                # (gl_PrimitiveID restarts at 0 each draw: the ids' base moves with it)
                put(prog, "u_face_id_base", id_base + first)
                vao.render(moderngl.PATCHES, vertices=count * points, first=first * points)
            id_base += len(model.patches)
        return id_base

    def _release_extra(self) -> None:
        for p in self._programs.values():
            p.release()
        self._programs.clear()
        for _, buf, vaos in self._buffers.values():
            for v in vaos.values():
                v.release()
            buf.release()
        self._buffers.clear()
