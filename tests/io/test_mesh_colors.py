"""Colours files hold come back as the mesh's linear colours: PLY bytes (a BOP-style
vertex-coloured model) decoded by the IEC 61966-2-1 formula written here, PLY floats as
they are; OBJ ``v x y z r g b``; OFF's COFF and face colours; a glTF's COLOR_0 (linear)
through trimesh; and Mesh.from_trimesh / to_trimesh both ways with colours, uv and the
texture."""

import struct

import numpy as np
import pytest

import glshade
from glshade import Mesh


def iec_decode(byte):
    """sRGB-encoded bytes to linear, by the standard's formula."""
    c = np.asarray(byte, np.float64) / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def bop_ply(path, vertices, faces, rgb):
    """A binary PLY as BOP's models are written: float xyz, float normals, uchar colours,
    uchar-count int-index triangles."""
    normals = vertices / np.linalg.norm(vertices, axis=1, keepdims=True)
    head = (f"ply\nformat binary_little_endian 1.0\nelement vertex {len(vertices)}\n"
            "property float x\nproperty float y\nproperty float z\nproperty float nx\n"
            "property float ny\nproperty float nz\nproperty uchar red\nproperty uchar green\n"
            f"property uchar blue\nelement face {len(faces)}\n"
            "property list uchar int vertex_indices\nend_header\n").encode()
    body = b"".join(struct.pack("<6f3B", *v, *n, *c)
                    for v, n, c in zip(vertices, normals, rgb))
    body += b"".join(struct.pack("<B3i", 3, *f) for f in faces)
    path.write_bytes(head + body)


def test_a_bop_model_reads_back_to_its_bytes_linear_values(tmp_path):
    sphere = glshade.geometry.primitives.icosphere(2)
    tri = sphere.triangles[0]
    rgb = np.random.default_rng(4).integers(0, 256, (sphere.n_vertices, 3), dtype=np.uint8)
    bop_ply(tmp_path / "obj_000001.ply", sphere.vertices, tri, rgb)
    mesh = glshade.load_mesh(tmp_path / "obj_000001.ply")
    assert mesh.colors.shape == (sphere.n_vertices, 4)
    assert np.abs(mesh.colors[:, :3] - iec_decode(rgb)).max() < 1e-12
    assert (mesh.colors[:, 3] == 1).all() and mesh.face_colors is None


def test_ply_floats_are_linear_and_faces_may_carry_colours(tmp_path):
    (tmp_path / "f.ply").write_text(
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
        "property float z\nproperty float red\nproperty float green\nproperty float blue\n"
        "element face 2\nproperty uchar red\nproperty list uchar int vertex_indices\n"
        "property uchar green\nproperty uchar blue\nproperty uchar alpha\nend_header\n"
        "0 0 0 0.25 0.5 1\n1 0 0 0 0 0\n1 1 0 1 1 1\n0 1 0 0.1 0.2 0.3\n"
        "255 3 0 1 2 0 10 128\n7 3 0 2 3 200 100 255\n")
    mesh = glshade.load_mesh(tmp_path / "f.ply")
    assert np.allclose(mesh.colors[:, :3], [[0.25, 0.5, 1], [0, 0, 0], [1, 1, 1],
                                            [0.1, 0.2, 0.3]])
    assert np.allclose(mesh.face_colors[:, :3], iec_decode([[255, 0, 10], [7, 200, 100]]))
    assert np.allclose(mesh.face_colors[:, 3], [128 / 255, 1.0])


def test_bad_colours_are_one_line_naming_the_row(tmp_path):
    (tmp_path / "bad.ply").write_text(
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nproperty float red\nproperty float green\nproperty float blue\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0 0 0 0\n1 0 0 0 2.5 0\n0 1 0 0 0 0\n3 0 1 2\n")
    with pytest.raises(glshade.errors.MeshFormatError, match=r"bad.ply: vertex 1 has colour"):
        glshade.load_mesh(tmp_path / "bad.ply")
    with pytest.raises(glshade.errors.GeometryError, match=r"colors: vertex 2 has"):
        Mesh(np.eye(3), [[0, 1, 2]], colors=[[0, 0, 0], [1, 1, 1], [0, -0.1, 0]])
    with pytest.raises(glshade.errors.GeometryError, match=r"face_colors must have shape"):
        Mesh(np.eye(3), [[0, 1, 2]], face_colors=np.ones((2, 3)))


def test_obj_and_off_colours(tmp_path):
    (tmp_path / "c.obj").write_text("v 0 0 0 1 0 0\nv 1 0 0 0 0.5 0\nv 0 1 0 0 0 0.25\n"
                                    "v 1 1 0\nf 1 2 3\nf 2 4 3\n")
    mesh = glshade.load_mesh(tmp_path / "c.obj")
    assert np.allclose(mesh.colors, [[1, 0, 0, 1], [0, 0.5, 0, 1], [0, 0, 0.25, 1],
                                     [1, 1, 1, 1]])  # (white where a line has none)
    (tmp_path / "c.off").write_text("COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 128\n"
                                    "0 1 0 0 0 51 255\n3 0 1 2 0.5 0.25 1\n")
    mesh = glshade.load_mesh(tmp_path / "c.off")
    assert np.allclose(mesh.colors[:, :3], iec_decode([[255, 0, 0], [0, 255, 0], [0, 0, 51]]))
    assert np.allclose(mesh.colors[:, 3], [1, 128 / 255, 1])
    assert np.allclose(mesh.face_colors, [[0.5, 0.25, 1, 1]])


def test_a_gltf_color_0_is_linear(tmp_path):
    trimesh = pytest.importorskip("trimesh")
    box = trimesh.creation.box()
    rgba = np.random.default_rng(2).integers(0, 256, (len(box.vertices), 4), dtype=np.uint8)
    box.visual.vertex_colors = rgba
    box.export(tmp_path / "box.glb")
    mesh = glshade.load_mesh(tmp_path / "box.glb")
    # (the same vertices in the same order: glTF keeps them)
    assert np.allclose(mesh.vertices, box.vertices)
    assert np.abs(mesh.colors - rgba / 255.0).max() < 1e-12


def test_trimesh_both_ways_keeps_colours_uv_and_the_texture():
    trimesh = pytest.importorskip("trimesh")
    from PIL import Image
    from scipy.spatial import cKDTree

    sphere = glshade.geometry.primitives.uv_sphere(8, 12)
    rng = np.random.default_rng(0)
    colors = rng.random((sphere.n_vertices, 4))
    mesh = Mesh(sphere.vertices, sphere.faces, colors=colors, uv=sphere.uv)
    image = Image.new("RGB", (4, 2), (200, 10, 10))
    tm = mesh.to_trimesh(image=image)
    assert isinstance(tm.visual, trimesh.visual.TextureVisuals)
    # trimesh's bytes are sRGB: decoded, each is within half a step of the colour
    back = Mesh.from_trimesh(tm)
    _, nearest = cKDTree(sphere.vertices).query(back.vertices)
    assert np.abs(back.colors[:, 3] - colors[nearest, 3]).max() <= 0.5 / 255 + 1e-12
    step = np.abs(iec_decode(np.arange(1, 256)) - iec_decode(np.arange(255))).max()
    assert np.abs(back.colors[:, :3] - colors[nearest, :3]).max() <= step
    # the uv of each corner and the texture's pixels
    assert back.uv is not None and len(back.uv) == len(back.face_indices)
    drawn = glshade.Scene()
    drawn.add(back)  # (the part's material, made from its description: the image its map)
    (model,) = drawn.models
    assert model.material.texture.pixels[0, 0, :3].tolist() == [200, 10, 10]
    # face colours go over per triangle, each its polygon's
    faces = Mesh(sphere.vertices, sphere.faces, face_colors=rng.random((sphere.n_faces, 3)))
    tb = Mesh.from_trimesh(faces.to_trimesh())
    owner = faces.triangles[1]
    assert np.abs(tb.face_colors[:, :3] - faces.face_colors[owner, :3]).max() <= step
