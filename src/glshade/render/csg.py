"""Drawing CSG solids on the GPU, the tree as *data*: sizes, places and operators never
compile GLSL.

Why: generated GLSL (one merge function per node) made Mesa's compile time grow with the
tree -- 17 s at 16 leaves, a crash at 900. Here a solid becomes one float texture
(:func:`tree_data`), written once per solid and cached; the fragment program
(shaders/include/csg.glsl) reads it: per leaf, its world -> leaf matrix, its normal matrix
(negated under a difference's right side), its sizes and kind; a bounding-volume
hierarchy over the leaves' world boxes; a tree of at most TABLE_LEAVES (14) leaves as its
truth table (bit ``b``: the tree's value when the leaves inside are the bits of ``b``,
:func:`truth_table`); and the tree as a post-order program on a stack of bits with skip
records, for larger trees.

**A small tree (at most 14 leaves) is cast in one step.** Every leaf's runs along the
pixel's whole line are found at once and kept in registers; then, since each leaf occurs
once in the tree under an even or odd number of right operands of differences, the tree's
answer can only *rise* at an entry of a positive leaf or an exit of a negative one (and
only fall at the others): the surface is the nearest such boundary past the near plane
after which the table says the answer differs from the start's -- one candidate a leaf, two
for a torus, each a lookup, with the leaves' states at a candidate found by comparing it
with every run at once (ties by leaf order: the left operand's face shows). No loops: on a
SIMD rasteriser (llvmpipe runs 8 pixels in lock-step; an if's untaken side runs, masked,
and loops cost far more than straight code) that is what makes it fast. Its slots hold
the leaves in kind order and each slot's code is its kind's alone, so the program is keyed
by how many leaves of each kind the tree has (``TreeData.slots``): editing sizes, places or
operators reuses it; a tree with another count of a kind compiles once (about 0.3-0.7 s,
kept by Mesa's disk cache).

**A larger tree walks** from one leaf boundary to the next (the hierarchy, or each kind's
leaves in turn below 33 leaves, finding the next four boundaries in one pass), flipping
that leaf's bit and running the tree program (skipping subtrees the ray is in none of the
leaves of); the first boundary where its answer changes is the surface. Its cost grows
with the boundaries a ray crosses before its surface; one program per size class (32, 64,
256, 1,024 leaves) and set of kinds.

**Only pixels that may show the solid run the cast, each once.** A solid is drawn as a
screen polygon that holds it (solids/proxy.py: the 16-sided k-DOP of the projected hull of
its positive leaves, or of its box cut by the near plane, the smaller, cut to the screen),
so the camera may be inside it or not. For a small tree the vertex stage also gives each
pixel its ray in every slot's own frame: affine in the pixel's NDC, so interpolated exactly
(csg.vert), where the fragment stage would spend a matrix product a slot. The fragment
program writes the surface's depth to gl_FragDepth, so solids and meshes share one
z-buffer.

Measured on llvmpipe (the 7-leaf tree of benchmarks/csg_bench.py at 512x512, one thread,
CPU time): 7.8 ms a frame against 4.9 ms for its 5,218-triangle manifold3d mesh (the walk
this replaced: 24 ms; without the interpolated rays 9.8, drawn as its box 11.0).

Shading: the lighting function of the meshes with the exact normal at every pixel.
Gouraud and Phong both light per pixel (a solid has no vertices to hold an intensity);
flat gives each planar leaf face -- a box's faces, a cylinder's or a cone's caps -- one
intensity, lit at the face's centre as a mesh polygon is lit at its centroid, while curved
faces (and a half-space's unbounded plane) have no centre and stay lit per pixel;
``normals`` and ``depth`` show what they show for meshes.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import weakref

import numpy as np

from ..errors import SceneError
from ..solids import leaves as L  # (the leaves: L.Box ...)
from ..solids.proxy import DIRECTIONS, hull_points, screen_polygon
from ..solids.tree import Difference, Intersection, Solid, Transformed, Union, _corners
from ..geometry.transforms import gl_bytes
from ..modes import ShadingMode
from .base import GLResource
from .programs import MaterialUniforms, ProgramKey, UniformWriter
from .state import DrawState

__all__ = ["CsgPass", "TreeData", "tree_data", "may_start_inside", "MAX_LEAVES",
           "leaf_words", "truth_table"]

#: leaves a solid may have on the GPU (the program keeps one bit per leaf in 32 words)
MAX_LEAVES = 1024
#: the leaf kinds as the program numbers them (csg.glsl's leaf_contains)
_KIND_CODE: dict[type, int] = {L.Sphere: 0, L.Box: 1, L.Cylinder: 2, L.Cone: 3, L.Torus: 4,
                               L.HalfSpace: 5}
_UNION, _INTERSECTION, _DIFFERENCE, _DIFFERENCE_SWAPPED = -1, -2, -3, -4
_ROW = 64  # texels a row of the data texture
#: the programs' size classes: (leaves at most, words of leaf bits, vec4s of a uniform
#: block holding the data, or 0: a texture). 1,024 vec4s are the 16 KiB every GL 3.3 has.
_CLASSES = ((32, 1, 1024), (64, 2, 1024), (256, 8, 0), (1024, 32, 0))
_FAR = 1e30  # an unbounded leaf's box
#: trees of at most this many leaves carry their truth table (2^L bits, 16 to a component:
#: 256 texels at 14 leaves), so an event costs one lookup instead of a run of the program
TABLE_LEAVES = 14


@dataclass(frozen=True)
class TreeData:
    """A solid as the program reads it: ``texels (T, 4) float32`` and where each part
    starts. ``leaves`` in ``solid.leaves()`` order; ``stack`` the bits the program needs;
    ``kinds`` a bit per leaf kind present (the program is built with only those kinds' code);
    ``table`` the first texel of the truth table (-1: none, the tree is over TABLE_LEAVES);
    ``by_kind`` the first texel of the leaves listed kind by kind, ``kind_start`` (7,) where
    each kind's list starts; ``boxes (L, 2, 3)`` the leaves' world boxes (float64);
    ``hull (N, 3)`` world points whose convex hull holds the solid (solids/proxy.py), or
    None. A tree with a truth table is cast in one step by a program with ``slots``, the
    leaf kinds in kind order (4, 8 or 16; -1 an empty slot), whose uniforms these are:
    ``slot_leaf (S,)`` each slot's leaf (-1 empty), ``slot_rows (S, 4, 4)`` its world ->
    leaf rows and sizes, ``slot_sign (S,)`` +1 where it counts positively in the tree,
    ``slot_words`` the truth table in slot order, 32 bits a uint32 word; else () and None."""

    texels: np.ndarray
    leaves: int
    nodes: int
    ops: int
    bvh: int
    program: int
    records: int
    stack: int
    kinds: int
    by_kind: int
    kind_start: tuple
    boxes: np.ndarray
    table: int = -1
    slot_words: Any = None
    hull: Any = None
    slots: tuple = ()
    slot_leaf: Any = None
    slot_rows: Any = None
    slot_sign: Any = None


def _flatten(solid: Solid):
    """Leaves (with their world matrices and normal signs) and booleans, iteratively (no
    recursion limit): ``leaves`` [(leaf, matrix, sign)], ``ops`` {node id: (op, a, b)},
    ``root`` id; a node id is ("L", leaf number) or ("B", boolean number)."""
    leaves: list = []
    booleans: list = []
    root: list = []
    stack: list = [(solid, np.eye(4), 1.0, root, 0)]
    while stack:
        node, matrix, sign, slot, pos = stack.pop()
        while isinstance(node, Transformed):
            matrix = matrix @ node.matrix
            node = node.child
        if isinstance(node, (Union, Intersection, Difference)):
            entry = [type(node), None, None]
            booleans.append(entry)
            _put(slot, pos, ("B", len(booleans) - 1))
            sub = -sign if isinstance(node, Difference) else sign
            stack.append((node.b, matrix, sub, entry, 2))
            stack.append((node.a, matrix, sign, entry, 1))
        else:
            leaves.append((node, matrix, sign))
            _put(slot, pos, ("L", len(leaves) - 1))
    return leaves, booleans, root[0]


def _put(slot: list, pos: int, value) -> None:
    if pos == 0:
        slot.append(value)
    else:
        slot[pos] = value


def _program(booleans: list, root) -> tuple[np.ndarray, np.ndarray, int]:
    """The post-order program, deeper operand first: ``(program (M, 2): code and first skip
    record per position, records (B, 4): end position, first and last leaf, next record,
    stack depth)``. A boolean's subtree starts at a leaf's position; the records of the
    subtrees starting at one position, largest first, let the program skip a subtree none of
    whose leaves the ray is inside (its value is then 0: booleans of empty sets are empty)."""
    need: dict = {}
    for b in range(len(booleans) - 1, -1, -1):  # (children come after parents)
        _, a, c = booleans[b]
        na = need.get(a, 1) if a[0] == "B" else 1
        nc = need.get(c, 1) if c[0] == "B" else 1
        need[("B", b)] = max(na, nc) if na != nc else na + 1
    depth = lambda x: need[x] if x[0] == "B" else 1  # noqa: E731
    codes: list[int] = []
    span: dict = {}  # node -> (start position, first leaf, last leaf)
    starts: dict[int, list] = {}
    stack: list = [(root, False)]
    while stack:
        node, done = stack.pop()
        if node[0] == "L":
            span[node] = (len(codes), node[1], node[1])
            codes.append(node[1])
            continue
        op, a, b = booleans[node[1]]
        swapped = depth(b) > depth(a)
        if done:
            first = b if swapped else a
            lo = min(span[a][1], span[b][1])
            hi = max(span[a][2], span[b][2])
            span[node] = (span[first][0], lo, hi)
            starts.setdefault(span[first][0], []).append((len(codes), lo, hi))
            codes.append(_UNION if op is Union else _INTERSECTION if op is Intersection
                         else _DIFFERENCE_SWAPPED if swapped else _DIFFERENCE)
            continue
        stack.append((node, True))
        first, second = (b, a) if swapped else (a, b)
        stack.append((second, False))
        stack.append((first, False))
    program = np.full((len(codes), 2), -1.0)
    program[:, 0] = codes
    records: list[tuple] = []
    for pos, subtrees in starts.items():  # (one per boolean)
        subtrees.sort(key=lambda r: -r[0])  # the largest (latest end) first
        program[pos, 1] = len(records)
        for k, (end, lo, hi) in enumerate(subtrees):
            nxt = len(records) + 1 if k + 1 < len(subtrees) else -1
            records.append((end, lo, hi, nxt))
    return program, np.array(records, np.float64).reshape(-1, 4), need.get(root, 1)


def truth_table(program: np.ndarray, leaves: int) -> np.ndarray:
    """The tree's value (2^leaves,) bool for every pattern of leaf inside-bits (bit k of
    the index: inside leaf k), by running the post-order ``program`` on all of them at
    once -- the shader's tree_inside, as a table."""
    index = np.arange(2 ** leaves, dtype=np.int64)
    stack: list = []
    for code in program[:, 0].astype(int):
        if code >= 0:
            stack.append(((index >> code) & 1).astype(bool))
            continue
        x, y = stack.pop(), stack.pop()  # (x the later operand, on top)
        stack.append(x | y if code == _UNION else x & y if code == _INTERSECTION
                     else y & ~x if code == _DIFFERENCE else x & ~y)
    return stack[0]


def _table_texels(table: np.ndarray) -> np.ndarray:
    """A truth table as texels (T, 4): 16 bits a component (exact in float32 anywhere)."""
    bits = np.zeros(-(-len(table) // 64) * 64, bool)
    bits[:len(table)] = table
    chunks = (bits.reshape(-1, 16) << np.arange(16)).sum(1)
    return chunks.reshape(-1, 4).astype(np.float64)


def _slot_uniforms(values: np.ndarray, order: np.ndarray, codes: list, signs: np.ndarray,
                   leaf_rows: np.ndarray) -> dict:
    """The one-step program's uniforms (TreeData's ``slot_*`` and ``slots``) for a tree
    whose truth table is ``values`` (2^L,), its leaves in kind order ``order`` (L,) with
    kinds ``codes`` and signs ``signs`` (L,), ``leaf_rows`` (L, 8, 4) its leaves' texels."""
    leaves = len(order)
    n = next(n for n in (4, 8, 16) if n >= leaves)
    pad = n - leaves
    index = np.arange(len(values))  # (bit s of a slot pattern: the leaf in slot s)
    as_leaves = sum(((index >> s) & 1) << int(k) for s, k in enumerate(order))
    bits = np.zeros(-(-len(values) // 32) * 32, np.uint64)
    bits[:len(values)] = values[as_leaves]
    rows = np.zeros((n, 4, 4), "f4")
    rows[:leaves, :3] = leaf_rows[order, :3]
    rows[:leaves, 3] = leaf_rows[order, 6]
    return {"slots": tuple(sorted(codes)) + (-1,) * pad,
            "slot_leaf": np.r_[order, [-1] * pad].astype("f4"),
            "slot_rows": rows,
            "slot_sign": np.r_[signs[order], [0] * pad].astype("f4"),
            "slot_words": (bits.reshape(-1, 32) << np.arange(32, dtype=np.uint64)).sum(1)
            .astype(np.uint32)}


def _size_class(leaves: int) -> tuple[int, int, int]:
    return next(c for c in _CLASSES if c[0] >= leaves)


def leaf_words(leaves: int) -> int:
    """The words of leaf bits (``CSG_WORDS``) the program keeps for a tree of ``leaves``:
    its size class, for another program that includes csg.glsl (the path tracer)."""
    return _size_class(leaves)[1]


def _leaf_boxes(leaves: list, matrices: np.ndarray) -> np.ndarray:
    """World boxes (L, 2, 3) of leaves placed by ``matrices`` (L, 4, 4), padded for float32;
    an unbounded leaf (a half-space) gets the whole of space."""
    local = [leaf.bounds for leaf in leaves]
    bounded = np.array([b is not None for b in local])
    b = np.array([x if x is not None else np.zeros((2, 3)) for x in local])  # (L, 2, 3)
    corners = _corners(b[:, 0], b[:, 1])  # (L, 8, 3)
    c = np.einsum("lij,lkj->lki", matrices[:, :3, :3], corners) + matrices[:, None, :3, 3]
    lo, hi = c.min(1), c.max(1)
    pad = 1e-5 * (hi - lo) + 1e-6 * np.abs(c).max((1, 2))[:, None] + 1e-30
    out = np.stack([lo - pad, hi + pad], 1)
    out[~bounded] = [[-_FAR] * 3, [_FAR] * 3]
    return out


def _hierarchy(boxes: np.ndarray) -> np.ndarray:
    """A BVH over leaf boxes (N, 2, 3), pre-order: (nodes, 8) rows of lo, skip, hi, leaf."""
    rows: list = []
    centre = np.clip(boxes.mean(1), -_FAR, _FAR)
    work: list = [("open", np.arange(len(boxes)))]
    while work:
        what, item = work.pop()
        if what == "close":
            rows[item][3] = len(rows)
            continue
        idx = item
        lo, hi = boxes[idx, 0].min(0), boxes[idx, 1].max(0)
        me = len(rows)
        rows.append([*lo, me + 1, *hi, idx[0] if len(idx) == 1 else -1])
        if len(idx) == 1:
            continue
        c = centre[idx]
        axis = int(np.argmax(c.max(0) - c.min(0)))
        order = idx[np.argsort(c[:, axis], kind="stable")]
        half = len(order) // 2
        work.append(("close", me))
        work.append(("open", order[half:]))
        work.append(("open", order[:half]))
    return np.array(rows, np.float64)


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


def tree_data(solid: Solid) -> TreeData:
    """The texture data of ``solid`` (see the module docstring); a SceneError past
    MAX_LEAVES."""
    leaves, booleans, root = _flatten(solid)
    if len(leaves) > MAX_LEAVES:
        raise SceneError(f"a solid of {len(leaves):,} leaves is more than the {MAX_LEAVES:,} "
                         "the GPU program serves")
    program, records, stack = _program(booleans, root)
    matrices = np.array([m for _, m, _ in leaves])  # (L, 4, 4) leaf -> world
    inv = np.linalg.inv(matrices)
    signs = np.array([s for _, _, s in leaves])
    leaf_rows = np.zeros((len(leaves), 8, 4))
    leaf_rows[:, 0:3] = inv[:, :3]
    leaf_rows[:, 3:6, :3] = signs[:, None, None] * inv[:, :3, :3].transpose(0, 2, 1)
    leaf_rows[:, 6] = [_params(leaf) for leaf, _, _ in leaves]
    codes = [_KIND_CODE[type(leaf)] for leaf, _, _ in leaves]
    leaf_rows[:, 3, 3] = codes
    boxes = _leaf_boxes([leaf for leaf, _, _ in leaves], matrices)
    bvh = _hierarchy(boxes).reshape(-1, 2, 4)
    ops = np.zeros((len(program), 4))
    ops[:, :2] = program
    by_kind = np.zeros((len(leaves), 4))
    by_kind[:, 0] = np.argsort(codes, kind="stable")
    parts = [leaf_rows.reshape(-1, 4), bvh.reshape(-1, 4), ops, records, by_kind]
    table, slots = -1, {}
    if len(leaves) <= TABLE_LEAVES:
        table = sum(len(p) for p in parts)
        values = truth_table(program, len(leaves))
        parts.append(_table_texels(values))
        slots = _slot_uniforms(values, by_kind[:, 0].astype(int), codes, signs, leaf_rows)
    texels = np.concatenate(parts)
    texels = np.concatenate([texels, np.zeros((-len(texels) % _ROW, 4))])
    return TreeData(texels.astype(np.float32), len(leaves), len(bvh), len(program),
                    len(parts[0]), len(parts[0]) + len(parts[1]),
                    len(parts[0]) + len(parts[1]) + len(parts[2]), stack,
                    sum(1 << c for c in set(codes)), sum(len(p) for p in parts[:4]),
                    tuple(int(x) for x in np.searchsorted(np.sort(codes), np.arange(7))), boxes,
                    table, hull=hull_points(leaves), **slots)


class CsgPass(GLResource):
    """The programs (per shading variant and tree class, :meth:`program`), each solid's data
    texture, the screen polygon's buffer and the drawing of solids, for one Renderer: a GL
    owner of the renderer's context, released with it. Shares the renderer's uniform writer
    and material cache (public collaborators, handed in)."""

    #: the texture unit the tree data is bound to
    UNIT = 7

    def __init__(self, context, shaders, uniforms: UniformWriter,
                 materials: MaterialUniforms):
        super().__init__(context)
        self.shaders, self.uniforms, self.materials = shaders, uniforms, materials
        self._programs: dict = {}
        self._fan: Any = None  # (buffer of the screen polygon's corners, vertex arrays)
        # per solid (solids are values: a new tree is a new object): its data and texture,
        # dropped (and the texture released) once the solid is gone
        self._data: dict[int, tuple] = {}
        # the most slots the one-step cast may have here: each takes six interpolated
        # floats (csg.vert), and GL 3.3 promises only 60 (desktop drivers give 124-128);
        # a tree over it walks instead
        limit = context.ctx.info.get("GL_MAX_FRAGMENT_INPUT_COMPONENTS") or 60
        self.max_slots = max((n for n in (16, 8, 4) if 6 * n + 6 <= limit), default=0)

    def data(self, solid: Solid) -> tuple[TreeData, Any]:
        """(tree data, its texture or uniform buffer) of a solid, made once while it
        lives."""
        self._check()
        for key in [k for k, v in self._data.items() if v[0]() is None]:
            self._data.pop(key)[2].release()
        found = self._data.get(id(solid))
        if found is None or found[0]() is not solid:
            if found is not None:
                found[2].release()
            data = tree_data(solid)
            block = _size_class(data.leaves)[2]
            ctx = self.context.ctx
            if block:
                assert len(data.texels) <= block  # (16 L - 4 texels: 1,020 at 64 leaves)
                store = ctx.buffer(data.texels.tobytes().ljust(16 * block, b"\0"))
            else:
                store = ctx.texture((_ROW, len(data.texels) // _ROW), 4,
                                    data.texels.tobytes(), dtype="f4")
                store.filter = (0x2600, 0x2600)  # NEAREST (texelFetch reads it anyway)
            found = self._data[id(solid)] = (weakref.ref(solid), data, store)
        return found[1], found[2]

    def program(self, key, leaves: int, kinds: int = 63, slots: tuple = ()):
        """The program of a variant for a tree of ``leaves`` whose leaf kinds are the bits
        of ``kinds``: one per size class (32, 64, 256 or 1,024 leaves: the words of leaf bits
        it keeps) and set of kinds -- and for a tree cast in one step, per ``slots`` (its
        leaves' kinds in kind order, :class:`TreeData`), never per tree."""
        self._check()
        _, words, block = _size_class(leaves)
        found = self._programs.get((key, words, kinds, slots))
        if found is None:
            defines = (*key.defines(), f"CSG_WORDS {words}", f"CSG_KINDS {kinds}")
            if block:
                defines += (f"CSG_BLOCK {block}",)
            if slots:
                defines += (f"CSG_SLOTS {len(slots)}",
                            *(f"CSG_KIND_{i} {k}" for i, k in enumerate(slots)))
            if words == 1:
                defines += ("CSG_LEAF_LOOP",)
            if key.mode is ShadingMode.NORMALS:
                defines += ("SHOW_NORMALS",)
            elif key.mode is ShadingMode.DEPTH:
                defines += ("SHOW_DEPTH",)
            elif key.mode is ShadingMode.FLAT:
                defines += ("FLAT_FACES",)
            found = self.shaders.compile("csg.vert", "csg.frag", defines=defines)
            self._programs[(key, words, kinds, slots)] = found
        return found

    def fan(self, program, corners: np.ndarray):
        """The vertex array of a screen polygon (M, 2) NDC (M <= DIRECTIONS + 4), drawn as
        a fan."""
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
            data, texture = self.data(model.solid)
            slots = data.slots if len(data.slots) <= self.max_slots else ()
            prog = self.program(ProgramKey.of(state.variant, two_sided=False), data.leaves,
                                data.kinds, slots)
            for name, value in state.frame_uniforms:
                put(prog, name, value)
            for name, value in self.materials(model.material, state.lights,
                                              state.scene.ambient):
                put(prog, name, value)
            if _size_class(data.leaves)[2]:
                prog["CsgData"].binding = self.UNIT
                texture.bind_to_uniform_block(self.UNIT)
            else:
                texture.use(location=self.UNIT)
                put(prog, "u_csg", self.UNIT)
            put(prog, "u_csg_nodes", data.nodes)
            inverse = np.linalg.inv(view_proj)
            put(prog, "u_csg_start", data.nodes if may_start_inside(data, inverse) else 0)
            put(prog, "u_csg_ops", data.ops)
            put(prog, "u_csg_bvh", data.bvh)
            put(prog, "u_csg_program", data.program)
            put(prog, "u_csg_records", data.records)
            put(prog, "u_csg_kinds", data.by_kind)
            put(prog, "u_csg_table", data.table)
            if slots:
                put(prog, "u_csg_slot_leaf", data.slot_leaf)
                put(prog, "u_csg_slot", data.slot_rows)
                put(prog, "u_csg_slot_sign", data.slot_sign)
                put(prog, "u_csg_slot_table", data.slot_words)
            put(prog, "u_csg_kind_start", np.array(data.kind_start, "i4"))
            bounds = model.solid.bounds
            assert bounds is not None  # (Scene.add refuses unbounded solids)
            put(prog, "u_solid_view_proj", gl_bytes(view_proj))
            put(prog, "u_inverse_view_proj", gl_bytes(inverse))
            put(prog, "u_view", gl_bytes(view))
            put(prog, "u_view_normal", np.ascontiguousarray(view[:3, :3].T, "f4").tobytes())
            put(prog, "u_viewport_origin", (float(viewport[0]), float(viewport[1])))
            put(prog, "u_viewport_size", (float(viewport[2]), float(viewport[3])))
            put(prog, "u_face_id_base", n_polygons)
            # the screen polygon that holds the solid (solids/proxy.py): only its pixels run
            # the cast; one layer, so each pixel once, the camera inside the solid or out
            polygon = screen_polygon(view_proj, bounds, data.hull,
                                     (int(viewport[2]), int(viewport[3])))
            if len(polygon):
                ctx.disable(moderngl.CULL_FACE)
                self.fan(prog, polygon).render(moderngl.TRIANGLE_FAN)
                ctx.enable(moderngl.CULL_FACE)
            n_polygons += data.leaves

    def _release_extra(self) -> None:
        """The programs, textures and vertex arrays (the polygon's buffer is in
        ``_objects``)."""
        for p in self._programs.values():
            p.release()
        self._programs.clear()
        for _, _, tex in self._data.values():
            tex.release()
        self._data.clear()
        if self._fan is not None:
            for vao in self._fan[1].values():
                vao.release()
            self._fan = None


def may_start_inside(data: TreeData, inverse_view_proj: np.ndarray) -> bool:
    """Whether any leaf's world box meets the box of the near plane's rectangle (clip to
    world: ``inverse_view_proj``), where the pixels' rays start: where none does, no ray
    starts inside a leaf, and the program skips finding which leaves each starts in."""
    corners = np.array([[x, y, -1.0, 1.0] for x in (-1, 1) for y in (-1, 1)])
    world = corners @ inverse_view_proj.T
    near = world[:, :3] / world[:, 3:]
    lo, hi = near.min(0), near.max(0)
    return bool(((data.boxes[:, 0] <= hi) & (data.boxes[:, 1] >= lo)).all(1).any())
