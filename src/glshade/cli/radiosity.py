"""``glshade radiosity``: solve a scene file's diffuse light transport and render it."""

from __future__ import annotations

import os
import time

from ..errors import EXIT_OK, UsageError
from .inputs import is_scene_file, load_job

__all__ = ["radiosity", "add_parser"]

#: frames of --steps: the unshot fraction at evenly spaced steps of its logarithm
STEP_FRAMES = 36


def add_parser(sub, validators) -> None:
    v = validators
    p = sub.add_parser("radiosity", help="solve a scene's diffuse interreflection (hemicube "
                       "form factors on the GPU) and render it")
    p.add_argument("scene", metavar="SCENE.toml", help="a scene file whose materials give "
                   "emission (e.g. assets/scenes/cornell-box.toml)")
    p.add_argument("-o", "--output", required=True, type=v.image_output,
                   help="the image (.png)")
    p.add_argument("--patch-size", type=v.positive_float, metavar="S", help="cut polygons "
                   "into patches of about S (scene units; default: a 24th of the diagonal)")
    p.add_argument("--hemicube", type=v.hemicube, default=128, metavar="N",
                   help="hemicube resolution, the top face's pixels a side (default 128)")
    p.add_argument("--method", choices=["progressive", "gauss-seidel"], default="progressive",
                   help="progressive refinement (default) or Gauss-Seidel gathering over the "
                   "full matrix (small scenes)")
    stop = p.add_mutually_exclusive_group()
    stop.add_argument("--until", type=v.fraction, default=0.01, metavar="F",
                      help="stop when the unshot fraction of the emitted energy is below F "
                      "(default 0.01)")
    stop.add_argument("--iterations", type=v.count, metavar="N", help="stop after N shots "
                      "(progressive) or N sweeps (Gauss-Seidel)")
    p.add_argument("--steps", metavar="OUT", help="also animate the solution at work, the "
                   "energy shot so far (.gif, .png, .mp4 or a folder/)")
    p.add_argument("--plot", metavar="PNG", help="convergence plot (default: OUTPUT's name "
                   "with -convergence.png)")
    p.add_argument("--exposure", type=v.positive_float, help="scale of radiosity to display "
                   "(default: the brightest lit surface shows as white)")
    p.add_argument("--no-ambient", action="store_true", help="show only the energy shot so "
                   "far (no ambient estimate of the rest)")
    p.add_argument("--seed", type=int, default=0, help="of the hemicubes' random turns")
    p.add_argument("--size", type=v.size, metavar="WxH", help="image size (default: the "
                   "scene's)")
    p.add_argument("--samples", type=v.samples, help="MSAA samples (default: the scene's)")
    p.add_argument("--srgb", action="store_true", default=None, help="encode as sRGB")
    p.add_argument("--backend", choices=["auto", "egl", "osmesa"], default="auto")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar or summary")
    p.set_defaults(func=radiosity)


def radiosity(args) -> int:
    from ..animate import output_format
    from ..io.images import save_image
    from ..modes import ShadingMode
    from ..parallel import Progress
    from ..radiosity import FormFactors, PatchScene, Solution, gauss_seidel, progressive
    from ..radiosity.plot import convergence_plot
    from ..render.context import create_context
    from ..render.renderer import Renderer

    if not is_scene_file(args.scene):
        raise UsageError(f"{args.scene}: radiosity needs a scene file (.toml) whose materials "
                         "give emission, such as assets/scenes/cornell-box.toml")
    if args.steps:
        output_format(args.steps)  # a bad extension fails before the work
    args.mode = None
    job = load_job(args, args.scene)
    options = job.options.replace(mode=ShadingMode.RADIOSITY)
    problem = PatchScene.from_scene(job.scene, args.patch_size)
    plot_path = args.plot or os.path.splitext(args.output)[0] + "-convergence.png"
    quiet = args.quiet
    if not quiet:
        print(problem.summary())
    snapshots: list = []
    levels = iter([10 ** (k / STEP_FRAMES * _log10(args.until)) for k in
                   range(1, STEP_FRAMES + 1)])
    want = [next(levels, 0.0)]

    def on_shot(sol, shot):
        if args.steps and sol.history[-1][2] <= want[0]:
            snapshots.append((sol.radiosity.copy(), sol.unshot.copy()))
            while sol.history[-1][2] <= want[0] and want[0] > 0:
                want[0] = next(levels, 0.0)

    w, h = job.size
    with create_context(args.backend) as ctx, \
            FormFactors(problem, args.hemicube, seed=args.seed, context=ctx) as ff, \
            Renderer(w, h, samples=job.settings.samples, context=ctx) as renderer, \
            Progress(None, enabled=None if not quiet else False,
                     unit="shots" if args.method == "progressive" else "rows") as bar:
        start = time.perf_counter()
        if args.method == "progressive":
            solution = progressive(ff, args.until if args.iterations is None else 0.0,
                                   args.iterations, bar, on_shot)
        else:
            solution = gauss_seidel(ff, iterations=args.iterations, progress=bar)
        seconds = time.perf_counter() - start
        exposure = args.exposure or solution.auto_exposure(not args.no_ambient)
        image = renderer.render(solution.scene(exposure, not args.no_ambient), job.camera,
                                options)
        # (the steps show the energy shot so far: light spreading through the scene)
        frames = [renderer.render(Solution(problem, b, u, "").scene(exposure, False),
                                  job.camera, options) for b, u in snapshots]
    save_image(image, args.output)
    save_image(convergence_plot(solution.history, f"{solution.method}: unshot energy "
                                "fraction (log)" if args.method == "progressive" else
                                "Gauss-Seidel: change per sweep (log)",
                                target=args.until if args.iterations is None else None),
               plot_path)
    if args.steps:
        from ..animate import write_animation

        write_animation(frames + [image] * 6, args.steps, fps=8)
    if not quiet:
        steps = len(solution.history) - 1
        unit = "shots" if args.method == "progressive" else "sweeps"
        print(f"{solution.method}: {steps} {unit}, {solution.hemicubes:,} hemicubes of "
              f"{ff.resolution}x{ff.resolution}, {seconds:.2f} s, unshot "
              f"{solution.unshot_fraction:.2%}, exposure {exposure:.4g}")
        print(f"{args.output}: {w}x{h}; convergence: {plot_path}"
              + (f"; steps: {args.steps} ({len(frames) + 1} frames)" if args.steps else ""))
    return EXIT_OK


def _log10(x: float) -> float:
    import math

    return math.log10(max(x, 1e-6))
