"""Patch files (the classic .bpt format) are inputs like meshes: of render, info, compare,
batch and view (through the one loader), and ``[[patches]]`` tables in scene files; a
file with anything after its last vertex is refused naming the line."""

import re

import numpy as np
import pytest

from tests.conftest import glshade

from glshade.errors import InputError, SceneFormatError
from glshade.io.meshes import load_source
from glshade.io.scenefile import load_scene
from glshade.patches import PatchSurface, teapot
from glshade.patches.files import read_patches, write_patches


@pytest.fixture
def pot(tmp_path):
    path = tmp_path / "pot.bpt"
    path.write_text(write_patches(teapot()))
    return path


def test_a_bpt_file_is_read_back_exactly(pot):
    surface = load_source(str(pot))
    assert isinstance(surface, PatchSurface) and surface.name == "pot"
    assert np.allclose(surface.patches.points, teapot().points, atol=1e-12)


def test_trailing_content_is_refused_naming_the_line(pot):
    lines = pot.read_text().count("\n")
    pot.write_text(pot.read_text() + "\n1, 2, 3\n")
    with pytest.raises(InputError, match=rf"pot.bpt:{lines + 2}: unexpected content"):
        read_patches(pot)
    with pytest.raises(InputError, match="no such file"):
        read_patches(pot.with_name("missing.bpt"))
    with pytest.raises(InputError, match="is a directory"):
        read_patches(pot.parent)


@pytest.mark.gl
def test_the_commands_take_a_patch_file(pot, tmp_path):
    out = glshade("info", str(pot))
    assert out.returncode == 0 and "32 of degree 3x3" in out.stdout, out.stderr
    out = glshade("render", str(pot), "-o", str(tmp_path / "pot.png"), "--size", "64x64")
    assert out.returncode == 0 and (tmp_path / "pot.png").stat().st_size > 0, out.stderr
    out = glshade("batch", str(tmp_path), "-o", str(tmp_path / "thumbs"), "--size", "48x48",
                  "--quiet")
    assert out.returncode == 0, out.stderr
    assert (tmp_path / "thumbs" / "pot.phong.png").stat().st_size > 0
    bad = tmp_path / "bad.bpt"
    bad.write_text(pot.read_text() + "junk\n")
    out = glshade("render", str(bad), "-o", str(tmp_path / "bad.png"))
    assert out.returncode == 2 and out.stderr.count("\n") == 1
    assert "unexpected content" in out.stderr and not (tmp_path / "bad.png").exists()


def test_scene_files_take_patches_tables(pot, tmp_path):
    scene_file = tmp_path / "s.toml"
    scene_file.write_text('[[patches]]\nsource = "pot.bpt"\nlevel = 3\n\n'
                          '[[patches]]\nsource = "patches:sphere"\ntessellation = "gpu"\n'
                          'level = 8\ntranslation = [3.0, 0.0, 0.0]\n')
    loaded = load_scene(scene_file)
    assert loaded.scene.models[0].mesh.n_faces > 0
    assert loaded.scene.patch_models[0].level == 8
    scene_file.write_text('[[patches]]\nsource = "pot.bpt"\nlevel = 0\n')
    with pytest.raises(SceneFormatError, match=r"s.toml:3: \[\[patches\]\] 1 key 'level'"):
        load_scene(scene_file)


@pytest.mark.parametrize("vertex, words", [
    ("1e20", r"pot.bpt: patch \d+: a control point coordinate of 1e\+20 is over the limit"),
    ("nan", r"pot.bpt:\d+: vertex 1 is not finite"),
])
@pytest.mark.parametrize("command", ["render", "info"])
def test_a_hostile_patch_file_is_one_line_naming_file_patch_and_rule(pot, tmp_path, vertex,
                                                                       words, command):
    lines = pot.read_text().splitlines()
    first = int(lines[0]) + 2  # (the first vertex's line, after the count and the patches)
    lines[first] = ",".join([vertex, *lines[first].split(",")[1:]])
    pot.write_text("\n".join(lines) + "\n")
    out_png = tmp_path / "out.png"
    args = [command, str(pot)] + (["-o", str(out_png)] if command == "render" else [])
    out = glshade(*args)
    assert out.returncode == 2 and re.search(words, out.stderr), out.stderr
    assert out.stderr.count("\n") == 1 and "Traceback" not in out.stderr
    assert not out_png.exists()
