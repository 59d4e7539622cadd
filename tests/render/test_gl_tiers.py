"""The 4.1 paths against their 4.3 twins, picture for picture, on one driver: a context held
to the 4.1 tier (``create_context(tier="4.1")``: what a Mac's GL takes) beside the shared
context's own 4.3 paths, over the sweeps the 4.3 paths have. Exact shadows: the same
visibility, byte for byte (fragment programs walking the hierarchy in textures against
the compute pass through storage buffers); maps: the same lookups; transparency: depth
peeling against the fragment lists within one 8-bit step at 1, 8, 32 and 64 layers and
over random soups. These compare two tiers, so they run where the shared context has
4.3 (the EGL pass); the suite's 4.1 pass (scripts/mac-gl41.sh) runs every feature test
against its own oracle on a real 4.1 core context."""

import numpy as np
import pytest

import glshade as g
from tests.conftest import BACKEND, require
from tests.render.test_shadows import FOV, H, W, light_and_eye, scene_of
from tests.render.test_transparency import CAMERA, a_buffer, crossing, soup
from tests.render.test_transparency import H as SOUP_H, W as SOUP_W
from tests.render.test_transparency import scene_of as soup_scene

require("hypothesis", "property-based sweeps are part of the test extra")
from hypothesis import HealthCheck, example, given, settings, strategies as st  # noqa: E402

SOUP = (SOUP_W, SOUP_H)
pytestmark = pytest.mark.once  # (two tiers on one driver: the EGL pass, where 4.3 is)


@pytest.fixture(scope="module")
def tiers(gl_context):
    """``pair(samples, size)``: a renderer at the shared context's tier (4.3) and one on a
    context held to 4.1, made once each."""
    from glshade.render.context import create_context
    from glshade.render.renderer import Renderer

    if not gl_context.features.storage:
        pytest.fail(f"the tier comparisons need a 4.3 context to compare with; this one "
                    f"is {gl_context.features.tier}", pytrace=False)
    held = create_context(BACKEND, tier="4.1")
    assert held.features.tier == "4.1" and not held.features.storage
    made: dict = {}

    def pair(samples, size=(W, H)):
        key = (samples, size)
        if key not in made:
            made[key] = tuple(Renderer(*size, samples=samples, context=c)
                              for c in (gl_context, held))
            gl_context.make_current()
        return made[key]

    yield pair
    for both in made.values():
        for r in both:
            r.close()
    held.release()
    gl_context.make_current()


def _both(pair, draw):
    out = []
    for r in pair:
        r.context.make_current()
        out.append(draw(r))
    pair[0].context.make_current()
    return out


@settings(max_examples=12, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@example(kind="bored", elevation=40.0, azimuth=30.0, eye_elevation=30.0, eye_azimuth=20.0,
         distance=5.0, point=True, samples=4, ortho=False)
@example(kind="torus", elevation=12.0, azimuth=200.0, eye_elevation=60.0, eye_azimuth=90.0,
         distance=3.0, point=False, samples=0, ortho=True)
@given(kind=st.sampled_from(["cube", "torus", "ball", "bored", "sphere"]),
       elevation=st.floats(2.0, 88.0), azimuth=st.floats(0.0, 360.0),
       eye_elevation=st.floats(2.0, 80.0), eye_azimuth=st.floats(0.0, 360.0),
       distance=st.floats(1.5, 8.0), point=st.booleans(), samples=st.sampled_from([0, 4]),
       ortho=st.booleans())
def test_shadows_at_4_1_are_the_4_3_visibility(tiers, kind, elevation, azimuth, eye_elevation,
                                              eye_azimuth, distance, point, samples, ortho):
    """Lights anywhere above the floor (a point light or a directional one), eyes from
    grazing to high, inside the scene's box too, perspective and orthographic, MSAA off and
    4, meshes and CSG solids casting: exact visibility byte for byte, map visibility byte
    for byte (one lookup, drawn by a fragment program instead of a compute pass), and the
    pictures the same bytes."""
    light, eye, target = light_and_eye(elevation, azimuth, eye_elevation, eye_azimuth,
                                       distance, point)
    camera = g.Camera.look_at(eye, target, fov_y=FOV)
    if ortho:
        camera = camera.replace(projection="orthographic", height=4.0)
    scene = scene_of(kind, light)
    methods = ("exact",) if kind in ("sphere", "bored") else ("exact", "map")
    for method in methods:
        f43, f41 = _both(tiers(samples), lambda r, m=method: r.render_frame(
            scene, camera, "phong", shadows=m))
        assert np.array_equal(f41.visibility, f43.visibility), (method, int(
            (f41.visibility != f43.visibility).sum()))
        assert np.array_equal(f41.color, f43.color), method


def _max_step(pair, scene, **options):
    lists, peeled = _both(pair, lambda r: r.render(scene, CAMERA, "flat", cull=False,
                                                   **options))
    assert pair[1].transparent.peeled > 0 and pair[0].transparent.peeled == 0
    return int(np.abs(lists.astype(int) - peeled.astype(int)).max())


@pytest.mark.parametrize("layers", [1, 8, 32, 64])
def test_depth_peeling_is_the_fragment_lists_picture_at_any_depth(tiers, layers):
    """n triangles all crossing the view's centre (depth complexity n there, piercing one
    another everywhere): depth peeling's picture is the fragment lists' within one 8-bit
    step, with as many layers peeled as the deepest pixel has, and the same report."""
    tri, col, a = crossing(layers, layers)
    scene = soup_scene(tri, col, a)
    pair = tiers(0, SOUP)
    assert _max_step(pair, scene, max_layers=64) <= 1
    assert pair[1].transparent.peeled == layers
    lists, peeled = pair[0].transparency, pair[1].transparency
    assert (peeled.fragments, peeled.pixels_over) == (lists.fragments, 0)


def test_depth_peeling_reports_what_max_layers_left_out_as_the_lists_do(tiers):
    tri, col, a = crossing(40, 7)
    scene = soup_scene(tri, col, a)
    pair = tiers(0, SOUP)
    with pytest.warns(g.RenderWarning, match="more than max_layers=16"):
        assert _max_step(pair, scene, max_layers=16) <= 1
    lists, peeled = pair[0].transparency, pair[1].transparency
    assert peeled.pixels_over == lists.pixels_over > 0
    assert peeled.fragments_over == lists.fragments_over > 0
    assert peeled.fragments == lists.fragments and pair[1].transparent.peeled == 16


@settings(max_examples=15, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(n=st.integers(1, 24), seed=st.integers(0, 2**16), spread=st.floats(0.2, 1.6),
       low=st.floats(0.01, 0.99), samples=st.sampled_from([0, 4]),
       mode=st.sampled_from(["flat", "phong"]))
def test_depth_peeling_over_soups_and_opacities(tiers, n, seed, spread, low, samples, mode):
    """The fragment lists' sweep: interpenetrating soups of any spread, opacities from
    nearly clear to nearly opaque, MSAA off and 4 (away from the polygon edges under MSAA,
    where the lists keep a pixel's first sample and peeling its centre)."""
    tri, col, _ = soup(n, seed, spread)
    a = np.random.default_rng(seed).uniform(low, 0.99, n)
    scene = soup_scene(tri, col, a)
    pair = tiers(samples, SOUP)
    frames = _both(pair, lambda r: r.render_frame(scene, CAMERA, mode, cull=False,
                                                  max_layers=32))
    d = np.abs(frames[0].color.astype(int) - frames[1].color.astype(int)).max(-1)
    if samples:  # (judged further than half a pixel's diagonal from every edge)
        d = d[a_buffer(tri, col, a, margin=0.75)[1]]
    assert d.max(initial=0) <= 1, int(d.max())
