"""Transparency's cost: the frame time of exact (per-pixel lists, sorted), weighted and
blend against the same surfaces drawn opaque, at depth complexity 1, 8 and 64 (that many
tilted, interpenetrating quads over the whole 512x512 view), Phong, interleaved in one
process, medians. Goal on llvmpipe: exact within 2x of blend at complexity <= 8 (blend
itself, drawn into a float target and rounded once, is about 2x opaque here). The "peeled
4.1" column: exact on a context held to a Mac's tier (create_context(tier="4.1")), by depth
peeling: two draws of the surfaces a layer, as many layers as the deepest pixel has.

Run: ``.venv/bin/python benchmarks/transparency_bench.py [--repeats 5] [--size 512]``.
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


def scene(layers: int, opacity: float) -> g.Scene:
    """``layers`` quads, each tilted a little about a random axis, all covering the view."""
    rng = np.random.default_rng(layers)
    s = g.Scene(ambient=(0.3, 0.3, 0.3))
    for k in range(layers):
        axis = rng.normal(size=3)
        s.add(P.plane(6.0), g.Material(color=tuple(rng.uniform(0.2, 1.0, 3)), opacity=opacity),
              rotation=Q.from_axis_angle(axis, rng.uniform(0, 0.3)),
              translation=(0, 0, -0.05 * k))
    s.add_light(g.PointLight(position=(2.0, 3.0, 5.0)))
    return s


def main() -> None:
    args = frame_arguments(__doc__)
    camera = g.Camera.look_at((0.0, 0.0, 3.0), (0.0, 0.0, 0.0), fov_y=45)
    rows = []
    with g.Renderer(args.size, args.size, samples=0) as r, \
            g.create_context(tier="4.1") as held, \
            g.Renderer(args.size, args.size, samples=0, context=held) as mac:
        print(frame_header(r, args.size, args.repeats))
        for layers in (1, 8, 64):
            glass, solid = scene(layers, 0.3), scene(layers, 1.0)
            series = {"opaque": lambda solid=solid: r.render(solid, camera, "phong")}
            for m in ("exact", "weighted", "blend"):
                series[m] = (lambda m=m, glass=glass: r.render(
                    glass, camera, "phong", transparency=m, max_layers=64))
            series["peeled 4.1"] = (lambda glass=glass: mac.render(
                glass, camera, "phong", max_layers=64))
            for fn in series.values():
                fn()  # (compiled and sized before the clock)
            med = interleaved(series, args.repeats)
            r.render(glass, camera, "phong", max_layers=64)
            fragments = r.transparency.fragments
            rows.append((layers, f"{fragments / args.size ** 2:.1f}",
                         *(f"{med[m] * 1000:.1f}" for m in series),
                         f"{med['exact'] / med['opaque']:.2f}",
                         f"{med['exact'] / med['blend']:.2f}",
                         f"{med['peeled 4.1'] / med['exact']:.2f}"))
    print(table(rows, ("quads", "layers a pixel", "opaque ms", "exact ms", "weighted ms",
                       "blend ms", "peeled 4.1 ms", "exact/opaque", "exact/blend",
                       "peeled/exact")))
    print("peers: pygfx (blended, weighted, stochastic), PyVista (depth peeling) not "
          "installed here")


if __name__ == "__main__":
    main()
