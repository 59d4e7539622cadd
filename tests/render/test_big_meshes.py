"""Big meshes: drawn in spatial chunks (the octree's cells over the triangles), each culled
against the view at every draw. Culling never changes a pixel (hypothesis over cameras,
near and far, inside the mesh's box and out: culled and unculled frames the same to the
byte), skips only chunks with no vertex in view by numpy's own projection, and a
2M-triangle mesh draws the same picture as its two halves added as two models."""

import numpy as np
import pytest

from tests.conftest import require

require("hypothesis", "property-based sweeps are part of the test extra")
from hypothesis import HealthCheck, given, settings, strategies as st  # noqa: E402

import glshade  # noqa: E402
from glshade.modes import Outputs  # noqa: E402
from glshade.octree import point_chunks  # noqa: E402
from glshade.octree import CHUNKED_FROM  # noqa: E402
from glshade.render.gpu_mesh import gpu_bytes  # noqa: E402
from glshade.render.passes.points import cloud_gpu_bytes  # noqa: E402

pytestmark = [pytest.mark.gl, pytest.mark.filterwarnings("ignore::glshade.RenderWarning")]


def terrain(n: int, normals: bool = False) -> glshade.Mesh:
    """An ``n`` x ``n`` height field of 2 n^2 triangles over [-1, 1]^2 (with ``normals``
    its vertex normals given as a file's, so that any part of it keeps them)."""
    x, y = np.meshgrid(np.linspace(-1, 1, n + 1), np.linspace(-1, 1, n + 1))
    z = 0.15 * np.sin(5 * x) * np.cos(4 * y)
    corner = (np.arange(n)[None, :] + np.arange(n)[:, None] * (n + 1)).ravel()
    tris = np.concatenate([np.c_[corner, corner + 1, corner + n + 2],
                           np.c_[corner, corner + n + 2, corner + n + 1]])
    mesh = glshade.Mesh(np.c_[x.ravel(), y.ravel(), z.ravel()], tris)
    return glshade.Mesh(mesh.vertices, tris, normals=mesh.vertex_normals) if normals else mesh


@pytest.fixture(scope="module")
def big():
    mesh = terrain(400, normals=True)   # 320,000 triangles: chunked
    assert mesh.n_faces >= CHUNKED_FROM
    scene = glshade.Scene()
    scene.add(mesh)
    return mesh, scene


def _in_view(cam, size, points):
    """Which points a camera's frustum holds, by the camera's own axes and field of view."""
    w, h = size
    rel = (points - cam.position) @ cam.rotation
    depth = -rel[:, 2]
    t = np.tan(np.radians(cam.fov_y) / 2)
    with np.errstate(divide="ignore", invalid="ignore"):
        x, y = rel[:, 0] / depth / (t * w / h), rel[:, 1] / depth / t
    near, far = cam.planes()
    return (depth >= near) & (depth <= far) & (np.abs(x) <= 1) & (np.abs(y) <= 1)


@settings(max_examples=8, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(eye=st.tuples(st.floats(-1.5, 1.5), st.floats(-1.5, 1.5), st.floats(0.05, 2.5)),
       look=st.tuples(st.floats(-1, 1), st.floats(-1, 1), st.floats(-0.2, 0.2)),
       fov=st.floats(15, 90), mode=st.sampled_from(["phong", "flat"]))
def test_culled_chunks_never_change_a_pixel(make_renderer, big, eye, look, fov, mode):
    mesh, scene = big
    look = np.asarray(look, float)
    if np.linalg.norm(look - eye) < 0.05:
        look = look + [0.3, 0.0, -0.3]
    cam = glshade.Camera.look_at(eye, look, up=(0, 0, 1) if abs(look[2] - eye[2]) < 0.95 *
                                 np.linalg.norm(look - eye) else (0, 1, 0), fov_y=fov)
    cam = cam.with_planes(scene.bounds)
    renderer = make_renderer(96, 72)
    culled = renderer.render_frame(scene, cam, mode, outputs=Outputs.ALL, frustum_cull=True)
    skipped = renderer.culled.chunks
    whole = renderer.render_frame(scene, cam, mode, outputs=Outputs.ALL, frustum_cull=False)
    assert renderer.culled.chunks == 0
    for a, b in zip((culled.color, culled.face_id, culled.depth),
                    (whole.color, whole.face_id, whole.depth)):
        np.testing.assert_array_equal(a, b)
    # never more skipped than the chunks with no triangle corner in view (the chunks
    # rebuilt here from the octree's grouping of the centroids)
    tri, _ = mesh.triangles
    centroids = mesh.vertices[tri].mean(1)
    order, starts = point_chunks(centroids, 65_536)
    seen = _in_view(cam, (96, 72), mesh.vertices)[tri].any(1)[order]
    empty = [not seen[a:b].any() for a, b in zip(starts[:-1], starts[1:])]
    assert skipped <= sum(empty)


def test_a_close_view_skips_most_chunks(make_renderer, big):
    _, scene = big
    renderer = make_renderer(96, 72)
    cam = glshade.Camera.look_at((0.7, 0.7, 0.25), (0.9, 0.9, 0.0)).with_planes(scene.bounds)
    renderer.render_frame(scene, cam, "phong")
    n_chunks = len(renderer.meshes.gpu_mesh(scene.models[0].mesh).chunks.starts) - 1
    assert n_chunks >= 4
    assert renderer.culled.chunks >= n_chunks // 2


def test_the_gpu_copy_takes_what_info_reports(make_renderer, big):
    """An indexed mesh's colour draws: 24 bytes a vertex and 12 a triangle, no more."""
    mesh, scene = big
    renderer = make_renderer(32, 32)
    renderer.render(scene, glshade.Camera.look_at((0, 0, 3), (0, 0, 0)))
    gpu = renderer.meshes.gpu_mesh(mesh)
    assert gpu.nbytes == gpu_bytes(mesh) == 24 * mesh.n_vertices + 12 * mesh.n_faces


@pytest.mark.once
def test_two_million_triangles_draw_as_their_halves_do(make_renderer):
    mesh = terrain(1000)
    assert mesh.n_faces == 2_000_000
    whole, halves = glshade.Scene(), glshade.Scene()
    whole.add(mesh)
    half = mesh.n_faces // 2
    halves.add(mesh.subset(np.arange(half)))
    halves.add(mesh.subset(np.arange(half, mesh.n_faces)))
    cam = glshade.Camera.look_at((0.4, -1.6, 1.3), (0, 0, 0)).with_planes(whole.bounds)
    renderer = make_renderer(160, 120)
    a = renderer.render_frame(whole, cam, "flat", outputs=Outputs.ALL)
    b = renderer.render_frame(halves, cam, "flat", outputs=Outputs.ALL)
    assert (a.face_id >= 0).mean() > 0.5
    np.testing.assert_array_equal(a.color, b.color)
    np.testing.assert_array_equal(a.face_id, b.face_id)
    np.testing.assert_array_equal(a.depth, b.depth)


def test_a_big_cloud_is_culled_by_chunks_and_keeps_its_point_numbers(make_renderer):
    """A cloud of CHUNKED_FROM points or more is drawn chunk by chunk: a close view skips
    chunks, the frame equal to the byte to the unculled one, and each pixel's id is the
    point numpy's own ray cast finds nearest along its ray among the points it could be."""
    rng = np.random.default_rng(2)
    points = rng.uniform(-1, 1, (CHUNKED_FROM, 3))
    scene = glshade.Scene()
    scene.add(glshade.PointCloud(points, radius=0.004))
    cam = glshade.Camera.look_at((0.6, 0.6, 1.4), (0.8, 0.8, 0.6), fov_y=40).with_planes(
        scene.bounds)
    renderer = make_renderer(64, 48)
    culled = renderer.render_frame(scene, cam, "phong", outputs=Outputs.ALL)
    assert renderer.culled.point_chunks > 0
    whole = renderer.render_frame(scene, cam, "phong", outputs=Outputs.ALL,
                                  frustum_cull=False)
    np.testing.assert_array_equal(culled.face_id, whole.face_id)
    np.testing.assert_array_equal(culled.color, whole.color)
    cloud = scene.clouds[0].cloud   # (12 bytes a position, 4 its place in the chunk order)
    assert renderer.points.gpu_cloud(cloud).nbytes == cloud_gpu_bytes(cloud) == 16 * len(cloud)
    # the id at a pixel is a point whose sphere its centre's ray meets
    drawn = np.argwhere(culled.face_id >= 0)
    assert len(drawn) > 50
    o, d = cam.rays((64, 48))
    for row, col in drawn[:: max(1, len(drawn) // 40)]:
        c = points[culled.face_id[row, col]]
        off = c - o[row, col]
        miss = np.linalg.norm(off - (off @ d[row, col]) * d[row, col])
        assert miss <= 0.004 * (1 + 1e-4), (row, col, miss)


@pytest.mark.parametrize("mode", ["flat", "phong", "gouraud"])
def test_shared_vertices_draw_what_corner_copies_draw(make_renderer, big, mode):
    """A big mesh's draws over its shared vertices (each triangle's polygon from a table;
    flat lit once a triangle in a geometry stage) give the picture, ids and depth of the
    same triangles drawn as two smaller meshes, whose draws copy the vertices to every
    corner -- and take 4 bytes a triangle and 32 a polygon besides the indexed mesh. (The
    view depth interpolated after a geometry stage may differ in its last bit.)"""
    mesh, scene = big
    half = mesh.n_faces // 2
    assert half < CHUNKED_FROM
    halves = glshade.Scene()
    halves.add(mesh.subset(np.arange(half)))
    halves.add(mesh.subset(np.arange(half, mesh.n_faces)))
    cam = glshade.Camera.look_at((0.3, -1.7, 1.2), (0, 0, 0)).with_planes(scene.bounds)
    renderer = make_renderer(120, 90)
    a = renderer.render_frame(scene, cam, mode, outputs=Outputs.ALL)
    b = renderer.render_frame(halves, cam, mode, outputs=Outputs.ALL)
    assert (a.face_id >= 0).mean() > 0.5
    for x, y in ((a.color, b.color), (a.face_id, b.face_id), (a.normal, b.normal)):
        np.testing.assert_array_equal(x, y)
    np.testing.assert_allclose(a.depth, b.depth, rtol=2e-6, atol=0)
    gpu = renderer.meshes.gpu_mesh(mesh)
    tables = 4 * mesh.n_faces + (32 * mesh.n_faces if mode == "flat" else 0)
    extra = gpu.nbytes - gpu_bytes(mesh)   # (no corner copies: the tables, rows padded)
    assert tables <= extra < tables + 2 * 4096 * 16
