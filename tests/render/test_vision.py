"""Ground truth for vision code, against oracles that share nothing with the renderer:
OpenCV's projectPoints for the camera, a float64 numpy ray caster (rays from K, Moller-
Trumbore) for instance and class ids and depth at every pixel centre, trimesh's closest
point for Frame.points."""

import numpy as np
import pytest

from tests.conftest import require

cv2 = require("cv2", "OpenCV is the camera oracle (the test extra's opencv-python-headless)")

import glshade  # noqa: E402
from glshade import Camera, GlshadeError, Outputs, Scene  # noqa: E402
from glshade.geometry import primitives as P  # noqa: E402

SIZE = (80, 60)
#: fx != fy, the principal point off centre
K = np.array([[95.0, 0.0, 37.3], [0.0, 83.0, 31.6], [0.0, 0.0, 1.0]])


def _pose(angles, t):
    R = cv2.Rodrigues(np.asarray(angles, np.float64))[0]
    return R, np.asarray(t, np.float64)


POSES = [_pose((0.0, 0.0, 0.0), (0.0, 0.0, 6.0)), _pose((0.3, -0.4, 0.2), (0.3, -0.2, 5.5)),
         _pose((-0.6, 0.9, -0.3), (-0.4, 0.3, 7.0))]


def _scene():
    scene = Scene()
    scene.add(P.cube(), label="box", translation=(-0.9, 0.1, 0.0), scale=1.2)
    scene.add(P.icosphere(2), label="ball", translation=(0.9, -0.2, 0.3))
    scene.add(P.cube(), label="box", translation=(0.2, 0.9, -1.0), scale=0.8)
    return scene


def _triangles(scene):
    """World triangles (T, 3, 3), each one's instance and class ids."""
    tris, inst, cls = [], [], []
    for model in scene.models:
        t, _ = model.mesh.triangulate()
        v = model.mesh.vertices @ model.transform[:3, :3].T + model.transform[:3, 3]
        tris.append(v[t])
        inst += [model.instance_id] * len(t)
        cls += [scene.labels[model.label]] * len(t)
    return np.concatenate(tris), np.array(inst), np.array(cls)


def _cast(tris, R, t, size):
    """Nearest hit of each pixel centre's ray, rays from K (OpenCV's pixel centres):
    (triangle index or -1, depth along the camera's z) -- float64 Moller-Trumbore."""
    w, h = size
    u, v = np.meshgrid(np.arange(w, dtype=np.float64), np.arange(h, dtype=np.float64))
    d_cam = np.stack([u, v, np.ones_like(u)], -1) @ np.linalg.inv(K).T  # (z = 1)
    d = (d_cam @ R).reshape(-1, 3)  # (R^T d: world)
    o = -R.T @ t
    p0, e1, e2 = tris[:, 0], tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0]
    pv = np.cross(d[:, None, :], e2[None])
    det = np.einsum("tk,rtk->rt", e1, pv)
    with np.errstate(divide="ignore", invalid="ignore"):
        f = 1.0 / det
        s = o - p0
        uu = f * np.einsum("tk,rtk->rt", s, pv)
        q = np.cross(s, e1)
        vv = f * np.einsum("rk,tk->rt", d, q)
        dist = f * np.einsum("tk,tk->t", e2, q)[None] * np.ones_like(uu)
    ok = (np.abs(det) > 1e-14) & (uu >= 0) & (vv >= 0) & (uu + vv <= 1) & (dist > 0)
    dist = np.where(ok, dist, np.inf)
    best = dist.argmin(1)
    z = dist[np.arange(len(d)), best]  # (d has camera z 1: the distance is the depth)
    hit = np.where(np.isfinite(z), best, -1)
    return hit.reshape(h, w), z.reshape(h, w)


def _near_an_edge(tris, R, t, size, margin=0.01):
    """Pixel centres within ``margin`` px of any projected triangle edge."""
    w, h = size
    pts, _ = cv2.projectPoints(tris.reshape(-1, 3), cv2.Rodrigues(R)[0], t, K, None)
    p = pts.reshape(-1, 3, 2)
    a, b = p, np.roll(p, -1, axis=1)
    a, b = a.reshape(-1, 2), b.reshape(-1, 2)
    u, v = np.meshgrid(np.arange(w, dtype=np.float64), np.arange(h, dtype=np.float64))
    c = np.stack([u, v], -1).reshape(-1, 1, 2)
    ab = b - a
    s = np.clip(np.einsum("rek,ek->re", c - a, ab) / np.maximum((ab ** 2).sum(1), 1e-300),
                0, 1)
    gap = np.linalg.norm(c - (a + s[..., None] * ab), axis=-1).min(1)
    return (gap < margin).reshape(h, w)


def test_opencv_round_trips_are_exact():
    for R, t in POSES:
        camera = Camera.from_opencv(K, R, t, SIZE)
        K2, R2, t2 = camera.to_opencv(SIZE)
        assert np.abs(K2 - K).max() < 1e-9 and np.abs(R2 - R).max() < 1e-9
        assert np.abs(t2 - t).max() < 1e-9
        assert np.abs(camera.intrinsics(SIZE) - K).max() < 1e-9
    # a camera without K: square pixels, the centre the principal point
    K3 = Camera(fov_y=60.0).intrinsics((100, 50))
    assert K3[0, 0] == pytest.approx(K3[1, 1]) == pytest.approx(25 / np.tan(np.radians(30)))
    assert (K3[0, 2], K3[1, 2]) == (49.5, 24.5)


@pytest.mark.parametrize("samples", [0, 4])
@pytest.mark.parametrize("pose", range(len(POSES)))
def test_ids_and_depth_match_a_ray_caster_at_every_pixel_centre(make_renderer, samples,
                                                                 pose):
    """Instance and class ids and depth at every pixel centre further than 0.01 px from a
    projected edge: 0 mismatches; the same with MSAA 0 and 4."""
    R, t = POSES[pose]
    scene = _scene()
    frame = make_renderer(*SIZE, samples).render_frame(
        scene, Camera.from_opencv(K, R, t, SIZE), "flat",
        outputs=Outputs.INSTANCE | Outputs.SEMANTIC | Outputs.DEPTH)
    tris, inst, cls = _triangles(scene)
    hit, z = _cast(tris, R, t, SIZE)
    judged = ~_near_an_edge(tris, R, t, SIZE)
    want_inst = np.where(hit >= 0, inst[hit], 0)
    want_cls = np.where(hit >= 0, cls[hit], 0)
    assert judged.mean() > 0.9 and (want_inst > 0).sum() > 300
    assert (frame.instance != want_inst)[judged].sum() == 0
    assert (frame.semantic != want_cls)[judged].sum() == 0
    lit = judged & (hit >= 0)
    assert np.allclose(frame.depth[lit], z[lit], rtol=1e-5)
    assert np.isinf(frame.depth[judged & (hit < 0)]).all()


@pytest.mark.parametrize("samples", [0, 4])
def test_render_many_frames_match_the_ray_caster_and_render_frame(make_renderer, samples):
    """render_many draws frames ahead of the one it reads (each into targets of its own):
    7 views -- more than it draws ahead, and not a multiple -- each with 0 mismatches
    against the ray caster and byte for byte render_frame's, the outputs not asked None."""
    scene = _scene()
    r = make_renderer(*SIZE, samples)
    poses = [POSES[k % len(POSES)] for k in range(7)]
    cameras = [Camera.from_opencv(K, R, t, SIZE) for R, t in poses]
    outputs = Outputs.DEPTH | Outputs.INSTANCE | Outputs.NORMAL
    tris, inst, _ = _triangles(scene)
    frames = list(r.render_many(scene, cameras, "phong", outputs=outputs))
    assert len(frames) == 7
    for (R, t), camera, frame in zip(poses, cameras, frames):
        hit, z = _cast(tris, R, t, SIZE)
        judged = ~_near_an_edge(tris, R, t, SIZE)
        assert (frame.instance != np.where(hit >= 0, inst[hit], 0))[judged].sum() == 0
        lit = judged & (hit >= 0)
        assert np.allclose(frame.depth[lit], z[lit], rtol=1e-5)
        one = r.render_frame(scene, camera, "phong", outputs=outputs)
        for name in ("color", "depth", "normal", "instance"):
            assert np.array_equal(getattr(frame, name), getattr(one, name)), name
        assert frame.face_id is None and frame.semantic is None
        assert frame.camera == one.camera


def test_render_many_hands_out_the_frames_before_a_bad_camera(make_renderer):
    """A camera that cannot be drawn, or a camera sequence that fails, ends the run where
    drawing one at a time would: every frame before it handed out first."""
    scene = _scene()
    r = make_renderer(*SIZE)
    cameras = [Camera.from_opencv(K, R, t, SIZE) for R, t in POSES * 2]
    got = []
    with pytest.raises(GlshadeError, match="expected a Camera, got str"):
        for frame in r.render_many(scene, [*cameras[:5], "front", cameras[0]]):
            got.append(frame)
    assert len(got) == 5
    assert np.array_equal(got[4].color, r.render_frame(scene, cameras[4]).color)

    def failing():
        yield from cameras[:3]
        raise ValueError("the camera file ended early")

    got = []
    with pytest.raises(ValueError, match="ended early"):
        got.extend(r.render_many(scene, failing()))
    assert len(got) == 3


def test_render_many_with_shadows_draws_one_at_a_time_in_the_frame_s_own_target(
        make_renderer):
    """Shadows read back a buffer every draw shares: such frames are drawn one at a time,
    into the target render_frame uses (no second set of targets), equal to its frames."""
    scene = _scene()
    scene.add_light(glshade.PointLight((2.0, 3.0, 4.0)))
    r = make_renderer(*SIZE, 4)
    cameras = [Camera.from_opencv(K, R, t, SIZE) for R, t in POSES]
    outputs = Outputs.DEPTH | Outputs.INSTANCE
    alone = [r.render_frame(scene, c, "phong", outputs=outputs, shadows="exact")
             for c in cameras]
    children = len(r.context._children)
    many = []
    for frame in r.render_many(scene, cameras, "phong", outputs=outputs, shadows="exact"):
        assert len(r.context._children) == children  # (while it runs, too)
        many.append(frame)
    for a, b in zip(alone, many):
        assert np.array_equal(a.color, b.color) and np.array_equal(a.instance, b.instance)
        assert np.array_equal(a.visibility, b.visibility)


def test_render_many_pending_frames_survive_other_draws_between_yields(make_renderer):
    """The frames drawn ahead are not disturbed by draws the caller makes between yields
    (annotations, other frames), nor by the caller stopping early."""
    scene = _scene()
    r = make_renderer(*SIZE, 4)
    cameras = [Camera.from_opencv(K, R, t, SIZE) for R, t in POSES * 2]
    outputs = Outputs.DEPTH | Outputs.INSTANCE
    alone = [r.render_frame(scene, c, "flat", outputs=outputs) for c in cameras]
    children = len(r.context._children)
    for k, frame in enumerate(r.render_many(scene, cameras, "flat", outputs=outputs)):
        r.render_frame(scene, cameras[-1 - k], "phong", outputs=Outputs.ALL)
        r.annotate(scene, cameras[0])
        assert np.array_equal(frame.color, alone[k].color)
        assert np.array_equal(frame.instance, alone[k].instance)
        assert np.array_equal(frame.depth, alone[k].depth)
        if k == 3:
            break
    assert len(r.context._children) == children  # (its targets freed when stopped)


def test_points_lie_on_the_surface_and_project_to_their_own_pixel(make_renderer):
    trimesh = require("trimesh", "the closest-point oracle")
    R, t = POSES[1]
    scene = _scene()
    camera = Camera.from_opencv(K, R, t, SIZE)
    frame = make_renderer(*SIZE).render_frame(scene, camera, "flat")
    assert frame.camera is not None
    world, cam = frame.points("world"), frame.points("camera")
    seen = np.isfinite(frame.depth)
    assert np.isnan(world[~seen]).all() and np.isnan(cam[~seen]).all()
    tris, _, _ = _triangles(scene)
    surface = trimesh.Trimesh(tris.reshape(-1, 3), np.arange(len(tris) * 3).reshape(-1, 3),
                              process=False)
    _, gap, _ = trimesh.proximity.closest_point(surface, world[seen].astype(np.float64))
    assert (gap <= 1e-5 * frame.depth[seen] + 1e-6).all(), gap.max()
    assert np.allclose(cam[seen][:, 2], frame.depth[seen], rtol=1e-6)
    uv = cam[seen].astype(np.float64) @ K.T
    uv = uv[:, :2] / uv[:, 2:]
    rows, cols = np.nonzero(seen)
    assert np.abs(uv[:, 0] - cols).max() < 1e-3 and np.abs(uv[:, 1] - rows).max() < 1e-3


def test_a_triangle_covers_the_pixel_centres_opencv_puts_inside_it(make_renderer):
    """One triangle's corners through cv2.projectPoints: exactly the pixel centres inside
    the projected triangle (more than 0.01 px from its edges) are drawn."""
    from glshade.geometry.mesh import Mesh

    corners = np.array([[-1.3, -0.8, 0.2], [1.1, -0.9, -0.3], [0.2, 1.2, 0.1]])
    scene = Scene()
    scene.add(Mesh(corners, [[0, 1, 2]]))
    for R, t in POSES:
        frame = make_renderer(*SIZE).render_frame(
            scene, Camera.from_opencv(K, R, t, SIZE), "flat", cull=False,
            outputs=Outputs.INSTANCE)
        p, _ = cv2.projectPoints(corners, cv2.Rodrigues(R)[0], t, K, None)
        p = p.reshape(3, 2)
        u, v = np.meshgrid(np.arange(SIZE[0], dtype=float), np.arange(SIZE[1], dtype=float))
        c = np.stack([u, v], -1)
        sides = []
        for i in range(3):  # (the 2D cross product: which side of edge i each centre is)
            e, r = p[(i + 1) % 3] - p[i], c - p[i]
            sides.append(e[0] * r[..., 1] - e[1] * r[..., 0])
        inside = np.all([s > 0 for s in sides], 0) | np.all([s < 0 for s in sides], 0)
        edge = _near_an_edge(corners[None], R, t, SIZE)
        assert inside.sum() > 100
        assert np.array_equal((frame.instance == 1)[~edge], inside[~edge])


def test_labels_and_instances_follow_the_order_added():
    scene = _scene()
    assert scene.labels == {"box": 1, "ball": 2}
    assert [m.instance_id for m in scene.models] == [1, 2, 3]
    with pytest.raises(GlshadeError, match="label must be a non-empty string"):
        scene.add(P.cube(), label=3)


@pytest.mark.parametrize("K_bad, words", [
    ([[95, 0.5, 37], [0, 83, 31], [0, 0, 1]], "skew of 0.5"),
    ([[-95, 0, 37], [0, 83, 31], [0, 0, 1]], "focal lengths must be positive"),
    ([[95, 0, 400], [0, 83, 31], [0, 0, 1]], "principal point (400, 31)"),
    ([[95, 0, 37], [0, 83, 31], [0, 0, 2]], "last row must be (0, 0, 1)"),
])
def test_a_bad_K_is_refused_naming_the_fault(K_bad, words):
    with pytest.raises(GlshadeError) as raised:
        Camera.from_opencv(K_bad, np.eye(3), (0, 0, 5), SIZE)
    assert words in str(raised.value)


def test_a_bad_R_is_refused_by_how_far_it_is_from_a_rotation():
    with pytest.raises(GlshadeError, match=r"R is not a rotation: .*det R = -1"):
        Camera.from_opencv(K, np.diag([1.0, 1.0, -1.0]), (0, 0, 5), SIZE)
    with pytest.raises(GlshadeError, match=r"\|R\^T R - I\| = 0\.21"):
        Camera.from_opencv(K, np.eye(3) * 1.1, (0, 0, 5), SIZE)


def test_annotations_recompose_each_pose_into_its_own_mask(make_renderer):
    """The BOP check: each model's vertices, moved by cam_R_m2c, cam_t_m2c and projected by
    K (OpenCV), land inside its own full mask (one pixel of slack at the silhouette)."""
    R, t = POSES[1]
    scene = _scene()
    records = make_renderer(*SIZE).annotate(scene, Camera.from_opencv(K, R, t, SIZE))
    assert [r.instance_id for r in records] == [1, 2, 3]
    assert [(r.label, r.obj_id) for r in records] == [("box", 1), ("ball", 2), ("box", 1)]
    for record, model in zip(records, scene.models):
        assert (record.mask_visib <= record.mask).all()
        assert record.px_count_all == record.mask.sum() > 0
        assert record.visib_fract == pytest.approx(record.px_count_visib / record.px_count_all)
        assert abs(np.linalg.det(record.cam_R_m2c) - 1) < 1e-9
        scale = np.linalg.norm(model.transform[:3, 0])
        local = model.mesh.vertices * scale
        uv, _ = cv2.projectPoints(local, cv2.Rodrigues(record.cam_R_m2c)[0],
                                  record.cam_t_m2c, K, None)
        col, row = np.floor(uv.reshape(-1, 2) + 0.5).astype(int).T
        pad = np.pad(record.mask, 1)  # (a silhouette's corner: one pixel, any way)
        grown = np.any([pad[1 + dy:1 + dy + SIZE[1], 1 + dx:1 + dx + SIZE[0]]
                        for dy in (-1, 0, 1) for dx in (-1, 0, 1)], axis=0)
        inside = (col >= 0) & (col < SIZE[0]) & (row >= 0) & (row < SIZE[1])
        assert grown[row[inside], col[inside]].all()
        x, y, w, h = record.bbox_obj
        rows, cols = np.nonzero(record.mask)
        assert (x, y, x + w - 1, y + h - 1) == (cols.min(), rows.min(), cols.max(),
                                                rows.max())


def test_a_scene_file_gives_K_R_t_and_labels(tmp_path):
    R, t = POSES[1]

    def rows(m):
        return "[" + ", ".join("[" + ", ".join(repr(float(v)) for v in r) + "]" for r in m) + "]"

    path = tmp_path / "s.toml"
    path.write_text(f'[render]\nsize = [{SIZE[0]}, {SIZE[1]}]\n[[mesh]]\nsource = '
                    f'"primitive:cube"\nlabel = "mug"\n[[mesh]]\nsource = "primitive:cube"\n'
                    f'translation = [2.0, 0.0, 0.0]\n[camera]\nK = {rows(K)}\nR = {rows(R)}\n'
                    f't = [{float(t[0])!r}, {float(t[1])!r}, {float(t[2])!r}]\n')
    made = glshade.load_scene(path)
    K2, R2, t2 = made.camera.to_opencv(SIZE)
    assert np.abs(K2 - K).max() < 1e-9 and np.abs(R2 - R).max() < 1e-9
    assert np.abs(t2 - t).max() < 1e-9
    assert made.scene.labels == {"mug": 1, "cube": 2}
    path.write_text(path.read_text().replace("[camera]\n", "[camera]\neye = [0, 0, 5]\n"))
    with pytest.raises(GlshadeError, match=r"s.toml:\d+: \[camera\] with K, R and t .*"
                                           r"cannot also give eye"):
        glshade.load_scene(path)
