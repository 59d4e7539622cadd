"""Path tracing against Mitsuba 3: paths a second and time to 1% RMS error on the Cornell
box and on the box holding a large mesh, at 128² (and 256² with ``--sizes 128,256``), for
each of glshade's ways of finding triangles (the hierarchy, the flat loop, the default) and
samplers (independent PCG numbers, Owen-scrambled Sobol points; a fragment program a pass
or the compute kernel, the same numbers; each pixel its own or,
``coherent``, blocks of 4x2 sharing them; with the radiosity control variate, whose values
for the large scene come from the box with a 320-triangle sphere; ``adaptive``, a pilot's
time counted) and Mitsuba's
``scalar_rgb`` (and ``llvm_ad_rgb`` where its LLVM loads) with its independent and its
low-discrepancy sampler, interleaved rounds in one process, medians. Each tracer is made
once and its renders alone are timed (glshade's tables and program, Mitsuba's scene file
and kd-tree: built before the clock, as a user's second render finds them). Error: RMS over pixels
of the difference from a long glshade render (``--reference-spp``, Sobol, another seed),
relative to the reference's mean. Time to 1%: the samples a pixel that leave 1% RMS error
at the paths a second measured nearest that count -- for independent samples by the
1/sqrt(N) law from the error at ``--spp``, at its speed there; for a low-discrepancy
sampler, whose error falls faster, its error and its speed measured again at ``--ld-spp``
(256 and 1,024; Mitsuba's scene for each count loaded and rendered once first) and the
count read off the log-log line through the points that bracket 1% (or the last two).

Samples a pixel default to 64, a power of 4: Mitsuba's ``ldsampler`` draws what it is asked
for, so every tracer's error is measured at the same count (asked for 32, it draws 64).

Run: ``.venv/bin/python benchmarks/pathtrace_bench.py [--sizes 128] [--spp 64] [--rounds 3]
[--reference-spp 16384] [--ld-spp 256,1024]``.
"""

from __future__ import annotations

import argparse
import contextlib
import glob
import math
import os
import re
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _timing import table  # noqa: E402

from glshade import pathtrace  # noqa: E402
from glshade.geometry import primitives  # noqa: E402
from glshade.pathtrace import PathTracer, TraceScene  # noqa: E402
from glshade.pathtrace.adaptive import pilot_samples  # noqa: E402
from glshade.radiosity import cornell_scene  # noqa: E402
from glshade.radiosity.control import radiosity_control  # noqa: E402
from glshade.radiosity.cornell import CORNELL_CAMERA  # noqa: E402
from glshade.render.context import create_context  # noqa: E402
from glshade.render.passes.pathtrace import GpuPathTracer  # noqa: E402
from glshade.scene import Material  # noqa: E402


def scenes(level: int = 6) -> dict:
    """The Cornell box (32 triangles), and the box holding a sphere of 81,920 triangles
    (``level``: the sphere's subdivisions, 6)."""
    small, camera = cornell_scene()
    large, _ = cornell_scene()
    large.add(primitives.icosphere(level), Material(color=(0.75, 0.75, 0.75), kd=0.9, ks=0.0),
              scale=110.0, translation=(280.0, 115.0, 280.0))
    return {"cornell (32 tris)": small, "cornell + sphere (81,952 tris)": large}, camera


def rms(image: np.ndarray, reference: np.ndarray) -> float:
    return float(np.sqrt(np.mean((image - reference) ** 2)) / reference.mean())


def llvm_library() -> str:
    """An LLVM >= 16 for Mitsuba's ``llvm_ad_rgb``: DRJIT_LIBLLVM_PATH, else the newest
    installed one (``apt-get install libllvm19``), else ""."""
    named = os.environ.get("DRJIT_LIBLLVM_PATH", "")
    if named:
        return named
    found = []
    for path in glob.glob("/usr/lib/*/libLLVM-*.so*") + glob.glob("/usr/lib/*/libLLVM.so.*"):
        version = re.search(r"LLVM(?:-|\.so\.)(\d+)", Path(path).name)
        if version and int(version.group(1)) >= 16:
            found.append((int(version.group(1)), path))
    return max(found)[1] if found else ""


def mitsuba_variants() -> list[str]:
    # llvm_ad_rgb needs an LLVM >= 16, named by DRJIT_LIBLLVM_PATH before Mitsuba loads:
    # with an older one it crashes in code generation -- the whole process
    library = llvm_library()
    if library:
        os.environ["DRJIT_LIBLLVM_PATH"] = library
    try:
        import mitsuba as mi
    except ImportError:
        return []
    usable = ["scalar_rgb"]
    if library:
        mi.set_variant("llvm_ad_rgb")
        usable.append("llvm_ad_rgb")
    return usable


def mitsuba_series(variant: str, ts, size: int, spp: int, folder: str, sampler: str):
    """A render of Mitsuba's scene, loaded once (its file, its kd-tree: not timed, as
    glshade's tables are built once), by ``variant``: a function of no arguments."""
    import mitsuba as mi

    from tests.oracle import mitsuba_scene

    mi.set_variant(variant)
    scene = mitsuba_scene.load(ts, CORNELL_CAMERA, size, spp, folder, sampler=sampler)

    def render():
        mi.set_variant(variant)
        return mitsuba_scene.picture(scene)
    return render


def drawn_spp(tracer: str, spp: int) -> int:
    """The samples a pixel ``tracer`` draws when asked for ``spp``: Mitsuba's ldsampler
    rounds up to a square power of two (32 -> 64)."""
    if "ldsampler" in tracer:
        return 4 ** math.ceil(math.log(spp, 4))
    return spp


def run(name, scene, proxy, camera, size, args, ctx, folder, stack) -> list:
    """One scene at one size: each tracer's paths a second and time to 1% (``proxy``: the
    scene whose radiosity gives the control values)."""
    ts = TraceScene.from_scene(scene)
    reference = pathtrace.trace(ts, camera, (size, size), spp=args.reference_spp,
                                context=ctx, progress=False, seed=99,
                                sampler="sobol").image
    series: dict = {}
    at: dict = {}  # (for a low-discrepancy tracer: its picture at a given count)
    # the control variate's values, one a model, from the scene's radiosity (solved once);
    # the large sphere is too many patches to solve here, so its scene's come from the same
    # box with a 320-triangle sphere in its place (any values leave the answer unbiased)
    t = time.perf_counter()
    control = radiosity_control(proxy, context=ctx)
    print(f"{name}: radiosity control values in {time.perf_counter() - t:.1f} s")
    for accel, sampler, coherent, ctl, adaptive, kernel in (
            ("bvh", "pcg", False, False, False, "fragment"),
            ("flat", "pcg", False, False, False, "fragment"),
            ("auto", "pcg", False, False, False, "fragment"),
            ("auto", "pcg", False, False, False, "compute"),
            ("auto", "sobol", False, False, False, "fragment"),
            ("auto", "sobol", False, False, False, "compute"),
            ("auto", "pcg", True, False, False, "fragment"),
            ("auto", "sobol", True, False, False, "fragment"),
            ("auto", "sobol", False, True, False, "fragment"),
            ("auto", "sobol", True, True, False, "fragment"),
            ("auto", "sobol", False, False, True, "fragment"),
            ("auto", "sobol", False, True, True, "fragment"),
            ("auto", "sobol", True, True, True, "fragment")):
        if accel == "flat" and len(ts.triangles) > GpuPathTracer.FLAT_MAX:
            continue  # (too many to compile in)
        tracer = stack.enter_context(PathTracer(ts, (size, size), context=ctx, accel=accel,
                                                sampler=sampler, coherent=coherent,
                                                control=control if ctl else None,
                                                kernel=kernel))
        key = f"glshade {accel} {sampler}" + (" control" if ctl else "") + (
            " adaptive" if adaptive else "") + (" compute" if kernel == "compute" else "") + (
            " coherent" if coherent else "")
        series[key] = lambda t=tracer, a=adaptive: _glshade(t, camera, args.spp, a)
        if sampler == "sobol":
            # (a function of the count giving the render: glshade's tracer is warm already)
            at[key] = lambda n, t=tracer, a=adaptive: lambda: _glshade(t, camera, n, a)
    for variant in mitsuba_variants():
        # its default sampler, and its low-discrepancy one (as glshade's sobol is)
        for sampler in ("independent", "ldsampler"):
            try:
                render = mitsuba_series(variant, ts, size, args.spp, folder, sampler)
                render()  # (compiles, loads its plugins)
            except Exception as exc:  # (an LLVM that will not load: say so, go on)
                print(f"{variant}: not usable here ({type(exc).__name__})")
                break
            series[f"Mitsuba {variant} {sampler}"] = render
            if sampler == "ldsampler":
                at[f"Mitsuba {variant} {sampler}"] = lambda n, v=variant: _warm(
                    mitsuba_series(v, ts, size, n, folder, "ldsampler"))
    for fn in series.values():
        fn()  # (compiled once before the clock)
    seconds: dict = {k: [] for k in series}
    errors: dict = {}
    for _ in range(args.rounds):
        for key, fn in series.items():
            t = time.perf_counter()
            image = fn()
            seconds[key].append(time.perf_counter() - t)
            errors[key] = rms(np.asarray(image)[..., :3], reference[..., :3])
    # a low-discrepancy sampler's error falls faster than 1 / sqrt(N): measured at more
    # samples, not extrapolated -- and its time there (adaptive sampling's pilot and last
    # passes cost more at 64 samples than near 1%), each tracer warm (Mitsuba's scene for
    # each count loaded and rendered once before the clock)
    curves, rates = {}, {}
    for key, fn in at.items():
        points = []
        for n in args.ld_spp:
            fn_n = fn(n)
            t = time.perf_counter()
            image = fn_n()
            points.append((n, time.perf_counter() - t, image))
        rates[key] = [(n, n * size * size / s) for n, s, _ in points]
        if not key.endswith(" coherent"):  # (a coherent tracer's error is its twin's)
            curves[key] = [(drawn_spp(key, args.spp), errors[key])] + [
                (n, rms(np.asarray(image)[..., :3], reference[..., :3]))
                for n, _, image in points]
    rows = []
    for key in series:
        # a coherent picture's pixels are drawn as its twin's are, so its expected error
        # is the twin's; its own RMS is not a fair sample of it (a block's errors come
        # eight at a time: more often under the expectation, now and then well over)
        twin = key.removesuffix(" coherent")
        curve = curves.get(twin, [(drawn_spp(key, args.spp), errors[twin])])
        s = statistics.median(seconds[key])
        rate = drawn_spp(key, args.spp) * size * size / s
        need = spp_at(curve, 0.01)
        # (the paths a second measured at the count nearest the samples to 1%)
        near = min(rates.get(key, []) + [(drawn_spp(key, args.spp), rate)],
                   key=lambda p: abs(math.log(p[0] / need)) if math.isfinite(need) else 0)
        to_1 = need * size * size / near[1]
        rows.append((name, f"{size}x{size}", key, f"{rate / 1e6:.2f}",
                     " / ".join(f"{e:.2%}" for _, e in curve), f"{need:,.0f}",
                     f"{near[1] / 1e6:.2f}", f"{to_1:.1f}"))
    return rows


def spp_at(curve: list, error: float) -> float:
    """The samples a pixel at which the RMS error reaches ``error``: ``curve`` (samples,
    error) pairs, rising samples; between the two measured points that bracket it on a
    log-log line, else from the last two (one point: the 1 / sqrt(N) of independent
    samples)."""
    if len(curve) == 1:
        n, e = curve[0]
        return n * (e / error) ** 2
    pairs = list(zip(curve, curve[1:]))
    (n0, e0), (n1, e1) = next(((a, b) for a, b in pairs if b[1] <= error), pairs[-1])
    slope = math.log(e1 / e0) / math.log(n1 / n0)  # (error ~ N^slope, slope < 0)
    if slope >= 0:  # (no fall measured: the reference's own error, or noise)
        return float("inf")
    return n0 * (error / e0) ** (1 / slope)


def _warm(render):
    """``render``, a render function, once rendered (compiled, loaded): itself."""
    render()
    return render


def _glshade(tracer, camera, spp: int, adaptive: bool = False) -> np.ndarray:
    """``spp`` samples a pixel from a tracer made once (its program and tables kept) --
    ``adaptive``: a mean of ``spp``, shared out by a pilot (its time counted)."""
    tracer.reset()
    if adaptive:
        sigma = tracer.deviations(camera, pilot_samples(spp))
        tracer.add(camera, counts=tracer.allocate(sigma, spp))
    else:
        tracer.add(camera, spp)
    return tracer.result().image


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", default="128")
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--reference-spp", type=int, default=16384)
    ap.add_argument("--scenes", default="cornell,large", help="which: cornell, large")
    ap.add_argument("--ld-spp", default="256,1024", help="the counts at which the "
                    "low-discrepancy tracers' error is measured besides --spp")
    args = ap.parse_args()
    args.ld_spp = [int(n) for n in args.ld_spp.split(",") if n]
    found, camera = scenes()
    proxies, _ = scenes(level=2)
    rows = []
    with create_context("egl") as ctx, tempfile.TemporaryDirectory() as folder, \
            contextlib.ExitStack() as stack:
        for size in (int(x) for x in args.sizes.split(",")):
            for (name, scene), proxy, short in zip(found.items(), proxies.values(),
                                                   ("cornell", "large")):
                if short not in args.scenes.split(","):
                    continue
                rows += run(name, scene, proxy, camera, size, args, ctx, folder, stack)
                print(rows[-1], flush=True)
    print(f"\n{args.spp} spp, medians of {args.rounds} interleaved rounds; RMS error against "
          f"glshade at {args.reference_spp} spp (Sobol, another seed), at {args.spp} spp and, "
          f"for a low-discrepancy sampler, at {', '.join(map(str, args.ld_spp))}; samples to 1%: "
          "independent samples by 1 / sqrt(N), low-discrepancy ones on the measured log-log "
          "line; seconds to 1% = those samples at the paths a second measured at the count "
          "nearest them; a coherent tracer's errors are its twin's (the same in "
          "expectation)")
    print(table(rows, ("scene", "size", "tracer", "M paths/s", "RMS error", "spp to 1%",
                       "M paths/s there", "s to 1%")))
    usable = mitsuba_variants()
    if not usable:
        print("Mitsuba 3 not installed (pip install mitsuba)")
    elif "llvm_ad_rgb" not in usable:
        print("Mitsuba llvm_ad_rgb not run: it needs LLVM >= 16 named by DRJIT_LIBLLVM_PATH "
              "(apt-get install libllvm19); none was found")


if __name__ == "__main__":
    main()
