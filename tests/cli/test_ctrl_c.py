"""Ctrl-C at any moment of a command -- while Python imports, while the GL context is made
and the shaders compile, during the work, while the image is written, while the interpreter
shuts down -- ends well: status 0 (it had finished) or 130, at most one line on stderr, no
traceback, no core dump, and nothing half-written (no temporary file; an output only if
the run finished, or the path tracer's picture so far, which it says it kept). (A Ctrl-C
that lands while the interpreter itself starts, before any of glshade runs, is Python's.)
What this caught: a Ctrl-C inside numpy's import surfaced as numpy's ImportError, a
traceback and status 1."""

import signal
import subprocess
import sys
import time

import pytest

from tests.conftest import BACKEND, ROOT

pytestmark = [pytest.mark.gl, pytest.mark.once]

COMMANDS = {
    "render": ["render", "primitive:teapot", "--size", "96x72"],
    "pathtrace": ["pathtrace", "assets/scenes/cornell-box.toml", "--spp", "64", "--size",
                  "64x64", "-q"],
    "compare": ["compare", "primitive:icosphere:2", "--size", "64x64"],
    "hidden": ["hidden", "primitive:teapot", "--algorithm", "bsp", "--size", "64x48"],
}
DELAYS = [0.05, 0.15, 0.3, 0.45, 0.6, 0.8, 1.1, 1.5]


@pytest.mark.parametrize("delay", DELAYS)
@pytest.mark.parametrize("command", list(COMMANDS))
def test_ctrl_c_at_any_moment_ends_well(command, delay, tmp_path, spawn):
    out = tmp_path / "out.png"
    proc = spawn([sys.executable, "-m", "glshade", *COMMANDS[command], "-o", str(out),
                  "--backend", BACKEND], cwd=ROOT, text=True, stdout=subprocess.PIPE,
                 stderr=subprocess.PIPE)
    time.sleep(delay)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    lines = err.strip().splitlines()
    if proc.returncode in (1, -signal.SIGINT) and lines[-1:] == ["KeyboardInterrupt"] and \
            "glshade" not in err:
        return  # (it landed while the interpreter itself started: before any of glshade)
    assert proc.returncode in (0, 130), (proc.returncode, err)
    assert len(lines) <= 1 and "Traceback" not in err, err
    left = sorted(p.name for p in tmp_path.iterdir())
    assert not [n for n in left if n != "out.png"], left  # (no temporary file)
    if proc.returncode == 130 and left:
        assert "the image so far is in" in err, (left, err)
    if proc.returncode == 0:
        assert left == ["out.png"]
    assert not any(p.name.startswith("core") for p in ROOT.iterdir())
