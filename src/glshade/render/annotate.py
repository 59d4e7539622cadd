"""Per-object ground truth for one view, in the BOP data set's terms: each object's pose in
the camera, its mask drawn alone (amodal) and as seen, pixel counts and boxes.

The masks come from the renderer's polygon ids, so they are exact: a pixel belongs to the
object whose surface its centre sees, never to a blend of a silhouette's samples, the same
with any MSAA. Poses are OpenCV's (x right, y down, z forward), model to camera:
``x_cam = cam_R_m2c @ x_model + cam_t_m2c`` in scene units, the model's frame being its
mesh's own (a scaled model's scale stays with the mesh: ``cam_R_m2c`` is a rotation).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..scene.intrinsics import GL_FROM_CV

__all__ = ["Annotation", "objects", "plan", "records", "bbox", "model_pose"]


@dataclass(frozen=True)
class Annotation:
    """One object in one view, by BOP's names.

    Parameters
    ----------
    instance_id : int
        The model's instance (1, 2, ... in the order added to the scene).
    label : str
        Its class's name.
    obj_id : int
        Its class id (:attr:`Scene.labels`): BOP's object id.
    cam_R_m2c : ndarray
        ``(3, 3)`` model-to-camera rotation (OpenCV's axes).
    cam_t_m2c : ndarray
        ``(3,)`` model-to-camera translation (scene units).
    mask : ndarray
        ``(H, W)`` bool: the object drawn alone (its full, amodal silhouette).
    mask_visib : ndarray
        ``(H, W)`` bool: the pixels it owns in the view.
    px_count_all, px_count_valid, px_count_visib : int
        The full mask's pixels -- over the object's whole projection where it leaves the
        image, as BOP's toolkit counts them (drawn into an image three times as wide and
        high around the view's) --, the in-image full mask's pixels with a depth, the
        visible mask's.
    visib_fract : float
        ``px_count_visib / px_count_all`` (0 where the object covers no pixel).
    bbox_obj, bbox_visib : (int, int, int, int)
        The masks' boxes ``(x, y, w, h)`` in whole pixels, inclusive (``bbox_obj`` over the
        whole projection: it may leave the image); ``(-1, -1, -1, -1)`` for an empty mask
        (BOP's).
    """

    instance_id: int
    label: str
    obj_id: int
    cam_R_m2c: np.ndarray
    cam_t_m2c: np.ndarray
    mask: np.ndarray
    mask_visib: np.ndarray
    px_count_all: int
    px_count_valid: int
    px_count_visib: int
    visib_fract: float
    bbox_obj: tuple[int, int, int, int]
    bbox_visib: tuple[int, int, int, int]


def bbox(mask: np.ndarray) -> tuple[int, int, int, int]:
    """``(x, y, w, h)`` of a boolean mask's pixels, inclusive (a one-pixel mask is w = h =
    1); ``(-1, -1, -1, -1)`` where it is empty.

    Parameters
    ----------
    mask : ndarray
        ``(H, W)`` bool.
    """
    rows, cols = np.flatnonzero(mask.any(1)), np.flatnonzero(mask.any(0))
    if not len(rows):
        return (-1, -1, -1, -1)
    return (int(cols[0]), int(rows[0]), int(cols[-1] - cols[0] + 1),
            int(rows[-1] - rows[0] + 1))


def model_pose(model, camera) -> tuple[np.ndarray, np.ndarray]:
    """``(cam_R_m2c, cam_t_m2c)`` of a scene model seen by ``camera``: the model's
    placement's rotation (its scale, the polar decomposition's other factor, stays with the
    mesh) and translation, in OpenCV's camera axes.

    Parameters
    ----------
    model : Model, PatchModel or SolidModel
        The model (a solid's placement is part of its tree: its frame is the world's).
    camera : Camera
        The view.
    """
    m = getattr(model, "transform", None)
    m = np.eye(4) if m is None else np.asarray(m, np.float64)
    u, _, vt = np.linalg.svd(m[:3, :3])
    rotation = u @ vt
    if np.linalg.det(rotation) < 0:  # (a mirroring placement: the nearest proper rotation)
        rotation = u @ np.diag([1.0, 1.0, -1.0]) @ vt
    r_w2c = GL_FROM_CV @ camera.rotation.T
    t_w2c = -r_w2c @ camera.position
    return r_w2c @ rotation, r_w2c @ m[:3, 3] + t_w2c


def _screen_boxes(models: dict, camera, size) -> dict:
    """Each instance's screen box ``(x0, y0, x1, y1)`` in pixels from its world box's
    corners, a pixel wider each way; None (the whole picture) where a corner is behind the
    eye."""
    from ..geometry.transforms import box_corners

    w, h = size
    view_proj = camera.projection_matrix(w / h) @ camera.view_matrix()
    out: dict[int, tuple | None] = {}
    for instance, parts in models.items():
        corners = []
        for m in parts:
            if hasattr(m, "corners"):
                corners.append(m.corners)
            else:  # (a solid: its tree's world box)
                corners.append(box_corners(np.asarray(m.solid.bounds, np.float64)))
        c = np.concatenate(corners)
        clip = np.c_[c, np.ones(len(c))] @ view_proj.T
        if (clip[:, 3] <= 1e-12).any():
            out[instance] = None
            continue
        ndc = clip[:, :2] / clip[:, 3:]
        x = (ndc[:, 0] + 1) / 2 * w
        y = (1 - ndc[:, 1]) / 2 * h
        out[instance] = (x.min() - 1, y.min() - 1, x.max() + 1, y.max() + 1)
    return out


def _overlap(a, b) -> bool:
    if a is None or b is None:
        return True
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def _batches(boxes: dict) -> tuple[list, list[list]]:
    """``(alone, batches)``: the instances whose box meets no other's (nothing can hide any
    of them: their full mask is their visible one), and the rest in batches whose boxes
    meet none of their batch's (their silhouettes cannot touch: one draw for the batch)."""
    alone: list[int] = []
    batches: list[list[int]] = []
    keys = sorted(boxes)
    for k in keys:
        if not any(_overlap(boxes[k], boxes[j]) for j in keys if j != k):
            alone.append(k)
            continue
        for batch in batches:
            if not any(_overlap(boxes[k], boxes[j]) for j in batch):
                batch.append(k)
                break
        else:
            batches.append([k])
    return alone, batches


def objects(scene) -> dict[int, list]:
    """Each visible instance's models (a multi-material mesh has several), by instance id.

    Parameters
    ----------
    scene : Scene
        The objects.
    """
    out: dict[int, list] = {}
    for model in scene.every_model:
        if model.visible and model.instance_id:
            out.setdefault(model.instance_id, []).append(model)
    return out


def plan(models: dict, camera, size) -> tuple[list, list[list], dict]:
    """Which full masks need draws of their own, and where each object's masks lie:
    ``(alone, batches, windows)`` -- the instances no other's screen box meets (their full
    mask is their visible one: nothing can hide any of them), the rest in batches whose
    boxes meet none of their batch's (their silhouettes cannot touch: one draw a batch, the
    others hidden), and each instance's pixel window ``(rows, columns)``: its screen box (a
    pixel wider each way) in whole pixels, clipped to the image, the whole image where a
    box corner is behind the eye. Every pixel centre an instance covers lies in its window,
    so its masks are worked out there alone (an object is a few percent of a view).

    Parameters
    ----------
    models : dict
        :func:`objects`' instances.
    camera : Camera
        The view, its planes fitted to the scene.
    size : (int, int)
        The image's width and height in pixels.
    """
    boxes = _screen_boxes(models, camera, size)
    return (*_batches(boxes), {key: _window(box, size) for key, box in boxes.items()})


def _window(box, size) -> tuple[slice, slice]:
    """A screen box's pixel window (rows, columns), clipped to the image."""
    w, h = size
    if box is None or not np.isfinite(box).all():
        return slice(0, h), slice(0, w)
    x0, y0, x1, y1 = (int(np.clip(v, 0, n)) for v, n in zip(
        (np.floor(box[0]), np.floor(box[1]), np.ceil(box[2]), np.ceil(box[3])),
        (w, h, w, h)))
    return slice(y0, y1), slice(x0, x1)


def _placed(window: tuple[slice, slice], crop: np.ndarray, shape) -> np.ndarray:
    """A window's mask placed in a picture of ``shape`` (False elsewhere)."""
    out = np.zeros(shape, bool)
    out[window] = crop
    return out


def _shifted(box: tuple[int, int, int, int], window) -> tuple[int, int, int, int]:
    """A window's box in the picture's pixels."""
    return box if box[0] < 0 else (box[0] + window[1].start, box[1] + window[0].start,
                                   box[2], box[3])


def crossing(models: dict, camera, size) -> list:
    """The instances whose screen box leaves the image (or is unbounded: a corner behind
    the eye): their whole projection is counted apart (``px_count_all``, as BOP's toolkit
    counts it).

    Parameters
    ----------
    models : dict
        :func:`objects`' instances.
    camera : Camera
        The view.
    size : (int, int)
        The image's width and height.
    """
    w, h = size
    boxes = _screen_boxes(models, camera, size)
    # (the boxes are a pixel wider each way: a box flush with the image's edge is inside)
    return [k for k, b in sorted(boxes.items())
            if b is None or b[0] < -1 or b[1] < -1 or b[2] > w + 1 or b[3] > h + 1]


def shifted_box(box: tuple[int, int, int, int], dx: int, dy: int) -> tuple[int, int, int, int]:
    """``(x, y, w, h)`` moved by (dx, dy) (an empty box stays as it is).

    Parameters
    ----------
    box : tuple
        ``(x, y, w, h)``.
    dx, dy : int
        The move, pixels.
    """
    x, y, bw, bh = box
    return (x + dx, y + dy, bw, bh) if bw > 0 and bh > 0 else box


def records(scene, camera, models: dict, instance: np.ndarray, depth: np.ndarray,
            full: dict, whole: dict | None = None) -> list[Annotation]:
    """The annotations of a view, in instance order, from its instance mask and each
    object's full mask (objects with an empty full mask are out of view: none).

    Parameters
    ----------
    scene : Scene
        The objects (their labels).
    camera : Camera
        The view.
    models : dict
        :func:`objects`' instances.
    instance : ndarray
        ``(H, W)`` int32 the view's instance mask.
    depth : ndarray
        ``(H, W)`` float32 the view's depth (``inf``: nothing drawn).
    full : dict
        Each instance's full (amodal) mask as ``(window, mask)``: its window
        (:func:`plan`) and the ``bool`` mask within it.
    whole : dict or None
        For an instance whose projection leaves the image: its pixels over the whole
        projection and their box (``(count, (x, y, w, h))``, the box in the image's
        pixels): ``px_count_all``, ``visib_fract`` and ``bbox_obj`` as BOP's toolkit
        counts them.
    """
    labels = scene.labels
    seen = np.bincount(instance.ravel(), minlength=max(models, default=0) + 1)
    out = []
    for key, parts in sorted(models.items()):
        window, crop = full[key]
        n_all = int(crop.sum())
        if not n_all:
            continue
        visib = instance[window] == key
        n_visib = int(visib.sum())
        if n_visib != seen[key]:  # (seen outside its window: never, but never wrong)
            window, crop = (slice(None), slice(None)), _placed(window, crop, instance.shape)
            visib = instance == key
            n_visib = int(visib.sum())
        rotation, translation = model_pose(parts[0], camera)
        label = parts[0].label
        box_all = _shifted(bbox(crop), window)
        if whole and key in whole:  # (its whole projection: BOP's count)
            n_all, box_all = max(whole[key][0], n_all), whole[key][1]
        out.append(Annotation(
            key, label, labels.get(label, 0), rotation, translation,
            _placed(window, crop, instance.shape), _placed(window, visib, instance.shape),
            n_all, int((crop & np.isfinite(depth[window])).sum()), n_visib, n_visib / n_all,
            box_all, _shifted(bbox(visib), window)))
    return out
