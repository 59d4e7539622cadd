"""The ray hierarchy: every triangle reachable, and the packed children's 16-bit boxes
(what a GPU ray reads) never smaller than the true ones once float32 rebuilds them."""

import numpy as np
import pytest
from hypothesis import given, strategies as st

from glshade.geometry.bvh import build, packed_children, QUANTUM_STEPS


def _triangles(rng, n, centre, size, flat_axis=None):
    t = centre + size * rng.uniform(-1, 1, (n, 3, 3))
    if flat_axis is not None:
        t[..., flat_axis] = centre[flat_axis]
    return t


def _unpack(words, base, step):
    """The boxes as the shader rebuilds them: float32 base + q * step (oracle: the GLSL
    expression, written again here)."""
    w = words.astype(np.uint32)
    q_lo = np.stack([w[:, 0] & 0xFFFF, w[:, 0] >> 16, w[:, 1] & 0xFFFF], 1)
    q_hi = np.stack([w[:, 1] >> 16, w[:, 2] & 0xFFFF, w[:, 2] >> 16], 1)
    f32 = np.float32
    lo = base.astype(f32) + q_lo.astype(f32) * step.astype(f32)
    hi = base.astype(f32) + q_hi.astype(f32) * step.astype(f32)
    return lo, hi, w[:, 3] >> 4, w[:, 3] & 15


def _walk(bvh, packed):
    """Every node reached from the root through the packed rows: (node id, box) pairs,
    checked against the hierarchy's own boxes; the leaves' triangles, each once."""
    lo, hi, index, count = _unpack(packed.root[None], packed.base, packed.step)
    pending = [(0, lo[0], hi[0], index[0], count[0])]
    seen = []
    inner_ids = np.flatnonzero(bvh.count == 0)
    while pending:
        node, lo, hi, index, count = pending.pop()
        assert np.all(lo <= bvh.lo[node]) and np.all(hi >= bvh.hi[node]), node
        if count:
            assert bvh.count[node] == count and bvh.first[node] == index
            seen.extend(range(index, index + count))
            continue
        assert inner_ids[index] == node  # (an inner child's row is its rank)
        row = packed.entries[index]
        clo, chi, cindex, ccount = _unpack(row.reshape(2, 4), packed.base, packed.step)
        for k, child in enumerate((bvh.first[node], bvh.first[node] + 1)):
            pending.append((child, clo[k], chi[k], cindex[k], ccount[k]))
    return np.sort(seen)


@given(seed=st.integers(0, 2**31), n=st.integers(1, 300),
       centre=st.sampled_from([0.0, 1.0, -37.5, 1e4, 3e6]),
       size=st.sampled_from([1e-4, 1.0, 50.0]),
       flat_axis=st.sampled_from([None, 0, 2]), sah=st.booleans())
def test_packed_boxes_hold_their_triangles_and_reach_every_one(seed, n, centre, size,
                                                               flat_axis, sah):
    # far from the origin (1e4, 3e6) a float32 step of the box is below the coordinates'
    # own rounding; flat scenes have a zero-width axis
    rng = np.random.default_rng(seed)
    tri = _triangles(rng, n, np.array([centre, -centre, 0.5 * centre]), size, flat_axis)
    tri = tri.astype(np.float32).astype(np.float64)  # (what the GPU holds)
    bvh = build(tri, sah=sah)
    packed = packed_children(bvh)
    assert np.array_equal(_walk(bvh, packed), np.arange(n))
    # each node's box holds its triangles (found from the tree's ranges, not its boxes)
    for node in range(bvh.n_nodes):
        leaves = [node]
        found = []
        while leaves:
            k = leaves.pop()
            if bvh.count[k]:
                found.extend(bvh.order[bvh.first[k]:bvh.first[k] + bvh.count[k]])
            else:
                leaves += [bvh.first[k], bvh.first[k] + 1]
        pts = tri[found].reshape(-1, 3)
        assert (pts >= bvh.lo[node]).all() and (pts <= bvh.hi[node]).all()
    assert bvh.count.max() <= 4


def _sah_cost(bvh):
    """The expected cost of a ray through the tree (unit cost a node, a triangle), each
    node weighed by its box's area over the root's."""
    d = np.maximum(bvh.hi - bvh.lo, 0.0)
    area = d[:, 0] * d[:, 1] + d[:, 1] * d[:, 2] + d[:, 2] * d[:, 0]
    inner = bvh.count == 0
    return (area[inner].sum() + (area * bvh.count)[~inner].sum()) / area[0]


@pytest.mark.parametrize("seed", range(4))
def test_sah_splits_cost_less_than_median_ones_where_triangles_cluster(seed):
    """A dense cluster beside sparse triangles (a detailed model on a wide floor): the
    median splits cut through empty space the heuristic avoids."""
    rng = np.random.default_rng(seed)
    centres = np.concatenate([rng.uniform(-0.1, 0.1, (2000, 3)),
                              rng.uniform(-10.0, 10.0, (200, 3))])
    tri = centres[:, None] + rng.uniform(-0.01, 0.01, (2200, 3, 3))
    sah, median = build(tri), build(tri, sah=False)
    assert _sah_cost(sah) < 0.8 * _sah_cost(median)


def test_packed_boxes_are_tight_where_float32_allows():
    rng = np.random.default_rng(3)
    bvh = build(_triangles(rng, 500, np.zeros(3), 1.0))
    packed = packed_children(bvh)
    extent = bvh.hi[0] - bvh.lo[0]
    lo, hi, _, _ = _unpack(packed.entries.reshape(-1, 4), packed.base, packed.step)
    children = np.concatenate([[bvh.first[i], bvh.first[i] + 1]
                               for i in np.flatnonzero(bvh.count == 0)])
    grow = np.maximum(bvh.lo[children] - lo, hi - bvh.hi[children]) / extent
    assert grow.max() < 4.0 / QUANTUM_STEPS  # (a step each way, and a margin's step)


def test_triangle_offset_and_limits():
    rng = np.random.default_rng(4)
    bvh = build(_triangles(rng, 40, np.zeros(3), 1.0))
    packed = packed_children(bvh, first_triangle=7)
    leaves = packed.entries.reshape(-1, 4)[:, 3]
    assert ((leaves >> 4)[(leaves & 15) > 0] >= 7).all()
    with pytest.raises(ValueError, match="more than 15 triangles"):
        packed_children(build(_triangles(rng, 40, np.zeros(3), 1.0), leaf_size=20))
