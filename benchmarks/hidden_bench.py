"""The hidden-surface lab's costs: seconds per algorithm against polygon count (100 ..
100k, at 256x256) and against resolution (128² .. 1024², 1,000 polygons), with the GPU
z-buffer in the same run, and the counters of the notes' cost model. Writes a log-log plot
(``--plot docs/hidden-cost.png``). An algorithm that took longer than ``--budget`` seconds
at one size is not run at the next (shown as "-").

Run: ``.venv/bin/python benchmarks/hidden_bench.py [--plot docs/hidden-cost.png]``;
``--dense``: depth sort and BSP on dense interpenetrating soups, against the ray caster.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import table  # noqa: E402

from glshade import Camera, Mesh, Scene  # noqa: E402
from glshade.hidden import ALGORITHMS, prepare  # noqa: E402
from glshade.modes import Outputs  # noqa: E402
from glshade.render.renderer import Renderer  # noqa: E402

CAMERA = Camera.look_at((0.3, 0.4, 5.0), (0.0, 0.0, 0.0), fov_y=45)
COLORS = {"zbuffer": (60, 110, 200), "scanline": (90, 170, 90), "depth-sort": (220, 110, 50),
          "bsp": (170, 80, 170), "raycast": (200, 60, 60), "gpu": (90, 90, 90)}


def soup(n: int, seed: int = 0) -> Scene:
    """``n`` triangles scattered through the view, sized so that the covered area (and
    the overdraw) stays about the same whatever n."""
    rng = np.random.default_rng(seed)
    centre = rng.uniform(-1.2, 1.2, (n, 1, 3))
    v = centre + rng.normal(0, 1.2 / np.sqrt(n), (n, 3, 3))
    s = Scene()
    s.add(Mesh(v.reshape(-1, 3), np.arange(3 * n).reshape(-1, 3)))
    return s


def dense_soup(n: int, spread: float, seed: int = 1) -> Scene:
    """``n`` triangles, centres in a 2-unit cube, vertices ``spread`` (sd) about them:
    randomly turned, so at 0.15 and above each pierces dozens of others (a dense
    interpenetrating soup: every cycle and piercing the painter's algorithm must split)."""
    rng = np.random.default_rng(seed)
    v = rng.uniform(-1, 1, (n, 1, 3)) + rng.normal(0, spread, (n, 3, 3))
    s = Scene()
    s.add(Mesh(v.reshape(-1, 3), np.arange(3 * n).reshape(-1, 3)))
    return s


DENSE_CAMERA = Camera.look_at((0.0, 0.0, 6.0), (0.0, 0.0, 0.0))


def dense(budget: float) -> None:
    """Depth sort and BSP on dense interpenetrating soups (128x128), each image checked
    against the ray caster's (a different algorithm): the fraction of pixels whose
    polygon id differs."""
    from glshade.hidden import bsp, depth_sort, raycast

    rows = []
    for n, spread in ((500, 0.15), (1000, 0.15), (2000, 0.1), (2000, 0.15), (2000, 0.2)):
        p = prepare(dense_soup(n, spread), DENSE_CAMERA, (128, 128))
        truth = raycast(p).face_id
        row = [f"{n:,}", f"{spread}"]
        for algorithm in (depth_sort, bsp):
            t = time.perf_counter()
            result = algorithm(p)
            dt = time.perf_counter() - t
            differ = float((result.face_id != truth).mean())
            c = result.counters
            row += [f"{dt:.1f}", f"{c['splits']:,}", f"{differ:.4f}"]
        rows.append(row)
        print(" ".join(row), flush=True)
    print("\ndense interpenetrating soups, 128x128 (ids != raycast: the fraction of pixels "
          "whose polygon differs from the ray caster's -- pixels on edges and where pieces "
          "meet at one depth)")
    print(table(rows, ("triangles", "spread", "depth sort s", "splits", "ids != raycast",
                       "BSP s", "BSP splits", "BSP ids != raycast")))


def measure(scene, size, skip, budget, renderer_cache):
    row = {}
    p = prepare(scene, CAMERA, size)
    for name, algorithm in ALGORITHMS.items():
        if name in skip:
            row[name] = None
            continue
        t = time.perf_counter()
        result = algorithm(p)
        row[name] = time.perf_counter() - t
        row[name + " counters"] = result.counters
        if row[name] > budget:
            skip.add(name)
    r = renderer_cache.get(size)
    if r is None:
        r = renderer_cache[size] = Renderer(*size, samples=0)
    r.render_frame(scene, CAMERA, "flat", cull=False, outputs=Outputs.FACE_ID)
    t = time.perf_counter()
    r.render_frame(scene, CAMERA, "flat", cull=False, outputs=Outputs.FACE_ID | Outputs.DEPTH)
    row["gpu"] = time.perf_counter() - t
    return row


def plot(series: dict, xs, path, xlabel: str, title: str) -> None:
    from PIL import Image, ImageDraw

    from glshade.io.images import font, save_image

    w, h = 640, 420
    left, right, top, bottom = 70, 130, 40, 50
    img = Image.new("RGB", (w, h), (250, 250, 250))
    d = ImageDraw.Draw(img)
    values = [v for ys in series.values() for v in ys if v]
    lo, hi = np.floor(np.log10(min(values))), np.ceil(np.log10(max(values)))
    x0, x1 = np.log10(xs[0]), np.log10(xs[-1])

    def px(x, y):
        return (left + (np.log10(x) - x0) / (x1 - x0) * (w - left - right),
                top + (hi - np.log10(y)) / (hi - lo) * (h - top - bottom))

    d.rectangle([left, top, w - right, h - bottom], outline=(120, 120, 120))
    for e in range(int(lo), int(hi) + 1):
        _, y = px(xs[0], 10.0 ** e)
        d.line([left, y, w - right, y], fill=(225, 225, 225))
        d.text((10, y - 7), f"1e{e} s", fill=(60, 60, 60), font=font(11))
    for x in xs:
        X, _ = px(x, 10.0 ** lo)
        d.text((X - 14, h - bottom + 6), f"{x:,}", fill=(60, 60, 60), font=font(11))
    d.text((w / 2 - 80, h - 24), xlabel, fill=(30, 30, 30), font=font(13))
    d.text((left, 12), title, fill=(30, 30, 30), font=font(13))
    for i, (name, ys) in enumerate(series.items()):
        pts = [px(x, y) for x, y in zip(xs, ys) if y]
        color = COLORS[name]
        if len(pts) > 1:
            d.line(pts, fill=color, width=3)
        for X, Y in pts:
            d.ellipse([X - 3, Y - 3, X + 3, Y + 3], fill=color)
        d.text((w - right + 10, top + 10 + 18 * i), name, fill=color, font=font(13))
    save_image(np.asarray(img), path)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--plot", help="write the log-log plot of seconds against polygons")
    ap.add_argument("--budget", type=float, default=20.0)
    ap.add_argument("--dense", action="store_true",
                    help="only the dense interpenetrating soups (depth sort and BSP)")
    a = ap.parse_args(argv)
    if a.dense:
        dense(a.budget)
        return
    names = [*ALGORITHMS, "gpu"]
    renderers: dict = {}
    counts = [100, 1_000, 10_000, 100_000]
    skip: set = set()
    by_n = {n: measure(soup(n), (256, 256), skip, a.budget, renderers) for n in counts}
    print("seconds against polygon count (random triangles, 256x256; '-': not run, the "
          "size before took over the budget)")
    print(table([(f"{n:,}", *[f"{by_n[n][k]:.3f}" if by_n[n].get(k) else "-" for k in names])
                 for n in counts], ("polygons", *names)))
    sizes = [128, 256, 512, 1024]
    skip = set()
    by_res = {s: measure(soup(1000), (s, s), skip, a.budget, renderers) for s in sizes}
    print("\nseconds against resolution (1,000 random triangles)")
    print(table([(f"{s}x{s}", *[f"{by_res[s][k]:.3f}" if by_res[s].get(k) else "-"
                                for k in names]) for s in sizes], ("pixels", *names)))
    print("\nthe cost model's counters (256x256)")
    rows = []
    for n in counts:
        c = by_n[n]
        rows.append((f"{n:,}", _get(c, "raycast", "ray-polygon tests"),
                     _get(c, "depth-sort", "comparisons"), _get(c, "bsp", "splits"),
                     _get(c, "zbuffer", "depth tests"), _get(c, "scanline", "spans")))
    print(table(rows, ("polygons", "ray-polygon tests (n N)", "depth-sort comparisons",
                       "BSP splits", "z-buffer depth tests", "scan-line spans")))
    for r in renderers.values():
        r.close()
    if a.plot:
        plot({k: [by_n[n].get(k) for n in counts] for k in names}, counts, a.plot,
             "polygons (random triangles, 256x256)",
             "hidden-surface algorithms: seconds against polygons (log-log)")
        print(f"plot: {a.plot}")


def _get(row, name, key):
    c = row.get(name + " counters")
    return f"{c[key]:,}" if c else "-"


if __name__ == "__main__":
    main()
