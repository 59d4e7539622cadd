"""EGL devices: ``glshade doctor`` lists each (index, vendor, renderer, from a context made
on it); ``--device`` and ``GLSHADE_EGL_DEVICE`` take an index or a part of a name; one that
is not there is one line naming those present, exit 2, nothing written."""

import os

import numpy as np
import pytest
from PIL import Image

from tests.conftest import glshade

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
    assert f"EGL devices ({egl_device_count()};" in out.stdout
    for d in devices:
        assert f"  {d['index']:<3} {d['vendor']} | {d['renderer']}" in out.stdout


def test_a_device_by_index_or_name_renders_the_same_picture(devices, tmp_path):
    name = devices[0]["renderer"].split()[0]          # e.g. "llvmpipe"
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
    assert devices[0]["renderer"] in out.stderr and not path.exists()
    env = {**os.environ, "GLSHADE_EGL_DEVICE": how[1]}
    out = glshade("render", "primitive:cube", "-o", str(path), env=env)
    assert out.returncode == 2 and f"GLSHADE_EGL_DEVICE: {words}" in out.stderr
    assert not path.exists()
