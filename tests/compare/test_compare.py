"""Comparing shading modes on spheres, the grid, the sweep, and the CLI."""

import json
import subprocess
import sys

import numpy as np
import pytest

from glshade import Camera, Material, PointLight, Scene, compare
from glshade.compare import sweep
from glshade.io.images import LABEL_HEIGHT
from glshade.geometry import primitives as P

from tests.conftest import BACKEND, ROOT

pytestmark = pytest.mark.gl  # renders, also in subprocesses: run on every backend

CAM = Camera.look_at([0.4, 0.6, 3.3], [0, 0, 0], fov_y=40)
MAT = Material(color=(0.9, 0.75, 0.6), ks=0.5, shininess=30)


def sphere(level):
    s = Scene()
    s.add(P.icosphere(level), MAT)
    s.add_light(PointLight((3.0, 4.0, 5.0)))
    return s


@pytest.fixture(scope="module")
def levels(gl_context):
    from glshade.render.renderer import Renderer

    with Renderer(160, 160, samples=0, context=gl_context) as r:
        return {k: {m.mode: m for m in compare(sphere(k), CAM, renderer=r, size=(160, 160),
                                               diff=False).metrics} for k in (1, 2, 3, 4)}


def test_error_order_at_each_level_and_decrease(levels):
    for k, m in levels.items():
        assert m["flat"].mean_abs > m["gouraud"].mean_abs > m["phong"].mean_abs, k
    for mode in ("flat", "gouraud", "phong"):
        errs = [levels[k][mode].mean_abs for k in sorted(levels)]
        assert all(a > b for a, b in zip(errs, errs[1:])), (mode, errs)


def test_gouraud_loses_the_highlight_on_a_coarse_sphere(levels):
    m = levels[1]
    assert m["gouraud"].peak < m["phong"].peak - 20
    assert m["gouraud"].peak < m["gouraud"].reference_peak - 20
    assert abs(m["phong"].peak - m["phong"].reference_peak) < 5


def test_mach_bands_large_for_flat_near_zero_for_phong(levels):
    m = levels[2]
    assert m["flat"].mach_band > 5
    assert m["phong"].mach_band < 0.5


def test_grid_columns_in_order_with_labels(make_renderer):
    r = make_renderer(96, 80)
    c = compare(sphere(2), CAM, ("phong", "flat"), renderer=r, size=(96, 80), diff=True)
    img = c.image
    # (the heat maps carry two bands: the mode's mean and max, its PSNR and SSIM)
    assert img.shape == (2 * 80 + 3 * LABEL_HEIGHT, 3 * 96, 4)
    # each label band has text (bright pixels) and each tile shows its own render
    for col in range(3):
        band = img[:LABEL_HEIGHT, col * 96:(col + 1) * 96, :3]
        assert (band.max(-1) > 200).sum() > 15
    tiles = [img[LABEL_HEIGHT:LABEL_HEIGHT + 80, i * 96:(i + 1) * 96, :3].astype(int)
             for i in range(3)]
    np.testing.assert_allclose(tiles[0], np.clip(c.images["phong"] + 0.5, 0, 255).astype(int),
                               atol=0)
    np.testing.assert_allclose(tiles[1], np.clip(c.images["flat"] + 0.5, 0, 255).astype(int),
                               atol=0)
    assert [m.mode for m in c.metrics] == ["phong", "flat"]
    # the diff row has the colour bar in the last column
    bar = img[80 + 3 * LABEL_HEIGHT:, 2 * 96 + 4:2 * 96 + 18, :3]
    assert bar[0].mean() > bar[-1].mean()  # bright at the top (max), dark at 0
    assert c._repr_png_().startswith(b"\x89PNG")


def test_phong_fine_reference_and_given_image(make_renderer):
    r = make_renderer(64, 64)
    s = Scene()
    s.add(P.torus(1, 0.4, 12, 8), MAT)
    s.add_light(PointLight((3.0, 4.0, 5.0)))
    cam = Camera.look_at([0, 2.5, 3], [0, 0, 0])
    fine = compare(s, cam, renderer=r, size=(64, 64), reference="phong-fine")
    m = {x.mode: x for x in fine.metrics}
    assert m["flat"].mean_abs > m["phong"].mean_abs
    # a given image: a grey card over the torus's pixels; the error is computed by hand
    frame = r.render_frame(s, cam, "phong", color_dtype="f4")
    covered = frame.face_id >= 0
    card = np.where(covered[..., None], 100.0, 0.0) * np.ones(3)
    given = compare(s, cam, ["phong"], renderer=r, size=(64, 64), reference=card)
    shown = np.clip(frame.color[..., :3] * 255 + 0.5, 0, 255).astype(np.uint8)  # (8-bit)
    by_hand = np.abs(shown.astype(float) - 100)[covered].mean()
    assert given.metrics[0].mean_abs == pytest.approx(by_hand, rel=1e-6)
    assert given.metrics[0].pixels == covered.sum()
    from glshade import ComparisonError

    assert compare(s, cam, renderer=r, size=(64, 64)).reference_kind == "phong-fine"  # auto
    with pytest.raises(ComparisonError, match="exact surface"):
        compare(s, cam, renderer=r, size=(64, 64), reference="analytic")


def test_sweep_phong_converges_fastest(make_renderer):
    rows = sweep(P.icosphere, [1, 2, 3], size=(96, 96), renderer=make_renderer(96, 96))
    first, last = rows[0], rows[-1]
    ratio = {m: first[m].mean_abs / last[m].mean_abs for m in ("flat", "gouraud", "phong")}
    assert last["phong"].mean_abs < last["gouraud"].mean_abs < last["flat"].mean_abs
    assert ratio["flat"] < ratio["phong"]


def test_cli_compare_and_sweep(tmp_path):
    grid, metrics = tmp_path / "grid.png", tmp_path / "m.json"
    out = subprocess.run([sys.executable, "-m", "glshade", "compare", "primitive:icosphere:2",
                          "-o", str(grid), "--diff", "--json", str(metrics), "--size", "96x96",
                          "--backend", BACKEND, "--csv", str(tmp_path / "m.csv")],
                         capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 0, out.stderr
    data = json.loads(metrics.read_text())
    assert [m["mode"] for m in data["modes"]] == ["flat", "gouraud", "phong"]
    assert "PSNR" in out.stdout and grid.exists()
    assert (tmp_path / "m.csv").read_text().startswith("mode,mean_abs")
    plot = tmp_path / "sweep.png"
    out = subprocess.run([sys.executable, "-m", "glshade", "compare", "primitive:icosphere",
                          "--sweep", "--levels", "0..2", "-o", str(plot), "--size", "64x64",
                          "--backend", BACKEND], capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 0, out.stderr
    assert plot.exists() and len(out.stdout.strip().splitlines()) == 6
    bad = subprocess.run([sys.executable, "-m", "glshade", "compare", "assets/teapot.obj",
                          "-o", str(tmp_path / "x.png"), "--backend", BACKEND, "--reference",
                          "analytic"], capture_output=True, text=True, cwd=ROOT)
    assert bad.returncode == 2 and "phong-fine" in bad.stderr  # (asked for; it has none)


@pytest.mark.parametrize("mesh, reference", [("primitive:teapot", "phong-fine"),
                                             ("assets/lprism.obj", "phong-fine"),
                                             ("primitive:icosphere:2", "analytic")])
def test_compare_any_mesh_with_numbers_recomputed_from_the_saved_images(mesh, reference,
                                                                        tmp_path):
    """The CLI compares a teapot, a CAD part (a concave prism) and a sphere with its default
    reference (analytic where the mesh has one, else phong-fine) and exits 0; each mode's
    numbers equal numpy's, recomputed from the images it saved."""
    import json
    import subprocess
    import sys

    from PIL import Image

    from tests.conftest import ROOT

    out = subprocess.run([sys.executable, "-m", "glshade", "compare", mesh, "-o",
                          str(tmp_path / "grid.png"), "--size", "96x80", "--json",
                          str(tmp_path / "m.json"), "--save-tiles", str(tmp_path / "tiles")],
                         capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 0, out.stderr
    facts = json.loads((tmp_path / "m.json").read_text())
    assert facts["reference"] == reference
    load = lambda name: np.asarray(Image.open(tmp_path / "tiles" / name))[..., :3]  # noqa
    ref = load("reference.png").astype(float)
    for m in facts["modes"]:
        img = load(f"{m['mode']}.png").astype(float)
        mask = load(f"{m['mode']}-mask.png")[..., 0] > 127
        diff = np.abs(img - ref)[mask]
        assert mask.sum() == m["pixels"] > 100
        assert m["mean_abs"] == pytest.approx(diff.mean(), rel=1e-9)
        assert m["max_abs"] == pytest.approx(diff.max(), rel=1e-9)
        rmse = np.sqrt((diff ** 2).mean())
        assert m["rmse"] == pytest.approx(rmse, rel=1e-9)
        assert m["psnr"] == pytest.approx(20 * np.log10(255 / rmse), rel=1e-9)
        assert 0 < m["silhouette"] < m["pixels"]
    grid = np.asarray(Image.open(tmp_path / "grid.png"))
    assert grid.shape[0] == 2 * 80 + 3 * LABEL_HEIGHT  # (the heat maps are there by default)


def test_the_heat_maps_scale_is_robust_and_can_be_fixed(make_renderer):
    """On a teapot against phong-fine the maximum error sits on the silhouette; the maps'
    default scale is the 99th percentile off it (well below the maximum), silhouette pixels
    are shown apart, and a given scale is used as it is."""
    r = make_renderer(128, 96)
    s = Scene()
    s.add(P.teapot(4), MAT)
    s.add_light(PointLight((3.0, 4.0, 5.0)))
    cam = Camera.look_at([3.5, 3.0, 6.0], [0, 1.2, 0], fov_y=40)
    c = compare(s, cam, ("flat", "phong"), renderer=r, size=(128, 96))
    assert c.reference_kind == "phong-fine"
    worst = max(m.max_abs for m in c.metrics)
    assert 1.0 <= c.scale < 0.8 * worst
    assert all(m.silhouette > 0 for m in c.metrics)
    heat = c.image[80 + 2 * LABEL_HEIGHT + 16 + LABEL_HEIGHT:, :128, :3]
    magenta = (heat == np.array([200, 60, 200])).all(axis=-1)
    assert magenta.sum() == c.metrics[0].silhouette
    fixed = compare(s, cam, ("flat",), renderer=r, size=(128, 96), scale=40.0)
    assert fixed.scale == 40.0


@pytest.mark.parametrize("extra, words", [
    (["--save-tiles", "{tmp}/taken.txt"], "is a file, not a folder"),
    (["--json", "{tmp}/nowhere/m.json"], "does not exist"),
    (["--csv", "{tmp}/grid.png"], "must be different files"),
    (["--json", "{tmp}"], "is a folder, not a file"),
])
def test_every_output_is_checked_before_any_work(tmp_path, extra, words):
    """A compare whose outputs cannot all be written says so in one line before it renders,
    and writes nothing (the grid included)."""
    from tests.conftest import glshade

    (tmp_path / "taken.txt").write_text("mine")
    args = [a.replace("{tmp}", str(tmp_path)) for a in extra]
    out = glshade("compare", "primitive:icosphere:1", "-o", str(tmp_path / "grid.png"),
                  "--size", "32x32", *args)
    assert out.returncode == 2 and out.stderr.count("\n") == 1 and words in out.stderr, \
        out.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["taken.txt"]
    assert (tmp_path / "taken.txt").read_text() == "mine"


@pytest.mark.parametrize("part", ["assets/lprism.obj", "primitive:cube", "primitive:cylinder"])
def test_the_fine_reference_of_a_cad_part_keeps_its_shape(part, make_renderer):
    """A flat-faced part's phong-fine reference has the part's own silhouette: its hard
    edges are found from the mesh (the crease angle, said in the summary) and kept, so the
    reference covers the flat render's pixels within 1.5% -- where the curved refinement of
    the unsplit mesh bulges the part by more than 5% (what compare did by default)."""
    from glshade.compare.comparison import reference_image
    from glshade.geometry.merge import detect_crease
    from glshade.geometry.subdivide import phong_tessellate
    from glshade.io.meshes import load_source
    from glshade.options import DrawOptions

    mesh = load_source(part if part.startswith("primitive") else str(ROOT / part))
    scene = Scene()
    scene.add(mesh, MAT)
    scene.add_light(PointLight((3.0, 4.0, 5.0)))
    lo, hi = mesh.bounds
    centre, reach = (lo + hi) / 2, np.linalg.norm(hi - lo) / 2
    cam = Camera.look_at(centre + reach * np.array([1.6, 1.2, 2.0]), centre, fov_y=45)
    r = make_renderer(96, 96)
    _, ref_mask, _, crease = reference_image(scene, cam, "phong-fine", r, (96, 96), DrawOptions())
    assert crease is not None and crease == detect_crease(mesh)
    flat = r.render_frame(scene, cam, "flat").face_id >= 0
    assert abs(ref_mask.sum() / flat.sum() - 1) < 0.015
    rounded = Scene()
    rounded.add(phong_tessellate(mesh, 6), MAT)
    bulged = r.render_frame(rounded, cam, "flat").face_id >= 0
    assert abs(bulged.sum() / flat.sum() - 1) > 0.05
    c = compare(scene, cam, renderer=r, size=(96, 96))
    assert c.reference_crease == crease and f"{crease:.3g}°" in c.table()


@pytest.mark.parametrize("width", [20, 32, 48, 64, 96, 160, 400])
def test_labels_fit_any_tile(width):
    """A heat map's long label on tiles from 20 to 400 pixels wide: shrunk, then cut with
    an ellipsis, it never reaches the band's edges (it ran off small tiles) and is there."""
    from glshade.io.images import BACKGROUND, LABEL_HEIGHT, label

    tile = np.zeros((30, width, 3), np.uint8)
    band = label(tile, "PSNR 31.25 dB, SSIM 0.987")[:LABEL_HEIGHT].astype(int)
    ink = np.abs(band - np.array(BACKGROUND)).max(-1) > 40
    assert ink.any()
    assert not ink[:, :2].any() and not ink[:, -2:].any()


def test_view_and_eye_together_are_refused_in_one_line(tmp_path):
    out = subprocess.run([sys.executable, "-m", "glshade", "compare", "primitive:cube", "-o",
                          str(tmp_path / "g.png"), "--view", "front", "--eye", "1,2,3",
                          "--backend", BACKEND], capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 2 and out.stderr.count("\n") == 1
    assert "--view front frames its own camera; give --view or --eye, not both" in out.stderr
    assert not (tmp_path / "g.png").exists()


@pytest.mark.parametrize("source, levels, words", [
    ("patches:teapot", "0", "--levels: a patch sweep's tessellation levels run from 1 to 512, "
     "got 0"),
    ("primitive:icosphere", "2,9", "--levels: a sphere's subdivision levels run from 0 to 8, "
     "got 9"),
])
def test_a_sweep_names_levels_out_of_its_range(tmp_path, source, levels, words):
    """Each sweep checks the levels it can draw and names the option (a patch sweep without
    --levels once failed on the sphere default's level 0 with 'level must be ...')."""
    from tests.conftest import glshade

    out = glshade("compare", source, "--sweep", "--levels", levels, "-o",
                  str(tmp_path / "s.png"))
    assert out.returncode == 2 and out.stderr.strip() == f"glshade: error: {words}", out.stderr
    assert list(tmp_path.iterdir()) == []


def test_a_patch_sweep_draws_its_own_default_levels(tmp_path):
    from glshade.compare.sweeps import PATCH_SWEEP_LEVELS
    from tests.conftest import glshade

    out = glshade("compare", "patches:sphere", "--sweep", "-o", str(tmp_path / "s.png"),
                  "--size", "24x24", "--modes", "phong")
    assert out.returncode == 0, out.stderr
    drawn = [int(line.split()[0]) for line in out.stdout.splitlines()
             if line.strip()[:1].isdigit()]
    assert drawn == list(PATCH_SWEEP_LEVELS)
