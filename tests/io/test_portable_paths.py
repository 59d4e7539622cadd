"""Paths a scene file names are portable: a scene written on Windows, its files named with
backslashes, loads on macOS and Linux (where a backslash is a letter of a name, so taken as a
separator only when no file has the name as written); forward slashes load everywhere."""

import shutil

import glshade
from tests.conftest import ROOT

SCENE = """
[[mesh]]
name = "pot"
source = "{source}"

[[light]]
position = [4.0, 5.0, 6.0]
"""


def _scene(folder, source):
    (folder / "models").mkdir(exist_ok=True)
    shutil.copy(ROOT / "assets" / "lprism.obj", folder / "models" / "prism.obj")
    file = folder / "scene.toml"
    file.write_text(SCENE.format(source=source.replace("\\", "\\\\")), encoding="utf-8")
    return glshade.load_scene(file)


def test_a_scene_written_on_windows_loads_here(tmp_path):
    direct = glshade.load_mesh(ROOT / "assets" / "lprism.obj")
    for source in ("models\\prism.obj", "models/prism.obj", ".\\models\\prism.obj"):
        loaded = _scene(tmp_path, source).scene.models[0].mesh
        assert len(loaded.vertices) == len(direct.vertices), source


def test_a_file_named_with_a_backslash_here_is_taken_as_named(tmp_path):
    """(On Linux a backslash may be part of a name: that file, where it exists, wins.)"""
    import pytest

    if "\\" in str(tmp_path) or __import__("os").name == "nt":
        pytest.skip("Windows has no backslash in a file's name")
    (tmp_path / "models").mkdir()
    shutil.copy(ROOT / "assets" / "teapot.obj", tmp_path / "models\\prism.obj")
    loaded = _scene(tmp_path, "models\\prism.obj").scene.models[0].mesh
    assert len(loaded.vertices) == len(glshade.load_mesh(ROOT / "assets" / "teapot.obj")
                                       .vertices)
