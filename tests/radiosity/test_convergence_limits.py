"""Solvers that cannot converge say so: a closed room facing in whose every surface
reflects all of a colour (reflectance 1: the spectral radius of rho F is 1) is refused
before any work, in one line; a closed surface facing out, or a room losing any light,
solves; and a solver stopped at its cap reports that it did not converge (never success)."""

import numpy as np
import pytest

import glshade
from glshade import Mesh
from glshade.errors import InputError
from glshade.geometry import primitives
from glshade.radiosity import solve

from tests.conftest import glshade as run


def room(inward: bool = True) -> Mesh:
    cube = primitives.cube()
    return Mesh(cube.vertices, [list(f)[::-1] for f in cube.faces]) if inward else cube


def scene(mesh, color):
    s = glshade.Scene()
    s.add(mesh, glshade.Material(color=color, kd=1.0, emission=(1, 1, 1)))
    return s


@pytest.mark.parametrize("method", ["progressive", "gauss-seidel"])
def test_a_closed_lossless_room_is_refused_before_work(method):
    with pytest.raises(InputError, match=r"reflects all red, green, blue light .* never "
                                         r"dies out"):
        solve(scene(room(), (1, 1, 1)), patch_size=0.5, method=method, backend="auto")
    with pytest.raises(InputError, match="reflects all green light"):
        solve(scene(room(), (0.5, 1, 0.5)), patch_size=0.5, method=method)


@pytest.mark.gl
def test_a_room_that_loses_light_or_faces_out_solves():
    lossy = solve(scene(room(), (0.9, 0.9, 0.9)), patch_size=0.5, progress=False)
    assert lossy.converged and lossy.unshot_fraction <= 0.01
    out = solve(scene(room(False), (1, 1, 1)), patch_size=0.5, progress=False)
    assert out.converged


@pytest.mark.gl
def test_a_solver_stopped_at_its_cap_is_not_converged(monkeypatch):
    from glshade.radiosity import solvers

    monkeypatch.setattr(solvers, "MAX_SWEEPS", 2)
    sol = solve(scene(room(), (0.95, 0.95, 0.95)), patch_size=0.5, method="gauss-seidel",
                progress=False)
    assert not sol.converged and sol.history[-1][1] == 2
    shots = solve(scene(room(), (0.95, 0.95, 0.95)), patch_size=0.5, max_shots=3,
                  progress=False)
    assert not shots.converged and shots.unshot_fraction > 0.01


def test_the_cli_refuses_a_closed_lossless_room_in_one_line(tmp_path):
    from glshade.io import save_mesh

    save_mesh(room(), tmp_path / "room.obj")
    path = tmp_path / "room.toml"
    path.write_text('[[mesh]]\nsource = "room.obj"\nreflectance = [1.0, 1.0, 1.0]\n'
                    'emission = [1.0, 1.0, 1.0]\n')
    out_png = tmp_path / "room.png"
    done = run("radiosity", str(path), "-o", str(out_png), "-q")
    assert done.returncode == 2 and done.stderr.count("\n") == 1, done.stderr
    assert "never dies out" in done.stderr and not out_png.exists()


def test_patch_corners_weld_by_the_geometrys_scale_not_the_patch_size():
    """Two squares 1e-5 apart (distinct corners) cut into large patches keep their own
    vertices (the weld grid was a millionth of the patch size: 1e-4 here, which merged
    them), and tiny patches of a scene far from the origin weld without overflow."""
    from glshade.radiosity import PatchScene

    square = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
    pair = Mesh(np.r_[square, square + [1 + 1e-5, 0, 0]], [[0, 1, 2, 3], [4, 5, 6, 7]])
    s = scene(pair, (0.5, 0.5, 0.5))
    patches = PatchScene.from_scene(s, patch_size=100.0).patches
    assert len(patches.vertices) == 8
    far = Mesh(square * 1e-3 + 1e4, [[0, 1, 2, 3]])
    tiny = PatchScene.from_scene(scene(far, (0.5, 0.5, 0.5)), patch_size=1e-4).patches
    side = round(np.sqrt(tiny.n_patches))  # (a grid of side x side patches)
    assert side >= 10 and len(tiny.vertices) == (side + 1) ** 2  # (every corner welded)
    assert np.isfinite(tiny.vertices).all()
