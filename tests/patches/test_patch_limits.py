"""Patches refuse what no tessellation can use, in one line naming the patch and the rule,
and a rational patch is the same surface whatever scale its weights have (hypothesis,
derandomized in CI): a quarter circle as a rational quadratic puts every point at radius 1
within 1e-12, its weights scaled by anything from 1e-300 to 1e300."""

import numpy as np
import pytest

from tests.conftest import require

from glshade.errors import GeometryError
from glshade.patches import PatchSet, tessellate
from glshade.patches.bezier import MAX_COORDINATE, MAX_DEGREE, MAX_WEIGHT_RATIO

require("hypothesis", "property-based sweeps are part of the test extra")
from hypothesis import given, settings, strategies as st  # noqa: E402

NET = np.random.default_rng(0).random((2, 3, 3, 3))


@pytest.mark.parametrize("args, words", [
    ((np.zeros((0, 3, 3, 3)),), "at least one patch"),
    ((NET, np.ones(5)), "one per control point"),
    ((NET, np.r_[np.ones(17), -1.0]), "patch 1: weights must be positive"),
    ((NET, np.r_[np.ones(9), 1.0, np.full(8, 1e13)]), "patch 1: weights span"),
    ((np.zeros((1, MAX_DEGREE + 2, 2, 3)),), f"limit of {MAX_DEGREE}"),
    ((NET * [1, 1, 2 * MAX_COORDINATE],), "patch 0: a control point coordinate"),
    ((np.where(NET > 0.99, np.nan, NET),), "finite"),
])
def test_refusals_name_the_patch_and_the_rule(args, words):
    with pytest.raises(GeometryError, match=words) as info:
        PatchSet(*args)
    assert "\n" not in str(info.value)
    assert MAX_WEIGHT_RATIO >= 1e6


def _quarter_circle_strip(scale: float) -> PatchSet:
    """The quarter circle of radius 1 in the xz plane (the rational quadratic with middle
    weight 1/sqrt 2), swept along y: a (2, 1) patch."""
    ring = np.array([[1.0, 0, 0], [1.0, 0, 1.0], [0, 0, 1.0]])
    points = np.stack([ring, ring + [0, 1.0, 0]], 1)[None]  # (1, 3, 2, 3)
    w = np.array([1.0, np.sqrt(0.5), 1.0])[:, None].repeat(2, 1)[None] * scale
    return PatchSet(points, w)


@settings(max_examples=30)
@given(exponent=st.floats(-300, 300), level=st.integers(1, 24))
def test_a_rational_circle_stays_a_circle_at_any_weight_scale(exponent, level):
    mesh = tessellate(_quarter_circle_strip(10.0 ** exponent), level=level).mesh
    radius = np.hypot(mesh.vertices[:, 0], mesh.vertices[:, 2])
    assert np.isfinite(mesh.vertices).all()
    assert np.abs(radius - 1).max() < 1e-12


def _sphere_octant(scale: float, rotation: np.ndarray) -> PatchSet:
    """An eighth of the unit sphere as one rational biquadratic patch: the quarter-circle
    meridian (equator at u = 0 to the pole at u = 1) swept a quarter turn about y, so the
    whole u = 1 side collapses to the pole."""
    s = np.sqrt(0.5)
    meridian = np.array([[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])   # (r, y)
    turn = np.array([[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])       # (x, z) per unit r
    w1 = np.array([1.0, s, 1.0])
    points = np.zeros((3, 3, 3))
    for i in range(3):
        for j in range(3):
            r, y = meridian[i]
            points[i, j] = [r * turn[j, 0], y, r * turn[j, 1]]
    return PatchSet((points @ rotation.T)[None], (np.outer(w1, w1) * scale)[None])


@settings(max_examples=40)
@given(exponent=st.floats(-300, 300), level=st.integers(1, 24),
       raise_by=st.tuples(st.integers(0, 6), st.integers(0, 6)),
       q=st.tuples(*[st.floats(-1, 1)] * 4).filter(lambda q: np.linalg.norm(q) > 0.2))
def test_a_sphere_octant_with_a_collapsed_side_is_exact(exponent, level, raise_by, q):
    """A patch with a collapsed side (a pole), at any weight scale, degree (elevated up to
    +6 each way) and pose: every tessellated vertex on the unit sphere within 1e-12, and
    every normal -- the pole's included, where Su x Sv vanishes and the limit is taken --
    radial within 1e-9 (the closed form: a sphere's normal is its point)."""
    from glshade.quaternion import to_matrix

    rotation = to_matrix(np.asarray(q) / np.linalg.norm(q))
    patch = _sphere_octant(10.0 ** exponent, rotation)
    patch = patch.elevated(2 + raise_by[0], 2 + raise_by[1])
    mesh = tessellate(patch, level=level).mesh
    assert np.isfinite(mesh.vertices).all()
    assert np.abs(np.linalg.norm(mesh.vertices, axis=1) - 1).max() < 1e-12
    g = np.linspace(0, 1, level + 1)
    u, v = np.meshgrid(g, g, indexing="ij")
    points = patch.evaluate(u.ravel(), v.ravel()).reshape(-1, 3)
    normals = patch.normals(u.ravel(), v.ravel()).reshape(-1, 3)
    assert np.abs(normals - points).max() < 1e-9


@settings(max_examples=40)
@given(live=st.integers(0, 3), points=st.integers(0, 3), level=st.integers(1, 6),
       at=st.floats(-1e6, 1e6), data=st.data())
def test_patches_collapsed_to_points_leave_the_others_whole(live, points, level, at, data):
    """A set of patches some of which collapse to a point (every control point the same):
    each live patch (random, sharing no edge) keeps its 2 L^2 triangles at level L, the
    collapsed ones add none -- and a set of nothing but points is refused in one line."""
    rng = np.random.default_rng(live * 7 + points)
    nets = [rng.random((4, 4, 3)) + 3 * k for k in range(live)] + \
        [np.full((4, 4, 3), at)] * points
    if not nets:
        return
    order = data.draw(st.permutations(range(len(nets))))
    patches = PatchSet(np.stack([nets[k] for k in order]))
    if not live:
        with pytest.raises(GeometryError, match="collapses to a point"):
            tessellate(patches, level=level)
        return
    mesh = tessellate(patches, level=level).mesh
    assert mesh.n_faces == 2 * level * level * live


@settings(max_examples=30)
@given(count=st.integers(0, 6), per=st.integers(1, 5))
def test_a_tolerance_per_patch_must_be_one_per_patch(count, per):
    """Tolerances as a list: exactly one per patch tessellates; any other count is one
    line with both numbers (not numpy's broadcasting error)."""
    patches = PatchSet(np.random.default_rng(1).random((per, 4, 4, 3)))
    tolerances = [0.01 * (k + 1) for k in range(count)]
    if count == per:
        assert tessellate(patches, tolerance=tolerances).mesh.n_faces > 0
    else:
        with pytest.raises(GeometryError, match=rf"one per patch \({per}\), got {count} "):
            tessellate(patches, tolerance=tolerances)
