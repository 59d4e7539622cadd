"""The hidden-surface lab against the GPU z-buffer: every algorithm gives the GPU's polygon
ids (exactly, away from edges) and its view depth, on soups, piercing triangles, cyclic
overlaps, the teapot and a closed mesh seen from inside, in perspective and orthographic
views; and the counters follow the notes' cost model."""

import numpy as np
import pytest

from glshade import Camera, Mesh, Scene, default_camera
from glshade.hidden import (ALGORITHMS, DepthSortCycle, bsp, depth_sort, edge_pixels,
                                prepare, raycast)
from glshade.geometry import primitives
from glshade.modes import Outputs

SIZE = (160, 120)


def soup(n, seed, piercing):
    """Random triangles; without piercing, each lies in a plane facing the camera at its
    own depth (so none can cut another)."""
    rng = np.random.default_rng(seed)
    centre = rng.uniform(-1, 1, (n, 1, 3))
    v = centre + rng.normal(0, 0.3, (n, 3, 3))
    if not piercing:
        v[:, :, 2] = np.linspace(-1, 1, n)[rng.permutation(n)][:, None]
    return Mesh(v.reshape(-1, 3), np.arange(3 * n).reshape(-1, 3))


def bars():
    """Three bars, each passing over the next and under the one before: a cycle."""
    verts, quads = [], []
    for k in range(3):
        a = 2 * np.pi * k / 3
        d, n = np.array([np.cos(a), np.sin(a), 0]), np.array([-np.sin(a), np.cos(a), 0])
        p0, p1 = -1.2 * d + [0, 0, -0.3], 1.2 * d + [0, 0, 0.3]
        verts += [p0 - 0.15 * n, p1 - 0.15 * n, p1 + 0.15 * n, p0 + 0.15 * n]
        quads.append([4 * k, 4 * k + 1, 4 * k + 2, 4 * k + 3])
    return Mesh(np.array(verts), quads)


def _scene(mesh):
    s = Scene()
    s.add(mesh)
    return s


def views():
    front = Camera.look_at((0.3, 0.4, 5), (0, 0, 0), fov_y=45)
    teapot = _scene(primitives.teapot(5))
    inside = _scene(primitives.icosphere(2, radius=3.0))
    return {
        "soup": (_scene(soup(120, 1, False)), front),
        "piercing soup": (_scene(soup(60, 2, True)), front),
        "cyclic bars": (_scene(bars()), Camera.look_at((0, 0, 6), (0, 0, 0))),
        "teapot": (teapot, default_camera(teapot.bounds, SIZE[0] / SIZE[1])),
        "inside a closed mesh": (inside, Camera.look_at((0.2, 0.1, 0.3), (1, 0.4, -1),
                                                        near=0.05)),
        # parallel rays: the eye is at infinity, so "which side of a plane faces the eye"
        # no longer depends on where the plane is (the painters' tests and BSP walk)
        "teapot, orthographic": (teapot, Camera.look_at((3, 2, 4), (0, 0.5, 0)).replace(
            projection="orthographic", height=4.0)),
        "cyclic bars, orthographic": (_scene(bars()), Camera.look_at(
            (0.5, 0.3, 6), (0, 0, 0)).replace(projection="orthographic", height=3.0)),
    }


VIEWS = views()


@pytest.fixture(scope="module")
def gpu_frames(gl_context):
    from glshade.render.renderer import Renderer

    out = {}
    with Renderer(*SIZE, samples=0, context=gl_context) as r:
        for name, (scene, camera) in VIEWS.items():
            out[name] = r.render_frame(scene, camera, "flat", cull=False,
                                       outputs=Outputs.FACE_ID | Outputs.DEPTH)
    return out


def depth_resolution(camera, depth, bounds):
    """The view-depth step of a 24-bit depth buffer at ``depth`` (linear in depth for an
    orthographic camera); the clip planes are the camera's as fitted to the scene."""
    n, f = camera.planes(bounds)
    if camera.projection == "orthographic":
        return (f - n) * 2.0 ** -24 + 0 * depth
    return depth ** 2 * (f - n) / (f * n) * 2.0 ** -24


@pytest.mark.parametrize("view", list(VIEWS))
@pytest.mark.parametrize("algorithm", list(ALGORITHMS))
def test_every_algorithm_gives_the_gpu_ids_and_depth(algorithm, view, gpu_frames):
    scene, camera = VIEWS[view]
    p = prepare(scene, camera, SIZE)
    result = ALGORITHMS[algorithm](p)
    gpu = gpu_frames[view]
    covered = int((gpu.face_id >= 0).sum())
    assert covered > 500
    edges = edge_pixels(p, 1 / 256)  # (pixel centres within the GPU's vertex snap of an edge)
    diff = result.face_id != gpu.face_id
    # away from edges: equal, but where the GPU's 24-bit depth buffer cannot tell the two
    # surfaces apart (piercing triangles, at their line of intersection)
    off = diff & ~edges
    with np.errstate(invalid="ignore"):  # (inf - inf where one of them saw nothing)
        tie = np.abs(result.depth - gpu.depth) <= 4 * depth_resolution(camera, gpu.depth,
                                                                        scene.bounds)
    assert (off & ~tie).sum() == 0, np.argwhere(off & ~tie)[:5]
    assert (off & tie).sum() <= 2
    assert (diff & edges).sum() < 0.005 * covered
    same = ~diff & (gpu.face_id >= 0)
    rel = np.abs(result.depth[same] - gpu.depth[same]) / gpu.depth[same]
    assert rel.max() < 1e-5
    assert np.isinf(result.depth[gpu.face_id < 0]).all()


def test_depth_sort_without_splitting_names_the_cycle():
    scene, camera = VIEWS["cyclic bars"]
    with pytest.raises(DepthSortCycle, match="overlap cyclically"):
        depth_sort(prepare(scene, camera, SIZE), split=False)
    result = depth_sort(prepare(scene, camera, SIZE))
    assert result.counters["splits"] > 0


def slope(x, y):
    return np.polyfit(np.log(x), np.log(y), 1)[0]


def _box_pixels(p):
    """The pixel centres inside each triangle's screen bounding box, summed: the pairs a
    box-culled ray caster must test (the test's own count, from the prepared screen)."""
    w, h = p.size
    lo, hi = p.screen.min(1), p.screen.max(1)
    total = 0
    for (x0, y0), (x1, y1) in zip(lo, hi):  # (a plain loop: the slow, obvious count)
        cols = [i for i in range(w) if x0 <= i + 0.5 <= x1]
        rows = [j for j in range(h) if y0 <= j + 0.5 <= y1]
        total += len(cols) * len(rows)
    return total


def test_ray_casting_counts_the_tests_it_makes():
    """The counter counts the ray-polygon pairs tested (not n N computed): equal to the
    test's own count of pixel centres in the polygons' screen boxes, growing linearly in n
    at a fixed image and linearly in the pixels N for a fixed scene."""
    camera = Camera.look_at((0.3, 0.4, 5), (0, 0, 0), fov_y=45)
    sizes = [25, 50, 100, 200]
    tests, own = [], []
    for n in sizes:
        p = prepare(_scene(soup(n, 3, False)), camera, (64, 48))
        tests.append(raycast(p).counters["ray-polygon tests"])
        own.append(_box_pixels(p))
    np.testing.assert_allclose(tests, own, rtol=0.01)  # (snapped vertices: a hair apart)
    assert abs(slope(sizes, tests) - 1) < 0.2  # ~ linear in n
    assert all(t < n * 64 * 48 for t, n in zip(tests, sizes))  # fewer than n N: culled
    pixels = [32, 64, 128]
    tests = [raycast(prepare(_scene(soup(50, 3, False)), camera, (w, w)))
             .counters["ray-polygon tests"] for w in pixels]
    assert abs(slope(np.square(pixels), tests) - 1) < 0.1  # linear in N
    r = raycast(prepare(_scene(soup(50, 3, False)), camera, (64, 64))).counters
    assert r["hits"] <= r["plane intersections"] <= r["ray-polygon tests"]


def test_depth_sort_comparisons_grow_as_n_squared():
    camera = Camera.look_at((0, 0, 6), (0, 0, 0), fov_y=45)
    sizes = [40, 80, 160, 320]
    comparisons = []
    for n in sizes:
        rng = np.random.default_rng(n)
        # overlapping depth ranges throughout: every polygon meets a share of the others
        m = soup(n, n, False)
        v = m.vertices.copy()
        v[:, 2] += rng.normal(0, 0.05, len(v))
        comparisons.append(depth_sort(prepare(_scene(Mesh(v, m.face_indices.reshape(-1, 3))),
                                              camera, (64, 64))).counters["comparisons"])
    assert slope(sizes, comparisons) > 1.6, comparisons


def test_step_frames_fill_in(gpu_frames):
    from glshade.hidden import ALGORITHMS
    from glshade.hidden.lab import step_frames

    scene, camera = VIEWS["teapot"]
    p = prepare(scene, camera, SIZE)
    for name in ("zbuffer", "scanline", "bsp", "depth-sort"):
        result = ALGORITHMS[name](p)
        frames = step_frames(name, p, result, 6)
        covered = [int((f >= 0).sum()) for f in frames]
        assert covered[0] < covered[-1] and np.array_equal(frames[-1], result.face_id), name


def test_the_command_line_lab(tmp_path):
    from PIL import Image

    from ..conftest import BACKEND, glshade

    out = tmp_path / "grid.png"
    r = glshade("hidden", "primitive:teapot:3", "-o", str(out), "--size", "96x72",
                "--steps", str(tmp_path / "steps.gif"), "--backend", BACKEND)
    assert r.returncode == 0, r.stderr
    table = {line.split()[0]: line.split() for line in r.stdout.splitlines()[3:9]}
    assert set(table) == {"zbuffer", "scanline", "depth-sort", "bsp", "raycast", "gpu"}
    for name in ("zbuffer", "scanline", "depth-sort", "bsp", "raycast"):
        assert table[name][-3] == "0", r.stdout  # no pixel differs from the GPU
    assert Image.open(out).size == (6 * 96, 2 * (72 + 22))  # two rows of labelled tiles
    with Image.open(tmp_path / "steps.gif") as gif:
        assert gif.n_frames >= 24
    r = glshade("hidden", "primitive:cube", "-o", str(out), "--algorithms", "zbuffer,magic")
    assert r.returncode == 2 and "unknown algorithm magic" in r.stderr


def test_the_lab_on_a_scene_with_a_background_and_a_solid(tmp_path):
    """The CSG part scene: a coloured background (which must not leak into the GPU's ids
    and depths) and a solid, which is not polygons: left out everywhere, with a warning."""
    from ..conftest import BACKEND, glshade

    r = glshade("hidden", "assets/scenes/csg-part.toml", "-o", str(tmp_path / "grid.png"),
                "--algorithms", "zbuffer,scanline,raycast,gpu", "--size", "128x96",
                "--backend", BACKEND)
    assert r.returncode == 0, r.stderr
    assert r.stderr.strip() == ("glshade: warning: the scene's CSG solids (part) are not "
                                "polygons: every algorithm here, the GPU's z-buffer "
                                "included, leaves them out")
    table = {line.split()[0]: line.split() for line in r.stdout.splitlines()[3:7]}
    for name in ("zbuffer", "scanline", "raycast"):
        assert table[name][-3] == "0", r.stdout


def test_algorithms_take_a_scene_and_camera_too():
    from glshade.hidden import run, zbuffer
    from glshade.errors import GeometryError, InputError

    scene, camera = VIEWS["teapot"]
    a = zbuffer(scene, camera, SIZE)
    b = run("zbuffer", scene, camera, SIZE)
    assert np.array_equal(a.face_id, b.face_id) and a.counters == b.counters
    with pytest.raises(InputError, match="unknown hidden-surface algorithm 'magic'"):
        run("magic", scene, camera)
    with pytest.raises(GeometryError, match="needs a camera"):
        zbuffer(scene)


def test_depth_sort_splits_its_way_through_a_dense_piercing_soup(gl_context):
    """40 large triangles all piercing each other: splitting makes many pieces, each of which
    may move, so the bound on moves grows with them (it was fixed by the triangle count
    before splitting -- 20 n + 100 = 900 here -- and depth sort gave up with a cycle). It
    finishes, and paints the GPU's picture away from edges."""
    from glshade.modes import Outputs
    from glshade.render.renderer import Renderer

    rng = np.random.default_rng(1)
    v = rng.uniform(-0.2, 0.2, (40, 1, 3)) + rng.normal(0, 0.9, (40, 3, 3))
    scene = _scene(Mesh(v.reshape(-1, 3), np.arange(120).reshape(-1, 3)))
    camera = Camera.look_at((0, 0, 6), (0, 0, 0))
    p = prepare(scene, camera, (48, 48))
    result = depth_sort(p)
    assert result.counters["moves"] > 20 * 40 + 100 and result.counters["splits"] > 0
    with Renderer(48, 48, samples=0, context=gl_context) as r:
        gpu = r.render_frame(scene, camera, "flat", cull=False, outputs=Outputs.FACE_ID)
    away = ~edge_pixels(p, 1 / 256)
    differ = (result.face_id != gpu.face_id) & away
    assert differ.sum() <= 0.01 * away.sum()  # (depth ties where the pieces pierce)


@pytest.mark.parametrize("name", list(ALGORITHMS))
@pytest.mark.parametrize("view", ["2x1", "collinear", "far away", "fov 179.99", "1x1024"])
def test_a_view_that_covers_no_pixel_centre_is_simply_blank(name, view):
    """Where no polygon covers a pixel centre -- an image of 2x1 pixels, a mesh of collinear
    points, a camera 1e30 away, a field of view of 179.99 degrees, a thin strip -- every
    algorithm gives the background (ids -1, depth inf), no error."""
    cube = _scene(primitives.cube())
    cases = {
        "2x1": (cube, Camera.look_at((0, 0, 4), (0, 0, 0)), (2, 1)),
        "collinear": (_scene(Mesh([[0, 0, 0], [1, 0, 0], [2, 0, 0]], [[0, 1, 2]])),
                      Camera.look_at((0, 0, 4), (1, 0, 0)), (16, 16)),
        "far away": (cube, Camera.look_at((0, 0, 1e30), (0, 0, 0)), (16, 16)),
        "fov 179.99": (cube, Camera.look_at((0, 0, 4), (0, 0, 0), fov_y=179.99), (8, 8)),
        "1x1024": (cube, Camera.look_at((3, 2, 4), (0, 0, 0)), (1, 1024)),
    }
    scene, camera, size = cases[view]
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")  # (no numpy warning leaks either)
        result = ALGORITHMS[name](prepare(scene, camera, size))
    if view != "1x1024":  # (a strip may catch a centre or two: the point is no error)
        assert (result.face_id == -1).all() and np.isinf(result.depth).all()


def test_the_lab_on_a_blank_view_writes_the_background_and_one_warning(tmp_path):
    import subprocess
    import sys

    out = subprocess.run([sys.executable, "-m", "glshade", "hidden", "primitive:cube",
                          "--size", "2x1", "--algorithms", "zbuffer", "-o",
                          str(tmp_path / "g.png")], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert (tmp_path / "g.png").exists()
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and "blank" in lines[0] and "2x1" in lines[0], out.stderr


@pytest.mark.parametrize("seed", [1, 4])
def test_depth_sort_on_a_dense_soup_paints_the_ray_casters_picture(seed):
    """300 randomly turned triangles packed so that each meets dozens of others in screen
    and depth (the benchmark's dense soup, benchmarks/hidden_bench.py --dense): depth sort
    finishes -- its overlap tests go through a screen grid, the list by bisection; a cycle
    of five whose consecutive pairs straddle no plane (seed 1) is split where some pair of
    it does, where it kept reordering them until it gave up -- with hundreds of splits,
    and paints the ray caster's ids (a different algorithm) away from edges, as BSP
    does."""
    rng = np.random.default_rng(seed)
    v = rng.uniform(-1, 1, (300, 1, 3)) + rng.normal(0, 0.3, (300, 3, 3))
    scene = _scene(Mesh(v.reshape(-1, 3), np.arange(900).reshape(-1, 3)))
    p = prepare(scene, Camera.look_at((0, 0, 6), (0, 0, 0)), (96, 96))
    truth = raycast(p).face_id
    away = ~edge_pixels(p, 1 / 256)
    for algorithm in (depth_sort, bsp):
        result = algorithm(p)
        assert result.counters["splits"] > 300
        differ = (result.face_id != truth) & away
        assert differ.sum() <= 0.002 * away.sum(), (algorithm.__name__, differ.sum())


def test_the_painters_one_triangle_split_agrees_with_the_vectorised_one():
    """Random triangles across random planes: the painter's one-at-a-time split gives
    pieces of the same total area as ``view.split_by_plane`` (and as the triangle), each
    wholly on one side, with the same number of cut edges."""
    from glshade.hidden.painter import split_one
    from glshade.hidden.view import split_by_plane

    rng = np.random.default_rng(7)
    area = lambda t: np.linalg.norm(np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]), axis=1) / 2  # noqa: E731
    done = 0
    for _ in range(300):
        tri, n = rng.normal(size=(3, 3)), rng.normal(size=3)
        n /= np.linalg.norm(n)
        d = float(tri.mean(0) @ n)
        side = tri @ n - d
        if not ((side > 1e-9).any() and (side < -1e-9).any()):
            continue
        cut = rng.random(3) < 0.5
        pieces, cuts = split_one(tri.tolist(), n.tolist(), d, 1e-12, cut.tolist())
        pieces, cuts = np.array(pieces), np.array(cuts)
        ft, _, fc, bt, _, bc = split_by_plane(tri[None], n, np.array([d]), 1e-12, cut[None])
        assert np.isclose(area(pieces).sum(), area(tri[None])[0])
        assert np.isclose(area(pieces).sum(), area(np.concatenate([ft, bt])).sum())
        s = pieces @ n - d
        assert ((s >= -1e-9).all(1) | (s <= 1e-9).all(1)).all()
        assert cuts.sum() == np.concatenate([fc, bc]).sum()
        done += 1
    assert done > 200


from hypothesis import given, settings, strategies as st  # noqa: E402


@settings(max_examples=40, deadline=None)
@given(n=st.integers(2, 120), spread=st.floats(0.02, 0.8), seed=st.integers(0, 2**16),
       look=st.tuples(*[st.floats(-1, 1)] * 3), ortho=st.booleans())
def test_depth_sort_sweep_paints_the_ray_casters_picture(n, spread, seed, look, ortho):
    """Random soups from sparse to densely piercing (2-120 triangles, vertices 0.02-0.8 about
    centres in a 2-unit cube), seen from any direction, perspective or orthographic: depth
    sort -- its cycles split once where found, its tests remembered per polygon between
    visits -- paints the ray caster's ids (a different algorithm) away from edges."""
    rng = np.random.default_rng(seed)
    v = rng.uniform(-1, 1, (n, 1, 3)) + rng.normal(0, spread, (n, 3, 3))
    scene = _scene(Mesh(v.reshape(-1, 3), np.arange(3 * n).reshape(-1, 3)))
    d = np.asarray(look, float)
    d = d / np.linalg.norm(d) if np.linalg.norm(d) > 0.1 else np.array([0.0, 0.0, 1.0])
    up = (0, 1, 0) if abs(d[1]) < 0.9 else (1, 0, 0)
    camera = Camera.look_at(tuple(6 * d), (0, 0, 0), up=up)
    if ortho:
        camera = camera.replace(projection="orthographic", height=3.0)
    p = prepare(scene, camera, (64, 64))
    truth = raycast(p).face_id
    away = ~edge_pixels(p, 1 / 256)
    differ = (depth_sort(p).face_id != truth) & away
    assert differ.sum() <= max(2, 0.002 * away.sum()), differ.sum()
