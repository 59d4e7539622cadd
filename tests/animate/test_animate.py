"""Key-frame animation: scene files, frames along paths, files, jobs and interrupts."""

import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from PIL import Image

from glshade import Camera, CameraPath, DrawOptions, Keyframe, Material, PointLight, Scene
from glshade import quaternion as Q
from glshade.animate import animate
from glshade.geometry import primitives as P
from glshade.io.scenefile import load_scene

from tests.conftest import BACKEND, ROOT, glshade

pytestmark = pytest.mark.gl  # renders, also in subprocesses: run on every backend


@pytest.mark.parametrize("options", [DrawOptions(), DrawOptions(mode="flat", srgb=True,
                                                                 depth_test=False, cull=True)])
def test_frame_at_key_time_equals_still(make_renderer, options):
    """The draw options reach every frame unchanged: frames on the keys equal stills drawn
    with the same options."""
    sf = load_scene(ROOT / "assets/scenes/teapot-orbit.toml")
    frames = list(animate(sf.scene, sf.path, 5, options, size=(96, 72), samples=0,
                          backend=BACKEND))
    assert sf.path.times.tolist() == [0.0, 2.0, 4.0]  # frames 0, 2, 4 sit on the keys
    r = make_renderer(96, 72)
    for frame, key in zip(frames[::2], sf.path.keyframes):
        cam = sf.path.camera.replace(position=key.position, orientation=key.orientation)
        np.testing.assert_array_equal(frame, r.render(sf.scene, cam, options))


def test_slerp_in_motion_turns_by_equal_angles():
    """A camera at the origin turns 90 degrees about y between two keys; the yaw measured
    from a red marker's position in each image advances by equal steps."""
    s = Scene(background=(0, 0, 0))
    s.add(P.icosphere(2), Material(color=(1, 0, 0), ka=1, kd=0, ks=0), scale=0.12,
          translation=(0, 0, -5))
    s.add_light(PointLight((0, 0, 0)))
    a, b = Q.from_axis_angle([0, 1, 0], -np.pi / 4), Q.from_axis_angle([0, 1, 0], np.pi / 4)
    lens = Camera(fov_y=60.0, near=0.1, far=20)
    path = CameraPath([Keyframe(0, [0, 0, 0], a), Keyframe(1, [0, 0, 0], b)], camera=lens)
    w, h = 480, 120
    frames = list(animate(s, path, 9, "flat", size=(w, h), samples=0, backend=BACKEND))
    tan_half_x = np.tan(np.radians(30)) * w / h
    yaws = []
    for f in frames:
        red = f[..., 0] > 128
        assert red.sum() > 10
        x_ndc = 2 * (np.nonzero(red)[1].mean() + 0.5) / w - 1
        yaws.append(np.degrees(np.arctan(x_ndc * tan_half_x)))
    steps = np.diff(yaws)
    # turning left (about +y) the camera sees the marker at -z drift right: 90/8 degrees
    # a frame, every frame
    np.testing.assert_allclose(steps, 90 / 8, atol=0.35)


def test_a_mesh_animates_as_a_seamless_turntable(tmp_path):
    out = tmp_path / "spin.gif"
    r = glshade("animate", "assets/teapot.obj", "-o", str(out), "--frames", "12", "--size",
                "64x48", "--jobs", "1", "--backend", BACKEND)
    assert r.returncode == 0, r.stderr
    with Image.open(out) as im:
        frames = [np.asarray(f.convert("RGB"), float) for f in _frames(im)]
    assert len(frames) == 12
    step = [np.abs(a - b).mean() for a, b in zip(frames, frames[1:] + frames[:1])]
    # the wrap from the last frame to the first is one more step of the turn, no jump
    assert step[-1] < 1.5 * np.median(step[:-1]) and min(step) > 0
    half = np.abs(frames[0] - frames[6]).mean()  # the far side of the teapot
    assert half > max(step)


def _frames(im):
    for i in range(im.n_frames):
        im.seek(i)
        yield im


def test_gif_and_apng_frame_count_and_duration(tmp_path):
    sf = load_scene(ROOT / "assets/scenes/teapot-orbit.toml")
    for name in ("a.gif", "a.png"):
        n = animate(sf.scene, sf.path, 6, output=tmp_path / name, fps=20, size=(64, 48),
                    samples=0, backend=BACKEND)
        assert n == 6
        with Image.open(tmp_path / name) as im:
            assert im.n_frames == 6
            assert im.info["duration"] == 50
            assert im.size == (64, 48)


def test_mp4_with_the_video_extra(tmp_path):
    import imageio.v2 as imageio  # installed with the test extra (glshade[video])

    sf = load_scene(ROOT / "assets/scenes/teapot-orbit.toml")
    animate(sf.scene, sf.path, 10, output=tmp_path / "a.mp4", fps=10, size=(64, 48),
            samples=0, backend=BACKEND)
    reader = imageio.get_reader(tmp_path / "a.mp4")
    assert reader.count_frames() == 10
    assert reader.get_meta_data()["fps"] == pytest.approx(10)
    assert oct((tmp_path / "a.mp4").stat().st_mode)[-3:] != "600"


def test_modes_side_by_side_and_frames_folder(tmp_path):
    r = glshade("animate", "assets/scenes/teapot-orbit.toml", "-o", str(tmp_path / "frames/"),
                "--frames", "3", "--modes", "flat,gouraud,phong", "--size", "80x60",
                "--jobs", "1", "--backend", BACKEND, "-q")
    assert r.returncode == 0, r.stderr
    files = sorted((tmp_path / "frames").iterdir())
    assert [f.name for f in files] == ["frame_00000.png", "frame_00001.png", "frame_00002.png"]
    assert Image.open(files[0]).size == (240, 60 + 22)


@pytest.mark.parametrize("source", ["assets/scenes/teapot-orbit.toml",
                                    "solid:box(1.6) - sphere(1)"])  # (solids go to workers too)
def test_jobs_2_equals_jobs_1_byte_for_byte(tmp_path, source):
    outs = []
    for jobs in ("1", "2"):
        out = tmp_path / f"j{jobs}.gif"
        r = glshade("animate", source, "-o", str(out), "--frames",
                    "12", "--size", "96x72", "--jobs", jobs, "--backend", BACKEND)
        assert r.returncode == 0, r.stderr
        assert "12 frames" in r.stdout
        outs.append(out.read_bytes())
    assert outs[0] == outs[1]


def test_render_still_from_scene_file(tmp_path):
    r = glshade("render", "assets/scenes/teapot-orbit.toml", "--time", "2", "-o",
                str(tmp_path / "t.png"), "--backend", BACKEND)
    assert r.returncode == 0, r.stderr
    assert Image.open(tmp_path / "t.png").size == (512, 384)  # the scene's own size


def test_a_time_off_the_path_warns_and_a_zero_frame_rate_is_refused(tmp_path):
    late = glshade("render", "assets/scenes/teapot-orbit.toml", "--time", "100", "-o",
                   str(tmp_path / "late.png"), "--backend", BACKEND)
    end = glshade("render", "assets/scenes/teapot-orbit.toml", "--time", "4", "-o",
                  str(tmp_path / "end.png"), "--backend", BACKEND)
    assert late.returncode == 0 and end.returncode == 0
    assert late.stderr.strip() == ("glshade: warning: --time 100 is outside "
                                   "assets/scenes/teapot-orbit.toml's camera path (0 to 4 s): "
                                   "the view at its end")
    assert (tmp_path / "late.png").read_bytes() == (tmp_path / "end.png").read_bytes()
    zero = glshade("animate", "assets/teapot.obj", "-o", str(tmp_path / "a.gif"), "--fps", "0")
    assert zero.returncode == 2 and "--fps: expected frames a second from 0.01 to 1000" \
        in zero.stderr
    assert not (tmp_path / "a.gif").exists()


MALFORMED = {
    "syntax": ("[render\nsize = [1, 2]\n", "Expected ']'"),
    "unknown_table": ("[lights]\nposition = [1, 2, 3]\n", ":1: unknown table [lights]"),
    "top_level_key": ('# light\nambient = [0.2, 0.2, 0.2]\n[[mesh]]\nsource = "primitive:cube"\n',
                      ":2: unknown top-level key 'ambient' (keys go in a table, such as "
                      "[render])"),
    "zero_direction": ('[[mesh]]\nsource = "primitive:cube"\n[[light]]\ntype = "directional"\n'
                       'direction = [0, 0, 0]\n', ":3: [[light]] 1: direction must be a "
                       "non-zero 3-vector"),
    "unknown_key": ('[[mesh]]\nsource = "primitive:cube"\ncolour = [1, 0, 0]\n',
                    ":3: unknown key 'colour' in [[mesh]] 1"),
    "wrong_type": ('[[mesh]]\nsource = "primitive:cube"\nks = "shiny"\n',
                   ":3: [[mesh]] 1 key 'ks' must be a finite number"),
    "bad_colour": ('[[mesh]]\nsource = "primitive:cube"\ncolor = [1, 0]\n',
                   ":3: [[mesh]] 1 key 'color' must be a list of 3 numbers"),
    "missing_mesh_file": ('[[mesh]]\nsource = "nowhere.obj"\n', "nowhere.obj' does not exist"),
    "no_source": ("[[mesh]]\ncolor = [1, 0, 0]\n", ":1: [[mesh]] 1 needs a 'source'"),
    "no_mesh": ("[render]\nsize = [10, 10]\n", "the scene has no [[mesh]]"),
    "bad_mode": ('[render]\nmode = "toon"\n[[mesh]]\nsource = "primitive:cube"\n',
                 ":2: [render] key 'mode': unknown shading mode 'toon'; choose one of flat"),
    "bad_size": ('[render]\nsize = [0, 10]\n[[mesh]]\nsource = "primitive:cube"\n',
                 "key 'size' must be whole pixels from 1 to 16384 a side"),
    "light_without_position": ('[[mesh]]\nsource = "primitive:cube"\n[[light]]\n'
                               'color = [1, 1, 1]\n', ":3: [[light]] 1: a point light needs"),
    "keyframe_times": ('[[mesh]]\nsource = "primitive:cube"\n[[camera.keyframe]]\ntime = 1\n'
                       'eye = [0, 0, 5]\ntarget = [0, 0, 0]\n[[camera.keyframe]]\ntime = 0\n'
                       'eye = [5, 0, 0]\ntarget = [0, 0, 0]\n',
                       ":7: [camera] keyframe 2: key frame times must increase"),
    "keyframe_inf": ('[[mesh]]\nsource = "primitive:cube"\n[[camera.keyframe]]\ntime = inf\n'
                     'eye = [0, 0, 5]\ntarget = [0, 0, 0]\n',
                     ":3: [camera] keyframe 1: 'time' must be a finite number"),
    "keyframe_half": ('[[mesh]]\nsource = "primitive:cube"\n[[camera.keyframe]]\ntime = 0\n'
                      'eye = [0, 0, 5]\n', ":3: [camera] keyframe 1: give both 'eye' and"),
    "bad_primitive": ('[[mesh]]\nsource = "primitive:blob"\n', ":2: unknown primitive 'blob'"),
    "one_view_eye_at_target": ('[[mesh]]\nsource = "primitive:cube"\n[camera]\n'
                               'eye = [1, 2, 3]\ntarget = [1, 2, 3]\n',
                               ":3: [camera]: look_at: eye and target are the same point"),
    "mesh_as_table": ('[mesh]\nsource = "primitive:cube"\n', "write meshes and lights as"),
}


@pytest.mark.parametrize("name", sorted(MALFORMED))
def test_malformed_scene_files_exit_2_with_one_line(tmp_path, name):
    text, message = MALFORMED[name]
    scene = tmp_path / f"{name}.toml"
    scene.write_text(text)
    r = glshade("animate", str(scene), "-o", str(tmp_path / "out.gif"), "--frames", "2")
    assert r.returncode == 2, r.stdout + r.stderr
    assert len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert message in r.stderr, r.stderr
    assert str(scene) in r.stderr
    assert not (tmp_path / "out.gif").exists()


def test_interrupt_leaves_no_partial_output(tmp_path, spawn):
    out = tmp_path / "long.gif"
    proc = spawn([sys.executable, "-m", "glshade", "animate",
                             "assets/scenes/teapot-orbit.toml", "-o", str(out), "--frames",
                             "20000", "--size", "128x96", "--jobs", "2", "--backend", BACKEND],
                            cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(4)
    assert proc.poll() is None, proc.stderr.read()
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert "interrupted" in err and "Traceback" not in err
    assert list(tmp_path.iterdir()) == []  # no output, no .part file


@pytest.mark.parametrize("delay", [0.2, 0.6, 2.0])
def test_ctrl_c_on_the_whole_process_group_at_any_moment(tmp_path, delay, spawn):
    """A terminal's Ctrl-C reaches the workers too, even while they are starting."""
    out = tmp_path / "long.gif"
    proc = spawn([sys.executable, "-m", "glshade", "animate",
                             "assets/scenes/teapot-orbit.toml", "-o", str(out), "--frames",
                             "20000", "--size", "64x48", "--jobs", "2", "--backend", BACKEND],
                            cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)
    time.sleep(delay)
    os.killpg(proc.pid, signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    # 130, or death by SIGINT when it lands while the interpreter itself starts up or exits
    assert proc.returncode in (130, -signal.SIGINT), err
    assert err.strip().splitlines() == ["glshade: interrupted"], err
    assert list(tmp_path.iterdir()) == []


def test_unknown_output_format(tmp_path):
    r = glshade("animate", "assets/scenes/teapot-orbit.toml", "-o", str(tmp_path / "a.avi"))
    assert r.returncode == 2 and ".gif, .png, .apng, .mp4" in r.stderr


def test_progress_bar_on_a_terminal_lines_in_a_log_and_quiet_for_short_work(monkeypatch):
    import io

    from glshade.animate import Progress
    from glshade.parallel import progress

    class Tty(io.StringIO):
        def isatty(self):
            return True

    out = Tty()
    bar = Progress(4, stream=out)
    for _ in range(4):
        bar.update()
    bar.close()
    text = out.getvalue()
    assert "4/4" in text and "frames" in text and "100%" in text
    quiet = io.StringIO()  # not a terminal, and the work ends at once
    Progress(4, stream=quiet).update()
    assert quiet.getvalue() == ""
    # a log of long work: a plain line at each tenth, no carriage returns
    monkeypatch.setattr(progress, "LOG_AFTER_S", 0.0)
    log = io.StringIO()
    bar = Progress(20, stream=log, unit="meshes")
    for _ in range(20):
        bar.update()
    lines = log.getvalue().splitlines()
    assert len(lines) == 10 and "\r" not in log.getvalue()
    assert lines[0].startswith("2/20 meshes (10%)") and lines[-1].startswith("20/20 meshes")
    assert "meshes/s" in lines[0] and "s left" in lines[0]


def test_compare_takes_a_scene_file(tmp_path):
    r = glshade("compare", "assets/scenes/spheres.toml", "-o", str(tmp_path / "g.png"),
                "--size", "96x48", "--backend", BACKEND)
    assert r.returncode == 0, r.stderr
    assert "flat" in r.stdout and (tmp_path / "g.png").exists()


def test_workers_do_not_rerun_an_unguarded_script(tmp_path):
    script = tmp_path / "unguarded.py"
    script.write_text(
        "import glshade\n"
        f"sf = glshade.load_scene({str(ROOT / 'assets/scenes/teapot-orbit.toml')!r})\n"
        "n = glshade.animate(sf.scene, sf.path, 6, output='o.gif', size=(48, 36), jobs=2,\n"
        f"                   backend={BACKEND!r})\n"
        "print('frames', n)\n")
    r = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True,
                       text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert r.stdout.count("frames 6") == 1  # printed once: the workers did not run it


def test_a_worker_without_gl_is_reported_not_restarted(tmp_path):
    env = dict(os.environ, GLSHADE_OSMESA_LIBRARY="/no/libOSMesa.so")
    r = subprocess.run([sys.executable, "-m", "glshade", "animate",
                        "assets/scenes/teapot-orbit.toml", "-o", str(tmp_path / "x.gif"),
                        "--frames", "4", "--jobs", "2", "--backend", "osmesa"],
                       cwd=ROOT, capture_output=True, text=True, timeout=120, env=env)
    assert r.returncode == 1
    assert "cannot load /no/libOSMesa.so" in r.stderr and "Traceback" not in r.stderr
    assert list(tmp_path.iterdir()) == []


def test_animate_a_loaded_scene_file_honours_its_render_table(tmp_path):
    """glshade.animate(scene_file, ...) takes the file's path, size, fps and draw options
    where the call gives none (it used to draw 512x512 at 30 fps whatever the file said)."""
    from PIL import Image

    import glshade

    path = tmp_path / "s.toml"
    path.write_text('[render]\nsize = [48, 32]\nfps = 10\nduration = 0.4\nmode = "flat"\n'
                    'samples = 0\n[[mesh]]\nsource = "primitive:cube"\n'
                    '[[camera.keyframe]]\ntime = 0\neye = [3, 2, 4]\ntarget = [0, 0, 0]\n'
                    '[[camera.keyframe]]\ntime = 1\neye = [-3, 2, 4]\ntarget = [0, 0, 0]\n')
    sf = glshade.load_scene(path)
    n = glshade.animate(sf, output=str(tmp_path / "a.gif"))
    assert n == 4  # duration 0.4 s at 10 fps
    with Image.open(tmp_path / "a.gif") as gif:
        assert gif.size == (48, 32) and gif.n_frames == 4
        assert gif.info["duration"] == 100  # ms: 10 fps
    frames = list(glshade.animate(sf, frames=2))
    flat = glshade.animate(sf.scene, sf.path, 2, "flat", size=(48, 32), samples=0)
    for a, b in zip(frames, flat):
        assert np.array_equal(a, b)  # the file's mode (flat) and samples, by default
    with pytest.raises(glshade.InputError, match="needs a camera path"):
        glshade.animate(sf.scene)


def test_a_path_file_is_a_scene_files_camera_table(tmp_path):
    """One key-frame format: CameraPath.save writes [camera] + [[camera.keyframe]], which a
    scene file takes as it is, and CameraPath.load reads a scene file's path."""
    import glshade

    p = glshade.CameraPath([glshade.Keyframe.look_at(0.0, (0, 1, 5), (0, 0, 0)),
                            glshade.Keyframe.look_at(2.0, (5, 1, 0), (0, 0, 0))],
                           orientation_interp="spline", camera=glshade.Camera(fov_y=35))
    p.save(tmp_path / "path.toml")
    text = (tmp_path / "path.toml").read_text()
    assert "[[camera.keyframe]]" in text and 'interpolation = "spline"' in text
    back = glshade.CameraPath.load(tmp_path / "path.toml")
    scene_file = tmp_path / "scene.toml"
    scene_file.write_text('[[mesh]]\nsource = "primitive:cube"\n\n' + text)
    from_scene = glshade.load_scene(scene_file).path
    also = glshade.CameraPath.load(scene_file)
    t = np.linspace(0, 2, 9)
    for q in (back, from_scene, also):
        pos, rot, fov = q.evaluate(t)
        ref = p.evaluate(t)
        np.testing.assert_allclose(pos, ref[0], atol=1e-9)
        np.testing.assert_allclose(np.abs(np.einsum("ij,ij->i", rot, ref[1])), 1, atol=1e-9)
        np.testing.assert_allclose(fov, 35.0)
    assert back.orientation_interp is glshade.scene.keyframes.OrientationInterp.SPLINE


def test_examples_by_name_in_the_api_and_the_cli(tmp_path):
    import subprocess
    import sys

    import glshade

    names = glshade.examples.names()
    assert {"cornell-box", "csg-part", "teapot-orbit", "teapot.obj", "torus.off"} <= set(names)
    assert glshade.examples.path("cornell-box").name == "cornell-box.toml"
    with pytest.raises(glshade.InputError, match="no example named 'cornel'; the examples"):
        glshade.examples.path("cornel")
    out = subprocess.run([sys.executable, "-m", "glshade", "render", "teapot.obj", "-o",
                          "t.png", "--size", "32x24"], capture_output=True, text=True,
                         cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    assert (tmp_path / "t.png").exists()
    (tmp_path / "teapot.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    out = subprocess.run([sys.executable, "-m", "glshade", "info", "teapot.obj", "--json"],
                         capture_output=True, text=True, cwd=tmp_path)
    assert '"faces": 1' in out.stdout  # a file of that name wins over the example


@pytest.mark.parametrize("ext", ["gif", "png"])
def test_n_frames_asked_n_frames_written_even_when_they_repeat(tmp_path, ext):
    """A still camera gives identical frames; Pillow merged them (6 asked, 1 written):
    now every frame is in the file, each with its own duration and the picture it had."""
    from PIL import Image

    from glshade.animate import write_animation

    a = np.zeros((12, 16, 4), np.uint8)
    a[..., 3] = 255
    a[:6, :, :3] = (200, 60, 20)
    b = a.copy()
    b[:, :8, :3] = (10, 220, 90)
    frames = [a, a, a, b, b, a]
    out = tmp_path / f"x.{ext}"
    assert write_animation(frames, out, fps=10) == 6
    with Image.open(out) as im:
        assert im.n_frames == 6
        for k, f in enumerate(frames):
            im.seek(k)
            assert np.array_equal(np.asarray(im.convert("RGB")), f[..., :3]), k
            assert im.info["duration"] == 100


def test_an_odd_sized_mp4_is_refused_before_any_frame(tmp_path):
    start = time.perf_counter()
    r = glshade("animate", "primitive:cube", "-o", str(tmp_path / "x.mp4"), "--frames", "200",
                "--size", "255x255")
    assert r.returncode == 2, r.stderr
    assert r.stderr.strip().splitlines() == [
        f"glshade: error: {tmp_path / 'x.mp4'}: MP4 (H.264) needs an even width and height, "
        "and the frames would be 255x255; make the size even (e.g. --size 256x256, or a "
        ".gif / .png output)"]
    assert list(tmp_path.iterdir()) == [] and time.perf_counter() - start < 30
    ok = glshade("animate", "primitive:cube", "-o", str(tmp_path / "y.mp4"), "--frames", "3",
                 "--size", "64x48")
    assert ok.returncode == 0, ok.stderr


def test_ctrl_c_while_writing_an_mp4_ends_promptly(tmp_path, spawn):
    """Interrupting an MP4 in the making ends the run (status 130, one line, no file) and
    never waits on the encoder: ffmpeg is killed, not asked to finish."""
    out = tmp_path / "long.mp4"
    for delay in (0.8, 1.6):
        proc = spawn([sys.executable, "-m", "glshade", "animate",
                                 "assets/scenes/teapot-orbit.toml", "-o", str(out), "--frames",
                                 "5000", "--size", "64x48", "--backend", BACKEND], cwd=ROOT,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        time.sleep(delay)
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=30)
        assert proc.returncode in (130, -signal.SIGINT), err
        assert "Traceback" not in err
        assert list(tmp_path.iterdir()) == []


def test_animate_and_batch_show_progress_by_default_in_a_notebook(monkeypatch, tmp_path):
    """Called as the README shows them (no ``progress``), animate() and batch() show
    tqdm's notebook bar (its widget) in a Jupyter kernel: their default is to show
    progress where a person watches (it was off)."""
    from glshade.batch import BatchSpec, batch
    from glshade.geometry import primitives
    from glshade.io import save_mesh
    from glshade.parallel import progress

    made = []

    class Bar:
        def __init__(self, **kwargs):
            made.append(kwargs)

        def update(self, n=1):
            pass

        def close(self):
            pass

        def set_postfix_str(self, *args, **kwargs):
            pass

    monkeypatch.setattr(progress, "in_notebook", lambda: True)
    monkeypatch.setattr(progress, "_tqdm", lambda notebook: Bar if notebook else None)
    import glshade as api

    scene = Scene()
    scene.add(primitives.cube())
    path = CameraPath([Keyframe.look_at(0, (3, 2, 4), (0, 0, 0)),
                       Keyframe.look_at(1, (-3, 2, 4), (0, 0, 0))])
    assert api.animate(scene, path, 2, output=str(tmp_path / "a.gif"),
                           size=(32, 24), samples=0, backend=BACKEND) == 2
    assert [m["unit"].strip() for m in made] == ["frames"]
    save_mesh(primitives.cube(), tmp_path / "c.obj")
    batch([str(tmp_path / "c.obj")], tmp_path / "out", BatchSpec(size=(32, 32),
                                                                backend=BACKEND))
    assert len(made) == 2


@pytest.mark.parametrize("where", ["--fps", "scene file"])
def test_a_frame_rate_an_animation_cannot_hold_is_refused(tmp_path, where):
    """A subnormal frame rate made the turntable's seconds infinite (a NaN camera and numpy
    warnings); the range is that of a GIF's frame delay, said in one line."""
    scene = tmp_path / "s.toml"
    scene.write_text('[render]\nfps = 1e-320\n[[mesh]]\nsource = "primitive:cube"\n')
    args = (["primitive:cube", "--fps", "1e-320"] if where == "--fps" else [str(scene)])
    out = glshade("animate", *args, "-o", str(tmp_path / "a.gif"), "-q")
    assert out.returncode == 2 and out.stderr.count("\n") == 1, out.stderr
    assert "from 0.01 to 1000" in out.stderr and "warning" not in out.stderr
    assert not (tmp_path / "a.gif").exists()
