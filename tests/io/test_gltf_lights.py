"""A glTF's KHR_lights_punctual lights and its cameras, placed by its node tree, read into
glshade's lights and cameras (the oracle: the poses worked by hand from the nodes' TRS), and
drawn by ``glshade render`` on the file alone: the floor under the file's spot light is lit
within its cone and in its colour, where the cone's closed form says."""

import math
import warnings

import numpy as np
import pytest

import glshade
from tests.conftest import glshade as run, require
from tests.io.test_gltf import with_json

S = math.sqrt(0.5)
DOWN = [-S, 0.0, 0.0, S]  # (a quarter turn about x: the node's -Z to world -Y)


def floor_glb(path, change):
    """A 4 x 4 floor at y = 0 facing up, glTF's rough white dielectric, through trimesh."""
    trimesh = require("trimesh", "glTF files are read through trimesh")
    floor = trimesh.Trimesh([[-2, 0, -2], [2, 0, -2], [2, 0, 2], [-2, 0, 2]],
                            [[0, 2, 1], [0, 3, 2]], process=False)
    floor.visual = trimesh.visual.TextureVisuals(material=trimesh.visual.material.PBRMaterial(
        name="floor", baseColorFactor=[255, 255, 255, 255], metallicFactor=0.0,
        roughnessFactor=1.0))
    scene = trimesh.Scene()
    scene.add_geometry(floor, geom_name="floor")
    scene.export(path)
    with_json(path, change)


def add(doc, lights, nodes, cameras=()):
    doc["extensionsUsed"] = doc.get("extensionsUsed", []) + ["KHR_lights_punctual"]
    doc.setdefault("extensions", {})["KHR_lights_punctual"] = {"lights": lights}
    first = len(doc["nodes"])
    for node in nodes:  # (children given relative to this list)
        if "children" in node:
            node["children"] = [first + c for c in node["children"]]
    doc["nodes"] += nodes
    doc["scenes"][doc.get("scene", 0)]["nodes"] += [
        first + i for i in range(len(nodes))
        if not any(first + i in n.get("children", []) for n in nodes)]
    if cameras:
        doc["cameras"] = list(cameras)


def test_lights_and_cameras_are_placed_by_the_node_tree(tmp_path):
    path = tmp_path / "lit.glb"
    lights = [
        {"type": "spot", "color": [1.0, 0.5, 0.25], "intensity": 30.0, "range": 50.0,
         "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.4}},
        {"type": "directional", "intensity": 3.0},
        {"type": "point", "intensity": 7.0},
    ]
    nodes = [
        {"translation": [0, 3, 0], "rotation": DOWN,
         "extensions": {"KHR_lights_punctual": {"light": 0}}},
        # (a parent that scales and moves: the direction is its rotation's alone)
        {"matrix": [2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 5, 5, 5, 1], "children": [2]},
        {"rotation": DOWN, "extensions": {"KHR_lights_punctual": {"light": 1}}},
        {"translation": [1, 0, 0], "children": [4]},
        {"translation": [0, 2, 0], "extensions": {"KHR_lights_punctual": {"light": 2}}},
        {"translation": [0, 2, 5], "camera": 0},
        {"translation": [0, 9, 0], "rotation": DOWN, "camera": 1},
    ]
    cameras = [{"type": "perspective", "name": "front",
                "perspective": {"yfov": 0.6, "znear": 0.1, "aspectRatio": 1.5}},
               {"type": "orthographic", "orthographic": {
                   "xmag": 3.0, "ymag": 2.0, "znear": 0.5, "zfar": 20.0}}]
    floor_glb(path, lambda doc: add(doc, lights, nodes, cameras))

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        asset = glshade.load_gltf(path)
    assert not [w for w in caught if "not drawn" in str(w.message)]  # (all of it is read)

    spot, sun, bulb = asset.lights
    assert isinstance(spot, glshade.SpotLight)
    assert np.allclose(spot.position, (0, 3, 0)) and np.allclose(spot.direction, (0, -1, 0))
    assert (spot.inner_angle, spot.outer_angle, spot.range) == (0.2, 0.4, 50.0)
    assert np.allclose(spot.color, (1.0, 0.5, 0.25)) and spot.intensity == 30.0
    assert isinstance(sun, glshade.DirectionalLight)
    assert np.allclose(sun.direction, (0, -1, 0)) and sun.intensity == 3.0
    assert isinstance(bulb, glshade.PointLight)
    assert np.allclose(bulb.position, (1, 2, 0)) and bulb.intensity == 7.0
    assert bulb.range is None

    front, top = asset.cameras
    assert front.name == "front" and front.aspect == 1.5
    assert np.allclose(front.camera.position, (0, 2, 5))
    assert front.camera.fov_y == pytest.approx(math.degrees(0.6))
    assert front.camera.near == 0.1 and front.camera.far is None
    forward = glshade.Camera.look_at((0, 2, 5), (0, 2, 0)).orientation
    assert abs(np.dot(front.camera.orientation, forward)) == pytest.approx(1.0)
    assert top.camera.projection is glshade.Projection.ORTHOGRAPHIC
    assert top.camera.height == 4.0 and top.aspect == 1.5
    assert (top.camera.near, top.camera.far) == (0.5, 20.0)
    assert np.allclose(top.camera.position, (0, 9, 0))

    # (loaded as a mesh alone, the lights and the cameras are named as not drawn)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        glshade.load_mesh(path)
    said = [str(w.message) for w in caught if "not drawn" in str(w.message)]
    assert len(said) == 1 and "3 lights" in said[0] and "2 cameras" in said[0], said
    assert "KHR_lights_punctual" not in said[0]


def test_a_bad_light_names_the_file_and_the_light(tmp_path):
    path = tmp_path / "bad.glb"
    lights = [{"type": "spot", "name": "lamp", "spot": {"innerConeAngle": 0.5,
                                                       "outerConeAngle": 0.3}}]
    floor_glb(path, lambda doc: add(doc, lights, [
        {"extensions": {"KHR_lights_punctual": {"light": 0}}}]))
    with pytest.raises(glshade.MeshFormatError, match=r"bad\.glb.*light 'lamp'"):
        glshade.load_gltf(path)
    r = run("render", str(path), "-o", str(tmp_path / "x.png"))
    assert r.returncode != 0 and "Traceback" not in r.stderr
    assert "bad.glb" in r.stderr and "lamp" in r.stderr and len(r.stderr.splitlines()) == 1


def test_render_draws_the_file_alone_in_its_lights_through_its_camera(tmp_path):
    """The camera 5 above the floor looking down (yfov 0.9 rad), the spot 3 above it
    pointing down with a 0.4 rad cone: lit pixels lie within 3 tan 0.4 of the centre on the
    floor, those within 3 tan 0.2 are lit fully, and the light's colour is the difference's."""
    path = tmp_path / "spot.glb"
    lights = [{"type": "spot", "color": [1.0, 0.5, 0.25], "intensity": 9.0,
               "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.4}}]
    nodes = [{"translation": [0, 3, 0], "rotation": DOWN,
              "extensions": {"KHR_lights_punctual": {"light": 0}}},
             {"translation": [0, 5, 0], "rotation": DOWN, "camera": 0}]
    camera = {"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.5}}
    floor_glb(path, lambda doc: add(doc, lights, nodes, [camera]))
    out = tmp_path / "spot.png"
    r = run("render", str(path), "-o", str(out), "--size", "96x96", "--mode", "phong")
    assert r.returncode == 0, r.stderr
    from PIL import Image

    image = np.asarray(Image.open(out).convert("RGB"), np.float64)
    n = 96
    ndc = (np.arange(n) + 0.5) / (n / 2) - 1
    x, y = np.meshgrid(ndc, ndc)
    radius = 5 * math.tan(0.45) * np.hypot(x, y)  # (on the floor, from under the lights)
    inner, outer, pixel = 3 * math.tan(0.2), 3 * math.tan(0.4), 2 * 5 * math.tan(0.45) / n
    outside = image[(radius > outer + 2 * pixel) & (radius < 1.9)]
    assert outside.std(0).max() < 1.0  # (one level: the ambient term alone)
    lit = image - outside.mean(0)
    assert (lit[radius > outer + 2 * pixel] < 2).all()
    core = lit[radius < inner - 2 * pixel]
    assert core[:, 0].min() > 40
    assert np.allclose(core[:, 1] / core[:, 0], 0.5, atol=0.03)
    assert np.allclose(core[:, 2] / core[:, 0], 0.25, atol=0.03)
    ring = lit[(radius > inner + 2 * pixel) & (radius < outer - 2 * pixel)]
    assert ring[:, 0].max() < core[:, 0].min() + 1  # (the falloff between the cones)


def test_info_lists_the_files_lights_cameras_and_materials_by_model(tmp_path):
    import json

    path = tmp_path / "lit.glb"
    lights = [{"type": "point", "intensity": 7.0, "range": 4.0}]
    nodes = [{"translation": [1, 2, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}},
             {"translation": [0, 2, 5], "camera": 0}]
    camera = {"type": "perspective", "name": "front", "perspective": {"yfov": 0.6}}
    floor_glb(path, lambda doc: add(doc, lights, nodes, [camera]))
    r = run("info", str(path))
    assert r.returncode == 0 and not r.stderr, r.stderr
    assert "PBR base (1, 1, 1), metallic 0, roughness 1" in r.stdout
    assert "point       at (1, 2, 3), intensity 7, range 4" in r.stdout
    assert f"front              at (0, 2, 5), {math.degrees(0.6):.3g} degrees high" in r.stdout
    data = json.loads(run("info", str(path), "--json").stdout)
    assert data["lights"][0]["range"] == 4.0 and data["cameras"][0]["name"] == "front"
    assert data["materials"][0]["model"] == "pbr"
