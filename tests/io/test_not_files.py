"""Inputs must be regular files: a link to /dev/zero, a FIFO or a directory given as a
mesh, a scene file or a patch file is refused in one line before anything is read (reading
one would hang or never end), with exit status 2 and nothing written."""

import os

import pytest

from tests.conftest import glshade


@pytest.fixture(params=["zero", "fifo", "dir"])
def not_a_file(request, tmp_path):
    def make(name):
        path = tmp_path / name
        if request.param == "zero":
            os.symlink("/dev/zero", path)
        elif request.param == "fifo":
            os.mkfifo(path)
        else:
            path.mkdir()
        return path
    return make


@pytest.mark.parametrize("name", ["model.obj", "scene.toml", "pot.bpt"])
def test_info_and_render_refuse_what_is_not_a_file(not_a_file, name, tmp_path):
    path = not_a_file(name)
    for args in (["info", str(path)], ["render", str(path), "-o", str(tmp_path / "o.png")]):
        out = glshade(*args, timeout=30)
        assert out.returncode == 2, (args, out.stderr)
        assert out.stderr.count("\n") == 1 and str(path) in out.stderr, out.stderr
        assert "Traceback" not in out.stderr
    assert not (tmp_path / "o.png").exists()
