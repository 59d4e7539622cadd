"""Adaptive sampling (glshade.pathtrace.adaptive): the budget spent and the counts in the
order of the pixels' spread (swept), a hand-worked picture's shares; on the GPU the
picture's samples are a plain render's at those counts from the picture's own seed (the
same bytes: independent of the pilot's, which came from another), the error on the Cornell
box falls for the same paths, and the answer stays unbiased (the furnace sweep,
test_sweeps.py, and Mitsuba, test_mitsuba.py, run it too)."""

import numpy as np
import pytest

from tests.conftest import require

require("hypothesis", "property-based sweeps are part of the test extra")
from hypothesis import example, given, settings, strategies as st  # noqa: E402
from hypothesis.extra import numpy as hnp  # noqa: E402

from glshade.errors import OptionError  # noqa: E402
from glshade.pathtrace import PathTracer, trace  # noqa: E402
from glshade.pathtrace.adaptive import allocate, block_sigma, pilot_samples  # noqa: E402
from glshade.radiosity import cornell_scene  # noqa: E402

TILES = st.sampled_from([(1, 1), (4, 2), (2, 2), (1, 8), (3, 1)])


def deviations(side: tuple = (2, 24)):
    return hnp.arrays(np.float64, st.tuples(st.integers(*side), st.integers(*side)),
                      elements=st.floats(0.0, 1e3) | st.just(0.0))


@settings(max_examples=80, deadline=None)
@given(sigma=deviations(), tile=TILES, mean=st.integers(1, 4096), clip=st.sampled_from(
    [None, 99.0, 50.0]))
# (found: deviations 60 orders of magnitude apart left the scale's bisection, halving from
# most / 1e-60, wider than the answer -- a mean of 2.39 for 3)
@example(sigma=np.array([[1.0, 1.44e-60, 0.0, 0.0, 1.0, 0.0, 0.0]] + [[0.0] * 7] * 3),
         tile=(1, 1), mean=3, clip=None)
def test_the_budget_is_spent_within_bounds_a_block_alike(sigma, tile, mean, clip):
    """The counts add up to the mean asked (within rounding: half a sample a pixel, or
    what the floor and cap force), none under the floor nor over the cap, and a block's
    pixels (they share random numbers) draw one count."""
    n = allocate(sigma, mean, tile=tile, clip=clip)
    floor, most = max(1, mean // 8), 3 * mean
    assert floor <= n.min() and n.max() <= most
    forced = ((n == floor) | (n == most)).all()  # (no count free to move)
    assert forced or abs(n.mean() - mean) <= 0.5 + 1e-9 * mean, (n.mean(), mean)
    tw, th = tile
    h, w = sigma.shape
    for by in range(0, h, th):
        for bx in range(0, w, tw):
            block = n[by:by + th, bx:bx + tw]
            assert (block == block.flat[0]).all()


@settings(max_examples=40, deadline=None)
@given(sigma=deviations(), mean=st.integers(8, 4096), k=st.floats(1e-3, 1e3))
def test_counts_follow_the_smoothed_spread(sigma, mean, k):
    """A pixel whose neighbourhood spreads more never draws fewer (clip=None: the 3 x 3
    mean of the squares, computed here again with an explicit loop), and the counts do not
    change when every deviation is scaled alike; no spread anywhere: the mean
    everywhere."""
    n = allocate(sigma, mean, clip=None)
    h, w = sigma.shape
    p = np.pad(sigma ** 2, 1, mode="edge")
    smooth = np.array([[p[y:y + 3, x:x + 3].mean() for x in range(w)] for y in range(h)])
    order = np.argsort(smooth.ravel(), kind="stable")
    assert (np.diff(n.ravel()[order]) >= 0).all()
    assert np.abs(allocate(k * sigma, mean, clip=None) - n).max() <= 1
    assert (allocate(np.zeros_like(sigma), mean) == mean).all()


def test_a_hand_worked_picture():
    """1 x 2 pixels of deviations 1 and 3: the squares 1 and 9 smoothed over 3 x 3 with
    the edge repeated are (1 + 1 + 9) / 3 and (1 + 9 + 9) / 3, so the 128 samples split as
    sqrt(11) : sqrt(19) -- 55.30 and 72.70 -- rounded 55 and 73."""
    n = allocate(np.array([[1.0, 3.0]]), 64, clip=None)
    assert n.tolist() == [[55, 73]]
    assert pilot_samples(1024) == 16 and pilot_samples(64) == 4


def test_a_blocks_deviation_is_its_pixels_rms():
    sigma = np.arange(12.0).reshape(3, 4)
    got = block_sigma(sigma, (2, 2))
    want = [[np.sqrt(np.mean(np.square([0, 1, 4, 5]))), np.sqrt(np.mean(np.square([2, 3, 6, 7])))],
            [np.sqrt(np.mean(np.square([8, 9]))), np.sqrt(np.mean(np.square([10, 11])))]]
    np.testing.assert_allclose(got, want)


def test_bad_deviations_are_named():
    for bad in (np.ones(4), -np.ones((2, 2)), np.full((2, 2), np.nan)):
        with pytest.raises(OptionError, match="sigma must be"):
            allocate(bad, 8)
    with pytest.raises(OptionError, match="must lie from floor"):
        allocate(np.ones((2, 2)), 4, floor=8)
    with pytest.raises(OptionError, match="must be at least 1"):
        allocate(np.ones((2, 2)), 0)


@pytest.mark.gl
@pytest.mark.parametrize("sampler, coherent", [("pcg", False), ("sobol", True)])
def test_a_pixels_samples_are_a_uniform_renders(gl_context, sampler, coherent):
    """Counts of 8, 16 or 24 a pixel, reached in two steps: each pixel's sums are, to the
    byte, those of a uniform render of its count (its k-th sample is the same)."""
    scene, camera = cornell_scene()
    size = (16, 12)
    rng = np.random.default_rng(1)
    counts = 8 * rng.integers(1, 4, size[::-1])
    kw = dict(context=gl_context, sampler=sampler, coherent=coherent, seed=4)
    with PathTracer(scene, size, **kw) as t:
        t.add(camera, counts=np.minimum(counts, 12))
        t.add(camera, counts=counts)
        got = t.gpu.read()
        assert np.array_equal(t.counts, counts)
    for n in (8, 16, 24):
        with PathTracer(scene, size, **kw) as t:
            t.add(camera, n)
            want = t.gpu.read()
        here = counts == n
        for a, b in zip(got, want):
            assert np.array_equal(a[here], b[here]), n


@pytest.mark.gl
def test_fewer_counts_than_drawn_are_refused(gl_context):
    scene, camera = cornell_scene()
    with PathTracer(scene, (8, 8), context=gl_context) as t:
        t.add(camera, 4)
        with pytest.raises(OptionError, match="counts must be"):
            t.add(camera, counts=np.full((8, 8), 3))
        with pytest.raises(OptionError, match="counts must be"):
            t.add(camera, counts=np.full((4, 8), 8))


@pytest.mark.gl
@pytest.mark.once
def test_the_cornell_boxs_error_falls_for_the_same_paths(gl_context):
    """At a mean of 64 independent samples the RMS error against a long render falls to
    under half (measured 26% -> 11% at 128²: the light's edge pixels hold most of it), the
    image's mean as before; the stop rule's estimate tracks the true error (within 1.5x)."""
    scene, camera = cornell_scene()
    size = (48, 48)
    reference = trace(scene, camera, size, spp=8192, seed=99, sampler="sobol",
                      context=gl_context, progress=False).image
    error = {}
    for adaptive in (False, True):
        r = trace(scene, camera, size, spp=64, seed=3, adaptive=adaptive, context=gl_context,
                  progress=False)
        assert abs(r.counts.mean() - 64) < 2
        error[adaptive] = np.sqrt(np.mean((r.image - reference) ** 2)) / reference.mean()
        assert 1 / 1.5 < r.relative_error / error[adaptive] < 1.5, (adaptive, error)
    assert error[True] < 0.5 * error[False], error
    assert r.adaptive and "adaptive" in repr(r)


@pytest.mark.gl
def test_until_stops_at_the_error_asked(gl_context):
    scene, camera = cornell_scene()
    r = trace(scene, camera, (24, 24), until=0.2, adaptive=True, context=gl_context,
              progress=False)
    assert r.relative_error <= 0.2 and r.history and r.history[-1][2] == r.relative_error


@pytest.mark.gl
def test_the_picture_is_a_plain_render_at_its_counts(gl_context):
    """What adaptive sampling returns is, to the byte, a plain render from the same seed at
    the counts it chose: the pilot's samples (another seed) are in no pixel."""
    scene, camera = cornell_scene()
    kw = dict(seed=6, sampler="sobol", context=gl_context)
    r = trace(scene, camera, (24, 16), spp=32, adaptive=True, progress=False, **kw)
    assert r.adaptive and r.counts.min() < 32 < r.counts.max()
    with PathTracer(scene, (24, 16), **kw) as t:
        t.add(camera, counts=r.counts)
        plain = t.result()
    assert np.array_equal(plain.image, r.image)
    # (the run's error from its halves: its steps end at each pixel's half; the plain
    # render's counts came in one step, so its error is the samples' spread)
    assert (r.se_from, plain.se_from) == ("halves", "spread")
