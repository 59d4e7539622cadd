"""``glshade radiosity``: solve a scene file's diffuse light transport and render it."""

from __future__ import annotations

import os
import sys
import time

from dataclasses import replace

from ..errors import EXIT_ENVIRONMENT, EXIT_OK, InputError, UsageError
from .arguments import RadiosityArgs
from .inputs import is_scene_file, load_job
from .validators import check_outputs

__all__ = ["radiosity"]

#: frames of --steps: the unshot fraction at evenly spaced steps of its logarithm
STEP_FRAMES = 36


def _prepare(args: RadiosityArgs):
    """The checked arguments (every output path before any work), the scene's job, its
    radiosity problem and the convergence plot's path."""
    from .. import examples
    from ..animate import output_format
    from ..radiosity import PatchScene

    args = replace(args, scene=examples.resolve(args.scene))
    if not is_scene_file(args.scene):
        raise UsageError(f"{args.scene}: radiosity needs a scene file (.toml) whose materials "
                         "give emission, such as assets/scenes/cornell-box.toml")
    if args.method == "monte-carlo" and (args.steps or args.plot):
        raise UsageError("--steps and --plot show a convergence, and monte-carlo light "
                         "tracing has none: leave them out")
    if args.steps:
        output_format(args.steps)  # a bad extension fails before the work
    plot_path = args.plot or os.path.splitext(args.output)[0] + "-convergence.png"
    steps = args.steps or ""  # (an animation file, or a folder/ of frames)
    check_outputs({"the image": args.output, "--plot": plot_path,
                   "--steps": None if steps.endswith("/") else steps or None},
                  {"--steps": steps or None} if steps.endswith("/") else None)
    job = load_job(replace(args, mode=None), args.scene)
    try:
        problem = PatchScene.from_scene(job.scene, args.patch_size)
    except InputError as exc:  # (say which scene: the message names a model or a size)
        raise UsageError(f"{args.scene}: {exc}") from None
    return args, job, problem, plot_path


def radiosity(args: RadiosityArgs) -> int:
    """``glshade radiosity``: solve a scene file for radiosity and draw it."""
    from ..io.images import save_image
    from ..modes import ShadingMode
    from ..parallel import Progress
    from ..radiosity import FormFactors, Solution, gauss_seidel, progressive
    from ..radiosity.solvers import check_converges
    from ..radiosity.plot import convergence_plot
    from ..render.context import create_context
    from ..render.renderer import Renderer

    args, job, problem, plot_path = _prepare(args)
    options = job.options.replace(mode=ShadingMode.RADIOSITY)
    quiet = args.quiet
    if not quiet:
        print(problem.summary())
    if args.method == "monte-carlo":
        return _monte_carlo(args, job, problem, options)
    check_converges(problem)  # (before any work: a closed lossless room never settles)
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
            FormFactors(problem, args.hemicube, seed=args.seed, context=ctx,
                        progress=False if quiet else None) as ff, \
            Renderer(config=job.config(args.backend), context=ctx) as renderer, \
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
        _exposure_warning(image, exposure)
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
        steps = solution.history[-1][1] if solution.history else 0  # (shots or sweeps made)
        unit = "shots" if args.method == "progressive" else "sweeps"
        print(f"{solution.method}: {steps} {unit}, {solution.hemicubes:,} hemicubes of "
              f"{ff.resolution}x{ff.resolution}, {seconds:.2f} s, unshot "
              f"{solution.unshot_fraction:.2%}, exposure {exposure:.4g}")
        print(f"{args.output}: {w}x{h}; convergence: {plot_path}"
              + (f"; steps: {args.steps} ({len(frames) + 1} frames)" if args.steps else ""))
    if not solution.converged and args.iterations is None:  # (a cap, not the goal)
        print(f"glshade: error: {solution.method} did not converge in "
              f"{solution.history[-1][1]:,} steps (unshot or change "
              f"{solution.history[-1][2]:.3g}); {args.output} is how far it got",
              file=sys.stderr)
        return EXIT_ENVIRONMENT
    return EXIT_OK


def _monte_carlo(args: RadiosityArgs, job, problem, options) -> int:
    """The scene solved by light tracing (no GL until the picture) and rendered."""
    import numpy as np

    from ..io.images import save_image
    from ..parallel import Progress
    from ..radiosity import Solution
    from ..radiosity.montecarlo import light_trace
    from ..render.renderer import Renderer

    start = time.perf_counter()
    with Progress(None, enabled=None if not args.quiet else False, unit="batches") as bar:
        mc = light_trace(problem, args.particles, seed=args.seed, progress=bar)
    seconds = time.perf_counter() - start
    solution = Solution(problem, mc.radiosity, np.zeros_like(mc.radiosity),
                        "Monte Carlo light tracing")
    exposure = args.exposure or solution.auto_exposure(False)
    with Renderer(config=job.config(args.backend)) as renderer:
        image = renderer.render(solution.scene(exposure, False), job.camera, options)
    _exposure_warning(image, exposure)
    save_image(image, args.output)
    if not args.quiet:
        lit = mc.model_radiosity > 0
        worst = float((mc.model_se[lit] / mc.model_radiosity[lit]).max()) if lit.any() else 0.0
        w, h = job.size
        print(f"{solution.method}: {mc.particles:,} particles, {seconds:.2f} s, largest "
              f"relative standard error of a surface {worst:.2%}, exposure {exposure:.4g}")
        print(f"{args.output}: {w}x{h}")
    if mc.cut:  # (a cap, not the goal: said as the hemicube solvers say theirs)
        from ..radiosity.montecarlo import MAX_BOUNCES

        print(f"glshade: error: Monte Carlo light tracing did not converge: {mc.cut:,} of "
              f"{mc.particles:,} particles were still going after {MAX_BOUNCES:,} surfaces "
              "(a room that loses no light: lower a reflectance below 1); "
              f"{args.output} is how far it got", file=sys.stderr)
        return EXIT_ENVIRONMENT
    return EXIT_OK


def _exposure_warning(image, exposure: float) -> None:
    """Say so when the exposure makes the picture black or white."""
    import warnings

    lum = image[..., :3].astype(float).mean(axis=2)
    if (lum <= 2).mean() > 0.98:
        warnings.warn(f"the picture is black at exposure {exposure:.4g}: raise --exposure "
                      "(or leave it out: the brightest lit surface then shows as white)",
                      UserWarning, stacklevel=2)
    elif (lum >= 253).mean() > 0.9:
        warnings.warn(f"the picture is white at exposure {exposure:.4g}: lower --exposure",
                      UserWarning, stacklevel=2)


def _log10(x: float) -> float:
    import math

    return math.log10(max(x, 1e-6))
