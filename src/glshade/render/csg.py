"""Drawing CSG solids on the GPU: the tree becomes generated GLSL (one event array per
node, sized from its leaves; the leaves and the merge of csg.glsl), compiled once per tree
*shape* and cached -- sizes and transforms are uniforms, so editing them recompiles
nothing. Each solid is drawn as the back faces of its bounding box; the fragment program
casts the pixel's ray through the tree and writes the first surface's depth to
gl_FragDepth, so solids and meshes share one z-buffer.

Shading: the lighting function of the meshes with the exact normal at every pixel.
Gouraud and Phong both light per pixel (a solid has no vertices to hold an intensity);
flat gives each planar leaf face -- a box's faces, a cylinder's or a cone's caps -- one
intensity, lit at the face's centre as a mesh polygon is lit at its centroid, while curved
faces (and a half-space's unbounded plane) have no centre and stay lit per pixel;
``normals`` and ``depth`` show what they show for meshes.
"""

from __future__ import annotations

from typing import Any

import weakref

import numpy as np

from ..solids import leaves as L  # (the leaves: L.Box ...)
from ..solids.tree import Difference, Intersection, Solid, Transformed, Union
from ..geometry.transforms import box_corners, gl_bytes
from ..modes import ShadingMode
from .base import GLResource
from .programs import MaterialUniforms, ProgramKey, UniformWriter
from .state import DrawState

__all__ = ["CsgPass", "tree_code", "leaf_uniforms", "shape_key", "box_matrix"]

_KIND: dict[type, str] = {L.Sphere: "sphere", L.Box: "box", L.Cylinder: "cylinder", L.Cone: "cone",
         L.Torus: "torus", L.HalfSpace: "halfspace"}
#: leaf kinds as the fragment program's flat shading numbers them (csg.frag's face_centre)
_KIND_CODE = {kind: code for code, kind in enumerate(_KIND)}
_OPS: dict[type, tuple[str, str]] = {
    Union: ("U", "ca > 0 || cb > 0"), Intersection: ("I", "ca > 0 && cb > 0"),
    Difference: ("D", "ca > 0 && !(cb > 0)")}


def shape_key(solid: Solid) -> str:
    """The tree's shape (what the generated code depends on), e.g. ``D(U(sphere,box),...)``."""
    if isinstance(solid, Transformed):
        return shape_key(solid.child)
    if type(solid) in _OPS:
        node: Any = solid  # (a boolean: it has a and b)
        return f"{_OPS[type(solid)][0]}({shape_key(node.a)},{shape_key(node.b)})"
    return _KIND[type(solid)]


def tree_code(solid: Solid) -> tuple[str, int, int]:
    """(GLSL defining ``csg_tree``, number of leaves, events width)."""
    lines: list[str] = []
    helpers: dict[str, str] = {}
    counter = [0, 0]

    def visit(node) -> tuple[str, int]:
        if isinstance(node, Transformed):
            return visit(node.child)
        if type(node) in _OPS:
            a, wa = visit(node.a)
            b, wb = visit(node.b)
            letter, test = _OPS[type(node)]
            name = f"comb_{letter}_{wa}_{wb}"
            helpers.setdefault(name, _combine(name, wa, wb, test))
            out = f"n{counter[1]}"
            counter[1] += 1
            lines.append(f"    Ev {out}[{wa + wb}]; {name}({a}, {b}, {out});")
            return out, wa + wb
        i = counter[0]
        counter[0] += 1
        width = 4 if isinstance(node, L.Torus) else 2
        out = f"l{i}"
        lines.append(f"    Ev {out}[{width}]; leaf_{_KIND[type(node)]}({i}, "
                     f"(u_leaf_inverse[{i}] * vec4(ro, 1.0)).xyz, "
                     f"mat3(u_leaf_inverse[{i}]) * rd, {out});")
        return out, width

    root, width = visit(solid)
    body = "\n".join(lines)
    code = "\n".join(helpers.values()) + (
        f"\nvoid csg_tree(vec3 ro, vec3 rd, out Ev events[{width}]) {{\n{body}\n"
        f"    events = {root};\n}}\n")
    return code, counter[0], width


def _combine(name: str, wa: int, wb: int, test: str) -> str:
    """Merge two sorted event lists; keep the events where ``test`` (in A, in B) changes."""
    n = wa + wb
    return f"""
void {name}(Ev A[{wa}], Ev B[{wb}], out Ev C[{n}]) {{
    int i = 0, j = 0, m = 0, ca = 0, cb = 0;
    bool before = false;
    for (int k = 0; k < {n}; ++k) C[k] = pad_event();
    for (int k = 0; k < {n}; ++k) {{
        Ev a = A[min(i, {wa - 1})], b = B[min(j, {wb - 1})];
        bool take_a = j >= {wb} || (i < {wa} && a.t <= b.t);
        Ev e = take_a ? a : b;
        if (take_a) {{ ca += a.kind; i++; }} else {{ cb += b.kind; j++; }}
        if (e.kind == 0) continue;
        bool inside = {test};
        if (inside != before) {{
            C[m] = Ev(e.t, inside ? 1 : -1, e.n, e.leaf);
            m++;
            before = inside;
        }}
    }}
}}"""


def leaf_uniforms(solid: Solid) -> dict:
    """Per leaf, in ``solid.leaves()`` order: world-to-leaf matrices, normal matrices
    (negated under a difference's right side) and size parameters."""
    inverse, normal, params = [], [], []

    def visit(node, matrix, sign):
        if isinstance(node, Transformed):
            visit(node.child, matrix @ node.matrix, sign)
            return
        if type(node) in _OPS:
            visit(node.a, matrix, sign)
            visit(node.b, matrix, -sign if isinstance(node, Difference) else sign)
            return
        inv = np.linalg.inv(matrix)
        inverse.append(inv)
        normal.append(sign * inv[:3, :3].T)
        params.append(_params(node))

    visit(solid, np.eye(4), 1.0)
    mats = np.array(inverse)
    return {"u_leaf_inverse": np.ascontiguousarray(mats.transpose(0, 2, 1), "f4"),
            "u_leaf_normal": np.ascontiguousarray(np.array(normal).transpose(0, 2, 1), "f4"),
            "u_leaf_param": np.array(params, "f4")}


def _params(leaf) -> list:
    if isinstance(leaf, L.Sphere):
        return [leaf.radius, 0, 0, 0]
    if isinstance(leaf, L.Box):
        return [*leaf.half, 0]
    if isinstance(leaf, L.Cylinder):
        return [leaf.radius, leaf.h, 0, 0]
    if isinstance(leaf, L.Cone):
        return [leaf.radius, leaf.apex, leaf.k, 0]
    if isinstance(leaf, L.Torus):
        return [leaf.R, leaf.r, 0, 0]
    return [*leaf.normal, leaf.offset]


class CsgPass(GLResource):
    """Programs (per tree shape and variant), the unit box and the drawing of solids, for
    one Renderer: a GL owner of the renderer's context, released with it. Shares the
    renderer's uniform writer and material cache (public collaborators, handed in)."""

    def __init__(self, context, shaders, uniforms: UniformWriter,
                 materials: MaterialUniforms):
        super().__init__(context)
        self.shaders, self.uniforms, self.materials = shaders, uniforms, materials
        self._programs: dict = {}
        self._box: Any = None
        # per solid (solids are values: a new tree is a new object), what each frame reuses
        self._solids: weakref.WeakKeyDictionary[Solid, tuple] = weakref.WeakKeyDictionary()

    def _facts(self, solid: Solid):
        """(shape key, leaf uniforms) of a solid, made once."""
        found = self._solids.get(solid)
        if found is None:
            found = self._solids[solid] = (shape_key(solid), {
                name: value.tobytes() for name, value in leaf_uniforms(solid).items()})
        return found

    def program(self, solid: Solid, key):
        self._check()
        shape = self._facts(solid)[0]
        found = self._programs.get((shape, key))
        if found is None:
            code, leaves, width = tree_code(solid)
            defines = (*key.defines(), f"LEAVES {leaves}", f"WIDTH {width}")
            if key.mode is ShadingMode.NORMALS:
                defines += ("SHOW_NORMALS",)
            elif key.mode is ShadingMode.DEPTH:
                defines += ("SHOW_DEPTH",)
            elif key.mode is ShadingMode.FLAT:
                kinds = ", ".join(str(_KIND_CODE[type(leaf)]) for leaf in solid.leaves())
                defines += ("FLAT_FACES", f"LEAF_KINDS_LIST {kinds}")
            found = self.shaders.compile("csg.vert", "csg.frag", defines=defines,
                                         insert=("// GLSHADE_CSG_TREE", code))
            self._programs[(shape, key)] = found
        return found

    def vertex_array(self, program):
        ctx = self.context.ctx
        if self._box is None:
            corners = box_corners(np.array([[0.0] * 3, [1.0] * 3]))
            faces = np.array([[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6],
                              [0, 2, 6, 4], [1, 5, 7, 3]])
            tri = np.concatenate([faces[:, [0, 1, 2]], faces[:, [0, 2, 3]]])
            self._box = (self._keep(ctx.buffer(corners.astype("f4").tobytes())),
                         self._keep(ctx.buffer(tri.astype("u4").tobytes())), {})
        vbo, ibo, vaos = self._box
        vao = vaos.get(id(program))
        if vao is None:
            vao = vaos[id(program)] = ctx.vertex_array(program, [(vbo, "3f", "in_position")],
                                                       ibo, 4)
        return vao

    def draw(self, state: DrawState, id_base: int) -> None:
        """Draw the scene's visible solids (after its meshes: their ids follow from
        ``id_base``, the meshes' polygon count)."""
        import moderngl

        self._check()
        ctx = self.context.ctx
        view, view_proj, viewport = state.view, state.view_proj, state.viewport
        put = self.uniforms.put
        n_polygons = id_base
        for model in state.scene.solids:
            if not model.visible:
                continue
            prog = self.program(model.solid, ProgramKey.of(state.variant, two_sided=False))
            for name, value in state.frame_uniforms:
                put(prog, name, value)
            for name, value in self.materials(model.material, state.lights,
                                              state.scene.ambient):
                put(prog, name, value)
            for name, value in self._facts(model.solid)[1].items():
                put(prog, name, value)
            bounds = model.solid.bounds
            assert bounds is not None  # (Scene.add refuses unbounded solids)
            put(prog, "u_view_proj", gl_bytes(view_proj @ box_matrix(bounds)))
            put(prog, "u_solid_view_proj", gl_bytes(view_proj))
            put(prog, "u_inverse_view_proj", gl_bytes(np.linalg.inv(view_proj)))
            put(prog, "u_view", gl_bytes(view))
            put(prog, "u_view_normal", np.ascontiguousarray(view[:3, :3].T, "f4").tobytes())
            put(prog, "u_viewport_origin", (float(viewport[0]), float(viewport[1])))
            put(prog, "u_viewport_size", (float(viewport[2]), float(viewport[3])))
            put(prog, "u_face_id_base", n_polygons)
            ctx.enable(moderngl.CULL_FACE)
            ctx.front_face = "cw" if state.flip_rows else "ccw"
            ctx.cull_face = "front"  # the box's back faces: inside it or outside, every pixel
            self.vertex_array(prog).render(moderngl.TRIANGLES)
            ctx.cull_face = "back"
            n_polygons += len(model.solid.leaves())

    def _release_extra(self) -> None:
        """The programs and vertex arrays (the box's buffers are in ``_objects``)."""
        for p in self._programs.values():
            p.release()
        self._programs.clear()
        if self._box is not None:
            for vao in self._box[2].values():
                vao.release()
            self._box = None


def box_matrix(bounds: np.ndarray) -> np.ndarray:
    """The matrix taking the unit cube onto ``bounds`` (slightly enlarged)."""
    lo, hi = bounds
    size = np.maximum(hi - lo, 1e-9 * max(float(np.abs(bounds).max()), 1.0))
    pad = 1e-4 * size + 1e-9
    m = np.diag([*(size + 2 * pad), 1.0])
    m[:3, 3] = lo - pad
    return m
