"""The viewer in a real window (under Xvfb in CI): its pixels equal headless renders, and
synthesised input drives it."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from glshade import Camera, Culling, Material, Mesh, PointLight, RenderWarning, Scene
from glshade.geometry import primitives as P

ROOT = Path(__file__).resolve().parents[2]


def teapot_scene():
    s = Scene(background=(0.1, 0.1, 0.12))
    s.add(P.teapot(4), Material(color=(0.85, 0.55, 0.3), ks=0.5, shininess=40))
    s.add_light(PointLight((4.0, 6.0, 8.0)))
    return s


def glass_scene():
    """The teapot behind a glass ball (composited from per-pixel lists)."""
    from glshade.geometry import primitives

    s = teapot_scene()
    s.add(primitives.icosphere(3, 1.2), Material(color=(0.3, 0.6, 0.9), opacity=0.4),
          translation=(0.8, 1.5, 2.0))
    return s


def csg_scene():
    """A CSG solid with the teapot through it (ray cast and rasterised, one z-buffer)."""
    from glshade.solids import Box, Sphere

    s = teapot_scene()
    s.add(Box((6.0, 0.4, 6.0)).translated((0, 0.9, 0)) - Sphere(1.5).translated((2, 1, 2)),
          Material(color=(0.4, 0.6, 0.85)))
    return s


def instances_scene():
    """The teapot on a ring of 24 coloured instances of a torus (one instanced draw)."""
    s = teapot_scene()
    angles = np.linspace(0, 2 * np.pi, 24, endpoint=False)
    t = np.tile(np.eye(4), (24, 1, 1))
    t[:, 0, 3], t[:, 2, 3] = 2.6 * np.cos(angles), 2.6 * np.sin(angles)
    t[:, :3, :3] *= 0.3
    colors = np.c_[0.5 + 0.5 * np.cos(angles), 0.5 + 0.5 * np.sin(angles), np.full(24, 0.4)]
    s.add(P.torus(), Material(), instances=t, colors=colors)
    return s


def clouds_scene():
    """The teapot in a ring of sphere impostors and a wide polyline round it."""
    from glshade import PointCloud, Polyline

    s = teapot_scene()
    angles = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    ring = np.c_[2.4 * np.cos(angles), 0.8 + 0.3 * np.sin(3 * angles), 2.4 * np.sin(angles)]
    s.add(PointCloud(ring, radius=0.15, colors=np.c_[0.5 + 0.5 * np.cos(angles),
                                                     np.full(40, 0.5), np.full(40, 0.8)]))
    s.add(Polyline(np.r_[ring, ring[:1]] * [1.2, 1.0, 1.2], width=4, joins="round"),
          Material(color=(0.9, 0.8, 0.2)))
    return s


def appearance_scene():
    """What #71 brought: a PBR gold teapot, a vertex-coloured ball, an emissive cube, lit
    by a spot light and a ranged point light."""
    from glshade import PBRMaterial, SpotLight

    s = Scene(background=(0.05, 0.05, 0.08))
    s.add(P.teapot(4), PBRMaterial(base_color=(1.0, 0.77, 0.33), metallic=1.0, roughness=0.35))
    ball = P.icosphere(3, 0.7)
    s.add(Mesh(ball.vertices, ball.faces, colors=ball.vertices / 1.4 + 0.5),
          PBRMaterial(roughness=0.6),
          translation=(2.2, 0.7, 0.5))
    s.add(P.cube(), Material(color=(0.2, 0.2, 0.2), emission=(0.6, 0.1, 0.1)),
          translation=(-2.2, 0.5, 0.5))
    s.add_light(SpotLight((0.0, 5.0, 2.0), (0.0, -1.0, -0.3), intensity=60.0,
                          inner_angle=0.3, outer_angle=0.7))
    s.add_light(PointLight((4.0, 3.0, 5.0), intensity=30.0, range=15.0))
    return s


CAM = Camera.look_at([3.5, 3.0, 6.0], [0, 1.2, 0], fov_y=40)

HEADLESS = """
import json, sys, numpy as np
from tests.viewer import test_viewer
from glshade import Camera, Renderer
job = json.loads(sys.argv[2])
cam = Camera(position=job["position"], orientation=job["orientation"], fov_y=job["fov_y"],
             near=job["near"], far=job["far"])
with Renderer(*job["size"], samples=0, backend="egl") as r:
    scene = getattr(test_viewer, job["scene"])()
    images = [r.render(scene, cam, **o) for o in job["renders"]]
    depth = r.render_depth(scene, cam)
np.savez(sys.argv[1], images=np.array(images, np.uint8).reshape(-1, *depth.shape, 4),
         depth=depth)
"""


def headless(tmp_path, *renders, camera=CAM, size=(240, 180), scene="teapot_scene"):
    """Renders of the teapot scene by the headless renderer in its own process (EGL): one
    colour image per dict of draw options (or mode name), and the view depth."""
    out = tmp_path / "headless.npz"
    job = {"size": list(size), "position": camera.position.tolist(),
           "orientation": camera.orientation.tolist(), "fov_y": camera.fov_y,
           "near": camera.near, "far": camera.far, "scene": scene,
           "renders": [r if isinstance(r, dict) else {"mode": r} for r in renders]}
    r = subprocess.run([sys.executable, "-c", HEADLESS, str(out), json.dumps(job)], cwd=ROOT,
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    data = np.load(out)
    return data["images"], data["depth"]


def test_window_equals_headless_render(viewer_factory, tmp_path):
    v = viewer_factory(teapot_scene(), CAM, options="phong")
    v.step()
    shot = v.screenshot().astype(int)
    ref = headless(tmp_path, "phong")[0][0].astype(int)
    assert shot.shape == ref.shape == (180, 240, 4)
    assert (shot[..., :3].max(-1) > 60).mean() > 0.1  # the teapot is there
    assert np.abs(shot - ref).max() <= 1


def test_window_draws_csg_solids_like_headless(viewer_factory, tmp_path):
    v = viewer_factory(csg_scene(), CAM)
    shot = v.screenshot().astype(int)
    ref = headless(tmp_path, "phong", scene="csg_scene")[0][0].astype(int)
    blue = (shot[..., 2] > shot[..., 0] + 30).mean()
    assert blue > 0.05  # the solid is there
    assert np.abs(shot - ref).max() <= 1


def test_window_draws_instances_like_headless(viewer_factory, tmp_path):
    v = viewer_factory(instances_scene(), CAM)
    shot = v.screenshot().astype(int)
    ref = headless(tmp_path, "phong", scene="instances_scene")[0][0].astype(int)
    assert len(np.unique(shot[..., :3].reshape(-1, 3), axis=0)) > 200  # (the ring is there)
    assert np.abs(shot - ref).max() <= 1


def test_window_draws_clouds_and_lines_like_headless(viewer_factory, tmp_path):
    v = viewer_factory(clouds_scene(), CAM)
    shot = v.screenshot().astype(int)
    ref = headless(tmp_path, "phong", scene="clouds_scene")[0][0].astype(int)
    yellow = (shot[..., 0] > 150) & (shot[..., 1] > 130) & (shot[..., 2] < 110)
    assert yellow.mean() > 0.005  # (the polyline is there)
    assert np.abs(shot - ref).max() <= 1


def test_window_draws_pbr_colours_emission_and_spot_lights_like_headless(viewer_factory,
                                                                          tmp_path):
    v = viewer_factory(appearance_scene(), CAM)
    refs = headless(tmp_path, "flat", "gouraud", "phong", scene="appearance_scene")[0]
    for key, ref in zip("123", refs.astype(int)):
        v.key(key)
        v.step()
        shot = v.screenshot().astype(int)
        assert (shot[..., 0] > shot[..., 2] + 40).mean() > 0.02, key  # (gold, lit)
        assert np.abs(shot - ref).max() <= 1, key


def test_keys_switch_modes_like_headless(viewer_factory, tmp_path):
    v = viewer_factory(teapot_scene(), CAM)
    refs = headless(tmp_path, "flat", "gouraud", "phong")[0].astype(int)
    for key, ref in zip("123", refs):
        v.key(key)
        v.step()
        assert np.abs(v.screenshot().astype(int) - ref).max() <= 1, key
    assert np.abs(refs[0] - refs[2]).max() > 20  # the modes really differ


def test_x_turns_shadows_exact_then_map_then_off_like_headless(viewer_factory, tmp_path):
    """The window's framebuffer is top row last (GL's own): its shadows still fall where
    the headless renderer's do (the slab's on the teapot, the teapot's on the slab)."""
    v = viewer_factory(csg_scene(), CAM)
    refs = headless(tmp_path, {"mode": "phong", "shadows": "exact"},
                    {"mode": "phong", "shadows": "map"}, "phong",
                    scene="csg_scene")[0].astype(int)
    v.key("3")
    for ref in refs:
        v.key("x")
        if v.options.shadows.value == "map":  # (said once: the solid casts no map shadow)
            with pytest.warns(RenderWarning, match="CSG solids receive map shadows"):
                v.step()
        else:
            v.step()
        assert np.abs(v.screenshot().astype(int) - ref).max() <= 1, v.options.shadows
    assert (np.abs(refs[0] - refs[2]).max(-1) > 20).sum() > 100  # shadows really show


def test_transparent_surfaces_in_the_window_like_headless(viewer_factory, tmp_path):
    """The window's framebuffer: the glass composited over the teapot as headless does."""
    v = viewer_factory(glass_scene(), CAM, options="phong")
    v.step()
    shot = v.screenshot().astype(int)
    refs = headless(tmp_path, "phong", scene="glass_scene")[0].astype(int)
    assert np.abs(shot - refs[0]).max() <= 1
    plain = headless(tmp_path, "phong")[0][0].astype(int)
    assert (np.abs(refs[0] - plain).max(-1) > 20).sum() > 500  # the glass is there


def test_z_toggles_depth_test(viewer_factory, tmp_path):
    v = viewer_factory(teapot_scene(), CAM)
    with_z = v.screenshot()
    v.key("z")
    without = v.screenshot()
    assert not v.options.depth_test
    expected = headless(tmp_path, {"mode": "phong", "depth_test": False})[0][0]
    assert np.abs(without.astype(int) - expected.astype(int)).max() <= 1
    assert np.abs(with_z.astype(int) - without.astype(int)).max() > 20
    v.key("z")
    assert np.array_equal(v.screenshot(), with_z)


def test_drag_rotates_the_view_by_the_arcball_rotation(viewer_factory, tmp_path):
    scene = teapot_scene()
    centre = scene.bounds.mean(0)
    start = Camera.look_at(centre + [0, 0, 9.0], centre, fov_y=40)
    v = viewer_factory(scene, start, size=(240, 180))
    w, h = 240, 180
    # centre to the right rim of the ball (radius = half the window height): 90 degrees
    v.mouse_down(w / 2, h / 2)
    v.mouse_move(w / 2 + h / 2, h / 2)
    v.mouse_up()
    # the object turned right, so the camera went round to its left (world -x)
    np.testing.assert_allclose(v.camera.position, centre + [-9.0, 0, 0], atol=1e-9)
    np.testing.assert_allclose(v.camera.forward, [1, 0, 0], atol=1e-12)
    expected = headless(tmp_path, "phong", camera=v.camera)[0][0]
    assert np.abs(v.screenshot().astype(int) - expected.astype(int)).max() <= 1


def test_s_writes_a_png(viewer_factory, tmp_path):
    from PIL import Image

    v = viewer_factory(teapot_scene(), CAM)
    v.key("s")
    (png,) = tmp_path.glob("glshade-*.png")
    assert Image.open(png).size == (240, 180)


def test_k_then_p_plays_the_path(viewer_factory):
    v = viewer_factory(teapot_scene(), CAM)
    v.key("k")
    v.mouse_down(120, 90)
    v.mouse_move(160, 90)
    v.mouse_up()
    turned = v.camera
    v.key("k")
    assert len(v.keyframes) == 2
    v.key("p")
    assert v.playing
    v.step(dt=0.5)
    mid = v.path.at(0.5)
    np.testing.assert_allclose(v.camera.position, mid.position)
    assert not np.allclose(mid.position, CAM.position)
    assert not np.allclose(mid.position, turned.position)
    v.key("p")
    assert not v.playing


def test_compare_split_view_and_other_keys(viewer_factory):
    from glshade.io.images import LABEL_HEIGHT, label_image

    v = viewer_factory(teapot_scene(), CAM, compare=True, size=(360, 120))
    img = v.screenshot()
    thirds = [img[:, i * 120:(i + 1) * 120].astype(int) for i in range(3)]
    for third, name in zip(thirds, ("flat", "gouraud", "phong")):  # labelled like the grid
        expected = label_image(name, 120)[..., :3].astype(int)
        assert np.abs(third[:LABEL_HEIGHT, :, :3] - expected).max() <= 1, name
    assert np.abs(thirds[0] - thirds[2]).max() > 20  # flat and phong differ side by side
    v.key("w")
    assert np.abs(v.screenshot().astype(int) - img.astype(int)).max() > 50  # wireframe on
    v.key("c")
    assert v.options.cull is Culling.ON
    v.key("l")
    np.testing.assert_allclose(v.scene.lights[0].position, v.camera.position)
    v.scroll(3)
    assert np.linalg.norm(v.camera.position - v.center) < np.linalg.norm(CAM.position -
                                                                          v.center)
    v.key("r")
    assert v.camera == CAM
    assert "triangles" in v.status()
    v.key("q")
    assert v.closed


def test_double_click_recentres_on_the_surface(viewer_factory, tmp_path):
    from glshade.cpu.raycast import pixel_rays

    v = viewer_factory(teapot_scene(), CAM)
    v.step()
    x, y = 120, 100
    assert v.recentre(x, y)
    # expected: the surface point under the pixel centre, from a headless depth render
    depth = headless(tmp_path, camera=CAM)[1]
    origin, direction = pixel_rays(CAM, 240, 180)
    d = float(depth[y, x])
    assert np.isfinite(d)
    point = origin[y, x] + direction[y, x] * d / (direction[y, x] @ CAM.forward)
    # the window's 24-bit depth buffer quantises depth: a few 1e-4 of the distance
    np.testing.assert_allclose(v.center, point, atol=2e-3 * np.linalg.norm(point - CAM.position))


def test_view_cli_screenshot(tmp_path):
    out = tmp_path / "view.png"
    r = subprocess.run([sys.executable, "-m", "glshade", "view", "primitive:teapot", "--frames",
                        "2", "--screenshot", str(out), "--size", "200x150", "--samples", "0"],
                       cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    from PIL import Image

    assert Image.open(out).size == (200, 150)


def test_a_blank_screenshot_says_why(tmp_path):
    """A screenshot of nothing warns as ``render`` does (the camera looks away here), and
    still writes the picture it was asked for."""
    out = tmp_path / "away.png"
    r = subprocess.run([sys.executable, "-m", "glshade", "view", "primitive:cube", "--frames",
                        "2", "--screenshot", str(out), "--size", "64x48", "--eye", "0,0,5",
                        "--target", "0,0,10"], cwd=ROOT, capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 0, r.stderr
    assert "glshade: warning: the render is blank: no part of the scene lies in the " \
        "camera's view" in r.stderr, r.stderr
    assert out.exists()


def test_resize_keeps_the_aspect(viewer_factory, tmp_path):
    import glfw

    v = viewer_factory(teapot_scene(), CAM, size=(240, 180))
    glfw.set_window_size(v.window, 300, 120)
    for _ in range(50):  # the X server answers asynchronously
        v.step()
        if (v.target.width, v.target.height) == (300, 120):
            break
    assert (v.target.width, v.target.height) == (300, 120)
    shot = v.screenshot()
    assert shot.shape == (120, 300, 4)
    expected = headless(tmp_path, "phong", size=(300, 120))[0][0]
    assert np.abs(shot.astype(int) - expected.astype(int)).max() <= 1


def test_six_shows_a_radiosity_solution(viewer_factory):
    """Key 6: the radiosity mode, drawing a solution's vertex radiosities unlit."""
    from glshade import ShadingMode

    scene = Scene(background=(0, 0, 0))
    plane = P.plane(4.0)
    scene.add(plane, vertex_colors=np.tile([[0.2, 0.6, 0.4]], (plane.n_vertices, 1)))
    v = viewer_factory(scene, Camera.look_at((0, 0, 3), (0, 0, 0)), size=(120, 90))
    v.key("6")
    v.step()
    assert v.options.mode is ShadingMode.RADIOSITY
    centre = v.screenshot()[45, 60, :3].astype(int)
    assert np.abs(centre - [51, 153, 102]).max() <= 1


def test_w_draws_polygon_edges_not_triangle_diagonals_in_the_window(viewer_factory):
    """A head-on quad in the window, edges on: its sides are dark, its diagonal is not (the
    overlay draws each polygon's boundary, not its triangles')."""
    s = Scene(background=(0, 0, 0))
    s.add(P.plane(2.0), Material(color=(1, 1, 1), ka=1.0, kd=0.0, ks=0.0))
    cam = Camera.look_at((0, 0, 4), (0, 0, 0))
    v = viewer_factory(s, cam, size=(128, 128), options="flat")
    filled = v.screenshot().astype(int)
    v.key("w")
    assert v.options.edges
    over = v.screenshot().astype(int)
    dark = (filled[..., :3] - over[..., :3]).max(axis=2) > 60
    t = np.tan(np.radians(45) / 2) * 4
    px = lambda x, y: ((x / t + 1) * 64, (1 - y / t) * 64)  # noqa: E731
    for (x0, y0), (x1, y1) in ((px(-1, -1), px(1, 1)), (px(1, -1), px(-1, 1))):
        k = np.linspace(0.05, 0.95, 200)
        assert dark[(y0 + k * (y1 - y0)).astype(int), (x0 + k * (x1 - x0)).astype(int)].sum() == 0
    k = np.linspace(0.05, 0.95, 200)
    x0, y0 = px(-1, -1)
    x1, y1 = px(1, -1)
    side = dark[np.clip((y0 + k * (y1 - y0)).astype(int), 0, 127),
                (x0 + k * (x1 - x0)).astype(int)]
    assert side.mean() > 0.9


def test_compare_panes_each_hold_the_whole_model(tmp_path):
    """glshade view --compare frames for a pane, not the window: nothing of the teapot
    touches a pane's side (it did at 800x600: the handle and spout were cut off)."""
    out = tmp_path / "shot.png"
    r = subprocess.run([sys.executable, "-m", "glshade", "view", "primitive:teapot",
                        "--compare", "--size", "480x240", "--samples", "0", "--frames", "2",
                        "--screenshot", str(out), "--hidden"], capture_output=True, text=True,
                       cwd=ROOT, timeout=120)
    assert r.returncode == 0, r.stderr
    from PIL import Image

    img = np.asarray(Image.open(out)).astype(int)
    for i in range(3):
        pane = img[30:, i * 160:(i + 1) * 160, :3]  # (below the label)
        lit = pane.max(axis=2) > 40
        assert lit.mean() > 0.05, i
        assert not lit[:, :2].any() and not lit[:, -2:].any(), i  # both sides clear


def test_a_click_picks_with_pick_on(viewer_factory):
    s = Scene()
    s.add(P.cube())
    cam = Camera.look_at((0, 0, 4), (0, 0, 0))
    v = viewer_factory(s, cam, size=(120, 90), pick=True)
    v.step()
    v.mouse_down(60, 45)
    v.mouse_up()
    found = v.picks[-1]
    assert found is not None and found.face_id >= 0
    np.testing.assert_allclose(found.point, [0, 0, 0.5], atol=0.02)  # the cube's +z face
    np.testing.assert_allclose(found.normal, [0, 0, 1], atol=1e-5)
    assert "pick: polygon" in v.messages[-1]
    v.mouse_down(2, 2)
    v.mouse_up()
    assert v.picks[-1] is None


def test_dollying_through_the_teapot_never_clips_its_front(viewer_factory):
    """Three and more wheel clicks towards the centre: every pixel the teapot covers in
    a render with generous explicit clip planes is covered in the window too."""
    s = teapot_scene()
    v = viewer_factory(s, CAM, size=(160, 120))
    from glshade import Renderer

    for clicks in (3, 3, 3):
        v.scroll(clicks)
        shot = v.screenshot()
        lit = shot[..., :3].astype(int).max(axis=2) > 40
        wide = v.camera.replace(near=1e-2, far=1e3)  # (1e5: the depth buffer's range)
        with Renderer(160, 120, samples=0, context=v.context) as r:
            ref = r.render_frame(s, wide, "phong").face_id >= 0
        assert (lit | ~ref).mean() > 0.995  # (a pixel or two of background-coloured shade)


def test_t_path_traces_and_refines_while_the_camera_rests(viewer_factory):
    """Key t: each frame adds one sample a pixel; after N frames the window shows what
    pathtrace.trace gives for N samples with the same seed and the renderer's smooth
    normals (the k-th sample of a pixel is
    seeded by k, however the passes are grouped), at the viewer's exposure. A move starts
    over; a mode key ends it."""
    from glshade import pathtrace
    from glshade.radiosity import cornell_scene

    scene, cam = cornell_scene()
    v = viewer_factory(scene, cam, size=(96, 96))
    v.key("t")
    assert v.tracer is not None
    for _ in range(8):
        v.draw()  # (what step draws, without the swap: the back buffer stays readable)
    assert v.tracer.samples == 8 and "8 samples a pixel" in v.status()
    shown = v.target.read_color()[..., :3].astype(int)
    smooth = pathtrace.TraceScene.from_scene(scene, smooth=True)  # (the viewer's normals)
    ref = pathtrace.trace(smooth, cam, (96, 96), spp=8, samples_per_pass=1, progress=False,
                          context=v.context)
    want = ref.rgba8(v._trace_exposure)[..., :3].astype(int)
    assert np.abs(shown - want).max() <= 1
    v.camera = v.camera.dolly(10.0)
    v.step()
    assert v.tracer.samples == 1
    v.key("3")
    assert v.tracer is None


def test_t_traces_gltfs_materials_colours_and_the_sky(viewer_factory):
    """The progressive view takes what the tracer takes: the appearance scene (glTF's
    gold, a vertex-coloured ball, an emissive cube, a spot and a ranged light) under a sky,
    shown as pathtrace.trace gives it for the same samples."""
    from glshade import Environment, pathtrace

    scene = appearance_scene()
    scene.environment = Environment((0.3, 0.35, 0.45))
    v = viewer_factory(scene, CAM, size=(64, 48))
    v.key("t")
    assert v.tracer is not None
    for _ in range(4):
        v.draw()
    shown = v.target.read_color()[..., :3].astype(int)
    smooth = pathtrace.TraceScene.from_scene(scene, smooth=True)
    ref = pathtrace.trace(smooth, CAM, (64, 48), spp=4, samples_per_pass=1, progress=False,
                          context=v.context)
    want = ref.rgba8(v._trace_exposure)[..., :3].astype(int)
    assert np.abs(shown - want).max() <= 1
    assert (shown[..., 0] > shown[..., 2] + 30).mean() > 0.02  # (the gold is there)


def test_t_on_a_scene_it_cannot_trace_says_why(viewer_factory, capsys):
    scene = Scene()
    scene.add(P.cube(), Material(kd=0.9, ks=0.5, color=(1, 1, 1)), name="cube")
    v = viewer_factory(scene, CAM, size=(64, 48))
    v.key("t")
    assert v.tracer is None and "rho_d + k_s" in capsys.readouterr().err
    v.step()


def test_a_framebuffer_twice_the_window_picks_and_recentres_by_window_coordinates(
        viewer_factory, monkeypatch):
    """A HiDPI screen (a Retina Mac): the framebuffer has twice the window's size, and the
    mouse reports window coordinates. Held here by glfw reporting the window at half its
    framebuffer (Xvfb has no scale of its own): the picture keeps the framebuffer's size,
    and a click at window (x, y) picks and recentres on framebuffer pixel (2x, 2y), as the
    same click at (2x, 2y) does on a screen of scale 1."""
    import glfw

    x, y = 120, 100
    plain = viewer_factory(teapot_scene(), CAM)
    plain.step()
    picked_1 = plain.pick(x, y)
    assert plain.recentre(x, y)
    monkeypatch.setattr(glfw, "get_window_size", lambda window: (120, 90))
    hidpi = viewer_factory(teapot_scene(), CAM)
    hidpi.step()
    assert (hidpi.target.width, hidpi.target.height) == (240, 180)   # (the framebuffer's)
    picked_2 = hidpi.pick(x / 2, y / 2)
    assert picked_1 is not None and picked_2.face_id == picked_1.face_id
    np.testing.assert_allclose(picked_2.point, picked_1.point, atol=1e-9)
    assert hidpi.recentre(x / 2, y / 2)
    np.testing.assert_allclose(hidpi.center, plain.center, atol=1e-9)
