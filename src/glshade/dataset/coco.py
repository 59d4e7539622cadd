"""A COCO instances data set: images and one JSON of their objects' visible masks as
run-length encodings (pycocotools', so ``pycocotools.coco.COCO`` reads them back exactly),
with boxes, areas and categories from the scene's labels::

    OUT/images/{image_id:06d}.png
    OUT/annotations.json     images, annotations (segmentation RLE, bbox, area, iscrowd
                             0), categories (id: the label's class id, name: the label)
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import EnvironmentFailure
from ..io.images import save_image
from .views import DataSetJob, load_scene_arg, renderers, run_views, write_json

__all__ = ["write_coco", "CocoViews"]


def _mask_api():
    try:
        from pycocotools import mask
    except ImportError:
        raise EnvironmentFailure("COCO masks are encoded by pycocotools: pip install "
                                 "'glshade[vision]'") from None
    return mask


@dataclass(frozen=True)
class CocoViews:
    """What a COCO view writes (picklable): its image, and its record of the objects seen
    (the view's own instance mask: COCO annotates what is seen, no draw alone).

    Parameters
    ----------
    out : Path
        The data set's folder.
    size : (int, int)
        The images' size.
    classes : dict
        Each instance id's class id.
    """

    out: Path
    size: tuple[int, int]
    classes: dict

    def __call__(self, k: int, frame, annotate) -> tuple[dict, list]:
        mask_api = _mask_api()
        name = f"images/{k + 1:06d}.png"
        objects = []
        # (the ids in column order once: each object's mask is then one comparison, already
        # in the order pycocotools encodes; its area and box come from the counts and RLE)
        ids = np.asfortranarray(frame.instance)
        areas = np.bincount(ids.ravel(order="K"))
        for instance in np.flatnonzero(areas[1:]).tolist():
            instance += 1
            rle = mask_api.encode((ids == instance).view(np.uint8))
            objects.append({"category_id": self.classes[instance], "instance_id": instance,
                            "segmentation": {"size": [int(v) for v in rle["size"]],
                                             "counts": rle["counts"].decode("ascii")},
                            "area": int(areas[instance]),
                            "bbox": [float(v) for v in mask_api.toBbox(rle)], "iscrowd": 0})
        return ({"image": {"file_name": name, "width": self.size[0], "height": self.size[1]},
                 "objects": objects}, [(save_image, frame.color[..., :3], self.out / name,
                                                     None, 1)])


def write_coco(scene, out_dir, *, views: int | None = None, size=None, cameras=None,
               samples: int = 4, options=None, progress=None, context=None, jobs: int = 1,
               scheduler: str | None = None, images: str = "raster", spp: int | None = None,
               until: float | None = None) -> Path:
    """Render ``scene`` into a COCO instances data set in ``out_dir``: resumable (a view
    already written is skipped), atomic, the same bytes on a rerun. Image ids count from
    1, annotation ids too, in view then instance order.

    Parameters
    ----------
    scene : Scene, str or Path
        The objects, or a scene file.
    out_dir : str or Path
        The data set's folder (made if missing).
    views : int or None
        How many views (cameras on a sphere around the scene, or the file's path sampled).
    size : (int, int) or None
        The images' width and height (None: the file's, else 640x480).
    cameras : list of Camera or None
        The views' cameras instead of ``views``.
    samples : int
        MSAA samples of the colour images (the masks are exact whatever).
    options : DrawOptions, ShadingMode, str or None
        How the images are drawn.
    progress : bool, tqdm-like or None
        The progress bar (None: one on a terminal).
    context : RenderContext or None
        A context to draw in (this process's).
    jobs : int
        Local worker processes sharing the views (1: this process).
    scheduler : str or None
        A Dask scheduler's address, or ``"local"`` (the ``distributed`` extra).
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
        The annotations file.
    """
    _mask_api()  # (a missing pycocotools said before any work)
    scene, cameras, size = load_scene_arg(scene, views, size, cameras)
    out = Path(out_dir)
    (out / "images").mkdir(parents=True, exist_ok=True)
    job = DataSetJob(scene, cameras, size, samples, options, images, spp, until)

    labels = scene.labels
    classes = {m.instance_id: labels.get(m.label, 0)
               for m in scene.every_model}
    writer = CocoViews(out, size, classes)
    records = run_views(job, out / ".views", writer, progress, context, jobs=jobs,
                        scheduler=scheduler)
    entries: list[dict] = []
    annotations: list[dict] = []
    for k, record in enumerate(records):
        entries.append({"id": k + 1, **record["image"]})
        for obj in record["objects"]:
            annotations.append({"id": len(annotations) + 1, "image_id": k + 1, **obj})
    categories = [{"id": cid, "name": label, "supercategory": "object"}
                  for label, cid in scene.labels.items()]
    path = out / "annotations.json"
    write_json(path, {"images": entries, "annotations": annotations,
                      "categories": categories,
                      "info": {"description": "rendered by glshade", "version": "1.0",
                               "renderer": renderers(records)}})
    return path
