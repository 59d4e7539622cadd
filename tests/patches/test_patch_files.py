"""Patch files (the classic .bpt format) are inputs like meshes: of render, info, compare,
batch and view (through the one loader), and ``[[patches]]`` tables in scene files; a
file with anything after its last vertex is refused naming the line."""

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
