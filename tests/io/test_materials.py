"""OBJ materials and texture coordinates: real files from another project (assimp's test
models, Debian's assimp-testmodels: assets/assimp), a multi-material round trip, and every
refusal naming its file and line. The spider is also drawn with nearest texels against a
numpy ray caster that looks its texels up by hand."""

import dataclasses
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import glshade
from glshade import Camera, Material, Mesh, Scene, Texture
from glshade.errors import MeshFormatError
from glshade.io.mtl import read_mtl
from tests.oracle.neighbours import inside_regions

ASSIMP = Path(__file__).resolve().parents[2] / "assets" / "assimp"


def test_the_spider_reads_its_materials_and_textures():
    mesh = glshade.load_mesh(ASSIMP / "spider.obj")
    assert mesh.n_faces == 1368 and mesh.uv is not None and mesh.uv.shape == (3 * 1368, 2)
    # five materials in the library, four used by usemtl
    assert sorted(mesh.materials) == ["Augentex", "BeinTex", "HLeibTex", "Skin"]
    assert sum(len(f) for f in mesh.material_groups.values()) == mesh.n_faces
    skin = mesh.materials["Skin"]
    assert skin.ambient == (0.2, 0.2, 0.2) and skin.diffuse == pytest.approx(
        (0.827451, 0.792157, 0.772549)) and skin.specular == (0, 0, 0)
    # ".\wal67ar_small.jpg": a Windows path, read beside the MTL
    assert skin.texture.path.name == "wal67ar_small.jpg" and skin.texture.size == (250, 250)
    assert mesh.materials["BeinTex"].texture.size == (768, 768)


def test_assimps_edge_cases_read_as_their_files_mean():
    cube = pytest.warns(UserWarning, match=r"cube_usemtl.obj:21: material 'mtl3' is in no "
                        "material library")
    with cube:
        mesh = glshade.load_mesh(ASSIMP / "cube_usemtl.obj")
    assert {k: len(v) for k, v in mesh.material_groups.items()} == {"mtl3": 2, "mtl": 6,
                                                                     "mtl2": 4}
    assert mesh.materials["mtl"].shininess == 200 and mesh.materials["mtl2"].specular == (
        0.375, 0.375, 0.375)
    spaces = glshade.load_mesh(ASSIMP / "box_mat_with_spaces.obj")
    assert list(spaces.materials) == ["Material name with many, many spaces"]
    blender = glshade.load_mesh(ASSIMP / "empty_mat.obj")   # (newmtl and usemtl nameless)
    assert list(blender.materials) == ["default"]
    assert blender.materials["default"].specular == (0, 0, 0)   # ("Ks 0": one number)


def test_a_scene_draws_each_material_part_with_its_material():
    mesh = glshade.load_mesh(ASSIMP / "spider.obj")
    scene = Scene()
    scene.add(mesh)
    assert sorted(m.name for m in scene.models) == [
        "spider:Augentex", "spider:BeinTex", "spider:HLeibTex", "spider:Skin"]
    assert sum(m.mesh.n_faces for m in scene.models) == mesh.n_faces
    for m in scene.models:
        assert m.material is mesh.materials[m.name.split(":")[1]]
        assert m.mesh.uv is not None
    # a material given to add() is used for every face instead
    one = Scene()
    one.add(mesh, Material(color=(1, 0, 0)))
    assert len(one.models) == 1


def _ray_cast_texels(scene, camera, size):
    """Per pixel: the linear colour of the nearest texel of the nearest textured triangle
    (numpy, float64), and whether the pixel is well inside one triangle and further than
    0.01 px from a texel edge."""
    o, d = camera.rays(size)
    o, d = o.reshape(-1, 3), d.reshape(-1, 3)
    w, h = size
    best = np.full(len(o), np.inf)
    colour = np.zeros((len(o), 3))
    coords = np.full((len(o), 2), np.nan)
    owner = np.full(len(o), -1)
    tex_of = np.full(len(o), -1)
    textures = []
    k = 0
    for model in scene.models:
        mesh, texture = model.mesh, model.material.texture
        textures.append(texture)
        tri = mesh.vertices[mesh.face_indices[mesh.corner_triangles]]
        uvs = mesh.uv[mesh.corner_triangles]
        p0, e1, e2 = tri[:, 0], tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
        for t in range(len(tri)):   # (rays in bulk; one triangle at a time)
            pv = np.cross(d, e2[t])
            with np.errstate(divide="ignore", invalid="ignore"):
                inv = 1.0 / (pv @ e1[t])
                s = o - p0[t]
                u = (s * pv).sum(1) * inv
                q = np.cross(s, e1[t])
                v = (d * q).sum(1) * inv
                dist = (q @ e2[t]) * inv
            hit = (u >= 0) & (v >= 0) & (u + v <= 1) & (dist > 1e-9) & (dist < best)
            best[hit], owner[hit], tex_of[hit] = dist[hit], k, len(textures) - 1
            coords[hit] = ((1 - u - v)[hit, None] * uvs[t, 0] + u[hit, None] * uvs[t, 1] +
                           v[hit, None] * uvs[t, 2])
            k += 1
    near_edge = np.zeros(len(o), bool)
    for i, texture in enumerate(textures):
        sel = tex_of == i
        lin = texture.linear()[..., :3]
        th, tw = lin.shape[:2]
        c = np.nan_to_num(coords[sel]) * [tw, th]
        colour[sel] = lin[th - 1 - (np.floor(c[:, 1]).astype(int) % th),
                          np.floor(c[:, 0]).astype(int) % tw]
        full = np.full((h * w, 2), np.nan)
        full[sel] = c
        grid = full.reshape(h, w, 2)
        for axis in (0, 1):
            gy, gx = np.gradient(grid[..., axis])
            rate = np.hypot(gx, gy).ravel()
            frac = full[:, axis] - np.floor(full[:, axis])
            near_edge |= sel & (np.minimum(frac, 1 - frac) <= 0.01 * np.nan_to_num(rate, nan=1e9))
    owner = owner.reshape(h, w)
    keep = inside_regions(owner) & (owner >= 0) & ~near_edge.reshape(h, w)
    return colour.reshape(h, w, 3), keep


def test_the_spiders_nearest_texels_against_a_numpy_ray_caster(gl_context):
    """The real model drawn unlit (illum 0, white Kd) with nearest texels: every pixel well
    inside a triangle and away from a texel edge shows its texel, within the GPU's sRGB
    decode (tests/render/test_textures.py: 2e-3)."""
    mesh = glshade.load_mesh(ASSIMP / "spider.obj")
    mesh.materials = {k: dataclasses.replace(m, illum=0, diffuse=(1, 1, 1),
                                             texture=m.texture.replace(filter="nearest"))
                      for k, m in mesh.materials.items()}
    scene = Scene()
    scene.add(mesh)
    body = next(m for m in scene.models if m.name == "spider:HLeibTex")   # (framed)
    camera = glshade.default_camera(np.stack([body.corners.min(0), body.corners.max(0)]), 1.0)
    size = (128, 128)
    with glshade.Renderer(*size, samples=0, context=gl_context) as r:
        got = r.render_frame(scene, camera, "phong", color_dtype="f4").color[..., :3]
    want, keep = _ray_cast_texels(scene, camera, size)
    assert keep.sum() > 1000, keep.sum()
    err = np.abs(got - want)[keep]
    assert np.quantile(err.max(1), 0.995) <= 2e-3 and err.max() <= 0.05, \
        (err.max(), np.quantile(err.max(1), 0.995))


def test_a_multi_material_obj_round_trips(tmp_path):
    """Texture coordinates per corner (a seam: one vertex, two uv), two material parts in
    face order, RGB coefficients, illum and a clamped texture survive save and load."""
    from PIL import Image

    Image.fromarray(np.full((2, 3, 3), 200, np.uint8)).save(tmp_path / "wood.png")
    v = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0], [2, 1, 0]]
    uv = [[0, 0], [1, 0], [1, 1], [0, 1], [0.25, 0], [0.5, 0], [0.5, 1], [0.25, 1]]
    mesh = Mesh(v, [[0, 1, 2, 3], [1, 4, 5, 2]], uv=uv)
    mesh.material_groups = {"wood": np.array([0]), "shiny red": np.array([1])}
    mesh.materials = {
        "wood": Material(name="wood", ambient=(0.1, 0.1, 0.05), diffuse=(0.6, 0.4, 0.2),
                         illum=1, texture=Texture(tmp_path / "wood.png", wrap="clamp")),
        "shiny red": Material(name="shiny red", diffuse=(0.8, 0, 0), specular=(1, 1, 1),
                              shininess=90, opacity=0.5)}
    glshade.save_mesh(mesh, tmp_path / "out.obj")
    assert (tmp_path / "out.mtl").exists()
    back = glshade.load_mesh(tmp_path / "out.obj")
    assert np.allclose(back.vertices, mesh.vertices)
    assert back.faces[0].tolist() == [0, 1, 2, 3] and back.faces[1].tolist() == [1, 4, 5, 2]
    assert np.array_equal(back.uv, mesh.uv)
    assert {k: g.tolist() for k, g in back.material_groups.items()} == {
        "wood": [0], "shiny red": [1]}
    wood, red = back.materials["wood"], back.materials["shiny red"]
    assert (wood.ambient, wood.diffuse, wood.illum) == ((0.1, 0.1, 0.05), (0.6, 0.4, 0.2), 1)
    assert wood.texture.wrap == "clamp" and wood.texture.path == tmp_path / "wood.png"
    assert (red.diffuse, red.specular, red.shininess, red.opacity) == (
        (0.8, 0, 0), (1, 1, 1), 90, 0.5)


@pytest.mark.parametrize("line,message", [
    ("Kd 0.5 x 0.5", r"bad.mtl:3: Kd needs 1 or 3 number\(s\), got '0.5 x 0.5'"),
    ("Ns", r"bad.mtl:3: Ns needs 1 number"),
    ("illum 2.5", r"bad.mtl:3: illum must be a model number 0..10"),
    ("map_Kd -clamp on", r"bad.mtl:3: map_Kd names no image file"),
    ("d 1e999", r"bad.mtl:3: d needs 1 number"),
])
def test_a_malformed_mtl_line_names_the_file_and_line(tmp_path, line, message):
    (tmp_path / "bad.mtl").write_text(f"# a library\nnewmtl a\n{line}\n")
    with pytest.raises(MeshFormatError, match=message):
        read_mtl(tmp_path / "bad.mtl")


def test_a_statement_before_newmtl_is_refused(tmp_path):
    (tmp_path / "bad.mtl").write_text("Kd 1 1 1\n")
    with pytest.raises(MeshFormatError, match=r"bad.mtl:1: .Kd. before any newmtl"):
        read_mtl(tmp_path / "bad.mtl")


def _obj(tmp_path, mtl_text=None, image=False):
    if mtl_text is not None:
        (tmp_path / "m.mtl").write_text(mtl_text)
    if image:
        from PIL import Image

        Image.fromarray(np.zeros((2, 2, 3), np.uint8)).save(tmp_path / "t.png")
    (tmp_path / "m.obj").write_text(
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
        "usemtl a\nf 1/1 2/2 3/3\n")
    return tmp_path / "m.obj"


def test_missing_files_warn_by_line_and_the_mesh_still_draws(tmp_path, gl_context):
    with pytest.warns(UserWarning, match=r"m.obj:1: material library 'm.mtl' not found"):
        mesh = glshade.load_mesh(_obj(tmp_path))
    assert mesh.materials == {} and list(mesh.material_groups) == ["a"]
    with pytest.warns(UserWarning, match=r"m.mtl:3: map_Kd: .*gone.png: no such image file; "
                      "the material is drawn without it"):
        mesh = glshade.load_mesh(_obj(tmp_path, "newmtl a\nKd 1 0 0\nmap_Kd gone.png\n"))
    assert mesh.materials["a"].texture is None and mesh.materials["a"].diffuse == (1, 0, 0)
    scene = Scene()
    scene.add(mesh)
    camera = Camera.look_at((0.3, 0.3, 2), (0.3, 0.3, 0))
    with glshade.Renderer(32, 32, samples=0, context=gl_context) as r:
        frame = r.render_frame(scene, camera, "phong")
    assert (frame.face_id >= 0).sum() > 50   # (drawn: never a blank)


def test_unused_statements_are_reported_not_drawn(tmp_path):
    mesh = glshade.load_mesh(_obj(tmp_path, "newmtl a\nKd 1 1 1\nNi 1.5\nillum 7\n"
                                  "bump -bm 0.5 t.png\nmap_Kd -blendu off t.png\n", True))
    assert mesh.material_notes == ["m.mtl:3: Ni", "m.mtl:4: illum 7 (drawn as illum 2)",
                                   "m.mtl:5: bump", "m.mtl:6: map_Kd -blendu"]
    assert mesh.materials["a"].illum == 2 and mesh.materials["a"].texture is not None


def test_texture_coordinates_refused_by_line(tmp_path):
    (tmp_path / "a.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/3\n")
    with pytest.raises(MeshFormatError, match=r"a.obj:5: texture coordinate index 2 is out of "
                       "range: the file defines 1"):
        glshade.load_mesh(tmp_path / "a.obj")
    (tmp_path / "b.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 nan\nf 1/1 2/1 3/1\n")
    with pytest.raises(MeshFormatError, match=r"b.obj:4: a texture coordinate \(vt\) is not "
                       "finite"):
        glshade.load_mesh(tmp_path / "b.obj")


def test_info_lists_materials_and_textures():
    out = subprocess.run([sys.executable, "-m", "glshade", "info",
                          str(ASSIMP / "spider.obj"), "--json"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    info = json.loads(out.stdout)
    assert info["texture_coordinates"] is True
    by_name = {m["name"]: m for m in info["materials"]}
    assert by_name["BeinTex"]["faces"] == 952
    assert by_name["BeinTex"]["textures"]["texture"]["size"] == [768, 768]
    text = subprocess.run([sys.executable, "-m", "glshade", "info",
                           str(ASSIMP / "cube_usemtl.obj")], capture_output=True, text=True)
    assert "mtl3                     2  (in no material library" in text.stdout
    assert "materials (3):" in text.stdout


def test_render_and_compare_take_a_textured_obj_and_the_filter(tmp_path):
    for command in (["render", "-o", str(tmp_path / "r.png")],
                    ["compare", "-o", str(tmp_path / "c.png")]):
        out = subprocess.run([sys.executable, "-m", "glshade", command[0],
                              str(ASSIMP / "spider.obj"), "--size", "96x72",
                              "--texture-filter", "nearest", *command[1:]],
                             capture_output=True, text=True)
        assert out.returncode == 0, out.stderr
        assert "no texture coordinates" not in out.stderr
    bad = subprocess.run([sys.executable, "-m", "glshade", "render", str(ASSIMP / "spider.obj"),
                          "--texture-filter", "cubic", "-o", str(tmp_path / "x.png")],
                         capture_output=True, text=True)
    assert bad.returncode == 2 and "--texture-filter: expected one of nearest, linear, " \
        "mipmap, got 'cubic'" in bad.stderr and "Traceback" not in bad.stderr


def test_a_gltf_base_colour_texture_comes_through_trimesh(tmp_path, gl_context):
    """A GLB written by another library (trimesh's exporter; the formats extra) with a
    base colour factor and texture: read back with its texture coordinates and a material
    whose texture is the image, drawn textured (illum 0 here: the texel times the factor)."""
    from tests.conftest import require

    trimesh = require("trimesh", "glTF is read through the formats extra")
    from PIL import Image

    image = np.array([[[200, 30, 30], [30, 200, 30]], [[30, 30, 200], [200, 200, 30]]],
                     np.uint8)
    quad = trimesh.Trimesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
                           [[0, 1, 2], [0, 2, 3]], process=False)
    quad.visual = trimesh.visual.TextureVisuals(
        uv=[[0, 0], [1, 0], [1, 1], [0, 1]], material=trimesh.visual.material.PBRMaterial(
            name="painted", baseColorTexture=Image.fromarray(image),
            baseColorFactor=[255, 255, 255, 255]))
    quad.export(tmp_path / "quad.glb")
    mesh = glshade.load_mesh(tmp_path / "quad.glb")
    assert mesh.uv is not None and list(mesh.materials) == ["painted"]
    painted = mesh.materials["painted"]  # (glTF's model, its base colour map)
    assert np.array_equal(painted.base_color_texture.pixels[..., :3], image)
    # (drawn here unlit, through the notes' model: the texel times the factor)
    material = glshade.Material(illum=0, color=painted.base_color, diffuse=painted.base_color,
                                texture=painted.base_color_texture.replace(filter="nearest"))
    mesh.materials = {"painted": material}
    scene = Scene()
    scene.add(mesh)
    camera = Camera.look_at((0.5, 0.5, 2), (0.5, 0.5, 0), fov_y=30)
    with glshade.Renderer(40, 40, samples=0, context=gl_context) as r:
        got = r.render_frame(scene, camera, "phong", color_dtype="f4").color[..., :3]
    lin = material.texture.linear()[..., :3]
    # the quad's lower-left quarter shows the image's bottom-left texel (row 1: v up)
    assert np.abs(got[26, 14] - lin[1, 0]).max() <= 2e-3
    assert np.abs(got[13, 26] - lin[0, 1]).max() <= 2e-3


@pytest.mark.parametrize("names", [("u", "v"), ("s", "t"), ("texture_u", "texture_v")])
@pytest.mark.parametrize("binary", [False, True])
def test_ply_texture_coordinates_are_read_per_corner(tmp_path, names, binary):
    """A PLY's per-vertex texture coordinates, by any of the names writers give them, ASCII
    or binary: each face corner takes its vertex's."""
    header = ("ply\nformat {} 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
              f"property float z\nproperty float {names[0]}\nproperty float {names[1]}\n"
              "element face 2\nproperty list uchar int vertex_indices\nend_header\n")
    table = np.array([[0, 0, 0, 0, 0], [1, 0, 0, 1, 0], [1, 1, 0, 1, 1], [0, 1, 0, 0, 0.5]],
                     np.float32)
    faces = [[0, 1, 2], [0, 2, 3]]
    if binary:
        body = table.astype("<f4").tobytes() + b"".join(
            np.uint8(3).tobytes() + np.array(f, "<i4").tobytes() for f in faces)
        data = header.format("binary_little_endian").encode() + body
    else:
        rows = "\n".join(" ".join(f"{x:g}" for x in r) for r in table)
        data = (header.format("ascii") + rows + "\n3 0 1 2\n3 0 2 3\n").encode()
    (tmp_path / "q.ply").write_bytes(data)
    mesh = glshade.load_mesh(tmp_path / "q.ply")
    assert np.array_equal(mesh.uv, table[[0, 1, 2, 0, 2, 3], 3:])


def test_meshes_joined_keep_their_coordinates_and_material_parts():
    from glshade.geometry import primitives

    spider = glshade.load_mesh(ASSIMP / "spider.obj")
    cube = primitives.cube()
    sphere = primitives.icosphere(0)   # (no texture coordinates: its corners get (0, 0))
    joined = glshade.concatenate([cube, sphere, spider])
    assert np.array_equal(joined.uv[:24], cube.uv)
    assert (joined.uv[24:24 + 60] == 0).all()
    assert np.array_equal(joined.uv[84:], spider.uv)
    offset = cube.n_faces + sphere.n_faces
    assert np.array_equal(joined.material_groups["Skin"], spider.material_groups["Skin"] + offset)
    assert joined.materials["Skin"] is spider.materials["Skin"]


def test_scene_files_name_a_texture_by_path_and_keep_an_objs_own_materials(tmp_path):
    """A [[mesh]]'s ``texture`` is relative to the scene file and its ``texture_filter``
    applies; an OBJ with no material key keeps its MTL's (filtered as asked); a missing
    image is one error naming the key's line."""
    import shutil

    from PIL import Image

    from glshade.errors import SceneFormatError
    from glshade.io.scenefile import load_scene

    for name in ("cube_usemtl.obj", "cube_usemtl.mtl", "spider.obj", "spider.mtl",
                 "wal67ar_small.jpg", "wal69ar_small.jpg", "SpiderTex.jpg", "drkwood2.jpg",
                 "engineflare1.jpg"):
        shutil.copy(ASSIMP / name, tmp_path / name)
    (tmp_path / "maps").mkdir()
    Image.fromarray(np.zeros((4, 4, 3), np.uint8)).save(tmp_path / "maps" / "w.png")
    scene_file = tmp_path / "s.toml"
    scene_file.write_text('[[mesh]]\nsource = "spider.obj"\ntexture_filter = "nearest"\n\n'
                          '[[mesh]]\nsource = "primitive:plane"\ntexture = "maps/w.png"\n'
                          'texture_filter = "mipmap"\n')
    scene = load_scene(scene_file).scene
    spider = [m for m in scene.models if m.name.startswith("spider:")]
    assert len(spider) == 4 and all(m.material.texture.filter == "nearest" for m in spider)
    plane = scene.models[-1]
    assert plane.material.texture.path == tmp_path / "maps" / "w.png"
    assert plane.material.texture.filter == "mipmap"
    scene_file.write_text('[[mesh]]\nsource = "primitive:plane"\ncolor = [1, 1, 1]\n'
                          'texture = "gone.png"\n')
    with pytest.raises(SceneFormatError, match=r"s.toml:4: \[\[mesh\]\] 1 key 'texture': "
                       ".*gone.png: no such image file"):
        load_scene(scene_file)


def test_gltf_parts_sharing_a_material_name_keep_their_own_colours(tmp_path):
    """Two meshes of a GLB whose materials share a name but not a colour: two parts, each
    drawn with its own (a name used twice is never merged into one material)."""
    from tests.conftest import require

    trimesh = require("trimesh", "glTF is read through the formats extra")
    scene = trimesh.Scene()
    for k, colour in enumerate(([255, 0, 0, 255], [0, 0, 255, 255])):
        part = trimesh.Trimesh([[0, 0, k], [1, 0, k], [0, 1, k]], [[0, 1, 2]], process=False)
        part.visual = trimesh.visual.TextureVisuals(
            uv=[[0, 0], [1, 0], [0, 1]], material=trimesh.visual.material.PBRMaterial(
                name="paint", baseColorFactor=colour))
        scene.add_geometry(part, geom_name=f"part{k}")
    scene.export(tmp_path / "two.glb")
    mesh = glshade.load_mesh(tmp_path / "two.glb")
    # (untextured glTF materials are glTF's model: PBRMaterials with their base colours)
    colours = {tuple(np.round(mesh.materials[n].base_color, 3)): len(f)
               for n, f in mesh.material_groups.items()}
    assert colours == {(1.0, 0.0, 0.0): 1, (0.0, 0.0, 1.0): 1}
