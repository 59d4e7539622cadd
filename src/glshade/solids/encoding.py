"""A CSG tree as the arrays the GPU ray caster reads: the numpy half of the GL seam.

Why data, not code: generated GLSL (one merge function per node) made Mesa's compile time
grow with the tree -- 17 s at 16 leaves, a crash at 900. Here a solid becomes one float
texture (:func:`tree_data`): per leaf, its world -> leaf matrix, its normal matrix (negated
under a difference's right side), its sizes and kind; a bounding-volume hierarchy over the
leaves' world boxes; a tree of at most :data:`TABLE_LEAVES` leaves as its truth table (bit
``b``: the tree's value when the leaves inside are the bits of ``b``, :func:`truth_table`);
and the tree as a post-order program on a stack of bits with skip records, for larger
trees. :mod:`glshade.render.passes.csg` uploads it; ``shaders/include/csg/`` reads it, with
the kind and opcode numbers injected from :class:`LeafKind` and :class:`Op` (never written
twice). Everything here is pure numpy and tested on its public names against the tree's own
membership test (:meth:`Solid.contains`).

**A small tree (at most TABLE_LEAVES leaves) is cast in one step.** Every leaf's runs along
the pixel's whole line are found at once and kept in registers; since each leaf occurs once
in the tree under an even or odd number of right operands of differences, the tree's answer
can only *rise* at an entry of a positive leaf or an exit of a negative one: the surface is
the nearest such boundary past the near plane after which the truth table says the answer
differs from the start's -- one candidate a leaf (two for a torus), each a lookup, ties by
leaf order (the left operand's face shows). No loops: on a SIMD rasteriser (llvmpipe runs 8
pixels in lock-step and an if's untaken side runs masked) that is what makes it fast. The
slots hold the leaves in kind order (``TreeData.slots``), so a program serves every tree
with the same count of leaves of each kind.

**A larger tree walks** from one leaf boundary to the next (the hierarchy, or each kind's
leaves in turn below 33 leaves, finding the next four boundaries in one pass), flipping that
leaf's bit and running the post-order program (skipping subtrees the ray is in none of the
leaves of); the first boundary where its answer changes is the surface.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import IntEnum
from typing import Any

import numpy as np

from ..errors import SceneError
from ..geometry.transforms import box_corners
from . import leaves as L
from .proxy import hull_points
from .tree import Difference, Intersection, Solid, Transformed, Union

__all__ = ["LeafKind", "Op", "TreeData", "tree_data", "flatten", "postorder", "truth_table",
           "size_class", "leaf_words", "may_start_inside", "glsl_defines", "MAX_LEAVES",
           "TABLE_LEAVES", "ROW"]

#: leaves a solid may have on the GPU (the program keeps one bit per leaf in 32 words)
MAX_LEAVES = 1024
#: trees of at most this many leaves carry their truth table (2^L bits, 16 to a component:
#: 256 texels at 14 leaves), so an event costs one lookup instead of a run of the program
TABLE_LEAVES = 14
#: texels a row of the data texture
ROW = 64
_FAR = 1e30  # an unbounded leaf's box
#: the programs' size classes: (leaves at most, words of leaf bits, vec4s of a uniform
#: block holding the data, or 0: a texture). 1,024 vec4s are the 16 KiB every GL 3.3 has.
_CLASSES = ((32, 1, 1024), (64, 2, 1024), (256, 8, 0), (1024, 32, 0))


class LeafKind(IntEnum):
    """A leaf's kind as the GLSL program numbers it (``LEAF_SPHERE`` ...); also its bit in
    ``TreeData.kinds`` and its order in the one-step cast's slots."""

    SPHERE = 0
    BOX = 1
    CYLINDER = 2
    CONE = 3
    TORUS = 4
    HALFSPACE = 5

    @classmethod
    def of(cls, leaf) -> LeafKind:
        """The kind of a leaf.

        Parameters
        ----------
        leaf : Solid
            A leaf (Sphere, Box ...).
        """
        return _KINDS[type(leaf)]


_KINDS = {L.Sphere: LeafKind.SPHERE, L.Box: LeafKind.BOX, L.Cylinder: LeafKind.CYLINDER,
          L.Cone: LeafKind.CONE, L.Torus: LeafKind.TORUS, L.HalfSpace: LeafKind.HALFSPACE}


class Op(IntEnum):
    """A boolean in the post-order program (``OP_UNION`` ... in GLSL); a leaf's code is its
    number (>= 0). ``DIFFERENCE_SWAPPED``: ``b - a`` with the operands pushed deeper first."""

    UNION = -1
    INTERSECTION = -2
    DIFFERENCE = -3
    DIFFERENCE_SWAPPED = -4


def glsl_defines() -> tuple[str, ...]:
    """``#define`` bodies for every constant the CSG GLSL shares with this module."""
    return (*(f"LEAF_{k.name} {k.value}" for k in LeafKind),
            *(f"OP_{o.name} ({o.value})" for o in Op), f"CSG_ROW {ROW}")


@dataclass(frozen=True)
class TreeData:
    """A solid as the program reads it (a tree with a truth table is cast in one step by a
    program with ``slots``, the leaf kinds in kind order; else the ``slot_*`` are () and
    None).

    Parameters
    ----------
    texels : ndarray
        ``(T, 4)`` float32: everything the program reads.
    leaves, nodes, ops : int
        The counts of leaves (in ``solid.leaves()`` order), hierarchy nodes and program
        operations.
    bvh, program, records : int
        The first texel of the hierarchy, the post-order program and its skip records.
    stack : int
        The bits the program needs.
    kinds : int
        A bit per :class:`LeafKind` present (the program has only those kinds' code).
    by_kind : int
        The first texel of the leaves listed kind by kind.
    kind_start : tuple
        ``(7,)`` where each kind's list starts.
    boxes : ndarray
        ``(L, 2, 3)`` the leaves' world boxes (float64).
    table : int
        The first texel of the truth table (-1: none, the tree is over TABLE_LEAVES).
    hull : ndarray or None
        ``(N, 3)`` world points whose convex hull holds the solid (solids/proxy.py).
    slots : tuple
        The one-step cast's leaf kinds by slot (4, 8 or 16; -1 an empty slot).
    slot_leaf : ndarray or None
        ``(S,)`` each slot's leaf (-1 empty).
    slot_rows : ndarray or None
        ``(S, 4, 4)`` each slot's world -> leaf rows and sizes.
    slot_sign : ndarray or None
        ``(S,)`` +1 where the slot counts positively in the tree.
    slot_words : ndarray or None
        The truth table in slot order, 32 bits a uint32 word.
    """

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
    hull: Any = None
    slots: tuple = ()
    slot_leaf: Any = None
    slot_rows: Any = None
    slot_sign: Any = None
    slot_words: Any = None

    def offsets(self) -> dict[str, int]:
        """The ``u_csg_*`` integer uniforms: the counts and where each table starts."""
        return {"u_csg_nodes": self.nodes, "u_csg_ops": self.ops, "u_csg_bvh": self.bvh,
                "u_csg_program": self.program, "u_csg_records": self.records,
                "u_csg_kinds": self.by_kind, "u_csg_table": self.table}


def flatten(solid: Solid) -> tuple[list, list, tuple]:
    """Leaves (with their world matrices and normal signs) and booleans, iteratively (no
    recursion limit): ``leaves`` [(leaf, matrix (4, 4), sign +-1)], ``booleans``
    [[type, a, b]], ``root``; a node is ("L", leaf number) or ("B", boolean number).

    Parameters
    ----------
    solid : Solid
        The solid.
    """
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


def _stack_needs(booleans: list, root) -> dict:
    """Stack depth (Sethi-Ullman number) of each boolean, children before parents."""
    need: dict = {}
    for b in range(len(booleans) - 1, -1, -1):  # (children come after parents)
        _, a, c = booleans[b]
        na = need.get(a, 1) if a[0] == "B" else 1
        nc = need.get(c, 1) if c[0] == "B" else 1
        need[("B", b)] = max(na, nc) if na != nc else na + 1
    return need


def postorder(booleans: list, root) -> tuple[np.ndarray, np.ndarray, int]:
    """The post-order program, deeper operand first: ``(program (M, 2): code (a leaf, or an
    :class:`Op`) and first skip record per position, records (B, 4): end position, first
    and last leaf, next record; stack depth)``. A boolean's subtree starts at a leaf's
    position; the records of the subtrees starting at one position, largest first, let the
    program skip a subtree none of whose leaves the ray is inside (its value is then 0:
    booleans of empty sets are empty).

    Parameters
    ----------
    booleans : list
        The tree's booleans (:func:`flatten`).
    root : tuple
        The root's slot.
    """
    need = _stack_needs(booleans, root)
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
            codes.append(Op.UNION if op is Union else Op.INTERSECTION if op is Intersection
                         else Op.DIFFERENCE_SWAPPED if swapped else Op.DIFFERENCE)
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
    once -- the shader's tree_inside, as a table.

    Parameters
    ----------
    program : ndarray
        ``(M, 2)`` the post-order program.
    leaves : int
        The leaves.
    """
    index = np.arange(2 ** leaves, dtype=np.int64)
    stack: list = []
    for code in program[:, 0].astype(int):
        if code >= 0:
            stack.append(((index >> code) & 1).astype(bool))
            continue
        x, y = stack.pop(), stack.pop()  # (x the later operand, on top)
        stack.append(x | y if code == Op.UNION else x & y if code == Op.INTERSECTION
                     else y & ~x if code == Op.DIFFERENCE else x & ~y)
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


def size_class(leaves: int) -> tuple[int, int, int]:
    """(leaves at most, words of leaf bits, uniform-block vec4s or 0) of a tree's program.

    Parameters
    ----------
    leaves : int
        The tree's leaves.
    """
    return next(c for c in _CLASSES if c[0] >= leaves)


def leaf_words(leaves: int) -> int:
    """The words of leaf bits (``CSG_WORDS``) the program keeps for a tree of ``leaves``.

    Parameters
    ----------
    leaves : int
        The tree's leaves.
    """
    return size_class(leaves)[1]


def _leaf_boxes(leaves: list, matrices: np.ndarray) -> np.ndarray:
    """World boxes (L, 2, 3) of leaves placed by ``matrices`` (L, 4, 4), padded for float32;
    an unbounded leaf (a half-space) gets the whole of space."""
    local = [leaf.bounds for leaf in leaves]
    bounded = np.array([b is not None for b in local])
    b = np.array([x if x is not None else np.zeros((2, 3)) for x in local])  # (L, 2, 3)
    corners = box_corners(b)  # (L, 8, 3)
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
    """A leaf's sizes as its texel 6 holds them."""
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


def _leaf_rows(leaves: list) -> np.ndarray:
    """Each leaf's eight texels (L, 8, 4): world -> leaf rows 0-2, normal matrix rows 3-5
    (its kind in 3.w), sizes in 6."""
    matrices = np.array([m for _, m, _ in leaves])  # (L, 4, 4) leaf -> world
    inv = np.linalg.inv(matrices)
    signs = np.array([s for _, _, s in leaves])
    rows = np.zeros((len(leaves), 8, 4))
    rows[:, 0:3] = inv[:, :3]
    rows[:, 3:6, :3] = signs[:, None, None] * inv[:, :3, :3].transpose(0, 2, 1)
    rows[:, 6] = [_params(leaf) for leaf, _, _ in leaves]
    rows[:, 3, 3] = [LeafKind.of(leaf) for leaf, _, _ in leaves]
    return rows


def tree_data(solid: Solid) -> TreeData:
    """The texture data of ``solid`` (see the module docstring); a SceneError past
    MAX_LEAVES.

    Parameters
    ----------
    solid : Solid
        The solid.
    """
    leaves, booleans, root = flatten(solid)
    if len(leaves) > MAX_LEAVES:
        raise SceneError(f"a solid of {len(leaves):,} leaves is more than the {MAX_LEAVES:,} "
                         "the GPU program serves")
    program, records, stack = postorder(booleans, root)
    matrices = np.array([m for _, m, _ in leaves])
    signs = np.array([s for _, _, s in leaves])
    leaf_rows = _leaf_rows(leaves)
    codes = [int(LeafKind.of(leaf)) for leaf, _, _ in leaves]
    boxes = _leaf_boxes([leaf for leaf, _, _ in leaves], matrices)
    bvh = _hierarchy(boxes).reshape(-1, 2, 4)
    ops = np.zeros((len(program), 4))
    ops[:, :2] = program
    by_kind = np.zeros((len(leaves), 4))
    by_kind[:, 0] = np.argsort(codes, kind="stable")
    parts = [leaf_rows.reshape(-1, 4), bvh.reshape(-1, 4), ops, records, by_kind]
    starts = np.cumsum([0] + [len(p) for p in parts])
    table, slots = -1, {}
    if len(leaves) <= TABLE_LEAVES:
        table = int(starts[-1])
        values = truth_table(program, len(leaves))
        parts.append(_table_texels(values))
        slots = _slot_uniforms(values, by_kind[:, 0].astype(int), codes, signs, leaf_rows)
    texels = np.concatenate(parts)
    texels = np.concatenate([texels, np.zeros((-len(texels) % ROW, 4))])
    return TreeData(
        texels=texels.astype(np.float32), leaves=len(leaves), nodes=len(bvh),
        ops=len(program), bvh=int(starts[1]), program=int(starts[2]),
        records=int(starts[3]), stack=stack, kinds=sum(1 << c for c in set(codes)),
        by_kind=int(starts[4]),
        kind_start=tuple(int(x) for x in np.searchsorted(np.sort(codes), np.arange(7))),
        boxes=boxes, table=table, hull=hull_points(leaves), **slots)


def may_start_inside(data: TreeData, inverse_view_proj: np.ndarray) -> bool:
    """Whether any leaf's world box meets the box of the near plane's rectangle (clip to
    world: ``inverse_view_proj`` (4, 4)), where the pixels' rays start: where none does, no
    ray starts inside a leaf, and the program skips finding which leaves each starts in.

    Parameters
    ----------
    data : TreeData
        The tree.
    inverse_view_proj : ndarray
        ``(4, 4)`` clip to world.
    """
    corners = np.array([[x, y, -1.0, 1.0] for x in (-1, 1) for y in (-1, 1)])
    world = corners @ inverse_view_proj.T
    near = world[:, :3] / world[:, 3:]
    lo, hi = near.min(0), near.max(0)
    return bool(((data.boxes[:, 0] <= hi) & (data.boxes[:, 1] >= lo)).all(1).any())
