"""The path tracer swept over its parameter space (hypothesis, derandomized in CI) against
closed forms: a furnace -- a closed room of emission E and reflectance rho -- shows
E (1 - rho^(D+1)) / (1 - rho) with paths of at most D vertices, E / (1 - rho) with no limit,
at every albedo up to 0.99, whatever the samples, their grouping into passes or the work
one invocation may do; and a pixel's k-th sample is the same bytes however it is reached."""

import numpy as np
import pytest

from tests.conftest import require

require("hypothesis", "property-based sweeps are part of the test extra")
from hypothesis import example, given, settings, strategies as st  # noqa: E402

from glshade.geometry import primitives  # noqa: E402
from glshade.pathtrace import TraceScene, trace  # noqa: E402
from glshade.render.passes.pathtrace import GpuPathTracer  # noqa: E402
from glshade.scene import Camera, Material, Scene  # noqa: E402

pytestmark = [pytest.mark.gl, pytest.mark.once]

INSIDE = Camera.look_at((0.0, 0.0, 0.0), (0.0, 0.0, -1.0), fov_y=60.0, near=0.01, far=10.0)


def furnace(rho: float, emission: float = 1.0, ball: bool = False) -> Scene:
    """A closed room whose every surface reflects ``rho`` and emits ``emission``; ``ball``:
    with an 80-triangle ball of the same inside (the answer is the same anywhere in a
    furnace; a small model beside a larger one, as a hybrid tracer splits them)."""
    scene = Scene(ambient=(0, 0, 0))
    material = Material(color=(1.0, 1.0, 1.0), kd=rho, ka=0.0, ks=0.0,
                        emission=(emission,) * 3)
    scene.add(primitives.cube().flipped(), material)
    if ball:
        scene.add(primitives.icosphere(1), material, scale=0.12, translation=(0.15, 0.1, -0.3))
    return scene


def closed_form(rho: float, depth: int | None, emission: float = 1.0) -> float:
    """E (1 + rho + ... + rho^D): the camera's hit emits E, and each of its D vertices'
    next-event estimate brings rho times what reaches it directly (E, the room all
    emitting) times the throughput rho^k of the vertices before it."""
    if depth is None:
        return emission / (1 - rho)
    return emission * (1 - rho ** (depth + 1)) / (1 - rho)


@settings(max_examples=32)
@given(rho=st.floats(0.0, 0.99), spp=st.integers(8, 48),
       per_pass=st.sampled_from([None, 1, 3, 16]),
       depth=st.one_of(st.none(), st.integers(1, 12)), seed=st.integers(0, 2**16),
       accel=st.sampled_from(["bvh", "flat", "hybrid"]), sampler=st.sampled_from(["pcg", "sobol"]),
       mis=st.booleans(), coherent=st.sampled_from([False, True, (2, 2), (1, 8)]),
       adaptive=st.booleans())
@example(rho=0.9, spp=32, per_pass=None, depth=None, seed=0, accel="bvh", sampler="pcg",
         mis=False, coherent=False, adaptive=False)
@example(rho=0.9, spp=32, per_pass=None, depth=None, seed=0, accel="flat", sampler="pcg",
         mis=True, coherent=False, adaptive=False)
@example(rho=0.99, spp=16, per_pass=16, depth=None, seed=1, accel="flat", sampler="sobol",
         mis=True, coherent=True, adaptive=False)
@example(rho=0.0, spp=8, per_pass=1, depth=1, seed=2, accel="bvh", sampler="sobol", mis=True,
         coherent=False, adaptive=False)
@example(rho=0.9, spp=32, per_pass=None, depth=3, seed=0, accel="flat", sampler="sobol",
         mis=True, coherent=False, adaptive=False)
@example(rho=0.95, spp=24, per_pass=3, depth=None, seed=4, accel="hybrid", sampler="sobol",
         mis=True, coherent=True, adaptive=False)
@example(rho=0.9, spp=16, per_pass=None, depth=None, seed=3, accel="bvh", sampler="pcg",
         mis=True, coherent=True, adaptive=False)
@example(rho=0.95, spp=48, per_pass=3, depth=None, seed=5, accel="hybrid", sampler="sobol",
         mis=True, coherent=False, adaptive=True)
def test_the_furnace_meets_its_closed_form_everywhere(gl_context, rho, spp, per_pass, depth,
                                                     seed, accel, sampler, mis, coherent,
                                                     adaptive):
    """Every way of finding triangles (the hierarchy, every triangle in turn, both: a ball
    in the room then, its walls compiled in and the ball's hierarchy), both
    samplers (independent numbers, Owen-scrambled Sobol points), with and without multiple
    importance sampling (in a room that all emits, every bounce finds emission), each pixel
    drawing its own numbers or blocks of pixels sharing them, and each pixel drawing the
    same samples or as many as a pilot's spread gives it (adaptive)."""
    r = trace(furnace(rho, ball=accel == "hybrid"), INSIDE, (32, 32), spp=spp,
              samples_per_pass=per_pass, seed=seed,
              max_depth=depth, context=gl_context, progress=False, accel=accel,
              sampler=sampler, mis=mis, coherent=coherent, adaptive=adaptive)
    assert abs(r.counts.mean() - spp) <= 0.5 and r.near_limit == 0
    want = closed_form(rho, depth)
    # the blocks that draw their own numbers are independent estimates of one number:
    # their spread is the error bar (a block's pixels share numbers: not independent)
    bw, bh = (4, 2) if coherent is True else (1, 1) if coherent is False else coherent
    pixels = r.image.mean(-1).reshape(32 // bh, bh, 32 // bw, bw).mean((1, 3)).ravel()
    bar = pixels.std(ddof=1) / np.sqrt(pixels.size)
    # (plus float32 rounding: the tracer sums in float32, a few ulps of the answer)
    assert abs(pixels.mean() - want) <= 5 * bar + 4e-7 * want, (pixels.mean(), want, bar)
    assert (r.coverage == 1).all()


@settings(max_examples=12)
@given(rho=st.floats(0.3, 0.95), budget=st.integers(16, 20000),
       chunks=st.lists(st.integers(1, 6), min_size=1, max_size=4),
       sampler=st.sampled_from(["pcg", "sobol"]), coherent=st.booleans())
def test_a_pixels_kth_sample_is_the_same_however_the_work_is_split(gl_context, rho, budget,
                                                                  chunks, sampler, coherent):
    """Every pixel ends with exactly the samples asked, and the same bytes, whether they
    came in one run or several, with much or little work per invocation."""
    ts = TraceScene.from_scene(furnace(rho))
    total = sum(chunks)
    with GpuPathTracer(gl_context, ts, 12, 10, sampler=sampler, coherent=coherent) as one:
        one.run(INSIDE, total, seed=5)
        want = one.read()
    with GpuPathTracer(gl_context, ts, 12, 10, budget=budget, sampler=sampler,
                       coherent=coherent) as split:
        for n in chunks:
            split.run(INSIDE, n, seed=5)
        got = split.read()
    assert (got[0][..., 3] == total).all()
    for a, b in zip(got, want):
        assert np.array_equal(a, b)


@pytest.mark.parametrize("scene_of", ["cornell", "cornell and a sphere"])
def test_the_flat_loop_and_the_hierarchy_give_the_same_picture(gl_context, scene_of):
    """Every variant draws the same random stream and finds the same nearest hits: the
    Cornell box (32 triangles, flat by default) and the box with an 80-triangle sphere
    (hybrid by default: the walls compiled in, the sphere's hierarchy), traced every way,
    agree to rounding (compiled triangles are constants the compiler folds, so their
    arithmetic rounds apart; a path that grazes an edge may go another way: at most 1% of
    pixels)."""
    from glshade.radiosity import cornell_scene

    scene, camera = cornell_scene()
    if scene_of != "cornell":
        scene.add(primitives.icosphere(1), Material(color=(0.7, 0.7, 0.7), kd=0.9, ks=0.0),
                  scale=90.0, translation=(280.0, 90.0, 280.0))
    images = {a: trace(scene, camera, (24, 24), spp=6, context=gl_context, progress=False,
                       accel=a).image for a in ("bvh", "flat", "hybrid")}
    a = images["bvh"]
    assert not np.array_equal(a, np.zeros_like(a))
    for other in ("flat", "hybrid"):
        b = images[other]
        close = np.isclose(a, b, rtol=1e-4, atol=1e-6).all(axis=-1)
        assert close.mean() >= 0.99, other
        assert abs(a.mean() - b.mean()) <= 1e-3 * a.mean(), other


def test_the_targets_hold_every_pixel_once():
    """The image in 8x8 blocks, 64 a target row (or more for a huge one): every image
    pixel has its own target pixel, inside the targets, at any size."""
    from glshade.render.film import film_layout, film_places

    for w, h in [(1, 1), (7, 9), (128, 128), (96, 96), (513, 3), (3, 700), (4096, 4096),
                 (9000, 20)]:
        (tw, th), blocks = film_layout(w, h)
        n = -(-w // 8) * -(-h // 8)  # (the image's blocks: no more than one target row
        assert tw <= 8192 and th <= 8192 and tw * th < 64 * (n + blocks[1])  # of waste)
        y, x = film_places(w, h, blocks)
        assert (x >= 0).all() and (x < tw).all() and (y >= 0).all() and (y < th).all()
        # (w * h places, no two the same: a count of each target pixel, none above one)
        assert np.bincount((y * tw + x).ravel(), minlength=tw * th).max() == 1


@settings(max_examples=30, deadline=None)
@given(w=st.integers(1, 300), h=st.integers(1, 300), side=st.sampled_from([64, 128, 256]))
def test_the_targets_fit_the_gls_largest_side_where_the_image_can(w, h, side):
    """Given the GL's largest framebuffer side, a row of blocks is never wider: an image
    that fits a side-by-side square of blocks is laid out within it (a 16384x16384 trace
    was refused for targets of 32768x8192 its size never needed), every pixel once."""
    from glshade.render.film import film_layout, film_places

    (tw, th), blocks = film_layout(w, h, max_side=side)
    n = -(-w // 8) * -(-h // 8)
    assert tw <= side
    if n <= (side // 8) ** 2:  # (the blocks fit a side x side target at all)
        assert th <= side
    y, x = film_places(w, h, blocks)
    assert (x < tw).all() and (y < th).all()
    assert np.bincount((y * tw + x).ravel(), minlength=tw * th).max() == 1


@settings(max_examples=16)
@given(w=st.integers(1, 90), h=st.integers(1, 90), shift=st.integers(0, 6))
@example(w=128, h=128, shift=0)
@example(w=513, h=2, shift=3)
def test_each_pixel_shows_its_own_ray(gl_context, w, h, shift):
    """Given rays, a pattern of pixels looks at an emitting square (E = 2, black, nothing
    else lit) and the rest into the void: the picture is the pattern, exactly -- so a
    pixel's path is traced where the tracer keeps it and read back to its own place."""
    scene = Scene(ambient=(0, 0, 0))
    scene.add(primitives.plane(8.0), Material(color=(1, 1, 1), kd=0.0, ks=0.0,
                                              emission=(2.0, 2.0, 2.0)),
              translation=(0.0, 0.0, -1.0))
    y, x = np.mgrid[0:h, 0:w]
    pattern = (7 * x + 3 * y + shift) % 5 == 0  # (top row first, as read gives it)
    rays = np.zeros((h, w, 2, 3))
    rays[..., 1, 2] = np.where(pattern, -1.0, 1.0)
    with GpuPathTracer(gl_context, TraceScene.from_scene(scene), w, h, rays=rays[::-1],
                       max_depth=1) as tracer:
        tracer.run(None, 1)
        total = tracer.read()[0]
    assert (total[..., 3] == 1).all()
    np.testing.assert_array_equal(total[..., :3], np.where(pattern, 2.0, 0.0)[..., None]
                                  * np.ones(3))


@pytest.mark.parametrize("accel", ["bvh", "hybrid"])
def test_the_walk_reads_storage_buffers_and_textures_alike(gl_context, accel):
    """The hierarchy's walk from storage buffers (GL 4.3) or from texel fetches (GL 3.3's
    way): the same bytes (the same rows, the same arithmetic), shadow rays (any hit stops
    the walk) and bounces alike, both samplers."""
    from glshade.radiosity import cornell_scene

    scene, camera = cornell_scene()
    scene.add(primitives.icosphere(2), Material(color=(0.7, 0.7, 0.7), kd=0.9, ks=0.0),
              scale=90.0, translation=(280.0, 90.0, 280.0))
    ts = TraceScene.from_scene(scene)
    for sampler in ("pcg", "sobol"):
        sums = []
        for storage in (True, False):
            with GpuPathTracer(gl_context, ts, 20, 16, accel=accel, sampler=sampler,
                               storage=storage) as tracer:
                assert tracer.storage is storage and tracer.accel == accel
                tracer.run(camera, 6, seed=2)
                sums.append(tracer.read())
        assert sums[0][0][..., :3].sum() > 0
        for a, b in zip(*sums):
            assert np.array_equal(a, b), sampler


@pytest.mark.parametrize("k", [1e-4, 1e5])
def test_every_way_draws_the_same_picture_at_any_scale(gl_context, k):
    """The Cornell box with a sphere and its camera scaled by ``k`` (the rays' offsets and
    the compiled constants scale with it): the same picture as at scale 1, to rounding,
    through the hierarchy, every triangle compiled in, and the hybrid."""
    import dataclasses

    from glshade.radiosity import cornell_scene

    scene, camera = cornell_scene()
    scene.add(primitives.icosphere(1), Material(color=(0.7, 0.7, 0.7), kd=0.9, ks=0.0),
              scale=90.0, translation=(280.0, 90.0, 280.0))
    ts = TraceScene.from_scene(scene)
    want = trace(ts, camera, (20, 20), spp=4, context=gl_context, progress=False,
                 accel="bvh").image
    scaled = dataclasses.replace(ts, triangles=ts.triangles * k, areas=ts.areas * k * k)
    seen = dataclasses.replace(camera, position=camera.position * k, near=camera.near * k,
                               far=camera.far * k)
    for accel in ("bvh", "flat", "hybrid"):
        got = trace(scaled, seen, (20, 20), spp=4, context=gl_context, progress=False,
                    accel=accel).image
        close = np.isclose(got, want, rtol=1e-3, atol=1e-6).all(axis=-1)
        assert close.mean() >= 0.98, (accel, close.mean())
        assert got.mean() == pytest.approx(want.mean(), rel=1e-3)


def test_compiled_emitters_pick_as_the_tables_search_does(gl_context, monkeypatch):
    """A few emitters' choice compiled in (constants, comparisons) and the table's binary
    search pick the same emitter with the same numbers: the Cornell box (two emitting
    triangles) and a room lit by a cube and a quad (14), the same picture both ways."""
    from glshade.radiosity import cornell_scene

    scene, camera = cornell_scene()
    lamp = Material(color=(0.5, 0.5, 0.5), kd=0.5, ks=0.0, emission=(3.0, 2.0, 1.0))
    lit = Scene(ambient=(0, 0, 0))
    lit.add(primitives.cube().flipped(), Material(color=(0.7, 0.6, 0.5), kd=0.8, ks=0.0),
            scale=4.0)
    lit.add(primitives.cube(), lamp, scale=0.5, translation=(0.3, 1.2, -0.6))
    lit.add(primitives.plane(0.8), lamp, translation=(-1.0, -1.9, 0.0))  # (12 + 2 emit)
    for s, cam in ((scene, camera), (lit, INSIDE)):
        compiled = trace(s, cam, (20, 20), spp=6, context=gl_context, progress=False).image
        monkeypatch.setattr(GpuPathTracer, "EMITTERS_COMPILED", 0)
        searched = trace(s, cam, (20, 20), spp=6, context=gl_context, progress=False).image
        monkeypatch.undo()
        assert compiled.mean() > 0
        close = np.isclose(compiled, searched, rtol=1e-5, atol=1e-7).all(axis=-1)
        assert close.mean() >= 0.99


def test_auto_picks_the_flat_loop_for_a_few_dozen_triangles(gl_context):
    from glshade.errors import OptionError
    from glshade.pathtrace import PathTracer
    from glshade.radiosity import cornell_scene

    scene, _ = cornell_scene()
    with PathTracer(scene, (8, 8), context=gl_context) as tracer:
        assert tracer.gpu.accel == "flat"
    scene.add(primitives.icosphere(3), Material())
    with PathTracer(scene, (8, 8), context=gl_context) as tracer:
        assert tracer.gpu.accel == "hybrid"  # (the walls compiled in, the sphere's hierarchy)
        assert tracer.gpu.layout["compiled"] == 32
    alone = Scene()
    alone.add(primitives.icosphere(3), Material())  # (one large model)
    with PathTracer(alone, (8, 8), context=gl_context, camera=Camera()) as tracer:
        assert tracer.gpu.accel == "bvh"
    with PathTracer(alone, (8, 8), context=gl_context, camera=Camera(),
                    accel="hybrid") as tracer:
        assert tracer.gpu.accel == "bvh"  # (nothing small to compile in)
    with pytest.raises(OptionError, match="accel must be 'auto', 'bvh', 'flat' or 'hybrid'"):
        PathTracer(scene, (8, 8), context=gl_context, accel="kd-tree")
    scene.add(primitives.icosphere(5), Material())   # (20,480 triangles: too many to compile)
    with pytest.raises(OptionError, match=r"accel='flat' compiles the triangles into the "
                       r"program: at most 256, the scene has 21,792 \(use accel='bvh'\)"):
        PathTracer(scene, (8, 8), context=gl_context, accel="flat")
