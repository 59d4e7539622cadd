"""Near blocks of points (the radiosity set-up's near patches, BOP's diameter) against
scipy's every pairwise distance: no near pair is ever left out of a block, every point is a
row exactly once, over the shapes a grid finds hard."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from glshade.geometry.cells import group, near_blocks


def points_of(shape: str, n: int, rng, scale: float) -> np.ndarray:
    """``n`` points of a shape a grid finds hard (and BOP's diameter a bound from the
    centre), ``scale`` across, off the origin by 3 ``scale``."""
    p = rng.normal(size=(n, 3))
    if shape == "sphere":  # (a surface: its box's volume counts on far more cells)
        p /= np.linalg.norm(p, axis=1, keepdims=True)
    elif shape == "segment":
        p = rng.uniform(size=(n, 1)) * [[1.0, 2.0, -0.5]]
    elif shape == "flat":
        p[:, 2] = 0.0
    elif shape == "one point":
        p = np.broadcast_to(p[:1], (n, 3))
    elif shape == "two":
        p = p[np.r_[0, 1, rng.integers(0, 2, n - 2)]] if n > 1 else p
    elif shape == "far apart":  # (a cluster and a lone point far from it: a stretched box)
        p[0] = 1e4
    return p * scale + 3 * scale


@settings(max_examples=40, deadline=None)
@given(shape=st.sampled_from(["sphere", "blob", "segment", "flat", "one point", "far apart"]),
       n=st.integers(1, 1500), seed=st.integers(0, 2 ** 16),
       scale=st.sampled_from([1e-6, 1.0, 1e6]),
       reach=st.sampled_from(["tiny", "spread", "one huge", "zero"]))
def test_near_blocks_hold_every_near_pair(shape, n, seed, scale, reach):
    from scipy.spatial.distance import cdist

    rng = np.random.default_rng(seed)
    p = points_of(shape, n, rng, scale)
    a = rng.uniform(0, 0.05, n) * scale
    b = rng.uniform(0, 0.05, n) * scale
    if reach == "spread":
        a *= rng.uniform(0, 20, n)
    elif reach == "one huge":
        b[rng.integers(n)] = 10 * scale
    elif reach == "zero":
        a[:] = b[:] = 0.0
    want = cdist(p, p) <= a[:, None] + b[None, :]
    covered = np.zeros((n, n), bool)
    rows_seen = np.zeros(n, np.int64)
    for rows, cols in near_blocks(p, a, b):
        covered[np.ix_(rows, cols)] = True
        rows_seen[rows] += 1
        assert set(rows) <= set(cols)  # (a point's columns include itself)
    assert (rows_seen == 1).all()
    missed = np.argwhere(want & ~covered)
    assert not len(missed), missed[:5]


@pytest.mark.parametrize("shape", ["sphere", "blob", "flat", "one point"])
def test_cells_hold_their_points_within_their_radii(shape):
    rng = np.random.default_rng(1)
    p = points_of(shape, 5000, rng, 1.0)
    cells = group(p)
    assert np.array_equal(np.sort(cells.order), np.arange(len(p)))
    owner = np.repeat(np.arange(len(cells.starts)), cells.counts)
    gaps = np.linalg.norm(p[cells.order] - cells.centres[owner], axis=1)
    assert (gaps <= cells.radii[owner] * (1 + 1e-12) + 1e-15).all()
    assert np.array_equal(cells.members(np.arange(len(cells.starts))), cells.order)
    if shape == "sphere":  # (a surface: cells halved until they hold about 32 each)
        assert cells.counts.mean() <= 64
