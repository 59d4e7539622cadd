"""The device check: what a machine's GL draws with, how fast, and whether it draws what
llvmpipe draws -- one table and a JSON, in under 5 minutes (``--quick``: seconds, run by the
tests).

1. The device: the EGL device a render takes and why (``glshade doctor``'s listing, no
   context made to list them), its CUDA ordinal where the driver says, and its renderer.
2. Opaque frames/s: the teapot x100 (an instanced group) at 1920x1080 Phong, no MSAA.
3. The path tracer: paths/s on the Cornell box, the fragment program against the compute
   kernel; and on a small picture (128²), the compute kernel with one stream a pixel
   against the streams a pixel this GL gets by default (``TraceOptions.streams``).
4. Exact transparency against blending: ms a frame, 8 layers at 256x256.
5. Exactness against llvmpipe: the same scenes drawn on Mesa's software device in a
   process of its own -- polygon ids and depth byte-identical, colours within 1/255, the
   traced image's mean within its noise.

    .venv/bin/python benchmarks/device_check.py [--quick] [--json out.json] [--device D]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))

from _timing import table  # noqa: E402

import glshade  # noqa: E402
from glshade import Camera, Material, Outputs, Scene  # noqa: E402
from glshade.geometry import primitives as P  # noqa: E402
from glshade.radiosity.cornell import cornell_scene  # noqa: E402
from glshade.render.context import chosen_device, egl_devices  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent


def teapots(k: int) -> Scene:
    """The teapot, k times on a grid (one instanced group)."""
    side = int(np.ceil(np.sqrt(k)))
    t = np.tile(np.eye(4), (k, 1, 1))
    t[:, 0, 3] = (np.arange(k) % side - side / 2) * 7.0
    t[:, 2, 3] = (np.arange(k) // side - side / 2) * 7.0
    scene = Scene()
    scene.add(glshade.load_mesh(ROOT / "assets" / "teapot.obj"),
              Material(color=(0.85, 0.55, 0.3)), instances=t)
    return scene


def glass(layers: int) -> Scene:
    """``layers`` transparent planes stacked in front of a box."""
    scene = Scene()
    scene.add(P.cube(), Material(color=(0.8, 0.8, 0.8)), translation=(0, 0, -2))
    for i in range(layers):
        scene.add(P.plane(3.0), Material(color=(0.2 + 0.08 * i, 0.5, 0.9 - 0.08 * i),
                                         opacity=0.3), translation=(0, 0, 0.2 * i))
    return scene


def timed(draw, frames: int) -> float:
    draw()
    start = time.perf_counter()
    for _ in range(frames):
        draw()
    return (time.perf_counter() - start) / frames


#: what the exactness check draws, here and in the software process: its arrays saved
EXACT = """
import sys, numpy as np
sys.path.insert(0, {bench!r})
import device_check as d
np.savez(sys.argv[1], **d.exact_arrays({quick!r}))
"""


def exact_arrays(quick: bool) -> dict:
    """The exactness scenes' arrays on this process's device: the teapot's ids, depth and
    colour at 320x240, and a traced Cornell box's image."""
    from glshade import pathtrace

    scene = Scene()
    scene.add(glshade.load_mesh(ROOT / "assets" / "teapot.obj"), Material())
    cam = Camera.look_at((4.0, 3.5, 6.0), (0.3, 1.2, 0.0))
    with glshade.Renderer(320, 240, samples=0) as r:
        frame = r.render_frame(scene, cam, "phong", outputs=Outputs.ALL)
    box, box_camera = cornell_scene()
    traced = pathtrace.trace(box, box_camera, size=(32, 32) if quick else (64, 64),
                             spp=8 if quick else 32, progress=False)
    return {"face_id": frame.face_id, "depth": frame.depth, "color": frame.color,
            "traced": traced.image}


def software_arrays(quick: bool) -> dict:
    """:func:`exact_arrays` drawn by Mesa's software device, in a process of its own."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "soft.npz"
        env = {**os.environ, "GLSHADE_BACKEND": "osmesa", "GLSHADE_REQUIRE_GPU": ""}
        env.pop("GLSHADE_EGL_DEVICE", None)
        code = EXACT.format(bench=str(Path(__file__).parent), quick=quick)
        subprocess.run([sys.executable, "-c", code, str(out)], check=True, env=env,
                       cwd=ROOT, timeout=600)
        with np.load(out) as data:
            return {k: data[k] for k in data.files}


def paths_per_s(scene, camera, size, spp: int, **options) -> tuple[int, float]:
    """The tracer's streams and its paths a second at ``size`` x ``spp``: one tracer made
    and compiled before the clock (its context, program and tables: a GPU traces a small
    picture in less time than a context takes to make), the picture read back inside it."""
    from glshade import pathtrace

    with pathtrace.PathTracer(scene, size, **options) as tracer:
        tracer.add(camera, 1)  # (compiled; the kernel chosen)
        tracer.reset()
        start = time.perf_counter()
        tracer.add(camera, spp)
        tracer.result()  # (read back: the passes done)
        return tracer.gpu.streams, size[0] * size[1] * spp / (time.perf_counter() - start)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="small sizes: seconds")
    parser.add_argument("--json", default=None, help="also write the results here")
    parser.add_argument("--device", default=None, help="an EGL index, cuda:N or a name")
    args = parser.parse_args(argv)
    if args.device is not None:
        os.environ["GLSHADE_EGL_DEVICE"] = args.device
    quick = args.quick
    devices = egl_devices()
    chosen, why = chosen_device()
    device = next((d for d in devices if d["index"] == chosen), None)
    results: dict = {"device": {"index": chosen, "why": why,
                                "name": device["name"] if device else None,
                                "cuda": device["cuda"] if device else None,
                                "listed": [d["name"] for d in devices]}}
    size = (320, 180) if quick else (1920, 1080)
    count = 4 if quick else 100
    with glshade.Renderer(*size, samples=0) as r:
        results["device"]["renderer"] = r.context.detail
        scene = teapots(count)
        cam = Camera.look_at((0.0, 40.0, 60.0), (0, 0, 0), fov_y=50).with_planes(scene.bounds)
        results["opaque_fps"] = 1.0 / timed(lambda: r.render(scene, cam, "phong"),
                                            1 if quick else 5)
    box, box_camera = cornell_scene()
    trace_size, spp = ((32, 32), 4) if quick else ((256, 256), 32)
    rates = {kernel: paths_per_s(box, box_camera, trace_size, spp, kernel=kernel)[1]
             for kernel in ("fragment", "compute")}
    results["trace_paths_per_s"] = rates
    small = (32, 32) if quick else (128, 128)
    # (one invocation a pixel, then the streams this GL takes by default)
    shared = dict(paths_per_s(box, box_camera, small, spp, kernel="compute", streams=asked)
                  for asked in (1, None))
    results["trace_streams_paths_per_s"] = {str(k): v for k, v in shared.items()}
    layered = glass(8)
    cam = Camera.look_at((0.5, 0.4, 4.0), (0, 0, 0))
    with glshade.Renderer(*((64, 64) if quick else (256, 256)), samples=0) as r:
        ms = {m: 1000 * timed(lambda m=m: r.render(layered, cam, "phong", transparency=m),
                              1 if quick else 10) for m in ("exact", "blend")}
    results["transparency_ms"] = ms
    here = exact_arrays(quick)
    soft = software_arrays(quick)
    traced_noise = float(np.std(here["traced"]) / np.sqrt(here["traced"].size))
    results["exact_vs_llvmpipe"] = {
        "ids_identical": bool(np.array_equal(here["face_id"], soft["face_id"])),
        "depth_identical": bool(np.array_equal(here["depth"], soft["depth"])),
        "color_max_diff": int(np.abs(here["color"].astype(int) -
                                     soft["color"].astype(int)).max()),
        "traced_mean_diff": float(abs(here["traced"].mean() - soft["traced"].mean())),
        "traced_mean_noise": traced_noise}
    e = results["exact_vs_llvmpipe"]
    rows = [("device", f"{chosen} ({why})", results["device"]["name"] or "-"),
            ("renderer", results["device"]["renderer"], ""),
            ("CUDA ordinal", str(results["device"]["cuda"]), ""),
            (f"opaque fps, {count} teapots, {size[0]}x{size[1]}",
             f"{results['opaque_fps']:.2f}", ""),
            ("path tracer M paths/s (fragment / compute)",
             f"{rates['fragment'] / 1e6:.3f} / {rates['compute'] / 1e6:.3f}",
             f"{trace_size[0]}x{trace_size[1]} x {spp}, Cornell box"),
            (f"compute M paths/s, streams {' / '.join(map(str, shared))}",
             " / ".join(f"{v / 1e6:.3f}" for v in shared.values()),
             f"{small[0]}x{small[1]} x {spp}, Cornell box"),
            ("exact / blend transparency ms", f"{ms['exact']:.1f} / {ms['blend']:.1f}",
             f"{ms['exact'] / ms['blend']:.2f}x"),
            ("against llvmpipe: ids, depth", f"{e['ids_identical']}, {e['depth_identical']}",
             ""),
            ("against llvmpipe: colour max diff (1/255)", str(e["color_max_diff"]), ""),
            ("against llvmpipe: traced mean diff (noise)",
             f"{e['traced_mean_diff']:.2e} ({e['traced_mean_noise']:.2e})", "")]
    print(table(rows, ("check", "value", "note")))
    if args.json:
        Path(args.json).write_text(json.dumps(results, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
