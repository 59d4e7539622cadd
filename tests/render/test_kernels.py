"""``kernel="auto"``'s measured choice outlives the process that measured it: kept in the
cache file by renderer and version, taken by a later process before its first pass (no
measurement), said by ``glshade doctor``; a broken file only means measuring again."""

import json
import os
import subprocess
import sys

import pytest

from tests.conftest import glshade

pytestmark = pytest.mark.gl

# a tracer's kernel before its first pass (what it took from the cache, or "auto": it will
# measure), then after it
_SCRIPT = """
from glshade.pathtrace import PathTracer
from glshade.radiosity import cornell_scene
scene, camera = cornell_scene()
tracer = PathTracer(scene, (16, 16), kernel="auto")
before = tracer.gpu.kernel.value
tracer.add(camera, 1)
print(before, tracer.gpu.kernel.value)
tracer.close()
"""


def _run(cache) -> list[str]:
    env = dict(os.environ, XDG_CACHE_HOME=str(cache))
    done = subprocess.run([sys.executable, "-c", _SCRIPT], capture_output=True, text=True,
                          env=env, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    return done.stdout.split()


def _without_compute(tmp_path, cache) -> None:
    """A GL without compute shaders (the 4.1 tier): kernel='auto' is the fragment program at
    once -- nothing measured, nothing kept -- and doctor says why."""
    assert _run(cache) == ["fragment", "fragment"]
    assert not (tmp_path / "glshade" / "kernels.json").exists()
    said = glshade("doctor", env=dict(os.environ, XDG_CACHE_HOME=str(cache))).stdout
    assert "fragment (no compute kernels before GL 4.3)" in said, said


def test_the_measured_kernel_is_kept_between_processes(tmp_path, gl_context):
    file = tmp_path / "glshade" / "kernels.json"
    if not gl_context.features.storage:
        return _without_compute(tmp_path, tmp_path)
    before, measured = _run(tmp_path)
    assert before == "auto" and measured in ("fragment", "compute")
    kept = json.loads(file.read_text())
    assert list(kept.values()) == [measured]   # (one GL here: one key, its renderer's)
    # the file's choice is what a later process takes, at once: turned to the other
    # kernel, the other is taken (a measurement would have found the first again)
    other = "compute" if measured == "fragment" else "fragment"
    (key,) = kept
    assert key.startswith(gl_context.ctx.info["GL_RENDERER"])   # (kept by the renderer)
    file.write_text(json.dumps({key: other}))
    assert _run(tmp_path) == [other, other]
    said = glshade("doctor", env=dict(os.environ, XDG_CACHE_HOME=str(tmp_path))).stdout
    assert f"path tracer kernel {other} (measured faster here before; kept in {file})" \
        in said, said
    # a broken file: measured again, and written whole
    file.write_text("{not json")
    before, measured = _run(tmp_path)
    assert before == "auto" and json.loads(file.read_text()) == {key: measured}


def test_an_unwritable_cache_only_means_measuring_again(tmp_path, gl_context):
    blocker = tmp_path / "blocked"
    blocker.write_text("a file where the cache's folder would go")
    if not gl_context.features.storage:
        return _without_compute(tmp_path, blocker)
    said = glshade("doctor", env=dict(os.environ, XDG_CACHE_HOME=str(blocker))).stdout
    assert "path tracer kernel not measured on this GL yet" in said, said
    assert _run(blocker)[0] == "auto"
    assert _run(blocker)[0] == "auto"   # (nothing kept, nothing broken)
