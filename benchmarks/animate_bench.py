"""Animation throughput: a 120-frame 512x512 teapot path (assets/scenes/teapot-orbit.toml)
rendered with 1 and 2 worker jobs, frames per second and the speed-up (worker start-up
included). Run: ``.venv/bin/python benchmarks/animate_bench.py``."""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import table  # noqa: E402

from glshade.animate import render_frames  # noqa: E402
from glshade.io.scenefile import load_scene  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent


def main() -> None:
    sf = load_scene(ROOT / "assets/scenes/teapot-orbit.toml")
    frames = 120
    results = {}
    for _ in range(2):  # alternate, keep the best of two
        for jobs in (1, 2):
            t = time.perf_counter()
            n = sum(1 for _ in render_frames(sf.scene, sf.path, frames, "phong",
                                             size=(512, 512), samples=4, jobs=jobs))
            fps = n / (time.perf_counter() - t)
            results[jobs] = max(results.get(jobs, 0.0), fps)
    rows = [(str(j), f"{results[j]:.1f}", f"{results[j] / results[1]:.2f}x") for j in (1, 2)]
    print(f"{frames} frames, 512x512, phong, MSAA 4 (best of 2 alternating runs)")
    print(table(rows, ("jobs", "frames/s", "speed-up")))


if __name__ == "__main__":
    main()
