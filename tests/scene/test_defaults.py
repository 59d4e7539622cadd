"""One rule per default: the light of an unlit scene, material defaults, draw options and
the auto-framed camera are each decided in one place."""

import dataclasses

import numpy as np
import pytest

from glshade import (
    Camera, Culling, DirectionalLight, DrawOptions, Material, OptionError,
    Outputs, PointLight, Scene, ShadingMode, default_camera,
)
from glshade.geometry import primitives as P
from glshade.io.scenefile import RenderSettings
from glshade.options import DEFAULT_SIZE


def test_no_lights_means_one_white_headlight_at_the_eye():
    scene = Scene()
    cam = Camera.look_at([1.0, 2.0, 3.0], [0, 0, 0])
    (light,) = scene.lights_for(cam)
    assert isinstance(light, PointLight)
    np.testing.assert_array_equal(light.position, cam.position)
    assert light.color == (1.0, 1.0, 1.0) and light.intensity == 1.0
    sun = DirectionalLight((0, -1, 0))
    scene.add_light(sun)
    assert scene.lights_for(cam) == [sun]  # given lights replace the default


def test_material_defaults_come_from_the_dataclass():
    defaults = {f.name: f.default for f in dataclasses.fields(Material)}
    assert Material.from_values({}) == Material()
    m = Material.from_values({"ks": 0.9, "color": None, "source": "ignored"})
    assert m.ks == 0.9 and m.color == defaults["color"] and m.kd == defaults["kd"]


def test_scene_file_settings_hold_the_renderers_draw_options():
    s = RenderSettings()
    assert s.options == DrawOptions() and s.size == DEFAULT_SIZE


def test_draw_options_validate_and_combine():
    o = DrawOptions.of("flat", depth_test=False)
    assert o.mode is ShadingMode.FLAT and not o.depth_test and o.outputs is Outputs.COLOR
    assert DrawOptions.of(o) is o
    assert o.replace(cull=True).cull is Culling.ON and o.replace(cull=False).cull is Culling.OFF
    with pytest.raises(OptionError, match="unknown draw option.*culling"):
        o.replace(culling=True)
    with pytest.raises(OptionError, match="cull must be 'auto', True or False"):
        DrawOptions(cull="sometimes")
    with pytest.raises(OptionError, match="unknown shading mode 'toon'; choose one of flat"):
        DrawOptions.of("toon")
    with pytest.raises(OptionError, match="must include COLOR|including COLOR"):
        DrawOptions(outputs=Outputs.DEPTH)
    with pytest.raises(dataclasses.FrozenInstanceError):
        o.mode = ShadingMode.PHONG
    assert Outputs.ALL.auxiliary and not Outputs.COLOR.auxiliary


def test_default_camera_takes_a_scene_a_mesh_or_bounds():
    scene = Scene()
    scene.add(P.cube(), translation=(5.0, 0, 0))
    from_scene = default_camera(scene, 1.5)
    from_bounds = default_camera(scene.bounds, 1.5)
    assert from_scene == from_bounds
    np.testing.assert_allclose(scene.bounds.mean(0), [5.0, 0, 0])
    # the centre of the scene is straight ahead
    to_centre = scene.bounds.mean(0) - from_scene.position
    np.testing.assert_allclose(to_centre / np.linalg.norm(to_centre), from_scene.forward,
                               atol=1e-12)
    assert default_camera(P.cube()) == default_camera(P.cube().bounds)


def test_a_scene_files_render_table_is_draw_options(tmp_path):
    from glshade.io.scenefile import load_scene

    path = tmp_path / "s.toml"
    path.write_text('[render]\nmode = "flat"\nsrgb = true\ndepth_test = false\ncull = true\n'
                    'wireframe = true\n[[mesh]]\nsource = "primitive:cube"\n')
    options = load_scene(path).settings.options
    assert options == DrawOptions(mode="flat", srgb=True, depth_test=False, cull=True,
                                  wireframe=True)
    path.write_text('[render]\ncull = "sometimes"\n[[mesh]]\nsource = "primitive:cube"\n')
    from glshade import SceneFormatError

    with pytest.raises(SceneFormatError, match=r":2: \[render\] key 'cull' must be 'auto', "):
        load_scene(path)
