"""The path tracer's materials at speed: paths a second on the Cornell box as the notes
draw it (diffuse, one colour a wall) against the same box holding glTF's materials -- a
gold GGX ball (metallic 1, roughness 0.35), a red-lacquer one (metallic 0, roughness 0.2),
a textured floor (a checkered base-colour map and a metallic-roughness map: polished and
rough checks) -- under a sky seen through the open front
(an equirectangular map, sampled by importance), interleaved rounds in one process,
medians; and the same triangles diffuse, which tells the materials' cost from the balls'
triangles'. The goal: the materials' box at 0.6x the diffuse box's paths a second or
better.

Mitsuba 3 renders the same triangles beside them (``scalar_rgb``, and ``llvm_ad_rgb``
where an LLVM >= 16 is installed), glTF's materials mapped approximately -- a metal as its
``roughconductor``, a dielectric as its ``roughplastic`` (their Fresnel exact, not
Schlick's; their Smith term separable): the same work for speed, not the same picture (the
tests compare the tracer with closed forms, quadrature and Mitsuba), the floor's maps not
carried over.

Run: ``.venv/bin/python benchmarks/pathtrace_materials_bench.py [--size 128] [--spp 16]
[--rounds 3]``.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _timing import table  # noqa: E402

import glshade  # noqa: E402
from glshade.geometry import primitives  # noqa: E402
from glshade.pathtrace import PathTracer  # noqa: E402
from glshade.radiosity import cornell_scene  # noqa: E402
from glshade.render.context import create_context  # noqa: E402


def materials_box(gltf: bool = True):
    """The Cornell box with two balls: glTF's materials, a textured floor and a sky
    (``gltf``), or the same triangles diffuse, as the notes draw them."""
    box, camera = cornell_scene()
    plain = glshade.Material(color=(0.75, 0.75, 0.75), kd=0.9, ks=0.0)
    box.add(primitives.uv_sphere(32, 64), glshade.PBRMaterial(
        base_color=(1.0, 0.77, 0.33), metallic=1.0, roughness=0.35) if gltf else plain,
        scale=90.0, translation=(180.0, 90.0, 160.0))
    box.add(primitives.uv_sphere(32, 64), glshade.PBRMaterial(
        base_color=(0.7, 0.05, 0.04), metallic=0.0, roughness=0.2) if gltf else plain,
        scale=70.0, translation=(390.0, 70.0, 120.0))
    if not gltf:
        return box, camera
    floor = next(m for m in box.models if m.name == "floor")
    v = floor.mesh.vertices
    # (a textured glTF floor: a checkered base colour, 64 x 64 texels, and a
    # metallic-roughness map whose checks alternate polished and rough)
    uv = (v[:, [0, 2]] - v[:, [0, 2]].min(0)) / np.ptp(v[:, [0, 2]], axis=0)
    checks = (np.add.outer(np.arange(64) // 8, np.arange(64) // 8) % 2).astype(bool)
    base = np.where(checks[..., None], (230, 225, 215), (60, 90, 150)).astype(np.uint8)
    mr = np.zeros((64, 64, 3), np.uint8)
    mr[..., 1] = np.where(checks, 60, 200)  # (glTF's roughness in green, metallic in blue)
    floor.mesh = glshade.Mesh(v, floor.mesh.faces, uv=uv)
    floor.material = glshade.PBRMaterial(
        base_color=(1.0, 1.0, 1.0), metallic=1.0, roughness=1.0,
        base_color_texture=glshade.Texture(base),
        metallic_roughness_texture=glshade.Texture(mr))
    sky = np.zeros((64, 128, 3))
    sky[:32], sky[32:] = (0.6, 0.7, 0.9), (0.15, 0.12, 0.1)
    sky[8:14, 40:52] = (20.0, 18.0, 15.0)  # (a sun)
    box.environment = glshade.Environment(sky)
    return box, camera


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--size", type=int, default=128)
    parser.add_argument("--spp", type=int, default=16)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    ctx = create_context("auto")
    diffuse, camera = cornell_scene()
    balls, _ = materials_box(gltf=False)
    painted, _ = materials_box()
    size = (args.size, args.size)
    tracers = {"cornell box, diffuse": PathTracer(diffuse, size, context=ctx),
               "+ two balls (8,192 tris), diffuse": PathTracer(balls, size, context=ctx),
               "+ two balls, glTF materials, textured floor, sky": PathTracer(painted, size,
                                                                             context=ctx)}

    def traced(tracer):
        def run():
            tracer.reset()
            tracer.add(camera, args.spp)
            tracer.result()
        return run

    runs = {name: traced(tracer) for name, tracer in tracers.items()}
    with tempfile.TemporaryDirectory() as folder:
        runs.update(mitsuba_runs(painted, args, folder))
        for run in runs.values():  # (a warm-up: programs compiled, kernels chosen)
            run()
        times: dict[str, list[float]] = {name: [] for name in runs}
        for _ in range(args.rounds):  # (interleaved: each round runs every renderer once)
            for name, run in runs.items():
                start = time.perf_counter()
                run()
                times[name].append(time.perf_counter() - start)
    paths = args.size * args.size * args.spp
    rates = {name: paths / statistics.median(ts) for name, ts in times.items()}
    base, same = rates["cornell box, diffuse"], rates["+ two balls (8,192 tris), diffuse"]
    ours = rates["+ two balls, glTF materials, textured floor, sky"]
    rows = [(name, f"{rate / 1e6:.3f}", f"{rate / base:.2f}x", f"{rate / same:.2f}x",
             f"{ours / rate:.2f}x" if name.startswith("Mitsuba") else "")
            for name, rate in rates.items()]
    print(f"{ctx.detail}, {args.size}x{args.size}, {args.spp} spp, medians of "
          f"{args.rounds} interleaved rounds")
    print(table(rows, ("scene", "Mpaths/s", "vs the diffuse box",
                       "vs the same triangles diffuse", "glshade's materials box vs it")))
    if not any(name.startswith("Mitsuba") for name in rates):
        print("Mitsuba 3 not installed (pip install mitsuba): no Mitsuba rows")
    for tracer in tracers.values():
        tracer.close()
    ctx.release()


def mitsuba_runs(scene, args, folder) -> dict:
    """A run of Mitsuba on the materials' box for each usable variant (each loaded once
    here, as glshade's tracers were made; its variant set again before each render)."""
    from pathtrace_bench import mitsuba_variants

    from glshade.pathtrace import TraceScene
    from glshade.radiosity.cornell import CORNELL_CAMERA
    from tests.oracle import mitsuba_scene

    variants = mitsuba_variants()
    if not variants:
        return {}
    import mitsuba as mi

    ts = TraceScene.from_scene(scene)
    runs = {}
    for variant in variants:
        mi.set_variant(variant)
        loaded = mitsuba_scene.load(ts, CORNELL_CAMERA, args.size, args.spp, folder)

        def run(variant=variant, loaded=loaded):
            mi.set_variant(variant)
            mitsuba_scene.picture(loaded)

        runs[f"Mitsuba 3 {variant}, the materials' box"] = run
    return runs


if __name__ == "__main__":
    main()
