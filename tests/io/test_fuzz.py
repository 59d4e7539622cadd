"""Hostile input: seeded mutations of small valid files in every format go through the
command line (in this process, for speed). Each ends with exit 0, or exit 2 and one line
naming the file -- never a traceback, a hang or a file left behind."""

import io
import os
from contextlib import redirect_stderr, redirect_stdout

import numpy as np
import pytest

from glshade import save_mesh
from glshade.cli import main
from glshade.geometry import primitives as P

MUTATIONS_PER_FILE = 300
TOKENS = [b"nan", b"inf", b"-inf", b"1e308", b"-1", b"0", b"1.5", b"999999999999", b"x",
          b"", b"-0", b"3 3 3", b"\xff\xfe", b"#", b"/", b"//"]


def seeds(tmp_path):
    """Small valid files: every reader and its variants."""
    mesh = P.cube().flipped().flipped()
    out = {}
    for name, binary in (("m.obj", False), ("m.off", False), ("a.ply", False),
                         ("b.ply", True), ("a.stl", False), ("b.stl", True)):
        path = tmp_path / name
        save_mesh(mesh, path, binary=binary)
        out[name] = path.read_bytes()
    big_endian = out["b.ply"].replace(b"binary_little_endian", b"binary_big_endian")
    out["be.ply"] = big_endian  # byte order misread on purpose: garbage in, clear error out
    return out


def mutate(data: bytes, rng) -> bytes:
    kind = rng.integers(7)
    b = bytearray(data)
    if kind == 0 and b:  # flip bytes
        for i in rng.integers(0, len(b), rng.integers(1, 6)):
            b[i] = int(rng.integers(256))
    elif kind == 1:  # truncate
        b = b[:rng.integers(0, len(b) + 1)]
    elif kind == 2:  # replace a token by a hostile one
        words = bytes(b).split(b" ")
        i = rng.integers(len(words))
        words[i] = TOKENS[rng.integers(len(TOKENS))] + words[i][-1:] * (words[i][-1:] == b"\n")
        b = bytearray(b" ".join(words))
    elif kind == 3:  # drop a line
        lines = bytes(b).split(b"\n")
        del lines[rng.integers(len(lines))]
        b = bytearray(b"\n".join(lines))
    elif kind == 4:  # repeat a line
        lines = bytes(b).split(b"\n")
        i = rng.integers(len(lines))
        lines.insert(i, lines[i])
        b = bytearray(b"\n".join(lines))
    elif kind == 5:  # insert random bytes
        i = rng.integers(len(b) + 1)
        b[i:i] = rng.integers(0, 256, rng.integers(1, 12)).astype(np.uint8).tobytes()
    else:  # change a number by a digit
        digits = [i for i, c in enumerate(b) if 48 <= c <= 57]
        if digits:
            b[digits[rng.integers(len(digits))]] = 48 + int(rng.integers(10))
    return bytes(b)


def run(*args):
    err, out = io.StringIO(), io.StringIO()
    with redirect_stderr(err), redirect_stdout(out):
        code = main(list(args))
    return code, err.getvalue()


@pytest.mark.filterwarnings("error")  # a numpy warning on bad input is a defect too
@pytest.mark.parametrize("name", ["m.obj", "m.off", "a.ply", "b.ply", "be.ply", "a.stl",
                                  "b.stl"])
def test_mutated_files_exit_0_or_2_with_one_line(tmp_path, name):
    rng = np.random.default_rng(sum(map(ord, name)))
    source = seeds(tmp_path)[name]
    work = tmp_path / "fuzz"
    work.mkdir()
    outcomes = {0: 0, 2: 0}
    for i in range(MUTATIONS_PER_FILE):
        path = work / f"case{i}{os.path.splitext(name)[1]}"
        path.write_bytes(mutate(source, rng))
        code, err = run("info", str(path), "--json")
        assert code in (0, 2), f"{path.name}: exit {code}: {err}"
        if code == 2:
            assert err.count("\n") == 1 and str(path) in err, (path.read_bytes()[:200], err)
        outcomes[code] += 1
    assert outcomes[2] > 10  # the mutations do break files
    assert sorted(p.name for p in work.iterdir()) == sorted(
        f"case{i}{os.path.splitext(name)[1]}" for i in range(MUTATIONS_PER_FILE))


@pytest.mark.gl
@pytest.mark.parametrize("name", ["m.obj", "b.ply"])
def test_mutated_files_render_or_exit_2_and_leave_only_good_outputs(tmp_path, name):
    import warnings

    from glshade.errors import RenderWarning
    from tests.conftest import BACKEND

    rng = np.random.default_rng(7 + len(name))
    source = seeds(tmp_path)[name]
    work, out = tmp_path / "fuzz", tmp_path / "out"
    work.mkdir()
    out.mkdir()
    rendered = []
    for i in range(25):
        path = work / f"case{i}{os.path.splitext(name)[1]}"
        path.write_bytes(mutate(source, rng))
        png = out / f"case{i}.png"
        with warnings.catch_warnings():
            warnings.simplefilter("default", RenderWarning)  # a broken mesh may draw nothing
            code, err = run("render", str(path), "-o", str(png), "--size", "24x24",
                            "--samples", "0", "--backend", BACKEND, "-q")
        assert code in (0, 2), f"{path.name}: exit {code}: {err}"
        if code == 0:
            rendered.append(png.name)
        else:
            assert err.count("\n") == 1 and str(path) in err, err
    assert 0 < len(rendered) < 25
    assert sorted(p.name for p in out.iterdir()) == sorted(rendered)


@pytest.mark.filterwarnings("error")
@pytest.mark.parametrize("endian, count_type, index_type", [
    ("little", "uchar", "int"), ("little", "int", "uint"), ("big", "char", "short"),
    ("big", "ushort", "int")])
def test_binary_ply_face_lists_with_hostile_counts(tmp_path, endian, count_type, index_type):
    """Counts of 0, 1, 2, negative or huge, in truncated records, for every list layout."""
    import struct

    e = "<" if endian == "little" else ">"
    cfmt = {"uchar": "B", "int": "i", "char": "b", "ushort": "H"}[count_type]
    ifmt = {"int": "i", "uint": "I", "short": "h"}[index_type]
    rng = np.random.default_rng(len(count_type) * 7 + len(index_type))
    vertices = struct.pack(e + "9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    choices = [0, 1, 2, 3, 4, 100] + ([-1] if cfmt in "ib" else [])
    for i in range(120):
        n_faces = int(rng.integers(1, 5))
        records = b""
        for _ in range(n_faces):
            c = int(rng.choice(choices))
            records += struct.pack(e + cfmt, c) + b"".join(
                struct.pack(e + ifmt, int(rng.integers(0, 4))) for _ in range(max(0, min(c, 5))))
        header = (f"ply\nformat binary_{endian}_endian 1.0\nelement vertex 3\n"
                  "property float x\nproperty float y\nproperty float z\n"
                  f"element face {n_faces}\nproperty list {count_type} {index_type} "
                  "vertex_indices\nend_header\n").encode()
        path = tmp_path / f"case{i}.ply"
        path.write_bytes(header + vertices + records[:int(rng.integers(0, len(records) + 1))])
        code, err = run("info", str(path), "--json")
        assert code in (0, 2), f"{path.name}: exit {code}: {err}"
        if code == 2:
            assert err.count("\n") == 1 and str(path) in err, err


MTL_SEED = b"""# a library
newmtl a
Ka 0.1 0.1 0.1
Kd 0.8 0.5 0.2
Ks 0.5 0.5 0.5
Ns 40
d 0.9
illum 2
map_Kd -clamp on -s 2 2 -o 0.5 0 t.png
newmtl b
Kd 0.2 0.3 0.9
map_d t.png
"""


def test_mutated_material_libraries_exit_0_or_2_with_one_line(tmp_path):
    """An OBJ whose MTL is mutated (and its texture line with it): ``info`` ends with exit 0
    (warnings, one line each, for what it cannot use) or exit 2 and one line naming the
    MTL file -- never a traceback."""
    import warnings

    from PIL import Image

    Image.fromarray(np.zeros((2, 2, 3), np.uint8)).save(tmp_path / "t.png")
    rng = np.random.default_rng(45)
    outcomes = {0: 0, 2: 0}
    for i in range(200):
        (tmp_path / f"case{i}.mtl").write_bytes(mutate(MTL_SEED, rng))
        obj = tmp_path / f"case{i}.obj"
        obj.write_text(f"mtllib case{i}.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\n"
                       "vt 0 1\nusemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 1/1 3/3 2/2\n")
        with warnings.catch_warnings():
            warnings.simplefilter("default")
            code, err = run("info", str(obj), "--json")
        assert code in (0, 2), f"case{i}: exit {code}: {err}"
        assert "Traceback" not in err, err
        if code == 2:
            assert err.count("\n") == 1 and f"case{i}.mtl" in err, err
        outcomes[code] += 1
    assert outcomes[2] > 10 and outcomes[0] > 10, outcomes
