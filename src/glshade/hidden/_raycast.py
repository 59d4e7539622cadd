"""Ray casting (image space), the notes' algorithm: through each pixel centre a ray;
intersect it with the plane of each polygon, reject intersections outside the polygon,
keep the closest (ties: the polygon drawn first, as the GPU's GL_LESS).

Every ray meets every polygon (n N ray-polygon tests, the notes' cost); a test whose ray
misses the polygon's screen bounding box is rejected at once, the rest intersect the
plane and test the inside. Vectorised over chunks of (ray, polygon) pairs."""

from __future__ import annotations

from .common import HiddenResult, Prepared, fragments, resolve_nearest, timed, takes_scene

__all__ = ["raycast"]


@takes_scene
def raycast(p: Prepared) -> HiddenResult:
    counters = {"polygons": p.n_polygons, "triangles": len(p.tris),
                "ray-polygon tests": len(p.tris) * p.n_pixels, "plane intersections": 0,
                "hits": 0}

    def run(result: HiddenResult):
        scratch: dict = {}
        for pix, tri, depth in fragments(p, p.screen, p.tris, scratch):
            counters["hits"] += len(pix)
            resolve_nearest(p, result, pix, tri, depth, p.order[tri])
        counters["plane intersections"] = scratch.get("inside tests", 0)

    result = timed("raycast", p, run)
    result.counters = counters
    return result
