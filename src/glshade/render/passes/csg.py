"""Drawing CSG solids on the GPU: the GL half of the seam.

A solid becomes its tree data once (:func:`glshade.solids.encoding.tree_data`, pure numpy:
why the tree is data, not generated code, is told there); this pass uploads it -- a uniform
block for trees of at most 64 leaves, a data texture beyond -- picks the program and draws
the solid's screen polygon (:mod:`glshade.solids.proxy`), so only pixels that may show it
run the cast, each once, the camera inside the solid or out.

A small tree (at most 14 leaves) is cast in one step (``include/csg/onestep.glsl``), with
no loops, by a program keyed by how many leaves of each kind it has, its rays interpolated
exactly from the vertex stage; a larger tree walks (``include/csg/walk.glsl``), one program
per size class and set of kinds: :mod:`glshade.solids.encoding` tells why. Measured on
llvmpipe (benchmarks/csg_bench.py's 7-leaf tree at 512x512, one thread): 7.8 ms a frame
against 4.9 ms for its 5,218-triangle manifold3d mesh.

Shading: the meshes' lighting with the exact normal at every pixel (Gouraud lights per
pixel too: a solid has no vertices); flat gives each planar leaf face one intensity, lit at
its centre. The fragment stage writes gl_FragDepth: solids and meshes share one z-buffer.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ...geometry.transforms import gl_bytes, ray_uniforms
from ...modes import ShadingMode
from ...solids.encoding import (ROW, TreeData, glsl_defines, may_start_inside, size_class,
                                tree_data)
from ...solids.proxy import DIRECTIONS, screen_polygon
from ...solids.tree import Solid, tie_length
from ..arrays import PerObject
from ..base import GLResource
from ..data import data_texture
from ..programs import MaterialUniforms, ProgramKey, UniformWriter
from ..state import DrawState
from ..units import Unit
from . import Stage

__all__ = ["CsgPass", "csg_defines"]


def csg_defines(data: TreeData, slots: tuple = (), blocks: bool = True) -> tuple[str, ...]:
    """The ``#define``s of a program that casts a tree like ``data``: the shared constants,
    its size class and kinds, the one-step cast's slot kinds where ``slots``, and whether
    its data is a uniform block (``blocks`` and a small tree) or a texture.

    Parameters
    ----------
    data : TreeData
        The tree.
    slots : tuple
        The one-step cast's leaf kinds by slot.
    blocks : bool
        Read the tree from a uniform block (else a texture).
    """
    _, words, block = size_class(data.leaves)
    defines = (*glsl_defines(), f"CSG_WORDS {words}", f"CSG_KINDS {data.kinds}")
    if block and blocks:
        defines += (f"CSG_BLOCK {block}",)
    if slots:
        defines += (f"CSG_SLOTS {len(slots)}",
                    *(f"CSG_KIND_{i} {k}" for i, k in enumerate(slots)))
    if words == 1:
        defines += ("CSG_LEAF_LOOP",)
    return defines


class _Tree:
    """A solid's tree data and its GPU copy (a texture, or a uniform buffer when small)."""

    def __init__(self, data: TreeData, store):
        self.data, self.store = data, store

    def release(self) -> None:
        self.store.release()


class CsgPass(GLResource, Stage):
    """The programs (per shading variant and tree class, :meth:`program`), each solid's data
    texture, the screen polygon's buffer and the drawing of solids, for one Renderer: a GL
    owner of the renderer's context, released with it. Shares the renderer's uniform writer
    and material cache (public collaborators, handed in).

    Parameters
    ----------
    context : RenderContext
        The context its GL objects live in.
    shaders : ShaderLibrary
        Where its programs are compiled.
    uniforms : UniformWriter
        The one uniform writer.
    materials : MaterialUniforms
        The materials' products, shared.
    """

    #: the texture unit the tree data is bound to
    UNIT = Unit.CSG_TREE

    def __init__(self, context, shaders, uniforms: UniformWriter,
                 materials: MaterialUniforms):
        super().__init__(context)
        self.shaders, self.uniforms, self.materials = shaders, uniforms, materials
        self._programs: dict = {}
        self._fan: Any = None  # (buffer of the screen polygon's corners, vertex arrays)
        # per solid (solids are values: a new tree is a new object): its data and texture,
        # dropped (and the texture released) once the solid is gone
        self._data = PerObject(self._tree)
        # the most slots the one-step cast may have here: each takes six interpolated
        # floats (csg.vert), and GL 3.3 promises only 60 (desktop drivers give 124-128);
        # a tree over it walks instead
        limit = context.ctx.info.get("GL_MAX_FRAGMENT_INPUT_COMPONENTS") or 60
        self.max_slots = max((n for n in (16, 8, 4) if 6 * n + 6 <= limit), default=0)

    def data(self, solid: Solid) -> tuple[TreeData, Any]:
        """(tree data, its texture or uniform buffer) of a solid, made once while it lives.

        Parameters
        ----------
        solid : Solid
            The solid.
        """
        self._check()
        tree = self._data(solid)
        return tree.data, tree.store

    def _tree(self, solid: Solid) -> _Tree:
        data = tree_data(solid)
        block = size_class(data.leaves)[2]
        if block:
            assert len(data.texels) <= block  # (16 L - 4 texels: 1,020 at 64 leaves)
            store = self.context.ctx.buffer(data.texels.tobytes().ljust(16 * block, b"\0"))
        else:
            store = data_texture(self.context.ctx, data.texels, ROW)
        return _Tree(data, store)

    def program(self, key: ProgramKey, data: TreeData, slots: tuple = ()):
        """The program of a variant for a tree like ``data``: one per size class (32, 64,
        256 or 1,024 leaves: the words of leaf bits it keeps) and set of kinds -- and for a
        tree cast in one step, per ``slots`` (its leaves' kinds in kind order), never per
        tree.

        Parameters
        ----------
        key : ProgramKey
            The variant.
        data : TreeData
            A tree of the size class and kinds wanted.
        slots : tuple
            The one-step cast's leaf kinds by slot (empty: the walk).
        """
        self._check()
        words = size_class(data.leaves)[1]
        found = self._programs.get((key, words, data.kinds, slots))
        if found is None:
            defines = (*key.defines(), *csg_defines(data, slots))
            if key.mode is ShadingMode.NORMALS:
                defines += ("SHOW_NORMALS",)
            elif key.mode is ShadingMode.DEPTH:
                defines += ("SHOW_DEPTH",)
            elif key.mode is ShadingMode.FLAT:
                defines += ("FLAT_FACES",)
            found = self.shaders.compile("csg.vert", "csg.frag", defines=defines)
            self._programs[(key, words, data.kinds, slots)] = found
        return found

    @property
    def compiled(self) -> tuple:
        """The keys of the programs compiled so far: ``(ProgramKey, words of leaf bits,
        kinds, one-step slots)`` each (one per variant and tree class, never per tree)."""
        return tuple(self._programs)

    def fan(self, program, corners: np.ndarray):
        """The vertex array of a screen polygon (M, 2) NDC (M <= DIRECTIONS + 4), drawn as
        a fan.

        Parameters
        ----------
        program : moderngl.Program
            The solid's program.
        corners : ndarray
            ``(M, 2)`` the polygon in NDC.
        """
        ctx = self.context.ctx
        if self._fan is None:
            self._fan = (self._keep(ctx.buffer(reserve=12 * (DIRECTIONS + 8), dynamic=True)),
                         {})
        vbo, vaos = self._fan
        vbo.write(np.c_[corners, np.zeros(len(corners))].astype("f4").tobytes())
        vao = vaos.get(id(program))
        if vao is None:
            vao = vaos[id(program)] = ctx.vertex_array(program, [(vbo, "3f", "in_position")])
        return vao

    def wanted(self, state: DrawState) -> bool:
        return bool(state.scene.solids) and not state.options.wireframe

    def draw(self, state: DrawState, id_base: int) -> int:
        """Draw the scene's visible solids (their ids, a leaf each, follow from
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
        ctx = self.context.ctx
        view, view_proj, viewport = state.view, state.view_proj, state.viewport
        put = self.uniforms.put
        n_polygons = id_base
        for model in state.scene.solids:
            if not model.visible:  # (its ids stay its own: the next solid's do not move)
                n_polygons += model.n_polygons
                continue
            data, texture = self.data(model.solid)
            slots = data.slots if len(data.slots) <= self.max_slots else ()
            prog = self.program(ProgramKey.of(state.variant, two_sided=False), data, slots)
            for name, value in state.frame_uniforms:
                put(prog, name, value)
            for name, value in self.materials(model.material, state.lights,
                                              state.scene.ambient):
                put(prog, name, value)
            if size_class(data.leaves)[2]:
                prog["CsgData"].binding = self.UNIT
                texture.bind_to_uniform_block(self.UNIT)
            else:
                texture.use(location=self.UNIT)
                put(prog, "u_csg", self.UNIT)
            inverse = np.linalg.inv(view_proj)
            bounds = model.solid.bounds
            assert bounds is not None  # (Scene.add refuses unbounded solids)
            eye = np.linalg.inv(view)[:3, 3]
            values = {"u_csg_tie": tie_length(bounds, eye), **data.offsets(),
                      "u_csg_kind_start": np.array(data.kind_start, "i4"),
                      "u_csg_start": data.nodes if may_start_inside(data, inverse) else 0,
                      "u_solid_view_proj": gl_bytes(view_proj),
                      **ray_uniforms(state.proj, view), "u_view": gl_bytes(view),
                      "u_view_normal": np.ascontiguousarray(view[:3, :3].T, "f4").tobytes(),
                      "u_viewport_origin": (float(viewport[0]), float(viewport[1])),
                      "u_viewport_size": (float(viewport[2]), float(viewport[3])),
                      "u_face_id_base": n_polygons}
            if slots:
                values.update(u_csg_slot_leaf=data.slot_leaf, u_csg_slot=data.slot_rows,
                              u_csg_slot_sign=data.slot_sign, u_csg_slot_table=data.slot_words)
            for name, value in values.items():
                put(prog, name, value)
            # the screen polygon that holds the solid (solids/proxy.py): only its pixels run
            # the cast; one layer, so each pixel once, the camera inside the solid or out
            polygon = screen_polygon(view_proj, bounds, data.hull,
                                     (int(viewport[2]), int(viewport[3])))
            if len(polygon):
                ctx.disable(moderngl.CULL_FACE)
                self.fan(prog, polygon).render(moderngl.TRIANGLE_FAN, vertices=len(polygon))
                ctx.enable(moderngl.CULL_FACE)
            n_polygons += data.leaves
        return n_polygons

    def _release_extra(self) -> None:
        """The programs, textures and vertex arrays (the fan's buffer is in ``_objects``)."""
        for p in self._programs.values():
            p.release()
        self._programs.clear()
        self._data.release()
        if self._fan is not None:
            for vao in self._fan[1].values():
                vao.release()
            self._fan = None
