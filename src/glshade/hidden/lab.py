"""Running several algorithms on one view and setting them side by side: the id images,
where each disagrees with a reference (the GPU, or the first algorithm), the numbers, and
frames of each algorithm at work."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._bsp import paint
from .result import HiddenResult
from .view import Prepared
from ..colormaps import id_colors
from ._zbuffer import zbuffer

__all__ = ["Agreement", "agreement", "id_colors", "disagreement_map", "step_frames"]


@dataclass
class Agreement:
    """How ``face_id`` images compare: pixels that differ away from edges, pixels that
    differ within ``tolerance`` px of an edge (two correct rasterisers may), the covered
    pixels, and the largest relative depth difference where the ids agree.

    Parameters
    ----------
    differ : int
        Pixels whose ids differ away from edges.
    near_edges : int
        Pixels that differ within the tolerance of an edge.
    covered : int
        The covered pixels.
    depth_error : float
        The largest relative depth difference where the ids agree.
    """

    differ: int
    near_edges: int
    covered: int
    depth_error: float

    @property
    def near_edge_fraction(self) -> float:
        return self.near_edges / max(self.covered, 1)


def agreement(result: HiddenResult, reference_ids, reference_depth, edges) -> Agreement:
    """How far a result's ids and depth agree with the reference's: the pixels that differ
    off and on the ``edges`` pixels, and the depth error where the ids agree.

    Parameters
    ----------
    result : HiddenResult
        An algorithm's ids and depth.
    reference_ids : ndarray
        ``(H, W)`` the reference's polygon ids.
    reference_depth : ndarray
        ``(H, W)`` the reference's depth.
    edges : ndarray
        ``(H, W)`` bool: the pixels near an edge (differences there are tolerated).
    """
    diff = result.face_id != reference_ids
    same = ~diff & (reference_ids >= 0)
    rel = np.abs(result.depth[same].astype(np.float64) - reference_depth[same]) / \
        np.maximum(np.abs(reference_depth[same]), 1e-30)
    return Agreement(int((diff & ~edges).sum()), int((diff & edges).sum()),
                     int((reference_ids >= 0).sum()), float(rel.max()) if rel.size else 0.0)


def disagreement_map(face_id, reference, edges) -> np.ndarray:
    """Grey where they agree on a polygon, red where they differ, yellow where they differ
    within the edge tolerance.

    Parameters
    ----------
    face_id : ndarray
        ``(H, W)`` an algorithm's polygon ids.
    reference : ndarray
        ``(H, W)`` the reference's.
    edges : ndarray
        ``(H, W)`` bool: the pixels near an edge.
    """
    out = np.full((*face_id.shape, 3), 18, np.uint8)
    out[reference >= 0] = (70, 70, 78)
    diff = face_id != reference
    out[diff & ~edges] = (235, 50, 40)
    out[diff & edges] = (240, 200, 40)
    return out


def step_frames(name: str, p: Prepared, result: HiddenResult, count: int = 24) -> list:
    """``count`` id images of the algorithm at work: the z-buffer after each share of the
    polygons (draw order), the painters after each share of their painting order, the scan
    line and ray casting as their sweep moves down the image.

    Parameters
    ----------
    name : str
        The algorithm's name.
    p : Prepared
        The view.
    result : HiddenResult
        The algorithm's result.
    count : int
        Frames.
    """
    height = p.size[1]
    frames = []
    if name in ("scanline", "raycast"):
        for k in range(1, count + 1):
            rows = int(round(height * k / count))
            f = np.full_like(result.face_id, -1)
            f[:rows] = result.face_id[:rows]
            frames.append(f)
        return frames
    if name in ("bsp", "depth-sort"):
        sub = getattr(result, "painted", None)
        n = len(sub.tris) if sub is not None else 0
        for k in range(1, count + 1):
            partial = p.empty_result(name)
            stop = int(round(n * k / count))
            if stop and sub is not None:
                _paint_prefix(p, sub, partial, stop)
            frames.append(partial.face_id)
        return frames
    n = len(p.tris)  # the z-buffer, and anything else: polygons in draw order
    for k in range(1, count + 1):
        stop = int(round(n * k / count))
        frames.append(zbuffer(p.subset(p.tris[:stop], p.ids[:stop], p.order[:stop]))
                      .face_id)
    return frames


def _paint_prefix(p: Prepared, sub: Prepared, result: HiddenResult, stop: int) -> None:
    """Repaint the first ``stop`` pieces of a painter's sequence (kept by the algorithm)."""
    from ._bsp import Pieces

    pieces = Pieces(sub.tris[:stop], sub.src[:stop], sub.cut[:stop])
    paint(p, result, pieces, np.arange(stop))
