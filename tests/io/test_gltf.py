"""A GLB written by another library (trimesh) round-trips into the right materials:
metallic-roughness materials into PBRMaterials with their factors and maps, vertex colours
as they were; what it holds and glshade does not draw (an extension, an animation) is one
warning naming it."""

import json
import struct
import warnings

import numpy as np
import pytest

import glshade


def with_json(path, change):
    """Rewrite a GLB's JSON chunk through ``change(doc)`` (padded to 4 bytes, as GLB asks)."""
    data = path.read_bytes()
    length, _ = struct.unpack_from("<II", data, 12)
    doc = json.loads(data[20:20 + length])
    change(doc)
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    rest = data[20 + length:]
    path.write_bytes(struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(text) + len(rest)) +
                     struct.pack("<II", len(text), 0x4E4F534A) + text + rest)


def test_factors_colours_maps_and_one_warning_for_what_is_not_drawn(tmp_path):
    trimesh = pytest.importorskip("trimesh")
    from PIL import Image

    scene = trimesh.Scene()
    metal = trimesh.creation.box()
    metal.visual = trimesh.visual.TextureVisuals(material=trimesh.visual.material.PBRMaterial(
        name="brass", baseColorFactor=[230, 180, 60, 255], metallicFactor=0.9,
        roughnessFactor=0.3, emissiveFactor=[0.1, 0.0, 0.0]))
    scene.add_geometry(metal, geom_name="metal")
    quad = trimesh.Trimesh([[2, 0, 0], [3, 0, 0], [3, 1, 0], [2, 1, 0]], [[0, 1, 2], [0, 2, 3]],
                           process=False)
    image = np.array([[[200, 30, 30], [30, 200, 30]]], np.uint8)
    quad.visual = trimesh.visual.TextureVisuals(
        uv=[[0, 0], [1, 0], [1, 1], [0, 1]], material=trimesh.visual.material.PBRMaterial(
            name="poster", baseColorTexture=Image.fromarray(image), metallicFactor=0.0,
            roughnessFactor=1.0))
    scene.add_geometry(quad, geom_name="poster")
    scene.export(tmp_path / "shop.glb")

    def add_clearcoat(doc):
        doc["extensionsUsed"] = ["KHR_materials_clearcoat"]
        doc["materials"][0].setdefault("extensions", {})["KHR_materials_clearcoat"] = {
            "clearcoatFactor": 1.0}
        doc["animations"] = [{"channels": [], "samplers": []}]
    with_json(tmp_path / "shop.glb", add_clearcoat)

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        mesh = glshade.load_mesh(tmp_path / "shop.glb")
    said = [str(w.message) for w in caught]
    unread = [s for s in said if "read and not drawn" in s]
    assert len(unread) == 1, said
    assert "extension KHR_materials_clearcoat" in unread[0] and "1 animation" in unread[0]
    brass = mesh.materials["brass"]
    assert isinstance(brass, glshade.PBRMaterial)
    assert np.allclose(brass.base_color, np.array([230, 180, 60]) / 255)
    assert (brass.metallic, brass.roughness) == pytest.approx((0.9, 0.3))
    assert brass.emissive == pytest.approx((0.1, 0.0, 0.0))
    poster = mesh.materials["poster"]  # (glTF's model with its base colour map)
    assert isinstance(poster, glshade.PBRMaterial)
    assert np.array_equal(poster.base_color_texture.pixels[..., :3], image)
    assert (poster.metallic, poster.roughness) == (0.0, 1.0)
    assert not [s for s in said if "not drawn" in s and "poster" in s], said


def test_mtl_pbr_keys_make_glTFs_material_and_round_trip(tmp_path):
    (tmp_path / "a.mtl").write_text(
        "newmtl gold\nKd 0.9 0.6 0.2\nPm 1\nPr 0.3\nKe 0.1 0 0\nnorm n.png\n"
        "newmtl wood\nKd 0.5 0.4 0.3\nPr 0.8\n")
    (tmp_path / "a.obj").write_text(
        "mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nusemtl gold\nf 1 2 3\n"
        "usemtl wood\nf 2 4 3\n")
    mesh = glshade.load_mesh(tmp_path / "a.obj")
    assert mesh.materials["gold"] == glshade.PBRMaterial(
        name="gold", base_color=(0.9, 0.6, 0.2), metallic=1.0, roughness=0.3,
        emissive=(0.1, 0.0, 0.0))
    assert mesh.materials["wood"].metallic == 0.0 and mesh.materials["wood"].roughness == 0.8
    assert mesh.material_notes == ["a.mtl:6: norm"]  # (read, not drawn: reported)
    glshade.save_mesh(mesh, tmp_path / "b.obj")
    assert glshade.load_mesh(tmp_path / "b.obj").materials == mesh.materials
