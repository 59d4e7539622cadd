"""A BOP data set (https://bop.felk.cvut.cz), laid out as the BOP toolkit's readers
(``bop_toolkit_lib/inout.py``) expect::

    OUT/camera.json                      fx, fy, cx, cy, width, height, depth_scale
    OUT/models/obj_{obj_id:06d}.ply      one model a label, in mm, triangles
    OUT/train/000000/scene_camera.json   {im_id: cam_K, cam_R_w2c, cam_t_w2c (mm), depth_scale}
    OUT/train/000000/scene_gt.json       {im_id: [cam_R_m2c, cam_t_m2c (mm), obj_id], ...}
    OUT/train/000000/scene_gt_info.json  {im_id: [bbox_obj, bbox_visib, px_count_all,
                                          px_count_valid, px_count_visib, visib_fract]}
    OUT/train/000000/rgb/{im_id:06d}.png
    OUT/train/000000/depth/{im_id:06d}.png       16-bit: depth in mm / depth_scale
    OUT/train/000000/mask/{im_id:06d}_{gt_id:06d}.png        the object drawn alone
    OUT/train/000000/mask_visib/{im_id:06d}_{gt_id:06d}.png  what it shows in the view

Matrices are written row by row, 9 numbers; translations and depths in mm (``units="m"``:
the scene is in metres, so x 1000). ``obj_id`` is the class id of the instance's label
(:attr:`Scene.labels`); a model file holds that label's first instance's mesh, its scale
baked in (a pose is a rotation and a translation).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .._version import __version__
from ..errors import OptionError, plain
from ..geometry.cells import group
from ..io.images import save_gray, save_image
from .views import DataSetJob, load_scene_arg, renderers, run_views, write_json

__all__ = ["write_bop", "BopViews", "UNITS", "diameter"]

#: millimetres a scene unit is, by the name ``units`` takes
UNITS = {"mm": 1.0, "m": 1000.0}
#: the scene (BOP's word) all views are written to
SCENE_DIR = Path("train") / "000000"


def _scale(units: str) -> float:
    if units not in UNITS:
        raise OptionError(f"units must be 'mm' or 'm' (the scene's unit), got {units!r}")
    return UNITS[units]


def _stretch(model) -> np.ndarray:
    """The placement's scale (the polar decomposition's symmetric factor, ``(3, 3)``)."""
    _, s, vt = np.linalg.svd(model.transform[:3, :3])
    return vt.T @ np.diag(s) @ vt


def _same_mesh(a, b) -> bool:
    return a is b or (a.vertices.shape == b.vertices.shape and
                      np.array_equal(a.vertices, b.vertices) and
                      np.array_equal(a.face_indices, b.face_indices))


def _check_models(scene) -> None:
    """BOP keeps one model a class: every instance of a label must be the same mesh at the
    same scale (its pose is a rotation and a translation). Refused naming the label."""
    if scene.solids or scene.patch_models:
        raise OptionError("a BOP data set's objects are meshes (its models are PLY files): "
                          "this scene has CSG solids or GPU-tessellated patches")
    instances: dict[int, list] = {}
    for model in scene.models:  # (an instance's parts: one multi-material mesh)
        instances.setdefault(model.instance_id, []).append(model)
    first: dict = {}
    for instance, parts in sorted(instances.items()):
        label = parts[0].label
        model = first.setdefault(label, (instance, parts))
        if model[0] == instance:
            continue
        key, twin = model
        if len(twin) != len(parts) or not all(_same_mesh(p.mesh, q.mesh)
                                              for p, q in zip(parts, twin)):
            raise OptionError(f"BOP keeps one model a label: instances {key} and {instance} "
                              f"of {label!r} are different meshes (give them different "
                              "labels)")
        a, b = _stretch(twin[0]), _stretch(parts[0])
        if not np.allclose(a, b, rtol=1e-9, atol=1e-12 * np.abs(a).max()):
            raise OptionError(f"BOP keeps one model a label: instances {key} and {instance} "
                              f"of {label!r} are scaled differently "
                              f"({plain(np.linalg.svd(a, compute_uv=False))} and "
                              f"{plain(np.linalg.svd(b, compute_uv=False))}; give them "
                              "different labels)")


def _models(scene, folder: Path, mm: float) -> None:
    """One PLY a label -- its first instance's mesh, triangulated, scale baked in, in mm,
    with vertex normals (BOP's format asks for them: the toolkit's renderer reads them) and
    its colours where it has them -- and ``models_info.json``: each model's diameter (the
    largest distance between two of its vertices, exact) and box (``min_x`` ... and
    ``size_x`` ...), in mm, as the toolkit's evaluation reads it."""
    from ..geometry.mesh import Mesh
    from ..io.meshes import save_mesh

    labels = scene.labels
    done = set()
    info = {}
    for model in sorted(scene.models, key=lambda m: m.instance_id):
        obj_id = labels.get(model.label)
        if obj_id is None or obj_id in done:
            continue
        done.add(obj_id)
        parts = [m for m in scene.models if m.instance_id == model.instance_id]
        stretch = _stretch(model)
        tris, verts, colors, base = [], [], [], 0
        for part in parts:
            t, _ = part.mesh.triangulate()
            tris.append(t + base)
            verts.append(part.mesh.vertices @ stretch.T * mm)
            colors.append(part.mesh.colors if part.mesh.colors is not None else
                          np.ones((part.mesh.n_vertices, 4)))
            base += part.mesh.n_vertices
        bare = Mesh(np.concatenate(verts), np.concatenate(tris))
        painted = any(p.mesh.colors is not None for p in parts)
        mesh = Mesh(bare.vertices, bare.faces, normals=bare.vertex_normals_weighted("area"),
                    colors=np.concatenate(colors) if painted else None)
        save_mesh(mesh, folder / f"obj_{obj_id:06d}.ply")
        lo, hi = mesh.vertices.min(0), mesh.vertices.max(0)
        info[str(obj_id)] = {"diameter": diameter(mesh.vertices),
                             **{f"min_{a}": float(v) for a, v in zip("xyz", lo)},
                             **{f"size_{a}": float(v) for a, v in zip("xyz", hi - lo)}}
    write_json(folder / "models_info.json", info)


def diameter(points: np.ndarray) -> float:
    """The largest distance between two of ``points`` ``(N, 3)``, exact: a lower bound from
    the points extreme along 26 directions; then the points grouped by the cells of a grid
    over their box (:func:`glshade.geometry.cells.group`), and only the pairs of cells that
    could hold a longer pair (the distance of their centres plus their radii exceeds the
    bound) compared point by point, by a matrix product for each cell against its partners.
    Points on a sphere are the worst case (every nearly opposite pair is nearly the
    longest): 40,000 took 8 s compared all against all, 0.4 s so; 200,000 take 9 to 12 s,
    a million-point blob 2 s.

    Parameters
    ----------
    points : ndarray
        ``(N, 3)``.
    """
    p = np.asarray(points, np.float64)
    if len(p) < 2:
        return 0.0
    dirs = np.array([(x, y, z) for x in (-1, 0, 1) for y in (-1, 0, 1) for z in (-1, 0, 1)
                     if (x, y, z) != (0, 0, 0)], np.float64)
    ends = p[np.unique(np.argmax(p @ dirs.T, axis=0))]
    best = float(np.max(np.linalg.norm(ends[:, None] - ends[None], axis=-1)))
    p = p - (p.min(0) + p.max(0)) / 2
    cells = group(p, max_side=32)  # (cells many times over: each against every other)
    centres, radii = cells.centres, cells.radii
    norms = (p ** 2).sum(1)
    for a in range(len(centres)):
        # (cells from a on: each pair once; a hair under the bound: its own rounding)
        reach = np.linalg.norm(centres[a:] - centres[a], axis=1) + radii[a:] + radii[a]
        partners = a + np.flatnonzero(reach >= best * (1 - 1e-12))
        if not len(partners):
            continue
        cols, rows = cells.members(partners), cells.members(np.array([a]))
        d2 = norms[rows, None] + norms[None, cols] - 2 * (p[rows] @ p[cols].T)
        best = max(best, float(np.sqrt(max(d2.max(), 0.0))))
    return best


def _save_mask(mask: np.ndarray, path: Path) -> None:
    """A bool mask as BOP keeps it: 8-bit, 255 on the object (made on the thread that
    writes the files, not the one that draws)."""
    save_gray(mask.view(np.uint8) * np.uint8(255), path)


@dataclass(frozen=True)
class BopViews:
    """What a BOP view writes (picklable: it travels to workers): its rgb, 16-bit depth and
    masks, and its record (camera, poses, info).

    Parameters
    ----------
    where : Path
        The views' folder.
    size : (int, int)
        The images' size.
    mm : float
        Millimetres a scene unit is.
    depth_scale : float
        BOP's: a depth pixel times this is millimetres.
    cameras : list of Camera
        The views' cameras.
    """

    where: Path
    size: tuple[int, int]
    mm: float
    depth_scale: float
    cameras: list

    def __call__(self, k: int, frame, annotate) -> tuple[dict, list]:
        where, mm, depth_scale, size = self.where, self.mm, self.depth_scale, self.size
        notes = annotate()
        K, R, t = self.cameras[k].to_opencv(size)
        depth_mm = np.where(np.isfinite(frame.depth), frame.depth * mm, 0.0)
        steps = np.round(depth_mm / depth_scale)
        if steps.max(initial=0) > 65535:
            raise OptionError(f"view {k}: a depth of {depth_mm.max():.6g} mm is "
                              f"{steps.max():.0f} steps of depth_scale {depth_scale:g}, past "
                              f"16 bits' 65,535: raise depth_scale to at least "
                              f"{depth_mm.max() / 65535:.3g}")
        files: list = [(save_image, frame.color[..., :3], where / "rgb" / f"{k:06d}.png",
                        None, 1),
                       (save_gray, steps.astype(np.uint16), where / "depth" / f"{k:06d}.png")]
        gt, info = [], []
        for g, note in enumerate(notes):
            for name, mask in (("mask", note.mask), ("mask_visib", note.mask_visib)):
                files.append((_save_mask, mask, where / name / f"{k:06d}_{g:06d}.png"))
            gt.append({"cam_R_m2c": note.cam_R_m2c.ravel().tolist(),
                       "cam_t_m2c": (note.cam_t_m2c * mm).tolist(), "obj_id": note.obj_id})
            info.append({"bbox_obj": list(note.bbox_obj), "bbox_visib": list(note.bbox_visib),
                         "px_count_all": note.px_count_all,
                         "px_count_valid": note.px_count_valid,
                         "px_count_visib": note.px_count_visib,
                         "visib_fract": note.visib_fract})
        camera = {"cam_K": K.ravel().tolist(), "cam_R_w2c": R.ravel().tolist(),
                  "cam_t_w2c": (t * mm).tolist(), "depth_scale": float(depth_scale)}
        return {"camera": camera, "gt": gt, "info": info}, files


def write_bop(scene, out_dir, *, views: int | None = None, size=None,
              depth_scale: float = 1.0, units: str = "m", cameras=None, samples: int = 4,
              options=None, progress=None, context=None, jobs: int = 1,
              scheduler: str | None = None, images: str = "raster", spp: int | None = None,
              until: float | None = None) -> Path:
    """Render ``scene`` into a BOP data set in ``out_dir`` (see the module's layout):
    resumable (a view already written is skipped), atomic (a file is whole or absent), the
    same bytes on a rerun.

    Parameters
    ----------
    scene : Scene, str or Path
        The objects, or a scene file (its [render] size, its key-framed path if it has one).
    out_dir : str or Path
        The data set's folder (made if missing).
    views : int or None
        How many views (cameras on a sphere around the scene, or the file's path sampled).
    size : (int, int) or None
        The images' width and height (None: the file's, else 640x480).
    depth_scale : float
        BOP's: a depth pixel times this is millimetres (> 0; 1: 1 mm steps up to 65.5 m).
    units : str
        What a scene unit is: ``"m"`` (x 1000 to BOP's mm) or ``"mm"``.
    cameras : list of Camera or None
        The views' cameras instead of ``views``.
    samples : int
        MSAA samples of the colour images (ids, depth and masks are exact whatever).
    options : DrawOptions, ShadingMode, str or None
        How the colour images are drawn.
    progress : bool, tqdm-like or None
        The progress bar (None: one on a terminal).
    context : RenderContext or None
        A context to draw in (this process's).
    jobs : int
        Local worker processes sharing the views (1: this process).
    scheduler : str or None
        A Dask scheduler's address, or ``"local"`` (the ``distributed`` extra): the views
        shared among its workers, which write into ``out_dir`` (a folder they all see).
    images : str
        ``"raster"`` (the colour images drawn with ``options``) or ``"pathtrace"`` (traced:
        :func:`glshade.pathtrace.trace`, in the tracer's radiosity units, clipped to 1 and
        encoded as the raster images are; masks, depth and poses the exact raster ones).
    spp : int or None
        ``images="pathtrace"``: samples a pixel (default 64).
    until : float or None
        ``images="pathtrace"``: or refine each image to this relative error.

    Returns
    -------
    Path
        The folder of the views (``OUT/train/000000``).
    """
    mm = _scale(units)
    if not (isinstance(depth_scale, (int, float)) and not isinstance(depth_scale, bool)
            and 0 < depth_scale < float("inf")):
        raise OptionError(f"depth_scale must be a number > 0 (mm a depth step), got "
                          f"{depth_scale!r}")
    scene, cameras, size = load_scene_arg(scene, views, size, cameras)
    _check_models(scene)
    out = Path(out_dir)
    where = out / SCENE_DIR
    for sub in ("rgb", "depth", "mask", "mask_visib"):
        (where / sub).mkdir(parents=True, exist_ok=True)
    (out / "models").mkdir(parents=True, exist_ok=True)
    _models(scene, out / "models", mm)
    job = DataSetJob(scene, cameras, size, samples, options, images, spp, until)

    writer = BopViews(where, size, mm, float(depth_scale), cameras)
    records = run_views(job, where / ".views", writer, progress, context, jobs=jobs,
                        scheduler=scheduler)
    write_json(where / "scene_camera.json", {str(k): r["camera"] for k, r in enumerate(records)})
    write_json(where / "scene_gt.json", {str(k): r["gt"] for k, r in enumerate(records)})
    write_json(where / "scene_gt_info.json", {str(k): r["info"] for k, r in enumerate(records)})
    K = cameras[0].to_opencv(size)[0]
    write_json(out / "camera.json", {"cx": K[0, 2], "cy": K[1, 2], "depth_scale":
                                     float(depth_scale), "fx": K[0, 0], "fy": K[1, 1],
                                     "height": size[1], "width": size[0]})
    # (beside BOP's own files: what drew the views, and which glshade)
    write_json(out / "glshade_info.json", {"renderer": renderers(records),
                                           "glshade": __version__})
    return where
