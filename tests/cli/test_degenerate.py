"""Degenerate geometry through every command: meshes whose polygons are all collinear, a
single point, zero-area faces beside good ones, a NaN vertex, a mesh 1e-30 across, each as
a mesh file and inside a scene file with an emitter (radiosity). Every run ends with a
correct picture (0, a warning line at most: the blank ones say why) or 2 with one line that
names the input -- never a traceback, numpy's words or a half-written file."""

import re

import pytest

from tests.conftest import BACKEND, glshade

pytestmark = [pytest.mark.gl, pytest.mark.once]

MESHES = {
    "collinear": "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 1 2 3\nf 2 3 4\n",
    "one point": "v 1 1 1\nv 1 1 1\nv 1 1 1\nf 1 2 3\n",
    "zero-area beside good": "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 2 4 5\n",
    "nan vertex": "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n",
    "1e-30 across": "v 0 0 0\nv 1e-30 0 0\nv 0 1e-30 0\nf 1 2 3\n",
}
#: whether the mesh has a polygon of area (then a run draws it: status 0, no warning)
DRAWN = {"zero-area beside good"}
COMMANDS = {
    "render": [],
    "pathtrace": ["--spp", "2"],
    "compare": [],
    "compare-pathtrace": ["--reference", "pathtrace", "--spp", "2"],
    "hidden": [],
    "radiosity": ["--patch-size", "0.5", "--iterations", "2"],
    "radiosity-mc": ["--method", "monte-carlo", "--particles", "64"],
}
LAMP = """[[mesh]]
source = "{mesh}"
[[mesh]]
source = "primitive:plane"
translation = [0.0, 0.0, 2.0]
emission = [1.0, 1.0, 1.0]
"""


@pytest.mark.parametrize("command", sorted(COMMANDS))
@pytest.mark.parametrize("kind", sorted(MESHES))
def test_degenerate_meshes_end_well_in_every_command(tmp_path, kind, command):
    mesh = tmp_path / "m.obj"
    mesh.write_text(MESHES[kind])
    source = mesh
    if command.startswith("radiosity"):  # (radiosity reads scene files: an emitter beside)
        source = tmp_path / "m.toml"
        source.write_text(LAMP.format(mesh=mesh.as_posix()))
    out_dir = tmp_path / "out"
    out_dir.mkdir()
    done = glshade(command.split("-")[0], str(source), *COMMANDS[command], "-o",
                   str(out_dir / "x.png"), "--size", "24x24", "--backend", BACKEND)
    err = done.stderr.strip()
    assert "Traceback" not in err and not re.search(r"np\.\w+\(|array\(\[", err), err
    assert done.returncode in (0, 2), err
    left = sorted(p.name for p in out_dir.iterdir())
    if done.returncode:
        assert len(err.splitlines()) == 1 and err.startswith("glshade: error: ") and \
            str(source) in err, err
        assert left == []
        assert kind not in DRAWN or command.startswith("radiosity"), err
    else:
        assert "x.png" in left
        lines = [x for x in err.splitlines() if not x.startswith("glshade: warning: ")]
        assert lines == [], err
        if kind not in DRAWN and not command.startswith("radiosity"):
            assert "warning" in err, err  # (a blank picture says why)


@pytest.mark.parametrize("kind", sorted(MESHES))
def test_info_on_a_degenerate_mesh_is_facts_or_one_line(tmp_path, kind):
    mesh = tmp_path / "m.obj"
    mesh.write_text(MESHES[kind])
    done = glshade("info", str(mesh))
    assert done.returncode in (0, 2) and "Traceback" not in done.stderr, done.stderr
    if done.returncode:
        assert done.stderr.count("\n") == 1 and str(mesh) in done.stderr
    else:
        assert "faces" in done.stdout or "polygons" in done.stdout, done.stdout


@pytest.mark.parametrize("command", ["info", "render", "hidden", "compare", "pathtrace",
                                     "radiosity", "animate", "batch"])
@pytest.mark.parametrize("kind", ["mesh", "cloud", "empty"])
def test_every_command_on_a_mesh_a_cloud_and_an_empty_file(tmp_path, command, kind):
    """Each command that takes a model draws a point cloud or refuses it in one line naming
    the file -- never a traceback, never a half-empty table -- and an empty file is one
    line too."""
    source = tmp_path / "in" / f"{kind}.obj"
    source.parent.mkdir()
    source.write_text({"mesh": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
                       "cloud": "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n",
                       "empty": ""}[kind])
    out = tmp_path / ("out" if command == "batch" else "x.png")
    args = {"info": [str(source)], "batch": [str(source.parent), "-o", str(out), "-q"],
            "animate": [str(source), "-o", str(tmp_path / "x.gif"), "--frames", "2",
                        "--size", "32x24"]}.get(
        command, [str(source), "-o", str(out), "--size", "32x24"])
    if command == "pathtrace":
        args += ["--spp", "1"]
    r = glshade(command, *args, timeout=300)
    assert "Traceback" not in r.stderr, r.stderr
    if r.returncode != 0:
        lines = [x for x in r.stderr.strip().splitlines() if not x.startswith("glshade: warn")]
        assert r.returncode == 2 and len(lines) == 1, r.stderr
        assert source.name in lines[0] or command == "batch", r.stderr
    if command == "hidden" and kind == "cloud":
        assert r.returncode == 2 and "not polygons" in r.stderr
