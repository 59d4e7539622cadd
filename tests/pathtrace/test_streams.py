"""A pixel's samples shared among streams (``streams``: sample k in stream k mod S, each
stream a copy of the pixel in the tracer's targets, their sums added when read), so that a
small picture gives a GPU's many cores work: the same samples as one stream -- the same
picture to float rounding, the same counts -- at any size, sample count, kernel, sampler,
block sharing, work per invocation and adaptive counts; the furnace's closed form with
many streams; given rays read back to their own pixels; the viewer's picture; one stream
on a software renderer; bad values refused."""

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from glshade.errors import OptionError
from glshade.pathtrace import TraceOptions, TraceScene, trace
from glshade.radiosity import cornell_scene
from glshade.render.passes.pathtrace import GpuPathTracer
from tests.conftest import glshade
from tests.pathtrace.test_sweeps import INSIDE, closed_form, furnace

pytestmark = pytest.mark.gl

_CORNELL, _CAMERA = cornell_scene()
_TS = TraceScene.from_scene(_CORNELL)


def _traced(ctx, w, h, runs, seed, counts=None, **options):
    """``read()`` after ``runs`` (samples added run by run), then ``counts`` if given."""
    with GpuPathTracer(ctx, _TS, w, h, **options) as tracer:
        for n in runs:
            tracer.run(_CAMERA, n, seed=seed)
        if counts is not None:
            tracer.run(_CAMERA, counts=counts, seed=seed)
        return tracer.read(), tracer.streams


def _same(got, want):
    """Sums to float32 rounding (the streams' sums added in another order); counts, first
    hits on emitters and camera rays that hit, exactly."""
    for a, b in zip(got, want):
        assert np.array_equal(a[..., 3], b[..., 3])
        assert (np.abs(a - b) <= 1e-5 * np.maximum(np.abs(b), 1e-3)).all(), \
            np.abs(a - b).max()
    assert np.array_equal(got[2][..., :2], want[2][..., :2])


@settings(max_examples=40)
@given(w=st.integers(1, 40), h=st.integers(1, 40), streams=st.integers(2, 9),
       runs=st.lists(st.integers(1, 7), min_size=1, max_size=3), seed=st.integers(0, 2**16),
       kernel=st.sampled_from(["fragment", "compute"]),
       sampler=st.sampled_from(["pcg", "sobol"]), coherent=st.booleans(),
       budget=st.sampled_from([GpuPathTracer.BUDGET, 40]), adaptive=st.booleans())
@example(w=16, h=16, streams=64, runs=[3], seed=0, kernel="fragment", sampler="sobol",
         coherent=False, budget=GpuPathTracer.BUDGET, adaptive=False)
@example(w=13, h=7, streams=5, runs=[2, 5], seed=9, kernel="compute", sampler="pcg",
         coherent=True, budget=40, adaptive=True)
def test_streams_trace_the_samples_one_stream_traces(gl_context, w, h, streams, runs, seed,
                                                     kernel, sampler, coherent, budget,
                                                     adaptive):
    """More streams than samples (some streams none), rows not a multiple of the film's
    8x8 blocks, runs in several parts, little work per invocation, adaptive counts."""
    counts = None
    if adaptive:
        counts = sum(runs) + np.random.default_rng(seed).integers(0, 6, (h, w))
    options = dict(kernel=kernel, sampler=sampler, coherent=coherent)
    want, one = _traced(gl_context, w, h, runs, seed, counts, streams=1, **options)
    got, many = _traced(gl_context, w, h, runs, seed, counts, streams=streams,
                        budget=budget, **options)
    assert (one, many) == (1, streams)
    assert (want[0][..., 3] == (sum(runs) if counts is None else counts)).all()
    assert want[0][..., :3].mean() > 0.0 or w * h * sum(runs) < 64  # (lit, but for a few)
    _same(got, want)


def test_many_streams_meet_the_furnace(gl_context):
    """Inside a closed room of emission 1 and reflectance 0.6 every pixel is 1 / (1 - 0.6):
    a 16x16 picture's 256 pixels each shared among 32 streams."""
    r = trace(furnace(0.6), INSIDE, (16, 16), spp=96, streams=32, seed=4,
              context=gl_context, progress=False)
    assert (r.counts == 96).all()
    pixels = r.image.mean(-1).ravel()
    bar = pixels.std(ddof=1) / np.sqrt(pixels.size)
    want = closed_form(0.6, None)
    assert abs(pixels.mean() - want) < 5 * bar and bar < 0.02, (pixels.mean(), want, bar)


def test_given_rays_read_back_to_their_own_pixels(gl_context):
    """A pattern of pixels looks at an emitting square (E = 2), the rest into the void: with
    three streams and four samples the picture is the pattern, exactly."""
    from glshade.geometry import primitives
    from glshade.scene import Material, Scene

    scene = Scene(ambient=(0, 0, 0))
    scene.add(primitives.plane(8.0), Material(color=(1, 1, 1), kd=0.0, ks=0.0,
                                              emission=(2.0, 2.0, 2.0)),
              translation=(0.0, 0.0, -1.0))
    h, w = 11, 29
    y, x = np.mgrid[0:h, 0:w]
    pattern = (7 * x + 3 * y) % 5 == 0  # (top row first, as read gives it)
    rays = np.zeros((h, w, 2, 3))
    rays[..., 1, 2] = np.where(pattern, -1.0, 1.0)
    with GpuPathTracer(gl_context, TraceScene.from_scene(scene), w, h, rays=rays[::-1],
                       max_depth=1, streams=3) as tracer:
        tracer.run(None, 4)
        total = tracer.read()[0]
    assert (total[..., 3] == 4).all()
    np.testing.assert_array_equal(total[..., :3], np.where(pattern, 8.0, 0.0)[..., None]
                                  * np.ones(3))


def test_the_viewer_shows_every_stream(gl_context):
    """The progressive picture on screen (each pixel's mean, its streams added) is one
    stream's, to a step of 8 bits."""
    shown = []
    for streams in (1, 6):
        with GpuPathTracer(gl_context, _TS, 24, 20, streams=streams) as tracer:
            tracer.run(_CAMERA, 5, seed=2)
            fbo = gl_context.ctx.simple_framebuffer((24, 20), components=4)
            try:
                tracer.show(fbo, exposure=1.0)
                shown.append(np.frombuffer(fbo.read(components=4), np.uint8).astype(int))
            finally:
                fbo.release()
    assert shown[0].max() > 0
    assert np.abs(shown[0] - shown[1]).max() <= 1


def test_a_software_renderer_takes_one_stream(gl_context):
    assert gl_context.software
    with GpuPathTracer(gl_context, _TS, 8, 8) as tracer:
        assert tracer.streams == 1


@pytest.mark.parametrize("bad", [0, 65, 2.5, True, "4"])
def test_bad_streams_are_refused(bad):
    with pytest.raises(OptionError, match="streams must be"):
        TraceOptions.of(streams=bad)


def test_the_command_line_takes_streams(tmp_path):
    """``--streams 3`` traces (the picture is written); 65 and 0 are refused in one line,
    exit 2, nothing written."""
    out = tmp_path / "t.png"
    done = glshade("pathtrace", "primitive:icosphere:2", "-o", str(out), "--spp", "4",
                   "--size", "24x16", "--streams", "3", "-q")
    assert done.returncode == 0, done.stderr
    assert out.stat().st_size > 0
    for bad in ("65", "0"):
        other = tmp_path / f"{bad}.png"
        done = glshade("pathtrace", "primitive:icosphere:2", "-o", str(other), "--streams",
                       bad, "-q")
        assert done.returncode == 2 and not other.exists()
        assert len(done.stderr.strip().splitlines()) == 1 and "streams" in done.stderr, \
            done.stderr
