"""glshade batch: outputs against independent renders, the manifest, resuming, and the same
bytes whether the work runs here, in local processes or on a real Dask cluster."""

import csv
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from glshade.batch import BatchSpec, batch, find_inputs, plan
from glshade.batch.manifest import read_manifest, write_manifest
from glshade.batch.worker import Row, view_directions, write_npz
from glshade.errors import UsageError
from glshade.geometry import primitives
from glshade.io.meshes import save_mesh
from glshade.modes import Outputs

from ..conftest import BACKEND, ROOT, glshade

pytestmark = pytest.mark.gl  # they render (in subprocesses, workers and clusters)


def make_collection(folder: Path, extra: int = 0) -> Path:
    """A small tree of meshes in several formats, one of them malformed."""
    (folder / "parts").mkdir(parents=True)
    save_mesh(primitives.icosphere(2), folder / "ball.obj")
    save_mesh(primitives.cube(), folder / "parts" / "cube.ply")
    save_mesh(primitives.torus(), folder / "parts" / "torus.stl")
    save_mesh(primitives.cylinder(), folder / "parts" / "cube.off")  # same stem as cube.ply
    (folder / "parts" / "broken.obj").write_text("v 0 0 0\nv 1 0 0\nf 1 2 9\n")
    for i in range(extra):
        save_mesh(primitives.uv_sphere(12 + i, 24), folder / f"sphere{i:02d}.obj")
    return folder


def tree(folder: Path) -> dict:
    """Every output file under ``folder`` (not the manifest) -> its bytes."""
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file() and p.name != "manifest.csv"}


def manifest(folder: Path) -> list[dict]:
    with open(folder / "manifest.csv", newline="") as f:
        return list(csv.DictReader(f))


def parts(folder: Path) -> list[Path]:
    return [p for p in folder.rglob("*") if ".part" in p.name]


def test_plan_mirrors_the_tree_and_separates_clashing_stems(tmp_path):
    src = make_collection(tmp_path / "in")
    files = find_inputs([str(src)])
    assert [f.relative_to(src).as_posix() for f in files] == [
        "ball.obj", "parts/broken.obj", "parts/cube.off", "parts/cube.ply", "parts/torus.stl"]
    tasks = plan(files, tmp_path / "out", ("flat", "phong"), Outputs.COLOR | Outputs.DEPTH, 2)
    out = (tmp_path / "out").resolve()
    names = [[Path(p).relative_to(out).as_posix() for p in t.outputs] for t in tasks]
    assert names[0] == ["ball.v00.flat.png", "ball.v00.phong.png", "ball.v01.flat.png",
                        "ball.v01.phong.png", "ball.v00.npz", "ball.v01.npz"]
    assert names[2][0] == "parts/cube_off.v00.flat.png"
    assert names[3][0] == "parts/cube_ply.v00.flat.png"
    one = plan(files[:1], tmp_path / "out", ("phong",), Outputs.COLOR, 1)
    assert [Path(p).name for p in one[0].outputs] == ["ball.phong.png"]


def test_inputs_by_glob_and_clear_errors(tmp_path):
    src = make_collection(tmp_path / "in")
    hits = find_inputs([str(src / "**" / "*.stl"), str(src / "ball.obj"), str(src / "ball.obj")])
    assert [h.name for h in hits] == ["torus.stl", "ball.obj"]  # each once
    with pytest.raises(UsageError, match="nothing.obj: no such file"):
        find_inputs([str(src / "nothing.obj")])
    with pytest.raises(UsageError, match="matches no files"):
        find_inputs([str(src / "*.xyz")])
    (tmp_path / "empty").mkdir()
    with pytest.raises(UsageError, match="no mesh files there"):
        find_inputs([str(tmp_path / "empty")])


def test_view_zero_is_the_render_commands_picture_and_views_turn_about_up(tmp_path):
    """Oracle: ``glshade render`` of the same file (its own auto-framed camera)."""
    src = tmp_path / "m.obj"
    save_mesh(primitives.box((2.0, 1.0, 0.5)), src)  # a quarter turn shows another side
    result = batch([str(src)], tmp_path / "out", BatchSpec(size=(96, 72), views=4,
                                                            backend=BACKEND))
    assert result.count("ok") == 1
    r = glshade("render", str(src), "--size", "96x72", "-o", str(tmp_path / "one.png"),
                "--backend", BACKEND)
    assert r.returncode == 0, r.stderr
    view0 = np.asarray(Image.open(tmp_path / "out" / "m.v00.phong.png"))
    assert np.array_equal(view0, np.asarray(Image.open(tmp_path / "one.png")))
    d = view_directions(4)
    assert np.allclose(d[:, 1], d[0, 1])  # the same height
    assert np.allclose(np.linalg.norm(d[:, [0, 2]], axis=1), np.linalg.norm(d[0, [0, 2]]))
    cos = d[:, [0, 2]] @ d[0, [0, 2]] / np.linalg.norm(d[0, [0, 2]]) ** 2
    assert np.allclose(cos, [1, 0, -1, 0], atol=1e-12)  # quarter turns
    imgs = [np.asarray(Image.open(tmp_path / "out" / f"m.v{k:02d}.phong.png"))
            for k in range(4)]
    assert not np.array_equal(imgs[0], imgs[1])


def test_arrays_are_the_renderers_frame(tmp_path, make_renderer):
    from glshade import Camera, Scene, default_camera

    src = tmp_path / "cube.ply"
    save_mesh(primitives.cube(), src)
    spec = BatchSpec(size=(64, 64), outputs=Outputs.ALL, backend=BACKEND)
    batch([str(src)], tmp_path / "out", spec)
    data = np.load(tmp_path / "out" / "cube.npz")
    assert sorted(data.files) == ["depth", "face_id", "normal"]
    scene = Scene()
    scene.add(primitives.cube())
    camera = default_camera(scene.bounds)
    assert isinstance(camera, Camera)
    renderer = make_renderer(64, 64, samples=4)  # as the batch's
    frame = renderer.render_frame(scene, camera, outputs=Outputs.ALL)
    assert np.array_equal(data["face_id"], frame.face_id)
    assert np.array_equal(data["depth"], frame.depth)
    assert np.array_equal(data["normal"], frame.normal)
    assert len(np.unique(frame.face_id)) == 4  # background and three faces of the cube


def test_npz_is_reproducible_byte_for_byte(tmp_path):
    a = {"depth": np.arange(12, dtype=np.float32).reshape(3, 4)}
    write_npz(tmp_path / "a.npz", a)
    time.sleep(1.1)  # numpy's own savez would stamp a new time
    write_npz(tmp_path / "b.npz", a)
    assert (tmp_path / "a.npz").read_bytes() == (tmp_path / "b.npz").read_bytes()
    assert np.array_equal(np.load(tmp_path / "a.npz")["depth"], a["depth"])


def test_manifest_round_trip_with_commas_and_quotes(tmp_path):
    out = tmp_path / "o"
    out.mkdir()
    rows = [Row("/x/a,b.obj", "ok", 12, 0.5, (str(out / "a.png"),), "", "llvmpipe (LLVM 15)"),
            Row('/x/"q".obj', "error", message='line 3: bad "f", really')]
    write_manifest(rows, out / "manifest.csv")
    back = read_manifest(out / "manifest.csv")
    assert back["/x/a,b.obj"] == Row("/x/a,b.obj", "ok", 12, 0.5, (str(out / "a.png"),), "",
                                     "llvmpipe (LLVM 15)")
    assert back['/x/"q".obj'].message == 'line 3: bad "f", really'
    assert (out / "manifest.csv").read_text().splitlines()[1].endswith(
        ",a.png,,llvmpipe (LLVM 15)")
    # (a manifest from before the renderer column still lends its rows)
    old = "input,status,polygons,seconds,outputs,message\n/x/b.obj,ok,3,0.1,b.png,\n"
    (out / "manifest.csv").write_text(old)
    assert read_manifest(out / "manifest.csv")["/x/b.obj"].polygons == 3


def test_cli_lists_the_malformed_file_and_goes_on(tmp_path):
    src = make_collection(tmp_path / "in")
    r = glshade("batch", str(src), "-o", str(tmp_path / "out"), "--size", "48x48",
                "--jobs", "1", "--backend", BACKEND)
    assert r.returncode == 2, r.stderr  # done, but not everything rendered
    assert "Traceback" not in r.stderr
    assert "broken.obj:3: face index 9 is out of range" in r.stderr
    rows = {Path(m["input"]).name: m for m in manifest(tmp_path / "out")}
    assert rows["broken.obj"]["status"] == "error"
    assert "face index 9 is out of range" in rows["broken.obj"]["message"]
    assert {rows[n]["status"] for n in ("ball.obj", "cube.ply", "cube.off", "torus.stl")} == \
        {"ok"}
    assert rows["cube.ply"]["polygons"] == "6"
    assert "llvmpipe" in rows["cube.ply"]["renderer"]   # (what drew it: this machine's GL)
    assert rows["broken.obj"]["renderer"] == ""
    for n in ("ball.obj", "cube.ply"):
        for o in rows[n]["outputs"].split(";"):
            assert (tmp_path / "out" / o).is_file()


def test_cli_errors_are_one_line(tmp_path):
    r = glshade("batch", str(tmp_path / "none"), "-o", str(tmp_path / "out"))
    assert r.returncode == 2 and r.stderr.strip().count("\n") == 0, r.stderr
    assert "none: no such file or folder" in r.stderr
    r = glshade("batch", "x.obj", "-o", str(tmp_path), "--scheduler", "localhost")
    assert r.returncode == 2 and "tcp://10.0.0.5:8786" in r.stderr
    r = glshade("batch", "x.obj", "-o", str(tmp_path), "--outputs", "depth,colour")
    assert r.returncode == 2 and "unknown output 'colour'" in r.stderr
    r = glshade("batch", "x.obj", "-o", str(tmp_path), "--eye", "1,2,3")
    assert r.returncode == 2 and "--views" in r.stderr


def test_without_the_extra_scheduler_says_how_to_install(tmp_path):
    code = ("import sys; sys.modules['distributed'] = None\n"
            "from glshade.cli import main\n"
            f"sys.exit(main(['batch', {str(tmp_path)!r}, '-o', {str(tmp_path / 'o')!r}, "
            "'--scheduler', 'local']))")
    save_mesh(primitives.cube(), tmp_path / "c.obj")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 1, r.stderr
    assert "pip install 'glshade[distributed]'" in r.stderr and "Traceback" not in r.stderr


def _start(spawn, args, **kwargs):
    return spawn([sys.executable, "-m", "glshade", "batch", *args], cwd=ROOT,
                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kwargs)


def _wait_for_outputs(folder: Path, n: int, proc, timeout=120):
    deadline = time.time() + timeout
    while len(list(folder.rglob("*.png"))) < n:
        assert proc.poll() is None, proc.communicate()
        assert time.time() < deadline
        time.sleep(0.05)


@pytest.mark.once
def test_interrupted_run_resumes_with_only_the_missing_outputs(tmp_path, spawn):
    src = make_collection(tmp_path / "in", extra=12)
    args = [str(src), "--size", "160x120", "--views", "2", "--modes", "flat,phong",
            "--backend", BACKEND]
    full = glshade("batch", *args, "-o", str(tmp_path / "full"), "--jobs", "1", "-q")
    assert full.returncode == 2, full.stderr
    expected = tree(tmp_path / "full")

    out = tmp_path / "out"
    proc = _start(spawn, [*args, "-o", str(out), "--jobs", "2"])
    _wait_for_outputs(out, 12, proc)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130, err
    assert err.strip().splitlines()[-1] == "glshade: interrupted", err
    assert parts(out) == []  # no temporary file left
    first = manifest(out)
    done = [m for m in first if m["status"] == "ok"]
    finished = [t.input for t in plan(find_inputs([str(src)]), out, ("flat", "phong"),
                                      Outputs.COLOR, 2) if t.done()]
    assert [m["input"] for m in done] == finished  # the manifest says what exists
    assert 0 < len(done) < 16 and any(m["status"] == "not run" for m in first)
    got = tree(out)
    assert all(expected[k] == v for k, v in got.items())  # whatever exists is whole

    again = glshade("batch", *args, "-o", str(out), "--jobs", "2")
    assert again.returncode == 2, again.stderr
    second = {m["input"]: m["status"] for m in manifest(out)}
    assert [second[m["input"]] for m in done] == ["exists"] * len(done)
    assert sum(s == "ok" for s in second.values()) == 16 - len(done)
    assert tree(out) == expected
    rerun = glshade("batch", *args, "-o", str(out), "--jobs", "2", "--overwrite", "-q")
    assert {m["status"] for m in manifest(out)} == {"ok", "error"}, rerun.stderr


def test_stale_temporaries_of_a_killed_run_are_removed(tmp_path):
    from glshade.atomic import HOST

    out = tmp_path / "out"
    (out / "sub").mkdir(parents=True)
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    stale = out / "sub" / f".x.phong.png.{HOST}-{dead.pid}.abc123.part"
    live = out / f".y.phong.png.{HOST}-{os.getppid()}.abc123.part"
    stale.write_bytes(b"half")
    live.write_bytes(b"in use")
    src = tmp_path / "c.obj"
    save_mesh(primitives.cube(), src)
    batch([str(src)], out, BatchSpec(size=(32, 32), backend=BACKEND))
    assert not stale.exists() and live.exists()


def test_the_same_bytes_on_a_dask_cluster(tmp_path, dask_cluster):
    src = make_collection(tmp_path / "in")
    args = [str(src), "--size", "64x48", "--views", "2", "--outputs", "depth,normal,face_id",
            "--modes", "gouraud,phong", "--backend", BACKEND, "-q"]
    local = glshade("batch", *args, "-o", str(tmp_path / "local"), "--jobs", "1")
    remote = glshade("batch", *args, "-o", str(tmp_path / "dask"), "--scheduler",
                     dask_cluster.address)
    assert local.returncode == remote.returncode == 2, remote.stderr
    assert tree(tmp_path / "dask") == tree(tmp_path / "local") != {}
    rows = {Path(m["input"]).name: m for m in manifest(tmp_path / "dask")}
    assert rows["broken.obj"]["status"] == "error"
    assert "face index 9 is out of range" in rows["broken.obj"]["message"]
    assert [m["input"] for m in manifest(tmp_path / "dask")] == \
        [m["input"] for m in manifest(tmp_path / "local")]


@pytest.mark.once
def test_a_worker_killed_mid_run_loses_nothing(tmp_path, dask_cluster, spawn):
    src = make_collection(tmp_path / "in", extra=16)
    args = [str(src), "--size", "200x150", "--views", "3", "--backend", BACKEND, "-q"]
    reference = glshade("batch", *args, "-o", str(tmp_path / "ref"), "--jobs", "2")
    assert reference.returncode == 2, reference.stderr
    victim = dask_cluster.start_worker()
    dask_cluster.wait_for(3)
    from distributed import Client

    out = tmp_path / "out"
    with Client(dask_cluster.address, timeout="30s") as client:
        [address] = [a for a, pid in client.run(os.getpid).items() if pid == victim.pid]
        proc = _start(spawn, [*args, "-o", str(out), "--scheduler", dask_cluster.address])
        deadline = time.time() + 120
        while not client.processing().get(address):  # kill it while it works on a mesh
            assert proc.poll() is None and time.time() < deadline, proc.communicate()
            time.sleep(0.02)
        victim.kill()
    victim.wait()
    _, err = proc.communicate(timeout=300)
    assert proc.returncode == 2, err
    assert {m["status"] for m in manifest(out)} == {"ok", "error"}
    assert tree(out) == tree(tmp_path / "ref")
    assert parts(out) == []


@pytest.mark.once
def test_ctrl_c_on_a_cluster_waits_for_running_tasks_and_accounts_for_them(tmp_path,
                                                                          dask_cluster,
                                                                          spawn):
    """After Ctrl-C the tasks a worker already runs cannot be stopped: glshade waits for
    them before writing the manifest (and says so), so no output appears after it exits
    and every input whose outputs exist is 'ok' in the manifest."""
    src = make_collection(tmp_path / "in", extra=14)
    out = tmp_path / "out"
    proc = _start(spawn, [str(src), "-o", str(out), "--size", "320x240", "--views", "3", "--modes",
                   "flat,phong", "--scheduler", dask_cluster.address, "--backend", BACKEND])
    _wait_for_outputs(out, 6, proc)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=180)
    assert proc.returncode == 130, err
    at_exit = tree(out)
    time.sleep(3.0)  # (were a task still running, its outputs would appear now)
    assert tree(out) == at_exit
    rows = manifest(out)
    finished = {t.input for t in plan(find_inputs([str(src)]), out, ("flat", "phong"),
                                      Outputs.COLOR, 3) if t.done()}
    assert {m["input"] for m in rows if m["status"] == "ok"} == finished
    assert any(m["status"] == "not run" for m in rows)
    assert parts(out) == []


@pytest.mark.once
def test_a_scheduler_that_never_answers_is_given_up_on_in_one_line(tmp_path, dask_cluster):
    """A real scheduler, stopped (SIGSTOP): it accepts the connection and never answers.
    glshade gives up at its deadline with one line and status 1 (it used to hang)."""
    import json

    folder = tmp_path / "sched"
    folder.mkdir()
    file = folder / "scheduler.json"
    dask = str(Path(sys.executable).with_name("dask"))
    sched = subprocess.Popen([dask, "scheduler", "--host", "127.0.0.1", "--port", "0",
                              "--no-dashboard", "--scheduler-file", str(file)], cwd=folder,
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.time() + 60
        while not file.exists() or not file.read_text().strip():
            assert time.time() < deadline and sched.poll() is None
            time.sleep(0.1)
        address = json.loads(file.read_text())["address"]
        os.kill(sched.pid, signal.SIGSTOP)
        src = make_collection(tmp_path / "in")
        start = time.time()
        r = subprocess.run([sys.executable, "-m", "glshade", "batch", str(src), "-o",
                            str(tmp_path / "out"), "--scheduler", address],
                           capture_output=True, text=True, cwd=ROOT, timeout=120,
                           env={**os.environ, "GLSHADE_SCHEDULER_TIMEOUT": "4"})
        assert r.returncode == 1, r.stderr
        assert r.stderr.strip().splitlines() == [
            f"glshade: error: the Dask scheduler at {address} did not answer within 4 s "
            "(stopped, wedged or overloaded?); GLSHADE_SCHEDULER_TIMEOUT sets the wait"]
        assert time.time() - start < 60
    finally:
        os.kill(sched.pid, signal.SIGCONT)
        sched.kill()
        sched.wait(timeout=30)


@pytest.mark.parametrize("fault", ["deleted", "truncated", "npz_truncated"])
def test_a_rerun_makes_again_what_is_gone_or_torn(tmp_path, fault):
    """A rerun keeps the outputs that are whole and makes again one deleted or cut short
    since (a PNG without its end, an .npz without its directory): the folder is then what
    a fresh run writes."""
    src = make_collection(tmp_path / "in", extra=0)
    args = [str(src), "--size", "64x48", "--modes", "phong", "--outputs", "color,depth",
            "--backend", BACKEND, "-q"]
    assert glshade("batch", *args, "-o", str(tmp_path / "fresh")).returncode in (0, 2)
    out = tmp_path / "out"
    assert glshade("batch", *args, "-o", str(out)).returncode in (0, 2)
    expected = tree(tmp_path / "fresh")
    pngs = sorted(out.rglob("*.png"))
    victim = pngs[0] if fault != "npz_truncated" else sorted(out.rglob("*.npz"))[0]
    if fault == "deleted":
        victim.unlink()
    else:
        victim.write_bytes(victim.read_bytes()[:-20])
    assert glshade("batch", *args, "-o", str(out)).returncode in (0, 2)
    rows = {m["input"]: m["status"] for m in manifest(out)}
    assert sum(s == "ok" for s in rows.values()) == 1  # (the one input whose output was torn)
    assert tree(out) == expected


def test_a_scheduler_address_where_nothing_listens_is_said_at_once(tmp_path):
    """Nothing listening at the address (a port just freed): one line within seconds,
    status 1 -- Dask's Client would retry the refused connection for its whole timeout."""
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    src = make_collection(tmp_path / "in")
    start = time.time()
    r = glshade("batch", str(src), "-o", str(tmp_path / "out"), "--scheduler",
                f"tcp://127.0.0.1:{port}")
    assert time.time() - start < 10
    assert r.returncode == 1, r.stderr
    (line,) = r.stderr.strip().splitlines()
    assert line.startswith(f"glshade: error: no Dask scheduler answers at tcp://127.0.0.1:{port}")
    assert not (tmp_path / "out").exists()
