"""Blocks of pixels that draw the same random numbers (``coherent``): their errors go
together within a block and not across its edge (a correlation measured in numpy between
two seeds' pictures), yet each pixel is as noisy as when it draws its own (the pooled
error against a long render); the furnace sweep (test_sweeps.py) shows it unbiased."""

import numpy as np
import pytest

from glshade.errors import OptionError
from glshade.pathtrace import trace
from glshade.radiosity import cornell_scene

pytestmark = [pytest.mark.gl]

SIZE = (32, 32)


def off_the_light(*results) -> np.ndarray:
    """(H, W - 1) bool: pixel pairs (x, x + 1) neither of which saw the light in any of
    ``results`` (a pixel half on the light is 17 or 0 by where a sample lands: a few such
    pixels would decide any statistic)."""
    seen = np.zeros(SIZE[::-1], bool)
    for r in results:
        seen |= r.emitting > 0
    return ~(seen[:, :-1] | seen[:, 1:])


@pytest.mark.parametrize("sampler", ["pcg", "sobol"])
def test_a_blocks_pixels_err_together_and_only_they(gl_context, sampler):
    """The difference of two seeds' pictures is each pixel's error twice over: with
    blocks of 4 x 2 sharing numbers, horizontal neighbours within a block correlate
    (measured 0.66-0.71) and pairs across a block's edge do not; with each pixel its own
    numbers, no pair does."""
    scene, camera = cornell_scene()
    x = np.arange(SIZE[0] - 1)
    within = (x % 4) != 3  # (the pair (x, x + 1) lies in one block of 4)
    for coherent in (True, False):
        a, b = (trace(scene, camera, SIZE, spp=4, seed=s, context=gl_context, progress=False,
                      sampler=sampler, coherent=coherent) for s in (1, 2))
        e = (a.image - b.image)[..., :3].mean(-1)
        keep = off_the_light(a, b)
        inside, across = (np.corrcoef(e[:, :-1][keep & m], e[:, 1:][keep & m])[0, 1]
                          for m in (within, ~within))
        assert abs(across) < 0.2, (coherent, across)
        assert (inside > 0.5) if coherent else (abs(inside) < 0.2), (coherent, inside)


@pytest.mark.once
def test_a_pixel_in_a_block_is_as_noisy_as_one_alone(gl_context):
    """Each pixel's estimate is drawn alike either way: the mean absolute error against a
    long render, pooled over pixels off the light and eight seeds, agrees within 10%
    (measured within 2%). (Not one picture's RMS error: a block's errors come eight at a
    time, so one coherent picture's RMS is more often below its expectation, and now and
    then well above.)"""
    scene, camera = cornell_scene()
    reference = trace(scene, camera, SIZE, spp=4096, seed=99, context=gl_context,
                      progress=False, sampler="sobol")
    keep = reference.emitting == 0
    for sampler in ("pcg", "sobol"):
        error = {}
        for coherent in (False, True):
            error[coherent] = np.mean([np.abs(trace(
                scene, camera, SIZE, spp=16, seed=10 + s, context=gl_context, progress=False,
                sampler=sampler, coherent=coherent).image - reference.image)[keep][:, :3]
                for s in range(8)])
        assert error[True] == pytest.approx(error[False], rel=0.1), (sampler, error)


@pytest.mark.parametrize("bad", [(0, 2), (4,), "4x2", (65, 1), (2.5, 2), 3])
def test_a_block_that_is_not_one_is_named(gl_context, bad):
    scene, camera = cornell_scene()
    with pytest.raises(OptionError, match="coherent must be True, False or a block's"):
        trace(scene, camera, (8, 8), spp=1, context=gl_context, progress=False, coherent=bad)
