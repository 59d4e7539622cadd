"""``glshade pathtrace``: the rendering equation by Monte Carlo path tracing on the GPU."""

from __future__ import annotations

import sys
from dataclasses import replace

import numpy as np

from ..errors import EXIT_OK, InputError, UsageError
from .arguments import PathtraceArgs
from .inputs import load_job

__all__ = ["pathtrace"]

EXIT_INTERRUPTED = 130


#: what the summary says of Sobol points' error where it could only be figured from the
#: samples' spread (no halves to compare -- one sample a pixel: PathTraced.se_from):
#: right for independent samples, too high for stratified points
_SPREAD_ERROR = " (figured as for independent samples: Sobol points' own is lower)"


def pathtrace(args: PathtraceArgs) -> int:
    """Path-trace a scene file or mesh to an image; a Ctrl-C writes the image so far."""
    from .. import pathtrace as pt
    from ..io.images import save_image
    from .validators import check_outputs

    check_outputs({"the image": args.output})  # (before any work)
    # (how paths are traced: one value, checked before the scene is read, passed whole)
    options = pt.TraceOptions.of(max_depth=args.max_depth, sampler=args.sampler,
                                 mis=not args.no_mis, coherent=args.coherent,
                                 kernel=args.kernel, streams=args.streams)

    job = load_job(replace(args, mode=None), args.scene)
    w, h = job.size
    try:
        scene = pt.TraceScene.from_scene(job.scene, lights=not args.no_lights,
                                         camera=job.camera)
    except InputError as exc:  # (say which scene: the message names a model or a value)
        raise UsageError(f"{args.scene}: {exc}") from None
    spp = None if args.until is not None else (args.spp or 64)
    control = None
    if args.control:  # (the scene's radiosity, solved once: the models' control values)
        from ..radiosity.control import radiosity_control

        control = radiosity_control(job.scene, backend=args.backend.value)
    result = pt.trace(scene, job.camera, (w, h), options=options, spp=spp, until=args.until,
                      seed=args.seed, backend=args.backend.value,
                      progress=False if args.quiet else None, control=control,
                      adaptive=args.adaptive)
    if result.interrupted and not result.samples:  # (nothing traced: nothing to keep)
        print("glshade: interrupted before the first sample; nothing written",
              file=sys.stderr)
        return EXIT_INTERRUPTED
    if not (result.image > 0).any():  # (a black picture says why, as render's blank does)
        import warnings

        from ..errors import RenderWarning
        from ..render.diagnostics import why_blank

        reason = why_blank(job.scene, job.camera.with_planes(job.scene.bounds))
        warnings.warn(RenderWarning(reason.replace("the render is blank", "the picture is "
                                                   "black", 1)), stacklevel=2)
    exposure = args.exposure or result.auto_exposure()
    srgb = args.srgb if args.srgb is not None else job.settings.options.srgb
    image = result.rgba8(exposure, srgb=bool(srgb))
    lit = float(np.nanmax(result.image, initial=0.0))
    if lit > 0 and (image[..., :3] == image[0, 0, :3]).all():
        import warnings

        from ..errors import RenderWarning, plain

        shown = "black" if not image[0, 0, :3].any() else "white" \
            if (image[0, 0, :3] == 255).all() else f"one colour {plain(image[0, 0, :3])}"
        warnings.warn(RenderWarning(f"the picture is {shown} throughout: exposure "
                                    f"{plain(exposure)} scales its brightest value, "
                                    f"{plain(lit)}, to {plain(lit * exposure)} (auto "
                                    f"exposure would be {plain(result.auto_exposure())}: "
                                    "leave --exposure out)"), stacklevel=2)
    save_image(image, args.output)
    rays = int(result.counts.sum()) if result.counts is not None else result.samples * w * h
    error = result.relative_error
    # (Sobol points' error figured from the samples' spread: only where no halves serve)
    sobol_spread = options.sampler.value == "sobol" and result.se_from == "spread"
    said = f"{error:.2%}" if np.isfinite(error) else "none (nothing lit)"
    line = (f"{w}x{h}, {result.samples:,} samples a pixel in {result.seconds:.2f} s "
            f"({rays / max(result.seconds, 1e-9) / 1e6:.2f} M paths/s, "
            f"{options.sampler.value}{', coherent' if options.coherent != (1, 1) else ''}"
            f"{', control' if args.control else ''}"
            f"{', adaptive' if args.adaptive else ''}), "
            f"relative error {said}{_SPREAD_ERROR if sobol_spread else ''}"
            f", exposure {exposure:.4g} -> {args.output}")
    if result.interrupted:
        print(f"glshade: interrupted after {result.samples:,} samples a pixel; the image so "
              f"far is in {args.output}", file=sys.stderr)
        return EXIT_INTERRUPTED
    if not args.quiet:
        print(line)
    return EXIT_OK
