"""The subcommands that draw: render, animate, compare, view and doctor. Heavy imports sit
inside each, so ``--help`` needs no GL."""

from __future__ import annotations

import json
import os
import sys

from ..errors import EXIT_ENVIRONMENT, EXIT_OK, EXIT_USAGE, InputError, SceneError, UsageError
from ..io.scenefile import RenderSettings
from ..options import RenderConfig
from . import arguments as a
from . import validators as v
from .info import info
from .inputs import load_job

__all__ = ["info", "render", "animate", "batch", "compare", "view", "doctor"]

#: compare renders small tiles, one sample per pixel like its references
COMPARE_DEFAULTS = RenderSettings(width=256, height=256, samples=0)


def render(args: a.RenderCommandArgs) -> int:
    """``glshade render``: one image of a mesh, scene or solid."""
    from ..io.images import save_image
    from ..render.renderer import Renderer
    from ..render.state import sees_through

    v.check_outputs({"the image": args.output})  # (before any work)
    job = load_job(args, args.mesh)
    (width, height), options = job.size, job.options
    with job.explained(), Renderer(config=job.config(args.backend)) as renderer:
        image = renderer.render(job.scene, job.camera, options)
        shadows = _shadow_summary(renderer, options)
        if sees_through(options, job.scene) and renderer.transparency is not None:
            shadows += f"; {renderer.transparency}"
    save_image(image, args.output)
    if not args.quiet:
        print(f"{args.output}: {width}x{height} {options.mode.value}, "
              f"{_contents(job.scene)} ({renderer.backend})" + shadows)
    return EXIT_OK


def _shadow_summary(renderer, options) -> str:
    """The render line's words on shadows: the method, and a map's sizes and footprint."""
    from ..modes import Shadows

    shadow_pass = renderer.shadow_pass
    if options.shadows is Shadows.OFF or shadow_pass is None:
        return ""
    if options.shadows is Shadows.MAP and shadow_pass.maps is not None:
        return "; " + shadow_pass.maps.summary()
    return "; exact shadows (a ray a pixel and light)"


def _contents(scene) -> str:
    """What a scene holds, in words: "1,200 polygons", "1 solid, 7 leaves", "2,000
    points", or several."""
    parts = []
    polygons = sum(m.mesh.n_faces for m in scene.models)
    if scene.models:
        parts.append(f"{polygons:,} polygon{'s' if polygons != 1 else ''}")
    if scene.solids:
        n, leaves = len(scene.solids), sum(s.solid.n_leaves for s in scene.solids)
        parts.append(f"{n} solid{'s' if n != 1 else ''}, {leaves:,} "
                     f"lea{'ves' if leaves != 1 else 'f'}")
    points = sum(c.cloud.n_points for c in scene.clouds)
    if scene.clouds:
        parts.append(f"{points:,} point{'s' if points != 1 else ''}")
    return ", ".join(parts) or "nothing"


#: seconds of a mesh's turntable when neither --frames nor --duration is given
TURNTABLE_SECONDS = 4.0


def animate(args: a.AnimateArgs) -> int:
    """``glshade animate``: a scene along its camera path, to GIF, APNG, MP4 or frames."""
    from ..animate import animate as run, output_format
    from ..animate.writers import check_fps

    output_format(args.output)  # a bad extension fails before any rendering
    folder = args.output.endswith(("/", os.sep))  # (a folder/ of frames)
    v.check_outputs({} if folder else {"-o": args.output}, {"-o": args.output} if folder
                    else None)
    job = load_job(args, args.scene)
    st = job.settings
    fps = args.fps or check_fps(st.fps, f"{args.scene}: [render] fps")
    duration = args.duration if args.duration is not None else st.duration
    if job.path is None and duration is None:
        duration = TURNTABLE_SECONDS
    if args.frames is not None:
        frames = args.frames
    elif duration:
        frames = max(1, int(round(duration * fps)))
    else:
        frames = 1
    if job.path is None:  # a mesh: one turn round it, the last frame one step short of
        from ..scene import CameraPath  # the first, so that the loop is seamless

        centre = job.scene.bounds.mean(0)
        job.path = CameraPath.turntable(job.camera, centre, max(frames - 1, 1) / fps,
                                        360.0 * (frames - 1) / frames)
    modes = [m.value for m in args.modes] if args.modes else [job.options.mode.value]
    jobs = args.jobs or os.cpu_count() or 1
    with job.explained():
        n = run(job.scene, job.path, frames, job.options, modes=modes, output=args.output,
                fps=fps, config=job.config(args.backend), jobs=jobs,
                progress=None if not args.quiet else False, scheduler=args.scheduler)
    if not args.quiet:
        where = (f"Dask at {args.scheduler}" if args.scheduler else
                 f"{jobs} job{'s' if jobs > 1 else ''}")
        print(f"{args.output}: {n} frames, {job.size[0]}x{job.size[1]}, {fps:g} fps, "
              f"{'/'.join(modes)}, {where}")
    return EXIT_OK


def batch(args: a.BatchArgs) -> int:
    """``glshade batch``: every mesh under the inputs to images, resumably."""
    from ..batch import BatchSpec, batch as run
    from ..scene import Material

    if args.eye is not None or args.target is not None:
        raise UsageError("batch frames every mesh itself; use --views N for more "
                         "directions, not --eye/--target")
    v.check_outputs({}, {"-o": args.output})  # (the folder; before any mesh is read)
    given = args.given("color", "ka", "kd", "ks", "shininess", "opacity")
    Material.from_values(given)  # bad values fail now, not once per mesh
    if args.shadows and len(args.shadows) > 1:
        raise UsageError("--shadows: one method for batch (several are for compare)")
    if args.transparency and len(args.transparency) > 1:
        raise UsageError("--transparency: one method for batch (several are for compare)")
    options = RenderSettings().options.replace(**({"srgb": True} if args.srgb else {}),
                                               **({"shadows": args.shadows[0]}
                                                  if args.shadows else {}),
                                               **({"transparency": args.transparency[0]}
                                                  if args.transparency else {}))
    spec = BatchSpec(modes=tuple(m.value for m in args.modes), outputs=args.outputs,
                     size=args.size or (256, 256),
                     samples=4 if args.samples is None else args.samples, views=args.views,
                     options=options, material=given, background=args.background,
                     lights=args.light, crease=args.crease, fov=args.fov,
                     backend=args.backend)
    jobs = args.jobs or (os.cpu_count() or 1)
    result = run(args.inputs, args.output, spec, jobs=jobs, scheduler=args.scheduler,
                 overwrite=args.overwrite, progress=None if not args.quiet else False)
    if not args.quiet:
        print(result.summary())
    for r in result.rows:
        if r.status == "error":
            print(f"glshade: error: {r.message}", file=sys.stderr)
    return EXIT_OK if not result.count("error") else EXIT_USAGE


#: a sphere sweep's deepest subdivision (level 8: 1.3 M triangles for the icosphere)
SPHERE_MAX_LEVEL = 8


def _sweep(args: a.CompareArgs, modes: list[str]) -> int:
    from ..atomic import atomic_write
    from ..compare import sweep, sweep_plot
    from ..compare.sweeps import icosphere_level, uv_sphere_level
    from ..io.images import save_image
    from ..parallel import Progress

    if args.mesh.startswith("patches:"):
        return _patch_sweep(args, modes)
    spec = args.mesh.removeprefix("primitive:").split(":")[0]
    if spec not in ("icosphere", "uv_sphere"):
        raise UsageError("--sweep needs a sphere primitive (primitive:icosphere or "
                         "primitive:uv_sphere) or patches:NAME")
    make = icosphere_level if spec == "icosphere" else uv_sphere_level
    levels = list(range(7)) if args.levels is None else args.levels
    if max(levels) > SPHERE_MAX_LEVEL:
        raise UsageError(f"--levels: a sphere's subdivision levels run from 0 to "
                         f"{SPHERE_MAX_LEVEL}, got {max(levels)}")
    with Progress(len(levels), unit="levels") as bar:
        config = RenderConfig(*(args.size or COMPARE_DEFAULTS.size), samples=0,
                              backend=args.backend)
        rows = sweep(make, levels, modes=modes, config=config, jobs=args.jobs or 1,
                     scheduler=args.scheduler, progress=bar)
    print("mean |error| against the analytic sphere (8-bit units) and the brightest pixel "
          "(the reference's: %.1f)" % rows[0][modes[0]].reference_peak)
    print("level  faces     " + "  ".join(f"{m:>9}" for m in modes) + "   " +
          "  ".join(f"{'peak ' + m:>13}" for m in modes))
    for r in rows:
        print(f"{r['level']:>5}  {r['faces']:>8,}  " +
              "  ".join(f"{r[m].mean_abs:>9.3f}" for m in modes) + "   " +
              "  ".join(f"{r[m].peak:>13.1f}" for m in modes))
    save_image(sweep_plot(rows, modes), args.output)
    if args.json:
        with atomic_write(args.json, "w") as f:
            json.dump([{"level": r["level"], "faces": r["faces"],
                        **{m: r[m].__dict__ for m in modes}} for r in rows], f, indent=2)
    print(f"plot: {args.output}")
    return EXIT_OK


def _patch_sweep(args: a.CompareArgs, modes: list[str]) -> int:
    """``compare patches:NAME --sweep``: exact against averaged normals, level by level."""
    from ..atomic import atomic_write
    from ..compare import patch_sweep, sweep_plot
    from ..compare.sweeps import PATCH_SWEEP_LEVELS
    from ..io.images import save_image
    from ..io.meshes import load_source
    from ..patches.tessellation import MAX_LEVEL

    levels = args.levels if args.levels is not None else PATCH_SWEEP_LEVELS
    if min(levels) < 1:
        raise UsageError(f"--levels: a patch sweep's tessellation levels run from 1 to "
                         f"{MAX_LEVEL}, got {min(levels)}")
    surface = load_source(args.mesh)
    # (flat shading lights each polygon by its own normal: the vertex normals do not show)
    modes = [m for m in modes if m in ("gouraud", "phong")] or ["phong"]
    size = args.size or COMPARE_DEFAULTS.size
    rows = patch_sweep(surface, levels=levels, modes=modes, size=size,
                       backend=args.backend, progress=None)
    series = [f"{m} {k}" for m in modes for k in ("exact", "averaged")]
    print(f"mean |error| against Phong on a fine tessellation with exact normals (8-bit "
          f"units), {args.mesh}")
    print("level  triangles  " + "  ".join(f"{s:>17}" for s in series))
    for r in rows:
        print(f"{r['level']:>5}  {r['faces']:>9,}  " +
              "  ".join(f"{r[s].mean_abs:>17.3f}" for s in series))
    save_image(sweep_plot(rows, series, title="error vs exact normals, finely tessellated"),
               args.output)
    if args.json:
        with atomic_write(args.json, "w") as f:
            json.dump([{"level": r["level"], "faces": r["faces"],
                        **{s: r[s].__dict__ for s in series}} for r in rows], f, indent=2)
    print(f"plot: {args.output}")
    return EXIT_OK


def compare(args: a.CompareArgs) -> int:
    """``glshade compare``: the modes against a reference, as a grid and numbers."""
    from ..compare import compare as run
    from ..io.images import save_image

    modes = list(args.modes)
    gltf = [m for m in modes if m.startswith("pbr-")]
    if gltf and (args.sweep or len(args.shadows or ()) > 1 or
                 len(args.transparency or ()) > 1):
        raise UsageError(f"--modes {gltf[0]} (glTF's model) is for a grid of modes, not with "
                         "--sweep or several --shadows/--transparency methods")
    if args.patch_size is not None and "radiosity" not in modes:
        raise UsageError("--patch-size is the radiosity mode's: add radiosity to --modes")
    if args.sweep:
        return _sweep(args, modes)
    v.check_outputs({"the grid": args.output, "--json": args.json, "--csv": args.csv},
                    {"--save-tiles": args.save_tiles})  # (before any work)
    job = load_job(args, args.mesh, COMPARE_DEFAULTS)
    if len(args.shadows or ()) > 1 and len(args.transparency or ()) > 1:
        raise UsageError("compare one option's methods at a time: several --shadows or "
                         "several --transparency, not both")
    if args.shadows and len(args.shadows) > 1:
        return _compare_methods(args, job, "shadows", args.shadows)
    if args.transparency and len(args.transparency) > 1:
        return _compare_methods(args, job, "transparency", args.transparency)
    scenes, surfaces = {}, None
    if "radiosity" in modes:
        scenes["radiosity"], surfaces = _radiosity_for_compare(args, job)
    try:
        result = run(job.scene, job.camera, modes, args.reference, diff=args.diff,
                     options=job.options, config=job.config(args.backend).replace(samples=0),
                     scale=args.scale, spp=args.spp, scenes=scenes)
    except SceneError as exc:  # (the path tracer's refusal of the scene: say which input)
        if str(exc).startswith(str(args.mesh)):
            raise
        raise SceneError(f"{args.mesh}: {exc}") from None
    if args.save_tiles:
        result.save_tiles(args.save_tiles)
    save_image(result.image, args.output)
    print(result.table())
    if surfaces is not None:
        print(surfaces)
    if args.json:
        result.write_json(args.json)
    if args.csv:
        result.write_csv(args.csv)
    print(f"grid: {args.output}")
    return EXIT_OK


def _compare_methods(args: a.CompareArgs, job, option: str, values) -> int:
    """``compare --shadows exact,map`` or ``--transparency exact,weighted,blend``: the
    methods side by side in one shading mode, each one's difference from the first, and
    the pixels that differ."""
    from ..compare.methods import compare_methods
    from ..io.images import save_image
    from ..render.renderer import SHADOWED_MODES

    from ..modes import ShadingMode

    mode = ShadingMode.parse(args.modes[0]) if len(args.modes) == 1 else ShadingMode.PHONG
    if mode not in SHADOWED_MODES:
        raise UsageError(f"--{option} compares its methods in a lit mode (flat, gouraud or "
                         f"phong; with several --modes, phong), not {mode.value}")
    with job.explained():
        result = compare_methods(job.scene, job.camera, option, [m.value for m in values],
                                 job.options.replace(mode=mode),
                                 config=job.config(args.backend).replace(samples=0))
    save_image(result.image, args.output)
    print(f"{option} in {mode.value}, against {result.reference}:")
    print(result.table())
    print(f"grid: {args.output}")
    return EXIT_OK


def _radiosity_for_compare(args: a.CompareArgs, job):
    """The radiosity mode's scene for compare -- the scene's solution at exposure 1, so its
    pixels are radiosities (the path-traced reference's units) -- and, against a pathtrace
    reference, the per-surface table: the solution's area means beside path tracing's."""
    from ..io.tables import format_table
    from ..radiosity import solve

    try:
        solution = solve(job.scene, args.patch_size, backend=args.backend, progress=False)
    except InputError as exc:
        raise UsageError(f"{args.mesh}: the radiosity mode needs a solution: {exc}") from None
    scene = solution.scene(exposure=1.0, background=job.scene.background)
    if args.reference != "pathtrace":
        return scene, None
    from ..pathtrace.surfaces import surface_radiosity

    names, means = solution.surface_means()
    traced = surface_radiosity(job.scene, points=1024, spp=max(args.spp, 16),
                               backend=args.backend.value)
    rows = []
    for name, b in zip(names, means):
        p, se = traced[name]
        gap = (b.mean() - p.mean()) / p.mean() if p.mean() > 0 else float("nan")
        rows.append((name, " ".join(f"{x:.4g}" for x in b), " ".join(f"{x:.4g}" for x in p),
                     f"{se.mean():.2g}", f"{gap:+.1%}"))
    head = ("surface", "radiosity B (RGB)", "path traced B (RGB)", "its SE", "radiosity vs")
    return scene, ("per surface, area means (radiosity units)\n" + format_table(rows, head))


def view(args: a.ViewArgs) -> int:
    """``glshade view``: the interactive window."""
    from ..viewer.window import Viewer

    v.check_outputs({"--screenshot": args.screenshot})  # (before the window opens)
    job = load_job(args, args.mesh, pane=1 / 3 if args.compare else 1.0)
    with job.explained(), Viewer(job.scene, job.camera, size=job.size, options=job.options,
                                 samples=job.settings.samples, compare=args.compare,
                                 visible=not args.hidden, pick=args.pick) as viewer:
        viewer.run(args.frames)
        if args.screenshot:
            viewer.screenshot(args.screenshot)
    return EXIT_OK


def doctor(args: a.DoctorArgs) -> int:
    """``glshade doctor``: which GL backends work here, and what they are."""
    import os

    from ..errors import OptionError
    from ..render import kernels
    from ..render.context import (chosen_device, create_context, egl_devices, probe_backends,
                                  worker_devices)
    from ..render.features import feature_table

    ok = True
    try:
        with create_context(args.backend) as ctx:
            facts = ctx.info
            features = ctx.features
            kernel = kernels.chosen(ctx).value if ctx.features.storage else None
        print(f"backend chosen     {facts['backend']}")
        for key in ("vendor", "renderer", "version", "max_samples", "max_texture_size"):
            print(f"{key.replace('_', ' '):<18} {facts[key]}")
        print("path tracer kernel " + (
            "fragment (no compute kernels before GL 4.3)" if kernel is None else
            f"{kernel} (measured faster here before; kept in {kernels.cache_file()})"
            if kernel != "auto" else "not measured on this GL yet (the first trace with "
            "kernel='auto' times both)"))
        # each feature and the path it takes on this GL: what a student's report needs
        for line in feature_table(features):
            print(line)
    except Exception as exc:  # report, then go on to the per-backend probe
        ok = False
        print(f"backend chosen     none: {exc}")
    print("backends:")
    for name, status in probe_backends().items():
        print(f"  {name:<8} {status}")
    devices = egl_devices()
    try:
        chosen, why = chosen_device()
    except OptionError as exc:  # (GLSHADE_EGL_DEVICE names no device: say so, list them)
        chosen, why = None, f"GLSHADE_EGL_DEVICE: {exc}"
    print(f"EGL devices ({len(devices)}, listed without a context on any; choose with "
          "--device or GLSHADE_EGL_DEVICE: an index, cuda:N or a part of a name):")
    for d in devices:
        kinds = ["software rasterizer" if d["software"] else "GPU"]
        if d["cuda"] is not None:
            kinds.append(f"cuda:{d['cuda']}")
        if d["node"]:
            kinds.append(d["node"])
        mark = "*" if d["index"] == chosen else " "
        print(f" {mark}{d['index']:<3} {d['name']} ({', '.join(kinds)})")
    if chosen is not None and chosen >= len(devices):
        why += f"; there is no device {chosen}: a render fails"
    print(f"a render takes: {chosen if chosen is not None else 'none'} ({why})")
    dealt = [] if os.environ.get("GLSHADE_EGL_DEVICE", "").strip() else worker_devices()
    print("--jobs and --scheduler workers take: " + (
        f"{', '.join(dealt)} in turn" if dealt else "what a render takes (no several GPUs "
        "here; GLSHADE_WORKER_DEVICES deals others)"))
    other = os.environ.get("GLCONTEXT_DEVICE_INDEX", "").strip()
    if other and chosen is not None and other != str(chosen):
        print(f"note: GLCONTEXT_DEVICE_INDEX={other} disagrees: glcontext would take it over "
              "a program's own choice; glshade sets it to its choice when it makes a context")
    return EXIT_OK if ok else EXIT_ENVIRONMENT
