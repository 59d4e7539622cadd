"""Transparency against a numpy A-buffer that shares no code with glshade: its own camera
matrices, triangles projected in float64 and snapped to GL's 1/256 sub-pixel grid, edge
functions with the top-left rule at each pixel centre, every fragment of a pixel sorted by
view depth and composited "over" onto the background. Unlit colours (ambient alone, ka = 1)
make each fragment's colour its material's.

exact: within 1/255 at every pixel further than 0.01 px from a projected edge (and away
from the lines where triangles pierce each other), at depth complexity up to 64; any
permutation of the draw order gives identical bytes; n stacked layers of opacity a cover
1 - (1 - a)^n; more layers than ``max_layers`` are reported with their count."""

import numpy as np
import pytest

import glshade as g
from tests.conftest import require

W, H = 96, 80
EYE, TARGET, FOV = np.array([0.3, 0.2, 6.0]), np.array([0.0, 0.0, 0.0]), 40.0
BACKGROUND = (26 / 255, 38 / 255, 51 / 255)  # (8-bit levels: the opaque picture is 8-bit)
SNAP = 256.0
NUDGES = [np.array(o) for o in ((0.01, 0.0), (-0.01, 0.0), (0.0, 0.01), (0.0, -0.01))]


def look_at(eye, target):
    f = (target - eye) / np.linalg.norm(target - eye)
    r = np.cross(f, (0.0, 1.0, 0.0))
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    return r, u, f


def window(points):
    """World points (N, 3) -> (x right, y down from the image's top, view depth)."""
    r, u, f = look_at(EYE, TARGET)
    q = points - EYE
    depth = q @ f
    tan = np.tan(np.radians(FOV) / 2)
    x = (q @ r) / (depth * tan * W / H)
    y = (q @ u) / (depth * tan)
    return np.stack([(x + 1) * W / 2, (1 - y) * H / 2, depth], -1)


def a_buffer(triangles, colors, opacity, margin=0.01):
    """The oracle: ``(H, W, 3)`` float composite, and ``(H, W)`` bool: pixels to judge
    (further than ``margin`` px from every projected edge)."""
    px = np.stack(np.meshgrid(np.arange(W) + 0.5, np.arange(H) + 0.5), -1)  # (H, W, 2)
    frags_d, frags_c, frags_a, nudged = [], [], [], []
    judge = np.ones((H, W), bool)
    for tri, col, a in zip(triangles, colors, opacity):
        w = window(tri)
        v = np.round(w[:, :2] * SNAP) / SNAP                      # sub-pixel snap
        area = (v[1, 0] - v[0, 0]) * (v[2, 1] - v[0, 1]) - \
            (v[2, 0] - v[0, 0]) * (v[1, 1] - v[0, 1])
        if area == 0:
            continue
        e = []
        for i in range(3):
            a0, a1 = v[i], v[(i + 1) % 3]
            # edge function of a0 -> a1 at the pixel centres, positive inside (any winding)
            fn = (a1[0] - a0[0]) * (px[..., 1] - a0[1]) - (a1[1] - a0[1]) * (px[..., 0] - a0[0])
            fn = fn * np.sign(area)
            judge &= np.abs(fn) / np.hypot(*(a1 - a0)) > margin   # (px from the edge)
            # top-left rule (y down): a point on a top or left edge is inside
            dy, dx = (a1[1] - a0[1]) * np.sign(area), (a1[0] - a0[0]) * np.sign(area)
            top_left = (dy < 0) or (dy == 0 and dx > 0)
            e.append(fn > 0 if not top_left else fn >= 0)
        inside = e[0] & e[1] & e[2]
        # perspective-correct view depth: 1 / depth is affine on the screen
        depth = 1.0 / (barycentric(v, px) @ (1.0 / w[:, 2]))
        frags_d.append(np.where(inside, depth, np.inf))
        nudged.append([np.where(inside, 1.0 / (barycentric(v, px + o) @ (1.0 / w[:, 2])),
                                np.inf) for o in NUDGES])
        frags_c.append(np.broadcast_to(col, (H, W, 3)))
        frags_a.append(np.where(inside, a, 0.0))
    d = np.stack(frags_d)                                         # (F, H, W)
    order = np.argsort(d, axis=0, kind="stable")
    # (where two surfaces pierce each other: their order must hold 0.01 px about the centre)
    for k in range(len(NUDGES)):
        moved = np.argsort(np.stack([n[k] for n in nudged]), axis=0, kind="stable")
        judge &= (moved == order).all(0)
    c = np.stack(frags_c)[order[..., None].repeat(3, -1), np.arange(H)[None, :, None, None],
                          np.arange(W)[None, None, :, None], np.arange(3)]
    a = np.take_along_axis(np.stack(frags_a), order, 0)
    out = np.zeros((H, W, 3))
    t = np.ones((H, W))
    for k in range(len(d)):
        out += (t * a[k])[..., None] * c[k]
        t *= 1 - a[k]
    return out + t[..., None] * np.asarray(BACKGROUND), judge


def covered_at_most(triangles) -> int:
    """The most triangles any pixel centre lies in (the depth complexity)."""
    _, _, counts = _coverage(triangles)
    return int(counts.max())


def _coverage(triangles):
    px = np.stack(np.meshgrid(np.arange(W) + 0.5, np.arange(H) + 0.5), -1)
    counts = np.zeros((H, W), int)
    for tri in triangles:
        lam = barycentric(window(tri)[:, :2], px)
        counts += (lam >= 0).all(-1)
    return px, None, counts


def barycentric(v, px):
    (x0, y0), (x1, y1), (x2, y2) = v
    det = (y1 - y2) * (x0 - x2) + (x2 - x1) * (y0 - y2)
    l0 = ((y1 - y2) * (px[..., 0] - x2) + (x2 - x1) * (px[..., 1] - y2)) / det
    l1 = ((y2 - y0) * (px[..., 0] - x2) + (x0 - x2) * (px[..., 1] - y2)) / det
    return np.stack([l0, l1, 1 - l0 - l1], -1)


def soup(n, seed, spread=1.0, reach=1.0):
    """``n`` random interpenetrating triangles in front of the camera, centres within
    ``reach``, corners ``spread`` (sd) about them, with colours and opacities."""
    rng = np.random.default_rng(seed)
    centre = rng.uniform(-reach, reach, (n, 1, 3)) * (1.2, 1.0, 1.0)
    tri = centre + rng.normal(0, spread, (n, 3, 3))
    return tri, rng.uniform(0, 1, (n, 3)), rng.uniform(0.15, 0.85, n)


def crossing(n, seed):
    """``n`` tilted triangles that all hold the view's centre (corners about 120 degrees
    apart around it, at random depths): depth complexity n there, piercing everywhere."""
    rng = np.random.default_rng(seed)
    turn = rng.uniform(0, 2 * np.pi, (n, 1)) + np.array([0, 2, 4]) * np.pi / 3 + \
        rng.uniform(-0.3, 0.3, (n, 3))
    radius = rng.uniform(1.2, 2.4, (n, 3))
    tri = np.stack([radius * np.cos(turn), radius * np.sin(turn),
                    rng.uniform(-1.5, 1.5, (n, 3))], -1)
    return tri, rng.uniform(0, 1, (n, 3)), rng.uniform(0.05, 0.3, n)


def scene_of(triangles, colors, opacity, order=None):
    s = g.Scene(ambient=(1.0, 1.0, 1.0), background=BACKGROUND)
    for k in (range(len(triangles)) if order is None else order):
        mesh = g.Mesh(triangles[k], [[0, 1, 2]])
        s.add(mesh, g.Material(color=tuple(colors[k]), ka=1.0, kd=0.0, ks=0.0,
                               opacity=float(opacity[k])))
    s.add_light(g.PointLight(position=(0, 0, 10), intensity=0.0))
    return s


CAMERA = g.Camera.look_at(EYE, TARGET, fov_y=FOV)


@pytest.fixture(params=["fetch", "atomics"])
def counting(request, monkeypatch):
    """Both ways a pixel's fragments are counted and linked: framebuffer fetch (where the
    GL has it) and storage-buffer atomics."""
    from glshade.render.passes.transparency import TransparencyPass

    monkeypatch.setattr(TransparencyPass, "use_fetch", request.param == "fetch")
    return request.param


def _counted_by(renderer, counting):
    """The path the last exact draw took is the one asked for (where the GL has fetch);
    where it has no storage buffers (a 4.1 tier), depth peeling, which counts nothing."""
    used = renderer.transparent.counted_by_fetch
    if not renderer.context.features.storage:
        assert not used and renderer.transparent.peeled
        return
    has = "GL_EXT_shader_framebuffer_fetch" in renderer.ctx.extensions
    assert used == (counting == "fetch" and has)


@pytest.mark.parametrize("n, seed, deepest", [(6, 1, 2), (24, 2, 6), (64, 3, 64)])
def test_exact_matches_the_a_buffer(make_renderer, counting, n, seed, deepest):
    """Random soups; the last one's triangles all cross the middle: up to 64 layers."""
    tri, col, a = soup(n, seed, 0.9, 1.0) if n < 64 else crossing(n, seed)
    expected, judge = a_buffer(tri, col, a)
    r = make_renderer(W, H)
    got = r.render(scene_of(tri, col, a), CAMERA, "flat", cull=False,
                   max_layers=64).astype(float)[..., :3]
    err = np.abs(got - expected * 255).max(-1)
    assert judge.mean() > 0.3
    assert err[judge].max() <= 1.0, (err[judge].max(), np.argwhere((err > 1) & judge)[:5])
    assert r.transparency.pixels_over == 0
    _counted_by(r, counting)
    layers = max(int((window(t)[:, 2] > 0).all()) for t in tri)  # (all in front)
    assert layers == 1 and covered_at_most(tri) >= deepest


def test_both_ways_of_counting_give_the_same_bytes_and_counts(make_renderer, monkeypatch):
    from glshade.render.passes.transparency import TransparencyPass

    tri, col, a = crossing(64, 3)
    r = make_renderer(W, H)
    out = {}
    for fetch in (True, False):
        monkeypatch.setattr(TransparencyPass, "use_fetch", fetch)
        with pytest.warns(g.RenderWarning, match="more than max_layers=16"):
            img = r.render(scene_of(tri, col, a), CAMERA, "phong", cull=False,
                           max_layers=16)
        out[fetch] = (img, r.transparency)
    assert np.array_equal(out[True][0], out[False][0])
    assert out[True][1] == out[False][1] and out[True][1].fragments_over > 0


def test_weighted_and_blend_are_the_approximations_they_are(make_renderer):
    """On the same soup: weighted blended OIT and drawing-order blending differ from the
    A-buffer by more than a level somewhere (they are not exact); exact does not."""
    tri, col, a = soup(24, 2, 0.9)
    expected, judge = a_buffer(tri, col, a)
    r = make_renderer(W, H)
    errors = {}
    methods = ("exact", "weighted", "blend")
    if not r.context.features.storage:  # (weighted keeps fragment lists: GL 4.3)
        with pytest.raises(g.errors.EnvironmentFailure, match=r"transparency='weighted' "
                           r"keeps .* need OpenGL 4\.3; this GL is .*use transparency="
                           r"'exact' \(depth peeling here\) or 'blend'"):
            r.render(scene_of(tri, col, a), CAMERA, "flat", transparency="weighted")
        methods = ("exact", "blend")
        errors["weighted"] = 2.0
    for method in methods:
        got = r.render(scene_of(tri, col, a), CAMERA, "flat", cull=False,
                       transparency=method).astype(float)[..., :3]
        errors[method] = np.abs(got - expected * 255)[judge].max()
    assert errors["exact"] <= 1 < errors["weighted"] and errors["blend"] > 1, errors


def test_any_draw_order_gives_the_same_bytes(make_renderer):
    tri, col, a = soup(24, 5, 0.9)
    r = make_renderer(W, H, samples=4)
    first = r.render(scene_of(tri, col, a), CAMERA, "phong")
    for seed in range(3):
        order = np.random.default_rng(seed).permutation(len(tri))
        assert np.array_equal(r.render(scene_of(tri, col, a, order), CAMERA, "phong"), first)


def _layers(n: int, opacity: float):
    """n parallel white squares of ``opacity`` 0.01 apart over black, lit by the ambient
    term alone: the centre's value is 1 - (1 - opacity)^n."""
    s = g.Scene(ambient=(1.0, 1.0, 1.0), background=(0, 0, 0))
    for k in range(n):
        s.add(g.geometry.primitives.plane(1.0),
              g.Material(color=(1, 1, 1), ka=1.0, kd=0.0, ks=0.0, opacity=opacity),
              translation=(0, 0, -0.01 * k))
    s.add_light(g.PointLight(position=(0, 0, 5), intensity=0.0))
    return s


@pytest.mark.parametrize("samples", [0, 4])
@pytest.mark.parametrize("opacity", [0.1, 0.2, 0.35])
def test_blending_in_drawing_order_rounds_once(make_renderer, opacity, samples):
    """Identical layers blended in drawing order ("blend": the order cannot matter here)
    give 1 - (1 - a)^n within half a level: the colour is blended in float and rounded
    once (each layer rounded to 8 bits gave 253 for 32 layers of 0.2, not 254.8)."""
    r = make_renderer(32, 32, samples)
    for n in (1, 4, 12, 32):
        s = _layers(n, opacity)
        camera = g.Camera.look_at((0, 0, 3), (0, 0, 0))
        want = 255 * (1 - (1 - opacity) ** n)
        img = r.render(s, camera, "flat", transparency="blend")
        assert abs(img[16, 16, 0] - want) <= 0.5 + 1e-9, (n, img[16, 16], want)
        frame = r.render_frame(s, camera, "flat", transparency="blend")
        assert np.array_equal(frame.color, img)


@pytest.mark.parametrize("opacity", [0.1, 0.35, 0.8])
def test_n_stacked_layers_cover_one_minus_one_minus_a_to_the_n(make_renderer, opacity):
    """n coplanar-free parallel squares of opacity a, white over black: the centre's value
    is 1 - (1 - a)^n."""
    r = make_renderer(32, 32)
    # (1 to 8 layers: a resolve that sorts only as many slots as the deepest pixel has)
    for n, sorted_slots in ((1, 1), (2, 2), (3, 4), (5, 8), (16, 0), (40, 0)):
        s = _layers(n, opacity)
        img = r.render(s, g.Camera.look_at((0, 0, 3), (0, 0, 0)), "flat",
                       max_layers=64)
        assert abs(img[16, 16, 0] - 255 * (1 - (1 - opacity) ** n)) <= 1.0, (n, img[16, 16])
        if not r.context.features.storage:  # (depth peeling: n layers peeled)
            assert r.transparent.peeled == n
            continue
        used = [key[-1] for key in r.transparent.compiled]
        assert used[-1] == sorted_slots or sorted_slots in used, (n, used)


def test_more_layers_than_max_layers_are_reported(make_renderer, counting):
    r = make_renderer(32, 32)
    s = g.Scene(ambient=(1.0, 1.0, 1.0), background=(0, 0, 0))
    for k in range(12):
        s.add(g.geometry.primitives.plane(1.0),
              g.Material(color=(1, 1, 1), ka=1.0, kd=0.0, ks=0.0, opacity=0.3),
              translation=(0, 0, -0.01 * k))
    with pytest.warns(g.RenderWarning, match=r"pixels had more than max_layers=8"):
        img = r.render(s, g.Camera.look_at((0, 0, 3), (0, 0, 0)), "flat", max_layers=8)
    report = r.transparency
    covered = int((img[..., 0] > 0).sum())
    assert report.pixels_over == covered and report.fragments_over == 4 * covered
    assert report.fragments == 12 * covered  # (summed from the lists when asked for)
    assert abs(img[16, 16, 0] - 255 * (1 - 0.7 ** 8)) <= 1.0  # (the nearest 8)
    _counted_by(r, counting)


def glass_over_cube():
    s = g.Scene(ambient=(0.3, 0.3, 0.3), background=(0.1, 0.1, 0.1))
    s.add(g.geometry.primitives.cube(), g.Material(color=(0.9, 0.2, 0.2)),
          translation=(0, 0, -1.0))
    s.add(g.geometry.primitives.icosphere(3, 0.8), g.Material(color=(0.2, 0.4, 0.9),
                                                              opacity=0.4))
    s.add_light(g.PointLight(position=(3, 4, 5)))
    return s, g.Camera.look_at((0, 0.3, 5), (0, 0, 0))


def test_depth_normal_and_ids_report_the_nearest_opaque_surface(make_renderer):
    """Documented: the auxiliary outputs are those of the nearest opaque surface -- the
    frame with the glass sphere equals the frame without it there."""
    scene, camera = glass_over_cube()
    r = make_renderer(80, 60)
    with_glass = r.render_frame(scene, camera, "phong")
    scene.models[1].visible = False
    without = r.render_frame(scene, camera, "phong")
    assert np.array_equal(with_glass.face_id, without.face_id)
    assert np.array_equal(with_glass.depth, without.depth)
    assert np.array_equal(with_glass.normal, without.normal)
    seen_through = (with_glass.face_id >= 0) & (np.abs(with_glass.color.astype(int) -
                                                        without.color.astype(int)).max(-1) > 20)
    assert seen_through.sum() > 100  # (the glass is there, over the cube)


@pytest.mark.parametrize("mode", ["flat", "gouraud", "phong"])
def test_every_lit_mode_and_msaa_composite_the_same_way(make_renderer, mode):
    """MSAA changes edges only: inside the silhouettes (the glass's too: a multisampled
    pixel's transparent fragment is its sample 0's) the 4-sample composite equals the
    1-sample one within a level; edges drawn over the glass still show."""
    scene, camera = glass_over_cube()
    plain = make_renderer(80, 60).render(scene, camera, mode).astype(int)
    msaa = make_renderer(80, 60, samples=4).render(scene, camera, mode).astype(int)
    solid = glass_over_cube()[0]
    solid.models[1].material = g.Material()  # (opaque: its silhouette in the ids too)
    ids = make_renderer(80, 60).render_frame(solid, camera, mode).face_id
    inside = np.ones_like(ids, bool)
    for axis in (0, 1):
        for step in (1, -1):
            inside &= np.roll(ids, step, axis) == ids
    assert np.abs(plain - msaa)[inside].max() <= 1
    edged = make_renderer(80, 60).render(scene, camera, mode, edges=True).astype(int)
    assert (np.abs(edged - plain).max(-1) > 30).sum() > 50


def test_the_debug_modes_draw_transparent_surfaces_as_they_are(make_renderer):
    """Normals and depth show values, not surfaces to see through: opacity is not used."""
    scene, camera = glass_over_cube()
    r = make_renderer(80, 60)
    a = r.render(scene, camera, "normals")
    scene.models[1].material = g.Material(color=(0.2, 0.4, 0.9))
    assert np.array_equal(a, r.render(scene, camera, "normals"))


@pytest.mark.parametrize("tier", ["4.1", "3.3"])
def test_a_gl_without_storage_buffers_peels_and_is_told_what_to_use(gl_context, tier):
    """Fragment lists need GL 4.3; on an older GL (a context held to its tier) the default,
    exact, peels depth layers -- the lists' picture within one 8-bit step -- and weighted
    gets one line naming the ways that work."""
    from glshade.render.context import create_context
    from glshade.render.renderer import Renderer
    from tests.conftest import BACKEND

    scene, camera = glass_over_cube()
    with create_context(BACKEND, tier=tier) as older:
        r = Renderer(32, 24, context=older)
        assert older.features.tier == tier and not older.features.storage
        with pytest.raises(g.errors.EnvironmentFailure, match=rf"need OpenGL 4\.3; this GL "
                           rf"is {tier}.*use transparency='exact' \(depth peeling here\) "
                           r"or 'blend'"):
            r.render(scene, camera, "phong", transparency="weighted")
        peeled = r.render(scene, camera, "phong")
        assert r.transparent.peeled == 2  # (the sphere's front and back)
        blended = r.render(scene, camera, "phong", transparency="blend")
        r.close()
    assert blended.shape == (24, 32, 4) and np.abs(peeled.astype(int) - blended).max() > 0


require("hypothesis", "property-based sweeps are part of the test extra")
from hypothesis import HealthCheck, assume, given, settings, strategies as st  # noqa: E402


@settings(max_examples=30, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(n=st.integers(1, 24), seed=st.integers(0, 2**16), spread=st.floats(0.2, 1.6),
       low=st.floats(0.01, 0.99), width=st.floats(0.0, 0.98), samples=st.sampled_from([0, 4]))
def test_exact_over_soups_and_opacities(make_renderer, n, seed, spread, low, width, samples):
    """The A-buffer sweep over the range: 1 to 24 interpenetrating triangles of any spread,
    opacities anywhere in [0.01, 0.99] (nearly clear to nearly opaque), MSAA off and 4."""
    tri, col, _ = soup(n, seed, spread)
    assume((window(tri.reshape(-1, 3))[:, 2] > 0.5).all())  # (all in front of the eye)
    assume(_coverage(tri)[2].sum() > 20)                     # (and in its view)
    a = np.random.default_rng(seed).uniform(low, min(low + width, 0.99), n)
    # (under MSAA a pixel's fragment is its first sample's: judged where no edge crosses
    # the pixel, further than half its diagonal from every edge)
    expected, judge = a_buffer(tri, col, a, margin=0.75 if samples else 0.01)
    r = make_renderer(W, H, samples=samples)
    got = r.render(scene_of(tri, col, a), CAMERA, "flat", cull=False,
                   max_layers=32).astype(float)[..., :3]
    err = np.abs(got - expected * 255).max(-1)
    assert err[judge].max(initial=0) <= 1.0, np.argwhere((err > 1) & judge)[:5].tolist()
