"""BOP and COCO data sets read back by readers that share nothing with the writers: BOP
through a reader written here from the format's document (JSON, 16-bit PNG depth in mm x
depth_scale, matrices row by row), COCO through pycocotools itself."""

import hashlib
import json
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from tests.conftest import glshade as run_glshade
from tests.conftest import require

cv2 = require("cv2", "OpenCV projects the poses")
trimesh = require("trimesh", "closest points on the models")

from glshade import Camera, GlshadeError, Scene, dataset  # noqa: E402
from glshade.geometry import primitives as P  # noqa: E402

SIZE = (64, 48)


def _scene():
    scene = Scene()
    scene.add(P.cube(), label="box", translation=(-0.7, 0.0, 0.0), scale=0.6)
    scene.add(P.icosphere(2), label="ball", translation=(0.6, 0.1, 0.2), scale=0.5)
    scene.add(P.cube(), label="box", translation=(0.1, 0.2, -0.9), scale=0.6)
    return scene


def _png(path):
    with Image.open(path) as im:
        return np.asarray(im)


def read_bop(root: Path):
    """The BOP format's document, read literally: scene_camera/scene_gt/scene_gt_info keyed
    by image id; cam_K and the R's 9 numbers row by row; t's 3 in mm; depth PNG x
    depth_scale = mm; masks named {im_id:06d}_{gt_id:06d}.png."""
    folder = root / "train" / "000000"
    cams = json.loads((folder / "scene_camera.json").read_text())
    gts = json.loads((folder / "scene_gt.json").read_text())
    infos = json.loads((folder / "scene_gt_info.json").read_text())
    views = []
    for key in sorted(cams, key=int):
        im = int(key)
        c = cams[key]
        view = {"K": np.array(c["cam_K"]).reshape(3, 3), "R": np.array(c["cam_R_w2c"])
                .reshape(3, 3), "t": np.array(c["cam_t_w2c"]),
                "rgb": _png(folder / "rgb" / f"{im:06d}.png"),
                "depth": _png(folder / "depth" / f"{im:06d}.png").astype(float)
                * c["depth_scale"], "objects": []}
        for g, (gt, info) in enumerate(zip(gts[key], infos[key])):
            view["objects"].append({
                "R": np.array(gt["cam_R_m2c"]).reshape(3, 3), "t": np.array(gt["cam_t_m2c"]),
                "obj_id": gt["obj_id"], **info,
                "mask": _png(folder / "mask" / f"{im:06d}_{g:06d}.png") > 127,
                "mask_visib": _png(folder / "mask_visib" / f"{im:06d}_{g:06d}.png") > 127})
        views.append(view)
    return views


def _tree_hash(root: Path) -> str:
    h = hashlib.sha256()
    for p in sorted(root.rglob("*")):
        if p.is_file():
            h.update(str(p.relative_to(root)).encode() + p.read_bytes())
    return h.hexdigest()


@pytest.fixture(scope="module")
def bop(tmp_path_factory, gl_context):
    root = tmp_path_factory.mktemp("bop")
    dataset.write_bop(_scene(), root, views=4, size=SIZE, depth_scale=0.5, units="m",
                      progress=False, context=gl_context)
    return root


def test_every_pose_recomposed_with_K_lands_the_model_in_its_own_mask(bop):
    """BOP's check: each model file's vertices (mm), moved by cam_R_m2c and cam_t_m2c and
    projected by cam_K (OpenCV), land inside the object's own full mask."""
    models = {int(p.stem[4:]): trimesh.load(p, process=False)
              for p in sorted((bop / "models").glob("obj_*.ply"))}
    assert sorted(models) == [1, 2]
    seen = 0
    for view in read_bop(bop):
        for obj in view["objects"]:
            v = np.asarray(models[obj["obj_id"]].vertices)
            uv, _ = cv2.projectPoints(v, cv2.Rodrigues(obj["R"])[0], obj["t"], view["K"], None)
            col, row = np.floor(uv.reshape(-1, 2) + 0.5).astype(int).T
            pad = np.pad(obj["mask"], 1)
            grown = np.any([pad[1 + dy:1 + dy + SIZE[1], 1 + dx:1 + dx + SIZE[0]]
                            for dy in (-1, 0, 1) for dx in (-1, 0, 1)], axis=0)
            inside = (col >= 0) & (col < SIZE[0]) & (row >= 0) & (row < SIZE[1])
            assert grown[row[inside], col[inside]].all()
            seen += inside.sum()
    assert seen > 100


def test_rgb_images_are_three_channels_showing_the_objects(bop):
    """BOP's rgb/ images are 8-bit RGB (the toolkit's readers take three channels): the
    background's colour everywhere a pixel from every visible mask (MSAA blends the
    silhouettes' pixels), and never inside one."""
    def grown(mask):
        pad = np.pad(mask, 1)
        return np.any([pad[1 + dy:1 + dy + SIZE[1], 1 + dx:1 + dx + SIZE[0]]
                       for dy in (-1, 0, 1) for dx in (-1, 0, 1)], axis=0)

    for view in read_bop(bop):
        rgb = view["rgb"]
        assert rgb.shape == (SIZE[1], SIZE[0], 3) and rgb.dtype == np.uint8
        seen = np.any([obj["mask_visib"] for obj in view["objects"]], axis=0)
        near, inner = grown(seen), ~grown(~seen)
        background = rgb[~near]
        assert len(background) > 100 and (background == background[0]).all()
        assert inner.sum() > 100 and not (rgb[inner] == background[0]).all(1).any()


def test_depth_back_projected_lies_on_the_models(bop):
    """Each visible pixel's depth (mm), back-projected through cam_K and moved into its
    object's model frame by the pose, lies on that model's surface (within the depth's
    0.5 mm step and a float's rounding)."""
    models = {int(p.stem[4:]): trimesh.load(p, process=False)
              for p in sorted((bop / "models").glob("obj_*.ply"))}
    checked = 0
    for view in read_bop(bop):
        rows, cols = np.mgrid[0:SIZE[1], 0:SIZE[0]]
        for obj in view["objects"]:
            m = obj["mask_visib"] & (view["depth"] > 0)
            if not m.any():
                continue
            z = view["depth"][m]
            pix = np.stack([cols[m], rows[m], np.ones(m.sum())], -1)
            cam = (pix @ np.linalg.inv(view["K"]).T) * z[:, None]
            local = (cam - obj["t"]) @ obj["R"]  # (R^T (x - t))
            _, gap, _ = trimesh.proximity.closest_point(models[obj["obj_id"]], local)
            assert gap.max() < 0.5, gap.max()
            checked += m.sum()
    assert checked > 300


def test_the_info_agrees_with_the_masks(bop):
    info = json.loads((bop / "glshade_info.json").read_text())
    assert "llvmpipe" in info["renderer"] and info["glshade"]   # (what drew the views)
    for view in read_bop(bop):
        for obj in view["objects"]:
            assert (obj["mask_visib"] <= obj["mask"]).all()
            assert obj["px_count_all"] == obj["mask"].sum()
            assert obj["px_count_visib"] == obj["mask_visib"].sum()
            assert obj["visib_fract"] == pytest.approx(obj["px_count_visib"] /
                                                       obj["px_count_all"])
            for box, mask in ((obj["bbox_obj"], obj["mask"]),
                              (obj["bbox_visib"], obj["mask_visib"])):
                if not mask.any():
                    assert box == [-1, -1, -1, -1]
                    continue
                rows, cols = np.nonzero(mask)
                assert box == [cols.min(), rows.min(), cols.max() - cols.min() + 1,
                               rows.max() - rows.min() + 1]


def test_a_rerun_writes_the_same_bytes_and_resumes(bop, tmp_path, gl_context):
    before = _tree_hash(bop)
    dataset.write_bop(_scene(), bop, views=4, size=SIZE, depth_scale=0.5, units="m",
                      progress=False, context=gl_context)
    assert _tree_hash(bop) == before
    # a run cut short: view 2's record and files gone -- only it is drawn again
    folder = bop / "train" / "000000"
    for p in [folder / ".views" / "000002.json", *folder.glob("*/000002*.png")]:
        p.unlink()
    kept = (folder / "rgb" / "000001.png").stat().st_mtime_ns
    dataset.write_bop(_scene(), bop, views=4, size=SIZE, depth_scale=0.5, units="m",
                      progress=False, context=gl_context)
    assert _tree_hash(bop) == before
    assert (folder / "rgb" / "000001.png").stat().st_mtime_ns == kept
    fresh = tmp_path / "again"
    dataset.write_bop(_scene(), fresh, views=4, size=SIZE, depth_scale=0.5, units="m",
                      progress=False, context=gl_context)
    assert _tree_hash(fresh) == before


def test_coco_masks_decode_to_the_visible_masks(tmp_path, make_renderer, gl_context):
    coco_module = require("pycocotools.coco", "COCO's own reader")
    scene = _scene()
    cameras = dataset.sphere_cameras(scene.bounds, 3, SIZE)
    path = dataset.write_coco(scene, tmp_path, cameras=cameras, size=SIZE, progress=False,
                              context=gl_context)
    coco = coco_module.COCO(str(path))
    assert {c["name"]: c["id"] for c in coco.loadCats(coco.getCatIds())} == {"box": 1,
                                                                              "ball": 2}
    renderer = make_renderer(*SIZE)
    for image_id, camera in zip(sorted(coco.getImgIds()), cameras):
        truth = {a.instance_id: a for a in renderer.annotate(scene, camera)}
        anns = coco.loadAnns(coco.getAnnIds(imgIds=[image_id]))
        assert {a["instance_id"] for a in anns} == {k for k, a in truth.items()
                                                    if a.px_count_visib}
        for ann in anns:
            mask = coco.annToMask(ann).astype(bool)
            assert np.array_equal(mask, truth[ann["instance_id"]].mask_visib)
            assert ann["area"] == mask.sum() and ann["iscrowd"] == 0
            assert ann["category_id"] == truth[ann["instance_id"]].obj_id
        assert (tmp_path / coco.loadImgs(image_id)[0]["file_name"]).is_file()
    assert "llvmpipe" in coco.dataset["info"]["renderer"]   # (what drew the views)


def test_the_command_writes_a_set_and_refuses_bad_input(tmp_path):
    scene = tmp_path / "s.toml"
    scene.write_text('[render]\nsize = [48, 32]\n[[mesh]]\nsource = "primitive:cube"\n'
                     'label = "box"\n')
    out = tmp_path / "set"
    r = run_glshade("dataset", str(scene), "-o", str(out), "--views", "2", "-q")
    assert r.returncode == 0, r.stderr
    assert len(read_bop(out)) == 2
    r = run_glshade("dataset", str(scene), "-o", str(tmp_path / "x"), "--views", "0")
    assert r.returncode == 2 and "--views" in r.stderr and not (tmp_path / "x").exists()
    scene.write_text(scene.read_text().replace('label = "box"', "label = 3"))
    r = run_glshade("dataset", str(scene), "-o", str(tmp_path / "y"))
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1
    assert "'label' must be a non-empty string, got 3" in r.stderr


def test_bad_arguments_are_refused_before_anything_is_written(tmp_path):
    with pytest.raises(GlshadeError, match="units must be 'mm' or 'm'"):
        dataset.write_bop(_scene(), tmp_path / "a", views=1, units="cm")
    with pytest.raises(GlshadeError, match="depth_scale must be a number > 0"):
        dataset.write_bop(_scene(), tmp_path / "a", views=1, depth_scale=0)
    with pytest.raises(GlshadeError, match="views must be a whole number >= 1"):
        dataset.write_bop(_scene(), tmp_path / "a", views=0)
    scene = _scene()
    scene.models[2].transform[:3, :3] *= 2  # (a box twice the size of the other)
    with pytest.raises(GlshadeError, match=r"instances 1 and 3 of 'box' are scaled "
                                           r"differently \(\(0\.6, 0\.6, 0\.6\) and "
                                           r"\(1\.2, 1\.2, 1\.2\)"):
        dataset.write_bop(scene, tmp_path / "a", views=1)
    assert not (tmp_path / "a").exists()


def test_a_camera_list_is_the_views(tmp_path, gl_context):
    cameras = [Camera.look_at((0, 0, 4), (0, 0, 0)), Camera.look_at((4, 0, 0), (0, 0, 0))]
    where = dataset.write_bop(_scene(), tmp_path, cameras=cameras, size=SIZE,
                              progress=False, context=gl_context)
    cams = json.loads((where / "scene_camera.json").read_text())
    assert list(cams) == ["0", "1"]
    R = np.array(cams["1"]["cam_R_w2c"]).reshape(3, 3)
    assert np.allclose(R @ [1, 0, 0], [0, 0, -1])  # (the camera on +x looks down -x: its z)


@pytest.mark.parametrize("where", ["processes", "cluster"])
def test_workers_write_the_same_bytes(bop, tmp_path, where):
    """The views shared among two local worker processes, or a Dask LocalCluster's two
    workers (a real scheduler, stopped after): the same files as one process wrote."""
    if where == "cluster":
        require("distributed", "the Dask cluster")
    out = tmp_path / where
    dataset.write_bop(_scene(), out, views=4, size=SIZE, depth_scale=0.5, units="m",
                      progress=False, jobs=2,
                      scheduler="local" if where == "cluster" else None)
    assert _tree_hash(out) == _tree_hash(bop)


def test_a_path_traced_set_has_the_raster_sets_masks_depth_and_poses(bop, tmp_path,
                                                                      gl_context):
    """``images="pathtrace"``: the masks, depth and every JSON byte-identical to the
    raster set's (they are the raster's exact buffers of the same cameras); each colour
    image the tracer's picture of its view, encoded as 8 bits."""
    from glshade.dataset.views import load_scene_arg
    from glshade.pathtrace import TraceScene, trace

    out = tmp_path / "traced"
    dataset.write_bop(_scene(), out, views=4, size=SIZE, depth_scale=0.5, units="m",
                      progress=False, context=gl_context, images="pathtrace", spp=8)
    a, b = bop / "train" / "000000", out / "train" / "000000"
    for sub in ("depth", "mask", "mask_visib"):
        names = sorted(p.name for p in (a / sub).glob("*.png"))
        assert names and names == sorted(p.name for p in (b / sub).glob("*.png"))
        assert all((a / sub / n).read_bytes() == (b / sub / n).read_bytes() for n in names)
    for name in ("scene_camera.json", "scene_gt.json", "scene_gt_info.json"):
        assert (a / name).read_bytes() == (b / name).read_bytes()
    _, cameras, _ = load_scene_arg(_scene(), 4, SIZE)
    for k, camera in enumerate(cameras):
        lit = TraceScene.from_scene(_scene(), camera=camera)  # (the headlight: no lights)
        traced = trace(lit, camera, SIZE, spp=8, context=gl_context, progress=False)
        want = np.round(np.clip(traced.image, 0, 1) * 255).astype(np.uint8)
        assert np.array_equal(_png(b / "rgb" / f"{k:06d}.png"), want)
        assert not np.array_equal(_png(a / "rgb" / f"{k:06d}.png"), want)  # (not the raster's)
    r = run_glshade("dataset", "assets/scenes/spheres.toml", "-o", str(tmp_path / "x"),
                    "--spp", "4")
    assert r.returncode == 2 and "--spp is for --images pathtrace" in r.stderr


@pytest.mark.parametrize("fmt", ["bop", "coco"])
@pytest.mark.parametrize("fault", ["deleted", "truncated", "record_only"])
def test_a_resume_remakes_the_views_whose_files_are_gone_or_torn(tmp_path, gl_context, fmt,
                                                                 fault):
    """A resumed run checks the files themselves, not its records alone: a view whose
    image or depth was deleted, cut short, or whose record outlived every file, is drawn
    again -- and the set is then byte for byte the one a fresh run writes."""
    def write(out):
        if fmt == "bop":
            dataset.write_bop(_scene(), out, views=3, size=SIZE, units="m", progress=False,
                              context=gl_context)
        else:
            dataset.write_coco(_scene(), out, views=3, size=SIZE, progress=False,
                               context=gl_context)

    fresh, hurt = tmp_path / "fresh", tmp_path / "hurt"
    write(fresh)
    write(hurt)
    folder = hurt / "train" / "000000" if fmt == "bop" else hurt
    images = sorted((folder / ("rgb" if fmt == "bop" else "images")).glob("*.png"))
    victim = images[1]
    if fault == "deleted":
        victim.unlink()
        if fmt == "bop":
            (folder / "depth" / victim.name).unlink()
    elif fault == "truncated":
        victim.write_bytes(victim.read_bytes()[:40])
    else:  # (every file of every view gone, the records kept)
        for image in images:
            image.unlink()
    stamps = {p: p.stat().st_mtime_ns for p in images if p.exists() and p != victim}
    write(hurt)
    assert _tree_hash(hurt) == _tree_hash(fresh)
    if fault != "record_only":  # (the whole views were kept as they were)
        assert all(p.stat().st_mtime_ns == t for p, t in stamps.items())


def test_models_carry_normals_and_an_info_bops_evaluation_reads(bop):
    """Each model PLY has vertex normals (BOP's format asks for them; trimesh reads them
    back unit length, on the outside), and models_info.json gives each model's diameter --
    against scipy's pairwise distances over trimesh's convex hull -- and its box, in mm."""
    from scipy.spatial.distance import pdist

    info = json.loads((bop / "models" / "models_info.json").read_text())
    plys = sorted((bop / "models").glob("obj_*.ply"))
    assert sorted(int(k) for k in info) == [int(p.stem[4:]) for p in plys]
    header = plys[0].read_bytes()[:400].decode("latin-1")
    assert all(f"property double {c}" in header for c in ("nx", "ny", "nz"))
    for path in plys:
        mesh = trimesh.load(path, process=False)
        n = np.asarray(mesh.vertex_normals)
        assert np.allclose(np.linalg.norm(n, axis=1), 1.0, atol=1e-6)
        outward = np.einsum("ij,ij->i", n, mesh.vertices - mesh.vertices.mean(0))
        assert (outward > 0).mean() > 0.9
        entry = info[path.stem[4:].lstrip("0") or "0"]
        hull = mesh.convex_hull.vertices
        assert entry["diameter"] == pytest.approx(pdist(hull).max(), rel=1e-12)
        lo, hi = mesh.vertices.min(0), mesh.vertices.max(0)
        assert [entry[f"min_{a}"] for a in "xyz"] == pytest.approx(lo.tolist())
        assert [entry[f"size_{a}"] for a in "xyz"] == pytest.approx((hi - lo).tolist())


def test_an_object_cut_by_the_border_counts_its_whole_projection(make_renderer):
    """BOP's visib_fract divides by the whole silhouette, in the image or not: a ball
    mostly outside the view -- px_count_all against an exact ray cast over an image three
    times as wide and high around the view's, visib_fract the in-image share of it."""
    scene = Scene()
    scene.add(P.uv_sphere(96, 192), label="ball", translation=(1.35, 0.0, 0.0))
    camera = Camera.look_at((0.0, 0.0, 4.0), (0.0, 0.0, 0.0), fov_y=30.0)
    w, h = SIZE
    note, = make_renderer(w, h, samples=0).annotate(scene, camera)
    K, R, t = camera.to_opencv((w, h))
    K = K.copy()
    K[0, 2] += w
    K[1, 2] += h
    o, d = Camera.from_opencv(K, R, t, (3 * w, 3 * h)).rays((3 * w, 3 * h))
    c = o - np.array([1.35, 0.0, 0.0])
    b = np.einsum("...k,...k", c, d)
    hit = b * b - (np.einsum("...k,...k", c, c) - 1) > 0
    inside = hit[h:2 * h, w:2 * w]
    # (the uv sphere's facets lie inside the ball: a few edge pixels less)
    assert note.px_count_all == pytest.approx(hit.sum(), rel=0.01)
    assert note.px_count_visib == pytest.approx(inside.sum(), rel=0.03)
    assert note.visib_fract == pytest.approx(inside.sum() / hit.sum(), rel=0.03)
    assert note.visib_fract < 0.5 and note.bbox_obj[0] + note.bbox_obj[2] > w


def test_a_lit_scenes_traced_views_share_one_traced_scene(tmp_path, gl_context):
    """With a light the traced scene does not depend on the view: made once, every view's
    image is still the tracer's picture of that view."""
    from glshade import PointLight
    from glshade.dataset.views import load_scene_arg
    from glshade.pathtrace import trace

    def lit():
        scene = _scene()
        scene.add_light(PointLight((2.0, 3.0, 4.0), intensity=1.5))
        return scene

    out = dataset.write_bop(lit(), tmp_path / "lit", views=3, size=SIZE, units="m",
                            progress=False, context=gl_context, images="pathtrace", spp=4)
    _, cameras, _ = load_scene_arg(lit(), 3, SIZE)
    for k, camera in enumerate(cameras):
        traced = trace(lit(), camera, SIZE, spp=4, context=gl_context, progress=False)
        want = np.round(np.clip(traced.image, 0, 1) * 255).astype(np.uint8)
        assert np.array_equal(_png(out / "rgb" / f"{k:06d}.png"), want)


from hypothesis import given, settings, strategies as st  # noqa: E402


@settings(max_examples=25, deadline=None)
@given(shape=st.sampled_from(["sphere", "blob", "segment", "flat", "one point", "two"]),
       n=st.integers(2, 3000), seed=st.integers(0, 2 ** 16), scale=st.sampled_from(
           [1e-6, 1.0, 250.0, 1e6]))
def test_a_models_diameter_is_its_farthest_pair(shape, n, seed, scale):
    """BOP's diameter (models_info.json) against scipy's every pairwise distance, over
    the shapes that defeat a bound from the centre -- points on a sphere, where every
    point is as far out -- and the degenerate ones: a segment, a plane, one point repeated,
    two points; at sizes from a micron to a thousand kilometres."""
    from scipy.spatial.distance import pdist

    from tests.geometry.test_cells import points_of

    p = points_of(shape, n, np.random.default_rng(seed), scale)
    assert dataset.bop.diameter(p) == pytest.approx(pdist(p).max(), rel=1e-12, abs=0)
