"""The tie rule (solids/tree.py TIE) over random CSG trees built to have coincident and
tangent faces -- boxes with corners on a half-unit lattice, balls and cylinders on it --
under random rigid poses and eyes outside and inside (hypothesis, derandomized in CI).

The oracle shares nothing with the code under test: a membership ray cast (``contains`` at
points marched along each pixel's ray, the change bracketed and bisected in float64), so
on a face two leaves share it sees what the solid is on either side, never which leaf's
rounding came first. Against it, outside the silhouette band: the GPU's one-step cast, the
GPU's walk and the numpy reference (Roth's event lists) give the same first surface, and
the two GPU casts show the reference's leaf wherever it shows one. Before the rule, a box
minus a box sharing its faces showed the whole box (the reference too), and the GPU
speckled between leaves."""

import numpy as np
import pytest

from tests.conftest import require

require("hypothesis", "property-based sweeps are part of the test extra")
from hypothesis import example, given, settings, strategies as st  # noqa: E402

import glshade  # noqa: E402
from glshade.cpu.csg import render_solids  # noqa: E402
from glshade.solids import Box, Cylinder, Sphere  # noqa: E402

from .test_csg import away_from_silhouettes  # noqa: E402

pytestmark = [pytest.mark.gl, pytest.mark.once,
              pytest.mark.filterwarnings("ignore::glshade.RenderWarning")]

W, H = 64, 48

lattice = st.integers(-2, 2).map(lambda i: 0.5 * i)


@st.composite
def leaves(draw):
    """(kind, sizes, centre): a box (full sizes), a ball (radius) or a cylinder (radius,
    height) on the lattice."""
    kind = draw(st.sampled_from(["box", "box", "box", "ball", "cylinder"]))
    centre = np.array([draw(lattice) for _ in range(3)])
    if kind == "box":
        size = np.array([draw(st.integers(1, 4)) * 0.5 for _ in range(3)])
        return kind, size, centre + size / 2 * (draw(st.booleans()) - 0.5)
    if kind == "ball":
        return kind, np.array([draw(st.sampled_from([0.5, 1.0]))]), centre
    return kind, np.array([0.5, draw(st.sampled_from([1.0, 2.0]))]), centre


unit = st.floats(-1, 1)
quaternions = st.tuples(unit, unit, unit, unit).filter(lambda q: np.linalg.norm(q) > 0.2)
directions = st.tuples(unit, unit, unit).filter(lambda v: np.linalg.norm(v) > 0.3)
trees = st.tuples(st.lists(leaves(), min_size=2, max_size=5),
                  st.lists(st.sampled_from("|&-"), min_size=4, max_size=4))


def build(specs, ops, rotation, shift):
    """The tree ``((l0 op0 l1) op1 l2) ...``, rotated (3x3) and moved."""
    q = glshade.quaternion.from_matrix(rotation)
    made = [(Box(size) if kind == "box" else Sphere(size[0]) if kind == "ball"
             else Cylinder(*size)).translated(centre) for kind, size, centre in specs]
    solid = made[0]
    for other, op in zip(made[1:], ops):
        solid = solid | other if op == "|" else solid & other if op == "&" else solid - other
    return solid.rotated(q).translated(shift)


def candidates(specs, o, d):
    """(rays, C) every t where a ray crosses a leaf's surface (inf: not), in closed form in
    each leaf's frame (the leaves' own code is not used): box faces, ball, a cylinder's
    side and caps."""
    out = []

    def on(t, keep):
        out.append(np.where(keep & np.isfinite(t), t, np.inf))

    for kind, size, centre in specs:
        lo, ld = o - centre, d
        with np.errstate(divide="ignore", invalid="ignore"):
            if kind == "box":
                half = size / 2
                for axis in range(3):
                    rest = [a for a in range(3) if a != axis]
                    for side in (-1, 1):
                        t = (side * half[axis] - lo[:, axis]) / ld[:, axis]
                        p = lo + t[:, None] * ld
                        on(t, (np.abs(p[:, rest]) <= half[rest] * (1 + 1e-9)).all(1))
                continue
            if kind == "ball":
                a, b, c = (ld * ld).sum(1), 2 * (lo * ld).sum(1), (lo * lo).sum(1) - size[0] ** 2
            else:
                r, h = size[0], size[1] / 2
                for side in (-1, 1):
                    t = (side * h - lo[:, 1]) / ld[:, 1]
                    p = lo + t[:, None] * ld
                    on(t, p[:, 0] ** 2 + p[:, 2] ** 2 <= r * r * (1 + 1e-9))
                xz = [0, 2]
                a = (ld[:, xz] ** 2).sum(1)
                b = 2 * (lo[:, xz] * ld[:, xz]).sum(1)
                c = (lo[:, xz] ** 2).sum(1) - r * r
            root = np.sqrt(b * b - 4 * a * c)
            for t in ((-b - root) / (2 * a), (-b + root) / (2 * a)):
                p = lo + np.nan_to_num(t)[:, None] * ld
                on(t, True if kind == "ball" else np.abs(p[:, 1]) <= size[1] / 2 * (1 + 1e-9))
    return np.stack(out, 1)


def membership_depth(specs, solid, rotation, shift, camera):
    """(H, W) view depth of the first place past the near plane after which ``contains``
    differs from the ray's start (inf: none): the closed-form candidates sorted, those
    within the tie rule's length of the one before taken as one place, ``contains`` tested
    at the middle of every gap between places."""
    o, d = camera.rays((W, H))
    o, d = o.reshape(-1, 3), d.reshape(-1, 3)
    cosf = d @ camera.forward
    t_near = camera.near / cosf                      # (the rays start at the eye)
    lo, hi = solid.bounds
    centre, reach = (lo + hi) / 2, np.linalg.norm(hi - lo) / 2
    start = o + t_near[:, None] * d
    tie = 2.0 ** -16 * (reach + np.linalg.norm(start - centre, axis=1))
    o_l, d_l = (o - shift) @ rotation, d @ rotation  # (into the tree's frame: rigid)
    t = candidates(specs, o_l, d_l)
    t = np.sort(np.where(t > t_near[:, None], t, np.inf), 1)
    n = len(o)
    with np.errstate(invalid="ignore"):  # (inf - inf past the last)
        gap = np.diff(t, axis=1) > tie[:, None]
    place = np.c_[np.ones((n, 1), bool), gap] & np.isfinite(t)
    # the middle of each gap after a place: halfway to the next place (or 1 past the last)
    width = t.shape[1]
    idx = np.where(place, np.arange(width), width)
    after = np.minimum.accumulate(idx[:, ::-1], 1)[:, ::-1]   # the first place at or after
    following = np.c_[after[:, 1:], np.full((n, 1), width)]    # ... strictly after
    nxt = np.take_along_axis(np.c_[t, np.full((n, 1), np.inf)], following, 1)
    mid = np.where(np.isfinite(nxt), (t + nxt) / 2, t + 1.0)
    mid = np.where(place, mid, np.nan)
    inside0 = solid.contains(start)
    points = o[:, None] + np.nan_to_num(mid)[..., None] * d[:, None]
    inside = solid.contains(points.reshape(-1, 3)).reshape(t.shape)
    change = place & (inside != inside0[:, None])
    first = np.argmax(change, 1)
    hit = change.any(1)
    depth = np.where(hit, t[np.arange(n), first], np.inf) * cosf
    return depth.reshape(H, W)


def smooth(depth):
    """Pixels whose 3x3 neighbourhood all hit or all miss, with no step: along each of the
    four lines through the pixel, the second difference of depth within 2% of it (planes
    seen at a grazing angle change depth fast, but evenly)."""
    hit = np.isfinite(depth)
    z = np.pad(np.where(hit, depth, 0.0), 1, mode="edge")
    h = np.pad(hit, 1, mode="edge")
    at = lambda dy, dx: (z[1 + dy:1 + dy + H, 1 + dx:1 + dx + W],  # noqa: E731
                         h[1 + dy:1 + dy + H, 1 + dx:1 + dx + W])
    c, _ = at(0, 0)
    ok = np.ones_like(hit)
    for dy, dx in ((0, 1), (1, 0), (1, 1), (1, -1)):
        (a, ha), (b, hb) = at(dy, dx), at(-dy, -dx)
        ok &= (ha == hit) & (hb == hit)
        ok &= ~hit | (np.abs(a + b - 2 * c) <= 0.02 * c)
    return ok


def agree(depth, want, ok, tie):
    """Pixels of ``ok`` where ``depth`` hits as ``want`` does, within 1e-3 relative (float32
    at grazing angles) and twice the tie rule's length (a group of tied boundaries is as
    deep as any of them)."""
    same_hit = np.isfinite(depth) == np.isfinite(want)
    both = np.isfinite(depth) & np.isfinite(want)
    close = np.ones_like(ok)
    close[both] = np.abs(depth[both] - want[both]) <= 1e-3 * want[both] + 2 * tie
    return ok & same_hit & close


@settings(max_examples=150, deadline=None)
@given(tree=trees, q=quaternions, shift=st.tuples(unit, unit, unit), look=directions,
       distance=st.sampled_from([0.0, 0.3, 2.0, 3.5]))
@example(tree=([("box", np.array([2.0, 2, 2]), np.zeros(3)),
                ("box", np.array([1.0, 2, 2]), np.array([0.5, 0, 0]))], ["-"] * 4),
         q=(0.3, 0.5, 0.1, 0.8), shift=(0, 0, 0), look=(0.6, 0.45, 0.7), distance=3.5)
@example(tree=([("box", np.array([2.0, 2, 2]), np.zeros(3)),
                ("box", np.array([2.0, 2, 1]), np.array([0, 0, 0.5]))], ["|"] * 4),
         q=(0.3, 0.5, 0.1, 0.8), shift=(0, 0, 0), look=(0.6, 0.45, 0.7), distance=3.5)
# a zero-thickness intersection (two boxes that touch along a face) seen at grazing rays:
# the face, computed in the two boxes' frames, came apart by more than the tie's length
@example(tree=([("box", np.array([0.5, 0.5, 0.5]), np.full(3, -0.125)),
                ("box", np.array([0.5, 0.5, 0.5]), np.full(3, -0.125)),
                ("box", np.array([0.5, 0.5, 1.0]), np.array([0.125, 0.125, -0.25])),
                ("box", np.array([0.5, 0.5, 1.0]), np.array([0.125, 0.125, 0.75]))],
               ["|", "|", "&", "|"]),
         q=(0.5, 0.0, 0.0, 1.0), shift=(0, 0, 0), look=(1.0, 0.0, 0.0625), distance=0.3)
# a box's face met by a cylinder's side at a grazing angle: a plane and a curved surface
# keep the plain tie (the reference's), so the surface is the cylinder's
@example(tree=([("box", np.array([0.5, 0.5, 1.0]), np.array([-0.125, -0.125, -0.25])),
                ("box", np.array([0.5, 0.5, 0.5]), np.array([-0.125, 0.375, 0.375])),
                ("box", np.array([2.0, 0.5, 0.5]), np.array([0.0, -0.125, -0.125])),
                ("cylinder", np.array([0.5, 1.0]), np.array([-0.5, 0.0, 0.0]))],
               ["|", "|", "&", "|"]),
         q=(0.0, 0.15625, -0.5, -0.25), shift=(0, 0, 0), look=(0.0, -1.0, 0.0), distance=2.0)
# a cylinder's flat end and a box's face that cross, both seen at a grazing angle near
# their common line: not one plane, so apart (the nearer leaf is the surface)
@example(tree=([("ball", np.array([0.5]), np.zeros(3)), ("ball", np.array([0.5]), np.zeros(3)),
                ("cylinder", np.array([0.5, 2.0]), np.zeros(3)),
                ("ball", np.array([0.5]), np.array([0.5, 0.0, 0.0])),
                ("box", np.array([1.0, 2.0, 1.5]), np.array([-0.25, 0.5, -0.375]))],
               ["|", "&", "|", "|"]),
         q=(0.0625, 0.0, -1.0, 0.40625), shift=(0, 0, 0), look=(0.03125, 0.75, -0.875),
         distance=0.0)
def test_coincident_faces_follow_one_rule(gl_context, tree, q, shift, look, distance):
    check(gl_context, tree, q, shift, look, distance)


@pytest.mark.parametrize("op", ["-", "|", "&"])
def test_the_sweep_compares_most_pixels(gl_context, op):
    """A box and a box sharing three faces, turned: the sweep's comparison covers most of
    the solid's pixels (outside its silhouette band and creases)."""
    tree = ([("box", np.array([2.0, 2, 2]), np.zeros(3)),
             ("box", np.array([1.0, 2, 2]), np.array([0.5, 0, 0]))], [op] * 4)
    compared, hits = check(gl_context, tree, (0.3, 0.5, 0.1, 0.8), (0, 0, 0),
                           (0.6, 0.45, 0.7), 2.0)
    assert compared >= 0.6 * hits and hits > 250


def check(gl_context, tree, q, shift, look, distance):
    """Assert the three casts agree with the oracle; (pixels compared, pixels hit)."""
    specs, ops = tree
    rotation = glshade.quaternion.to_matrix(np.asarray(q) / np.linalg.norm(q))
    shift = np.asarray(shift, float)
    solid = build(specs, ops, rotation, shift)
    lo, hi = solid.bounds
    centre = (lo + hi) / 2
    look = np.asarray(look) / np.linalg.norm(look)
    reach = np.linalg.norm(hi - lo) / 2
    eye = centre + distance * reach * look   # (0 and 0.3 of its reach: inside its box)
    up = (0, 1, 0) if abs(look[1]) < 0.9 else (1, 0, 0)
    camera = glshade.Camera.look_at(eye, eye - look, up=up, fov_y=50, near=1e-2, far=30)
    scene = glshade.Scene()
    scene.add(solid)
    want = membership_depth(specs, solid, rotation, shift, camera)
    ok = smooth(want)
    tie = 2.0 ** -16 * reach * (1 + distance)
    ref_depth, _, ref_ids = render_solids(scene, camera, (W, H))
    bad = ok & ~agree(ref_depth, want, ok, tie)
    assert bad.sum() == 0, f"the numpy reference misses the oracle at {bad.sum()} pixels"
    with glshade.Renderer(W, H, samples=0, context=gl_context) as renderer:
        for slots in (16, 0):           # the one-step cast, then the walk
            renderer.csg.max_slots = slots
            frame = renderer.render_frame(scene, camera, "phong")
            bad = ok & ~agree(np.where(frame.face_id >= 0, frame.depth, np.inf), want, ok, tie)
            assert bad.sum() == 0, (f"{'one-step' if slots else 'walk'}: {bad.sum()} of "
                                    f"{ok.sum()} pixels differ from the oracle")
            same = ok & away_from_silhouettes(ref_ids) & (ref_ids >= 0)
            wrong = same & (frame.face_id != ref_ids)
            assert wrong.sum() == 0, (f"{'one-step' if slots else 'walk'}: {wrong.sum()} "
                                      f"pixels show another leaf than the reference's")
    return int((ok & np.isfinite(want)).sum()), int(np.isfinite(want).sum())
