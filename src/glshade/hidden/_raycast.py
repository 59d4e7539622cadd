"""Ray casting (image space), the notes' algorithm: through each pixel centre a ray;
intersect it with the plane of each polygon, reject intersections outside the polygon,
keep the closest (ties: the polygon drawn first, as the GPU's GL_LESS).

Every ray meets every polygon (n N ray-polygon tests, the notes' cost); here the rays that
miss a polygon's screen bounding box are never paired with it (one box per polygon), and
each pair left is tested: inside the polygon or not, and for those inside, the plane's
intersection along the ray. The counters count those, as done: ``ray-polygon tests`` (the
pairs tested: about n N times the mean box's share of the image), ``plane intersections``
(the pairs inside), ``hits`` (within the near and far planes). Vectorised over chunks of
(ray, polygon) pairs."""

from __future__ import annotations

from .raster import fragments, resolve_nearest
from .result import HiddenResult
from .view import Prepared, takes_scene, timed

__all__ = ["raycast"]


@takes_scene
def raycast(p: Prepared) -> HiddenResult:
    """Ray casting (the notes' image-space classic): one ray a pixel, tested against every
    polygon whose screen box holds the pixel; the nearest hit wins. Same inputs and result as
    :func:`zbuffer`, counting bounding-box and ray-polygon tests."""
    counters = {"polygons": p.n_polygons, "triangles": len(p.tris), "bounding boxes": 0,
                "ray-polygon tests": 0, "plane intersections": 0, "hits": 0}

    def run(result: HiddenResult):
        scratch: dict = {}
        for pix, tri, depth in fragments(p, p.screen, p.tris, scratch):
            counters["hits"] += len(pix)
            resolve_nearest(p, result, pix, tri, depth, p.order[tri])
        counters["bounding boxes"] = len(p.tris)
        counters["ray-polygon tests"] = scratch.get("inside tests", 0)
        counters["plane intersections"] = scratch.get("inside", 0)

    result = timed("raycast", p, run)
    result.counters = counters
    return result
