"""Cast shadows' cost: the frame time of shadows off, map and exact at 512x512 for a mesh
of about 1k and 100k triangles over a floor, under one and four lights (Phong), interleaved
in one process, medians; the ratios to off are the figures that matter (goals on llvmpipe:
map <= 2x off, exact <= 5x off at 100k triangles and one light). Each series draws once
before it is timed (programs compiled, the BVH built, the maps drawn: a moving camera keeps
both, so the timed frames are what an animation or the viewer pays). The 4.1 columns: the
same draws on a context held to a Mac's tier (create_context(tier="4.1")), where exact
shadows go through a G-buffer and fragment programs walking the hierarchy in textures.

Run: ``.venv/bin/python benchmarks/shadows_bench.py [--repeats 5] [--size 512]``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import frame_arguments, frame_header, interleaved, table  # noqa: E402

import glshade as g  # noqa: E402
from glshade import quaternion as Q  # noqa: E402
from glshade.geometry import primitives as P  # noqa: E402

LIGHTS = [g.PointLight(position=(-2.0, 5.0, 1.5)),
          g.DirectionalLight(direction=(1.0, -1.6, -0.4), color=(0.4, 0.4, 0.45)),
          g.PointLight(position=(3.0, 4.0, -2.0), color=(0.3, 0.3, 0.3)),
          g.DirectionalLight(direction=(-0.5, -1.0, 1.0), color=(0.2, 0.2, 0.25))]


def scene(triangles: int, lights: int) -> g.Scene:
    """A torus of about ``triangles`` triangles over a floor, ``lights`` lights."""
    # a torus of n x m quads has 2 n m triangles
    m = max(3, int(round(np.sqrt(triangles / 8))))
    n = max(3, int(round(triangles / (2 * m))))
    s = g.Scene(ambient=(0.2, 0.2, 0.2))
    s.add(P.plane(8.0), g.Material(color=(0.8, 0.8, 0.8)),
          rotation=Q.from_axis_angle((1, 0, 0), -np.pi / 2))
    s.add(P.torus(1.0, 0.35, n, m), g.Material(color=(0.8, 0.5, 0.3)),
          rotation=Q.from_axis_angle((1, 0, 0.4), 0.7), translation=(0, 1.4, 0))
    for light in LIGHTS[:lights]:
        s.add_light(light)
    return s


def main() -> None:
    args = frame_arguments(__doc__)
    camera = g.Camera.look_at((4.0, 4.0, 6.0), (0.0, 0.8, 0.0), fov_y=45)
    rows = []
    with g.Renderer(args.size, args.size, samples=0) as r, \
            g.create_context(tier="4.1") as held, \
            g.Renderer(args.size, args.size, samples=0, context=held) as mac:
        print(frame_header(r, args.size, args.repeats))
        for triangles in (1_000, 100_000):
            for lights in (1, 4):
                s = scene(triangles, lights)
                count = sum(len(m.mesh.triangles[0]) for m in s.models)
                series = {m: (lambda m=m, s=s: r.render(s, camera, "phong", shadows=m))
                          for m in ("off", "map", "exact")}
                for m in ("map", "exact"):
                    series[m + " 4.1"] = (lambda m=m, s=s: mac.render(s, camera, "phong",
                                                                      shadows=m))
                for fn in series.values():
                    fn()  # (compiled, built and drawn once before the clock)
                med = interleaved(series, args.repeats)
                rows.append((f"{count:,}", lights, *(f"{med[m] * 1000:.1f}" for m in series),
                             f"{med['map'] / med['off']:.2f}",
                             f"{med['exact'] / med['off']:.2f}",
                             f"{med['exact 4.1'] / med['exact']:.2f}"))
    print(table(rows, ("triangles", "lights", "off ms", "map ms", "exact ms", "map 4.1 ms",
                       "exact 4.1 ms", "map/off", "exact/off", "exact 4.1/4.3")))
    print("peers: pyvista (enable_shadows) and pyrender (SHADOWS_ALL) not installed here")


if __name__ == "__main__":
    main()
