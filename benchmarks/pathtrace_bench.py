"""Path tracing the Cornell box: paths and ray queries per second on this GL, samples and
seconds to a relative error of 5% (and 1%, extrapolated by the 1 / sqrt(N) law when it
is out of reach here), the numpy twin's speed, and Mitsuba 3 (``scalar_rgb``) on the same
box when it is installed.

Run: ``.venv/bin/python benchmarks/pathtrace_bench.py [--size 256]``.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import table  # noqa: E402

from glshade import pathtrace  # noqa: E402
from glshade.pathtrace import twin  # noqa: E402
from glshade.radiosity import cornell_scene  # noqa: E402
from glshade.render.context import create_context  # noqa: E402


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--size", type=int, default=256)
    args = ap.parse_args()
    n = args.size
    scene, camera = cornell_scene()
    rows = []
    with create_context("egl") as ctx:
        for accel, label in (("bvh", "GPU, hierarchy"), ("flat", "GPU, flat loop"),
                             ("auto", "GPU (default)")):
            pathtrace.trace(scene, camera, (32, 32), spp=1, context=ctx, progress=False,
                            accel=accel)  # (compiles)
            r = pathtrace.trace(scene, camera, (n, n), spp=32, context=ctx, progress=False,
                                accel=accel)
            paths = r.samples * n * n / r.seconds
            rows.append([label, f"{n}x{n}", r.samples, f"{r.seconds:.2f}",
                         f"{paths / 1e6:.2f}", f"{r.relative_error:.2%}"])
        t0 = time.perf_counter()
        r5 = pathtrace.trace(scene, camera, (n, n), until=0.05, context=ctx, progress=False)
        t5 = time.perf_counter() - t0
        rows.append(["GPU to 5%", f"{n}x{n}", r5.samples, f"{t5:.2f}",
                     f"{r5.samples * n * n / r5.seconds / 1e6:.2f}",
                     f"{r5.relative_error:.2%}"])
        k = (r5.relative_error / 0.01) ** 2
        rows.append(["GPU to 1% (extrapolated)", f"{n}x{n}", int(r5.samples * k),
                     f"{t5 * k:.0f}", "", "1.00%"])
    t0 = time.perf_counter()
    c = twin.trace(scene, camera, (32, 32), 16)
    tc = time.perf_counter() - t0
    rows.append(["numpy twin", "32x32", c.samples, f"{tc:.2f}",
                 f"{c.samples * 32 * 32 / tc / 1e6:.3f}", f"{c.relative_error:.2%}"])
    try:
        import mitsuba  # noqa: F401
    except ImportError:
        rows.append(["Mitsuba 3 scalar_rgb", "not installed", "", "", "", ""])
    else:
        import tempfile

        sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
        from tests.oracle import mitsuba_scene
        from glshade.pathtrace import TraceScene
        from glshade.radiosity.cornell import CORNELL_CAMERA

        ts = TraceScene.from_scene(scene)
        with tempfile.TemporaryDirectory() as folder:
            mitsuba_scene.render(ts, CORNELL_CAMERA, 16, 1, folder)  # (loads its plugins)
            t0 = time.perf_counter()
            mitsuba_scene.render(ts, CORNELL_CAMERA, n, 32, folder)
            tm = time.perf_counter() - t0
        rows.append(["Mitsuba 3 scalar_rgb", f"{n}x{n}", 32, f"{tm:.2f}",
                     f"{32 * n * n / tm / 1e6:.2f}", ""])
    print(table(rows, ("tracer", "size", "spp", "seconds", "M paths/s", "rel. error")))


if __name__ == "__main__":
    main()
