"""EGL devices: ``glshade doctor`` lists each without making a context on any (what the
driver says of it: name, software or GPU, CUDA ordinal, DRM node) and marks the one a
render takes and why; ``--device`` and ``GLSHADE_EGL_DEVICE`` take an index, ``cuda:N``
(through CUDA_VISIBLE_DEVICES) or a part of a name; one that is not there is one line
naming those present, exit 2, nothing written; ``GLCONTEXT_DEVICE_INDEX`` disagreeing is
told and overruled; a GPU required where only llvmpipe answers is refused."""

import os
import subprocess

import numpy as np
import pytest
from PIL import Image

from tests.conftest import ROOT, glshade

from glshade.errors import OptionError
from glshade.render.context import egl_device_count, device_index, egl_devices

pytestmark = [pytest.mark.gl, pytest.mark.once]


@pytest.fixture(scope="module")
def devices():
    found = egl_devices()
    if not found:
        if os.environ.get("CI"):
            pytest.fail("no EGL device listed in CI", pytrace=False)
        pytest.skip("no EGL device here")
    return found


def test_doctor_lists_every_egl_device(devices):
    out = glshade("doctor")
    assert out.returncode == 0, out.stderr
    assert f"EGL devices ({egl_device_count()}, listed without a context" in out.stdout
    for d in devices:
        assert f"{d['index']:<3} {d['name']} (" in out.stdout
    assert " *0 " in out.stdout and "a render takes: 0 (the driver's first)" in out.stdout
    gpus = [d for d in devices if not d["software"]]
    if len(gpus) < 2:
        assert "workers take: what a render takes (no several GPUs here" in out.stdout
    dealt = glshade("doctor", env={**os.environ, "GLSHADE_WORKER_DEVICES": "0,llvmpipe"})
    assert "--jobs and --scheduler workers take: 0, llvmpipe in turn" in dealt.stdout


def test_listing_devices_makes_no_context(monkeypatch):
    """Every context glshade makes goes through moderngl.create_context: counted, none."""
    import moderngl

    made = []
    real = moderngl.create_context
    monkeypatch.setattr(moderngl, "create_context",
                        lambda *a, **k: made.append(k) or real(*a, **k))
    listed = egl_devices()
    assert len(listed) == egl_device_count() >= 1 and made == []
    software = [d for d in listed if d["software"]]
    assert software and "llvmpipe" in software[0]["name"]   # (Mesa's device, this machine)


@pytest.mark.parametrize("spec, visible, words", [
    ("cuda:0", None, r"cuda:0 \(CUDA device 0\) is no EGL device here.*present: 0: "),
    ("cuda:1", "3,5", r"cuda:1 \(CUDA device 5\) is no EGL device here"),
    ("cuda:2", "3,5", "cuda:2 does not exist: CUDA_VISIBLE_DEVICES='3,5' shows 2 devices"),
    ("cuda:0", "GPU-6f1c2d", "names devices by UUID"),
])
def test_cuda_ordinals_go_through_cuda_visible_devices(monkeypatch, spec, visible, words):
    """``cuda:N`` is the N-th device CUDA shows (CUDA_VISIBLE_DEVICES), matched to the EGL
    device that says it is that CUDA device; on this machine none is, which is said in one
    line with the devices present."""
    if visible is None:
        monkeypatch.delenv("CUDA_VISIBLE_DEVICES", raising=False)
    else:
        monkeypatch.setenv("CUDA_VISIBLE_DEVICES", visible)
    with pytest.raises(OptionError, match=words):
        device_index(spec)


def test_glcontext_device_index_disagreeing_is_told_and_overruled(devices, tmp_path):
    """glcontext takes GLCONTEXT_DEVICE_INDEX over the index a program gives it: with it
    naming a device that does not exist, ``--device 0`` still renders (glshade sets it to
    its own choice for its context) and says so in one warning; doctor notes it."""
    env = {**os.environ, "GLCONTEXT_DEVICE_INDEX": "7"}
    path = tmp_path / "cube.png"
    out = glshade("render", "primitive:cube", "-o", str(path), "--size", "32x24",
                  "--backend", "egl", "--device", "0", env=env)
    assert out.returncode == 0, out.stderr
    assert "GLCONTEXT_DEVICE_INDEX=7 is set and disagrees" in out.stderr and path.exists()
    doctor = glshade("doctor", env=env)
    assert "a render takes: 7 (GLCONTEXT_DEVICE_INDEX" in doctor.stdout
    assert "there is no device 7" in doctor.stdout


def test_a_device_by_index_or_name_renders_the_same_picture(devices, tmp_path):
    name = devices[0]["name"].split()[-1].strip("()")   # e.g. "llvmpipe"
    assert device_index(name) == device_index("0") == 0
    paths = []
    for how in (["--device", "0"], ["--device", name.upper()]):
        path = tmp_path / f"cube{len(paths)}.png"
        out = glshade("render", "primitive:cube", "-o", str(path), "--size", "64x48",
                      "--backend", "egl", *how)
        assert out.returncode == 0, out.stderr
        paths.append(path)
    env = {**os.environ, "GLSHADE_EGL_DEVICE": name}
    path = tmp_path / "env.png"
    assert glshade("render", "primitive:cube", "-o", str(path), "--size", "64x48",
                   "--backend", "egl", env=env).returncode == 0
    images = [np.asarray(Image.open(p)) for p in (*paths, path)]
    assert all(np.array_equal(images[0], im) for im in images[1:])


@pytest.mark.parametrize("how, words", [
    (["--device", "99"], "EGL device 99 does not exist; present: 0: "),
    (["--device", "no-such-gpu"], "EGL device 'no-such-gpu' matches none; present: 0: "),
])
def test_a_device_not_there_is_one_line_naming_those_present(devices, tmp_path, how, words):
    path = tmp_path / "x.png"
    out = glshade("render", "primitive:cube", "-o", str(path), *how)
    assert out.returncode == 2 and out.stderr.count("\n") == 1 and words in out.stderr
    assert devices[0]["name"] in out.stderr and not path.exists()
    env = {**os.environ, "GLSHADE_EGL_DEVICE": how[1]}
    out = glshade("render", "primitive:cube", "-o", str(path), env=env)
    assert out.returncode == 2 and f"GLSHADE_EGL_DEVICE: {words}" in out.stderr
    assert not path.exists()


def test_a_gpu_required_refuses_the_software_rasterizer(tmp_path, gl_context):
    """``--require-gpu``, ``GLSHADE_REQUIRE_GPU=1`` and ``Renderer(require_gpu=True)`` on
    llvmpipe: one line naming it and the usual cause, exit 2, nothing written; a caller's
    own context is refused without being released."""
    import glshade as gs

    assert gl_context.software  # (this machine: Mesa's llvmpipe)
    out = tmp_path / "x.png"
    for extra, env in ((["--require-gpu"], {}), ([], {"GLSHADE_REQUIRE_GPU": "1"})):
        r = glshade("render", "primitive:cube", "-o", str(out), *extra,
                    env={**os.environ, **env})
        assert r.returncode == 2, r.stderr
        assert r.stderr.count("\n") == 1 and "llvmpipe" in r.stderr, r.stderr
        assert "a GPU was required" in r.stderr and "glshade doctor" in r.stderr
        assert not out.exists()
    with pytest.raises(gs.NoGpuError, match="software rasterizer .*llvmpipe"):
        gs.Renderer(32, 32, require_gpu=True)
    with pytest.raises(gs.NoGpuError):
        gs.Renderer(32, 32, context=gl_context, require_gpu=True)
    assert not gl_context.released
    with gs.Renderer(32, 32, context=gl_context, require_gpu=False):
        pass


def test_a_software_rasterizer_beside_gpu_device_files_is_told(monkeypatch, tmp_path):
    """Where the machine has GPU device files (stood in for here by files matching the
    patterns) and llvmpipe answers anyway, the fallback is one warning naming both."""
    import glshade as gs
    from glshade.render import context as module

    (tmp_path / "nvidia0").write_text("")
    monkeypatch.setattr(module, "GPU_DEVICE_FILES", (str(tmp_path / "nvidia[0-9]*"),))
    with pytest.warns(gs.RenderWarning, match=r"software rasterizer .*nvidia0"):
        module.create_context("egl").release()


def test_the_device_check_runs_quick(tmp_path):
    """``benchmarks/device_check.py --quick``: its table and JSON, the device named with
    why, and this machine's GL exact against llvmpipe (itself, here)."""
    import json
    import sys

    out = tmp_path / "check.json"
    r = subprocess.run([sys.executable, "benchmarks/device_check.py", "--quick", "--json",
                        str(out)], capture_output=True, text=True, cwd=ROOT, timeout=300)
    assert r.returncode == 0, r.stderr
    found = json.loads(out.read_text())
    assert found["device"]["why"] == "the driver's first" and "llvmpipe" in r.stdout
    assert found["exact_vs_llvmpipe"]["ids_identical"] is True
    assert found["exact_vs_llvmpipe"]["depth_identical"] is True
    assert found["exact_vs_llvmpipe"]["color_max_diff"] <= 1
    assert found["opaque_fps"] > 0 and found["trace_paths_per_s"]["fragment"] > 0
