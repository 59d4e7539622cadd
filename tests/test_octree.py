"""Octrees of solids and meshes: the volume bracketed at every depth with the gap halving,
boundary cells growing about 4x per level, classification never wrong, and the winding
number."""

import numpy as np
import pytest

from glshade.errors import GeometryError
from glshade.geometry import primitives
from glshade.octree import BOUNDARY, INSIDE, OUTSIDE, Octree, winding_number
from glshade.solids import Box, Cylinder, Torus


@pytest.mark.parametrize("solid, exact", [
    (Box(2.0) - Cylinder(0.5, 3.0), 8 - 2 * np.pi * 0.25),
    (Torus(1.0, 0.3), 2 * np.pi ** 2 * 1.0 * 0.09),
], ids=["block with a hole", "torus"])
def test_volume_bounds_bracket_and_halve(solid, exact):
    gaps, boundary = [], []
    for depth in range(3, 8):
        tree = Octree.from_solid(solid, depth)
        inner, outer = tree.volume_bounds()
        assert inner <= exact <= outer
        gaps.append(outer - inner)
        boundary.append(tree.counts()[-1]["boundary"])
    ratios = np.array(gaps[:-1]) / np.array(gaps[1:])
    assert (ratios[1:] > 1.7).all() and (ratios < 2.3).all(), ratios
    growth = np.array(boundary[1:]) / np.array(boundary[:-1])
    assert (growth[1:] > 3.5).all() and (growth < 5).all(), growth  # a surface: ~4x, not 8x


def test_classification_is_never_wrong():
    solid = Box(2.0) - Cylinder(0.5, 3.0)
    tree = Octree.from_solid(solid, 6)
    p = np.random.default_rng(3).uniform(-1.2, 1.2, (100_000, 3))
    state, truth = tree.classify(p), solid.contains(p)
    assert not truth[state == OUTSIDE].any() and truth[state == INSIDE].all()
    assert (state == BOUNDARY).mean() < 0.1
    mesh = tree.to_mesh()
    assert np.isclose(mesh.signed_volume(), tree.volume_bounds()[0])
    assert np.isclose(tree.to_mesh("inside+boundary").signed_volume(), tree.volume_bounds()[1])


def test_octree_of_a_closed_mesh():
    sphere = primitives.icosphere(3)
    tree = Octree.from_mesh(sphere, 4)
    inner, outer = tree.volume_bounds()
    assert inner <= sphere.signed_volume() <= outer
    p = np.random.default_rng(4).uniform(-1.1, 1.1, (20_000, 3))
    state = tree.classify(p)
    w = winding_number(p, sphere.vertices[sphere.triangles[0]])
    assert (w[state == INSIDE] > 0.5).all() and (w[state == OUTSIDE] < 0.5).all()
    with pytest.raises(GeometryError, match="closed"):
        Octree.from_mesh(primitives.plane(), 3)


def test_winding_number_inside_outside_and_on_the_surface():
    cube = primitives.box((2.0, 2.0, 2.0))
    tri = cube.vertices[cube.triangles[0]]
    w = winding_number(np.array([[0, 0, 0], [3, 0, 0], [0.3, -0.2, 0.9], [5, 5, 5.0]]), tri)
    assert np.allclose(w, [1, 0, 1, 0], atol=1e-12)
    # a hair inside or outside, at a face, an edge and a corner (where triangles meet)
    eps = 1e-7
    spots = np.array([[1.0, 0.2, 0.3], [1.0, 1.0, 0.3], [1.0, 1.0, 1.0]])
    inside = winding_number(spots * (1 - eps), tri)
    outside = winding_number(spots * (1 + eps), tri)
    assert np.allclose(inside, 1, atol=1e-6) and np.allclose(outside, 0, atol=1e-6)


def test_neighbours_and_bad_depths():
    tree = Octree.from_solid(Box(2.0) - Cylinder(0.5, 3.0), 3)
    cells = np.argwhere(np.ones((8, 8, 8), bool))
    nb = tree.neighbours(3, cells)
    steps = np.array([[-1, 0, 0], [1, 0, 0], [0, -1, 0], [0, 1, 0], [0, 0, -1], [0, 0, 1]])
    centres = tree.origin + (cells[:, None, :] + steps + 0.5) * tree.cell_size(3)
    assert np.array_equal(nb, tree.classify(centres.reshape(-1, 3)).reshape(-1, 6))
    assert {OUTSIDE, INSIDE, BOUNDARY} <= set(nb.ravel().tolist())
    with pytest.raises(GeometryError, match="depth"):
        Octree.from_solid(Box(), 13)
    from glshade.solids import HalfSpace

    with pytest.raises(GeometryError, match="unbounded"):
        Octree.from_solid(HalfSpace(), 3)
