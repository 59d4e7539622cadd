"""Form factors in the near field -- a small receiver close over a large emitter, rectangles
sharing an edge -- against closed forms, as one patch and subdivided; and the exact
point-to-polygon factor that corrects them, against the catalogue's point factors."""

import numpy as np
import pytest

from glshade.radiosity.contour import clip_to_plane, point_polygon_factors

from ..oracle.formfactors import (parallel_offset_rectangles, parallel_rectangles,
                                  perpendicular_rectangles, point_to_rectangle)
from .pairs import group_factor, pair


def square(half, z, up=True):
    c = [[-half, -half, z], [half, -half, z], [half, half, z], [-half, half, z]]
    return c if up else c[::-1]


def hovering(size, small, height):
    """A ``size`` square emitter facing up, a ``small`` square facing down ``height``
    above its centre."""
    return (square(size / 2, 0.0), square(small / 2, height, up=False),
            parallel_offset_rectangles((-size / 2, size / 2) * 2, (-small / 2, small / 2) * 2,
                                       height), size)


def hinged(length, height, width):
    """A ``length x width`` shooter and a ``length x height`` receiver at right angles,
    sharing the edge of ``length``."""
    return ([[0, 0, 0], [length, 0, 0], [length, width, 0], [0, width, 0]],
            [[0, 0, 0], [0, 0, height], [length, 0, height], [length, 0, 0]],
            perpendicular_rectangles(length, height, width), max(length, height, width))


FAMILY = {
    "2x2 emitter, 0.2 square 0.2 above": hovering(2, 0.2, 0.2),
    "2x2 emitter, 0.2 square 0.05 above": hovering(2, 0.2, 0.05),
    "2x2 emitter, 0.5 square 0.1 above": hovering(2, 0.5, 0.1),
    "1x0.3 against 1x2": hinged(1, 2, 0.3),
    "1x1 against 1x0.1": hinged(1, 0.1, 1),
    "1x0.2 against 1x5": hinged(1, 5, 0.2),
    "0.2x1 against 0.2x1": hinged(0.2, 1, 1),
    "1x2 against 1x0.3": hinged(1, 0.3, 2),
}


def test_the_catalogue_agrees_with_itself():
    """C-11 (offset parallel rectangles) is the opposed-squares formula when they are
    opposed, and the point factor in the limit of a tiny first rectangle."""
    assert parallel_offset_rectangles((0, 1, 0, 1), (0, 1, 0, 1), 1) == \
        pytest.approx(parallel_rectangles(1, 1, 1), rel=1e-12)
    e = 1e-4
    assert parallel_offset_rectangles((0, e, 0, e), (0, 2, 0, 3), 1.5) == \
        pytest.approx(point_to_rectangle(2, 3, 1.5), rel=1e-3)


def test_the_contour_factor_is_the_point_factor():
    """Lambert's contour integral from random points to a rectangle 1 above them: the sum of
    the four catalogue rectangles that meet below the point."""
    rng = np.random.default_rng(3)
    pts = np.c_[rng.uniform(0.05, 1.95, (50, 2)), np.zeros(50)]
    rect = np.array(square(1, 1.0, up=False)) + [1, 1, 0]  # [0, 2]^2 at z = 1, facing down
    got = point_polygon_factors(pts, np.array([0.0, 0, 1]), rect[None], np.array([[0.0, 0, -1]]))
    exact = [sum(point_to_rectangle(a, b, 1.0) for a in (x, 2 - x) for b in (y, 2 - y))
             for x, y, _ in pts]
    np.testing.assert_allclose(got[0], exact, rtol=1e-12)
    # a point behind the receiver's plane sees its back: nothing
    assert point_polygon_factors(np.array([[1.0, 1, 2]]), np.array([0.0, 0, -1]), rect[None],
                                 np.array([[0.0, 0, -1]]))[0, 0] == 0


def test_clipping_keeps_the_part_in_front():
    """A wall crossing the shooter's plane counts only above it: clipped, it gives the
    factor of the upper half built by hand."""
    wall = np.array([[1, -1, -1], [1, 1, -1], [1, 1, 1], [1, -1, 1]], float)
    upper = np.array([[1, -1, 0], [1, 1, 0], [1, 1, 1], [1, -1, 1]], float)
    n = np.array([0.0, 0, 1])
    clipped = clip_to_plane(wall[None], np.zeros((1, 3)), n[None])
    assert clipped.shape == (1, 5, 3) and (clipped[..., 2] >= -1e-15).all()
    pts = np.array([[0.0, 0, 0], [0.5, 0.3, 0], [-2, 0.5, 0]])
    normal = np.array([[-1.0, 0, 0]])
    np.testing.assert_allclose(point_polygon_factors(pts, n, clipped, normal),
                               point_polygon_factors(pts, n, upper[None], normal), rtol=1e-12)
    behind = clip_to_plane(wall[None] - [0, 0, 5], np.zeros((1, 3)), n[None])
    assert point_polygon_factors(pts, n, behind, normal).max() == 0


@pytest.mark.parametrize("pieces", [1, 5, 10], ids=["one patch", "5 a side", "10 a side"])
@pytest.mark.parametrize("case", FAMILY.values(), ids=FAMILY.keys())
def test_near_field_form_factors_match_closed_forms(case, pieces, factors):
    """At the default resolution and quadrature: within 1% (the hemicubes alone, before the
    near field was integrated exactly, were off by up to 85% as one patch)."""
    first, second, exact, size = case
    problem = pair(first, second, 100.0 if pieces == 1 else size / pieces)
    ff = factors(problem)
    error = abs(group_factor(problem, ff) - exact) / exact
    assert error < 0.01, f"{error:.2%} off"
    assert ff.near_corrected > 0


def _plain_near_pairs(problem):
    """Each shooter's quadrature and near receivers by their definitions (the form-factor
    module's docstring), every pair of patches one by one."""
    p = problem.patches
    corners = [p.vertices[[k for k in row if k >= 0]] for row in p.corners]
    c, n = p.centers, p.normals
    diameter = np.array([max(np.linalg.norm(a - b) for a in q for b in q) for q in corners])
    radius = np.array([np.linalg.norm(q - m, axis=1).max() for q, m in zip(corners, c)])
    counts, near = [], []
    for i in range(p.n_patches):
        d = np.linalg.norm(c - c[i], axis=1)
        off = np.abs((c - c[i]) @ n[i]) > 1e-6 * d
        nearest = d[off].min() if off.any() else np.inf
        counts.append(int(np.clip(np.ceil(1.5 * diameter[i] / nearest), 1, 8))
                      if nearest > 0 else 1)
    for i in range(p.n_patches):
        spacing = diameter[i] / counts[i]
        for j in range(p.n_patches):
            height = (corners[j] - c[i]) @ n[i]
            gap = np.linalg.norm(c[j] - c[i]) - radius[i] - radius[j]
            if j != i and height.max() > 1e-9 * diameter[i] and \
                    max(gap, height.min()) < 1.5 * spacing:
                near.append((i, j))
    return np.array(counts), near


@pytest.mark.parametrize("scene", ["cornell", "ball under a light", "sharing an edge"])
def test_the_set_up_finds_the_near_pairs_all_pairs_would(scene):
    """The set-up seeks each shooter's nearest receiver and near receivers only among the
    patches near it (cells of a grid: 81 s -> 1.3 s for a 20,480-patch sphere); every pair
    compared one by one finds the same ones."""
    from glshade import Material, Scene
    from glshade.geometry import primitives
    from glshade.radiosity import PatchScene
    from glshade.radiosity.cornell import cornell_scene
    from glshade.radiosity.formfactors import near_pairs, quadrature_counts

    if scene == "cornell":
        problem = PatchScene.from_scene(cornell_scene()[0], 90.0)
    elif scene == "ball under a light":
        s = Scene()
        s.add(primitives.icosphere(2), Material(color=(0.8, 0.8, 0.8)))
        # (the light's patches large and just over the ball: many near pairs)
        s.add(primitives.cube(), Material(emission=(5, 5, 5)), translation=(0, 1.33, 0),
              scale=0.6)
        problem = PatchScene.from_scene(s, 0.6)
    else:
        problem = pair([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
                       [[0, 0, 0], [0, 1, 0], [0, 1, 1], [0, 0, 1]], 0.25)
    counts, near = _plain_near_pairs(problem)

    class Told:  # (the set-up's progress: each patch told once per search)
        done = 0

        def update(self, n=1, note=None):
            self.done += n

    told = Told()
    found = quadrature_counts(problem, progress=told)
    np.testing.assert_array_equal(found, counts)
    first, receiver, _ = near_pairs(problem, found, progress=told)
    assert told.done == 2 * problem.n_patches
    shooter = np.repeat(np.arange(problem.n_patches), np.diff(first))
    assert len(near) > 0
    assert sorted(zip(shooter.tolist(), receiver.tolist())) == sorted(near)
