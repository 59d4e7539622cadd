"""Patches tessellated on the GPU (GL 4.0 tessellation shaders) draw the pictures the CPU
tessellation draws at the same level; their ids are the patches'; what the GPU cannot draw
is refused with one line."""

import numpy as np
import pytest

from glshade import Camera, Material, PointLight, Scene
from glshade import patches as G
from glshade.errors import SceneError
from glshade.modes import Outputs

pytestmark = pytest.mark.gl

CAM = Camera.look_at((3.5, 3.0, 6.0), (0.0, 1.2, 0.0), fov_y=40.0)


def _scene(model, **kw):
    s = Scene()
    s.add(model, Material(color=(0.8, 0.5, 0.3), ks=0.4, shininess=30.0), **kw)
    s.add_light(PointLight((4.0, 6.0, 8.0)))
    return s


@pytest.mark.parametrize("mode", ["phong", "gouraud", "normals"])
@pytest.mark.parametrize("level", [8, 24, 64])
def test_gpu_tessellation_draws_the_cpu_tessellation_s_picture(make_renderer, mode, level):
    """The teapot at one level, tessellated by the GPU and by the CPU (numpy): the same
    picture but for the few pixels where the two split a quad along different diagonals
    (GL leaves the diagonal to the driver); the same depth buffer."""
    teapot = G.teapot()
    r = make_renderer(240, 180)
    gpu = r.render_frame(_scene(teapot, tessellation="gpu", level=level), CAM, mode,
                         outputs=Outputs.DEPTH)
    cpu = r.render_frame(_scene(teapot, level=level), CAM, mode, outputs=Outputs.DEPTH)
    d = np.abs(gpu.color.astype(int) - cpu.color.astype(int))[..., :3].max(-1)
    assert (gpu.color[..., :3].max(-1) > 0).mean() > 0.2  # (the teapot is there)
    assert d.mean() < 0.25 and (d > 2).mean() < 0.02, (d.mean(), (d > 2).mean())
    both = np.isfinite(gpu.depth) & np.isfinite(cpu.depth)
    assert (np.isfinite(gpu.depth) != np.isfinite(cpu.depth)).mean() < 0.005
    assert np.median(np.abs(gpu.depth[both] - cpu.depth[both])) < 1e-4


def test_rational_patches_tessellate_on_the_gpu_to_the_exact_sphere(make_renderer):
    """The rational sphere's patches on the GPU: the depth buffer against the exact
    sphere's, ray cast here (the silhouette aside), converging as the chords shorten
    (their sagitta falls as 1 / level^2)."""
    r = make_renderer(96, 96)
    cam = Camera.look_at((0.0, 0.0, 4.0), (0.0, 0.0, 0.0), fov_y=40.0, near=1.0, far=10.0)
    errors = [_sphere_depth_error(r, cam, level) for level in (16, 64)]
    assert errors[1] < 1e-3 and errors[1] < errors[0] / 4, errors


def _sphere_depth_error(r, cam, level):
    frame = r.render_frame(_scene(G.sphere(1.0), tessellation="gpu", level=level), cam,
                           "phong", outputs=Outputs.DEPTH)
    ys, xs = np.mgrid[0:96, 0:96]
    t = np.tan(np.radians(20.0))
    d = np.stack([(2 * (xs + 0.5) / 96 - 1) * t, (1 - 2 * (ys + 0.5) / 96) * t,
                  -np.ones((96, 96))], -1)
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    o = np.array([0.0, 0.0, 4.0])
    b = d @ o
    disc = b ** 2 - (o @ o - 1.0)
    hit = disc > 0
    dist = -b - np.sqrt(np.where(hit, disc, 0))
    view_depth = dist * -d[..., 2]
    inner = hit & (disc > 0.05)
    return float(np.abs(frame.depth[inner] - view_depth[inner]).max())


def test_ids_are_the_patches(make_renderer):
    teapot = G.teapot()
    r = make_renderer(160, 120)
    frame = r.render_frame(_scene(teapot, tessellation="gpu", level=8), CAM, "phong",
                           outputs=Outputs.FACE_ID)
    ids = np.unique(frame.face_id[frame.face_id >= 0])
    assert ids.min() >= 0 and ids.max() < len(teapot) and len(ids) > 16


def test_what_the_gpu_cannot_draw_is_refused(make_renderer):
    teapot = G.teapot()
    with pytest.raises(SceneError, match="1 to 64"):
        Scene().add(teapot, tessellation="gpu", level=65)
    with pytest.raises(SceneError, match="'cpu' or 'gpu'"):
        Scene().add(teapot, tessellation="shader")
    with pytest.raises(SceneError, match="tessellation='gpu' is for patches"):
        Scene().add(G.tessellate(teapot, level=2).mesh, tessellation="gpu")
    r = make_renderer(64, 48)
    with pytest.raises(SceneError, match="the flat mode needs its CPU tessellation"):
        r.render(_scene(teapot, tessellation="gpu"), CAM, "flat")


def test_level_is_honoured_on_the_cpu_path_too():
    """``Scene.add(patches, level=N)`` tessellates N segments a side on the CPU as on the
    GPU (it was ignored: the CPU path always tessellated to its default tolerance)."""
    from glshade.geometry import primitives

    teapot = G.teapot()
    counts = []
    for level in (1, 3, 9):
        model = Scene().add(teapot, level=level)
        want = G.tessellate(teapot, level=level).mesh
        assert np.array_equal(model.mesh.vertices, want.vertices)
        counts.append(model.mesh.n_faces)
    assert counts[0] < counts[1] < counts[2]
    assert Scene().add(teapot).mesh.n_faces not in counts  # (the default: a tolerance)
    with pytest.raises(SceneError, match="level is for patches"):
        Scene().add(primitives.cube(), level=4)
    with pytest.raises(SceneError, match="level must be"):
        Scene().add(teapot, level=0)
