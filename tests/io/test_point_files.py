"""Point sets from PLY (ASCII and binary) and OBJ files: the values written come back (the
writer here is numpy's own bytes, not glshade's), colours decoded from sRGB bytes, normals
made unit; bad files are one line naming the file and what is wrong."""

import numpy as np
import pytest

import glshade
from tests.conftest import BACKEND, glshade as run_glshade

RNG = np.random.default_rng(7)
POINTS = RNG.normal(size=(50, 3))
NORMALS = RNG.normal(size=(50, 3))
COLORS = RNG.integers(0, 256, (50, 3)).astype(np.uint8)

HEADER = ("ply\nformat {fmt} 1.0\nelement vertex 50\nproperty float x\nproperty float y\n"
          "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
          "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n")


def _srgb_decode(c):  # IEC 61966-2-1, written out here
    c = c / 255.0
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


@pytest.mark.parametrize("fmt", ["ascii", "binary_little_endian", "binary_big_endian"])
def test_ply_points_normals_and_colours_come_back(tmp_path, fmt):
    path = tmp_path / "scan.ply"
    p32, n32 = POINTS.astype(np.float32), NORMALS.astype(np.float32)
    if fmt == "ascii":
        rows = "".join(" ".join([*(repr(float(x)) for x in p), *(repr(float(x)) for x in n),
                                 *(str(int(x)) for x in c)]) + "\n"
                       for p, n, c in zip(p32, n32, COLORS))
        path.write_bytes((HEADER.format(fmt=fmt) + rows).encode())
    else:
        order = "<" if fmt.endswith("little_endian") else ">"
        rec = np.zeros(50, [(k, order + "f4") for k in ("x", "y", "z", "nx", "ny", "nz")] +
                       [(k, "u1") for k in ("r", "g", "b")])
        for i, k in enumerate(("x", "y", "z")):
            rec[k] = p32[:, i]
        for i, k in enumerate(("nx", "ny", "nz")):
            rec[k] = n32[:, i]
        for i, k in enumerate(("r", "g", "b")):
            rec[k] = COLORS[:, i]
        path.write_bytes(HEADER.format(fmt=fmt).encode() + rec.tobytes())
    cloud = glshade.load_points(path)
    assert cloud.n_points == 50
    np.testing.assert_array_equal(cloud.points, p32.astype(np.float64))
    unit = n32.astype(np.float64) / np.linalg.norm(n32.astype(np.float64), axis=1)[:, None]
    np.testing.assert_allclose(cloud.normals, unit, rtol=0, atol=1e-12)
    np.testing.assert_allclose(cloud.colors, _srgb_decode(COLORS.astype(np.float64)),
                               rtol=0, atol=1e-12)
    diagonal = np.linalg.norm(p32.max(0).astype(float) - p32.min(0))
    assert cloud.radius == pytest.approx(diagonal / 200)


def test_obj_vertices_alone_are_points(tmp_path):
    path = tmp_path / "samples.obj"
    rows = "".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in POINTS.tolist())
    path.write_text("# samples\n" + rows)
    cloud = glshade.load_points(path, radius=0.1, style="square")
    np.testing.assert_array_equal(cloud.points, POINTS)
    assert cloud.colors is None and cloud.radius == 0.1


@pytest.mark.parametrize("body, message", [
    ("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
     "property float z\nend_header\n0 0 0\n1 2\n", r"bad.ply:9: vertex 1 has 2 values"),
    ("ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
     "property float z\nend_header\n0 0 0\n1 inf 2\n", r"points\[1\] is not finite"),
    ("ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\n"
     "end_header\n", "a point set needs a 'vertex' element"),
])
def test_bad_point_files_are_one_line_naming_the_file(tmp_path, body, message):
    path = tmp_path / "bad.ply"
    path.write_text(body)
    with pytest.raises(glshade.MeshFormatError, match=message) as caught:
        glshade.load_points(path)
    assert "bad.ply" in str(caught.value) and "\n" not in str(caught.value)
    r = run_glshade("render", str(path), "-o", str(tmp_path / "x.png"))
    assert r.returncode == 2 and r.stderr.count("\n") == 1, r.stderr


@pytest.mark.gl
def test_the_command_line_draws_a_point_file(tmp_path):
    from PIL import Image

    path = tmp_path / "scan.ply"
    rows = "".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in POINTS.tolist())
    path.write_text("ply\nformat ascii 1.0\nelement vertex 50\nproperty double x\n"
                    "property double y\nproperty double z\nend_header\n" + rows)
    out = tmp_path / "scan.png"
    r = run_glshade("render", str(path), "-o", str(out), "--size", "120x90", "--samples",
                    "0", "--backend", BACKEND)
    assert r.returncode == 0, r.stderr
    assert "50 points" in r.stdout
    lit = np.asarray(Image.open(out))[..., :3].max(-1) > 10
    assert 0.002 < lit.mean() < 0.5
    info = run_glshade("info", str(path))
    assert info.returncode == 0 and "600 (12 a point)" in info.stdout.replace(",", "")
