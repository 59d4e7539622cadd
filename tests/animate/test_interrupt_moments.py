"""A Ctrl-C can land between any two steps of writing an output. Wherever it lands -- just
after the temporary file is made, just after the encoder process is started, between frames
or while the encoder finishes -- the run ends with KeyboardInterrupt, no file is left (not
even one a forgotten encoder writes later) and no encoder process outlives the call. The
signal is sent to this process at the named moment, as a terminal would."""

import os
import signal
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np
import pytest

from glshade.animate.writers import write_animation

from ..conftest import require

require("imageio_ffmpeg", "the video extra is part of the test extra")


def _frames(n, interrupt_at=None):
    for k in range(n):
        if k == interrupt_at:
            os.kill(os.getpid(), signal.SIGINT)
        yield np.full((48, 64, 4), 40 * k % 256, np.uint8)


def _children() -> list[str]:
    """Processes whose parent is this one, alive or not yet reaped."""
    me, found = str(os.getpid()), []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
        except OSError:
            continue
        if fields[1] == me:
            found.append(stat.parent.name)
    return found


def _after(tmp_path, before):
    time.sleep(0.5)  # (an orphaned encoder would write its file by now)
    assert sorted(p.name for p in tmp_path.iterdir()) == []
    assert [c for c in _children() if c not in before] == []


@pytest.mark.parametrize("fmt", ["mp4", "gif", "png", "dir"])
@pytest.mark.parametrize("at", [0, 1, 4])
def test_ctrl_c_between_frames(tmp_path, fmt, at):
    out = tmp_path / ("frames/" if fmt == "dir" else f"a.{fmt}")
    before = _children()
    with pytest.raises(KeyboardInterrupt):
        write_animation(_frames(6, interrupt_at=at), out, fps=10)
    _after(tmp_path, before)


def _signal_after(monkeypatch, owner, name, when=lambda *args: True):
    real = getattr(owner, name)

    def wrapped(*args, **kwargs):
        result = real(*args, **kwargs)
        if when(*args):
            os.kill(os.getpid(), signal.SIGINT)
        return result

    monkeypatch.setattr(owner, name, wrapped)


@pytest.mark.parametrize("fmt", ["mp4", "gif", "dir"])
def test_ctrl_c_just_after_the_temporary_is_made(tmp_path, monkeypatch, fmt):
    before = _children()  # (other tests' servers and workers may be running)
    _signal_after(monkeypatch, tempfile, "mkdtemp" if fmt == "dir" else "mkstemp")
    out = tmp_path / ("frames/" if fmt == "dir" else f"a.{fmt}")
    with pytest.raises(KeyboardInterrupt):
        write_animation(_frames(3), out, fps=10)
    monkeypatch.undo()
    _after(tmp_path, before)


@pytest.mark.parametrize("marker", ["-version", "pipe:0"])
def test_ctrl_c_just_after_ffmpeg_starts(tmp_path, monkeypatch, marker):
    """Finding ffmpeg runs it once (``-version``), then the encoder starts (``pipe:0``);
    each is started and its handle kept as one step, so interrupted there nothing is left:
    the encoder, killed and reaped, cannot write the abandoned temporary file again."""
    import imageio_ffmpeg

    imageio_ffmpeg._utils._get_ffmpeg_exe.cache_clear()  # (found once, then remembered)
    _signal_after(monkeypatch, subprocess, "Popen", when=lambda cmd, *_: marker in cmd)
    before = _children()
    with pytest.raises(KeyboardInterrupt):
        write_animation(_frames(3), tmp_path / "a.mp4", fps=10)
    monkeypatch.undo()
    _after(tmp_path, before)


def test_ctrl_c_while_the_encoder_finishes(tmp_path, monkeypatch):
    real_wait = subprocess.Popen.wait

    def wait(self, *args, **kwargs):
        os.kill(os.getpid(), signal.SIGINT)
        return real_wait(self, *args, **kwargs)

    monkeypatch.setattr(subprocess.Popen, "wait", wait)
    before = _children()
    with pytest.raises(KeyboardInterrupt):
        write_animation(_frames(3), tmp_path / "a.mp4", fps=10)
    monkeypatch.undo()
    _after(tmp_path, before)


def test_a_written_mp4_has_every_frame(tmp_path):
    """(The oracle for the writer itself: imageio reads back what ffmpeg encoded.)"""
    imageio = require("imageio.v2", "imageio is part of the test extra")
    assert write_animation(_frames(7), tmp_path / "a.mp4", fps=10) == 7
    with imageio.get_reader(tmp_path / "a.mp4") as reader:
        frames = list(reader.iter_data())
    assert len(frames) == 7 and frames[0].shape == (48, 64, 3)
    means = [f.mean() for f in frames]
    assert np.allclose(means, [40 * k % 256 for k in range(7)], atol=2)
