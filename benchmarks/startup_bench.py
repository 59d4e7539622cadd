"""Start-up: how long ``import glshade`` and a whole ``glshade render primitive:cube``
process take, and where the render's time goes (interpreter, imports, GL context, shader
compile, first draw, PNG). Medians of several fresh processes.

Run: ``.venv/bin/python benchmarks/startup_bench.py [--runs 7]``.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import table  # noqa: E402

STAGES = r"""
import json, sys, time
t0 = time.perf_counter()
import glshade
t1 = time.perf_counter()
from glshade.geometry import primitives
from glshade.render.renderer import Renderer
from glshade import Scene, default_camera, save_image
t2 = time.perf_counter()
mesh = primitives.from_spec("primitive:cube")
scene = Scene(); scene.add(mesh)
camera = default_camera(scene, 800 / 600)
t3 = time.perf_counter()
r = Renderer(800, 600, samples=4)
t4 = time.perf_counter()
r.shaders.program(glshade.ShadingMode.PHONG, aux=False)
t5 = time.perf_counter()
image = r.render(scene, camera, "phong")
t6 = time.perf_counter()
save_image(image, sys.argv[1])
t7 = time.perf_counter()
r.close()
print(json.dumps({"import glshade": t1 - t0, "import numpy, moderngl, renderer": t2 - t1,
                  "mesh and camera": t3 - t2, "GL context and targets": t4 - t3,
                  "compile the first program": t5 - t4, "first render and read-back": t6 - t5,
                  "write the PNG": t7 - t6}))
"""


def wall(cmd) -> float:
    t = time.perf_counter()
    subprocess.run(cmd, check=True, capture_output=True)
    return time.perf_counter() - t


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", type=int, default=7)
    args = ap.parse_args()
    py = sys.executable
    out = Path(tempfile.mkdtemp()) / "cube.png"
    whole = {
        "python -c pass": [py, "-c", "pass"],
        "python -c 'import glshade'": [py, "-c", "import glshade"],
        "glshade --help": [py, "-m", "glshade", "--help"],
        "glshade render primitive:cube": [py, "-m", "glshade", "render", "primitive:cube", "-o",
                                          str(out), "-q"],
    }
    rows = []
    for name, cmd in whole.items():
        wall(cmd)  # warm the file cache
        rows.append((name, f"{statistics.median(wall(cmd) for _ in range(args.runs)) * 1000:.0f}"))
    print("whole processes, median of", args.runs, "(ms)")
    print(table(rows, ("command", "ms")))
    stages = [json.loads(subprocess.run([py, "-c", STAGES, str(out)], check=True,
                                        capture_output=True, text=True).stdout)
              for _ in range(args.runs)]
    print("\nwhere glshade render's time goes, in-process stages, median (ms)")
    print(table([(k, f"{statistics.median(s[k] for s in stages) * 1000:.1f}")
                 for k in stages[0]], ("stage", "ms")))


if __name__ == "__main__":
    main()
