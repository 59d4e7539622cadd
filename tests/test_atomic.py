"""Atomic outputs: temporary names say who writes them; a writer killed outright leaves
one behind, and the next writer of the same output removes it (never a live writer's)."""

import os
import signal
import subprocess
import sys
import time

import pytest

from glshade.atomic import HOST, atomic_write, remove_stale

from .conftest import BACKEND, ROOT


def _dead_pid() -> int:
    p = subprocess.Popen([sys.executable, "-c", "pass"])
    p.wait()
    return p.pid


def test_the_next_writer_removes_a_dead_writers_temporary(tmp_path):
    stale = tmp_path / f".out.gif.{HOST}-{_dead_pid()}.k2j4h1.part"
    other_output = tmp_path / f".other.gif.{HOST}-{_dead_pid()}.k2j4h1.part"
    live = tmp_path / f".out.gif.{HOST}-{os.getppid()}.k2j4h1.part"
    other_host = tmp_path / ".out.gif.elsewhere-1.k2j4h1.part"
    for p in (stale, other_output, live, other_host):
        p.write_bytes(b"half")
    with atomic_write(tmp_path / "out.gif") as f:
        f.write(b"GIF89a")
    assert (tmp_path / "out.gif").read_bytes() == b"GIF89a"
    assert not stale.exists()
    assert other_output.exists() and live.exists() and other_host.exists()
    assert remove_stale(tmp_path) == 1 and not other_output.exists()


@pytest.mark.gl
def test_sigkill_mid_animation_then_rerun_leaves_no_temporary(tmp_path, spawn):
    """A folder of frames is written under a temporary name; SIGKILL leaves it, the next
    run of the same output removes it."""
    out = tmp_path / "frames"
    cmd = [sys.executable, "-m", "glshade", "animate", "assets/scenes/teapot-orbit.toml",
           "-o", f"{out}/", "--size", "64x48", "--jobs", "1", "--backend", BACKEND, "-q"]
    proc = spawn([*cmd, "--frames", "5000"], cwd=ROOT)
    deadline = time.time() + 60
    while not any(p.is_dir() and any(p.iterdir()) for p in tmp_path.iterdir()):
        assert proc.poll() is None and time.time() < deadline
        time.sleep(0.05)
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    [left] = list(tmp_path.iterdir())
    assert left.name.startswith(f".frames.{HOST}-{proc.pid}.") and ".part" in left.name
    assert subprocess.run([*cmd, "--frames", "2"], cwd=ROOT).returncode == 0
    assert [p.name for p in tmp_path.iterdir()] == ["frames"]
    assert len(list(out.iterdir())) == 2


def test_writing_many_files_into_one_folder_looks_for_stale_ones_once(tmp_path,
                                                                     monkeypatch):
    """A data set writes tens of thousands of files into one folder: looking there for a
    dead writer's temporaries before every file made the writing quadratic. One look a
    folder -- and a stale temporary found then is still removed by its output's writer."""
    stale = tmp_path / f".late.png.{HOST}-{_dead_pid()}.k2j4h1.part"
    stale.write_bytes(b"half")
    looks = []
    scandir = os.scandir
    monkeypatch.setattr(os, "scandir", lambda p=".": looks.append(os.fspath(p)) or scandir(p))
    for k in range(40):
        with atomic_write(tmp_path / f"{k:03d}.png") as f:
            f.write(b"png")
    assert looks.count(os.fspath(tmp_path)) == 1
    assert stale.exists()  # (another output's: left to its writer)
    with atomic_write(tmp_path / "late.png") as f:
        f.write(b"png")
    assert not stale.exists() and looks.count(os.fspath(tmp_path)) == 1
    assert len(list(tmp_path.iterdir())) == 41
