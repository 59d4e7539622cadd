"""``glshade hidden``: the hidden-surface lab on the command line."""

from __future__ import annotations

from dataclasses import replace

from ..errors import EXIT_OK, UsageError
from .arguments import HiddenArgs
from .inputs import load_job

__all__ = ["hidden"]

def _polygons_only(scene, spec: str) -> None:
    """The lab's algorithms sort, clip and scan polygons: a point cloud or polylines alone
    is refused in one line naming the file."""
    if not scene.models and (scene.clouds or scene.lines):
        kind = "a point cloud" if scene.clouds else "polylines"
        raise UsageError(f"{spec} is {kind}, not polygons: the hidden-surface algorithms "
                         "need polygons (glshade render draws it)")


def hidden(args: HiddenArgs) -> int:
    """``glshade hidden``: the hidden-surface lab on a mesh or scene."""
    import numpy as np

    from ..animate import output_format
    from ..hidden import ALGORITHMS, edge_pixels, prepare
    from ..hidden.lab import agreement, disagreement_map, id_colors
    from ..io.images import label, opaque, save_image
    from ..io.tables import format_table
    from .validators import check_outputs

    check_outputs({"the grid": args.output, "--steps": args.steps})
    if args.steps and output_format(args.steps) == "dir":
        raise UsageError("--steps needs an animation file (.gif, .png or .mp4)")
    args = replace(args, size=args.size or (256, 256))
    job = load_job(args, args.mesh)
    _polygons_only(job.scene, args.mesh)
    if job.scene.solids:  # the algorithms are for polygons: so is the GPU's reference here
        import copy
        import warnings

        names = ", ".join(str(x.name) for x in job.scene.solids)
        warnings.warn(f"the scene's CSG solids ({names}) are not polygons: every algorithm "
                      "here, the GPU's z-buffer included, leaves them out", UserWarning,
                      stacklevel=2)
        job.scene = copy.copy(job.scene)
        job.scene.solids = []
    w, h = job.size
    p = prepare(job.scene, job.camera, (w, h))
    results = {}
    for name in args.algorithms:
        if name != "gpu":
            results[name] = ALGORITHMS[name](p)
    reference_name = "gpu" if "gpu" in args.algorithms else next(iter(results))
    gpu: tuple | None = None
    if "gpu" in args.algorithms:
        gpu = _gpu(job, w, h, args.backend)
    ref_ids = gpu[0] if gpu else results[reference_name].face_id
    ref_depth = gpu[1] if gpu else results[reference_name].depth
    edges = edge_pixels(p)
    rows, top, bottom = [], [], []
    for name in args.algorithms:
        if name == "gpu":
            assert gpu is not None  # (made above when asked for)
            ids = gpu[0]
            top.append(label(id_colors(ids), name))
            bottom.append(label(disagreement_map(ids, ref_ids, edges), "reference"))
            rows.append(("gpu", f"{gpu[2] * 1000:.1f}", "-", "0", "0", "-"))
            continue
        ids = results[name].face_id
        top.append(label(id_colors(ids), name))
        r = results[name]
        a = agreement(r, ref_ids, ref_depth, edges)
        bottom.append(label(disagreement_map(ids, ref_ids, edges),
                            f"vs {reference_name}: {a.differ}"))
        counts = ", ".join(f"{k} {v:,}" for k, v in r.counters.items()
                           if k not in ("polygons", "triangles"))
        rows.append((name, f"{r.seconds * 1000:.1f}", counts, str(a.differ),
                     str(a.near_edges), f"{a.depth_error:.1e}"))
    if not (ref_ids >= 0).any():  # a blank view: a background image, and why, in one line
        import warnings

        from ..errors import RenderWarning
        from ..render.diagnostics import why_blank

        reason = why_blank(job.scene, job.camera.with_planes(job.scene.bounds))
        if "no part of the scene lies in the camera's view" in reason:
            reason = (f"the render is blank: no polygon covers a pixel centre of the {w}x{h} "
                      "image (out of view, too small, or edge on)")
        warnings.warn(reason, RenderWarning, stacklevel=2)
    grid = opaque(np.vstack([np.hstack(top), np.hstack(bottom)]))
    save_image(grid, args.output)
    print(f"{p.n_polygons:,} polygons ({len(p.tris):,} triangles) at {w}x{h}; reference: "
          f"{reference_name}")
    print(format_table(rows, ("algorithm", "ms", "counters", "differ",
                              "near edges", "depth err")))
    if args.steps:
        _steps(args, p, results, gpu)
    print(f"grid: {args.output}" + (f"; steps: {args.steps}" if args.steps else ""))
    return EXIT_OK


def _gpu(job, w, h, backend):
    import time

    from ..modes import Outputs
    from ..options import RenderConfig
    from ..render.renderer import Renderer

    import warnings

    from ..errors import RenderWarning

    with Renderer(config=RenderConfig(w, h, samples=0, backend=backend)) as r, \
            warnings.catch_warnings():
        warnings.simplefilter("ignore", RenderWarning)  # (the lab says it once, below)
        start = time.perf_counter()
        frame = r.render_frame(job.scene, job.camera, "flat", cull=False,
                               outputs=Outputs.FACE_ID | Outputs.DEPTH)
        seconds = time.perf_counter() - start
    return frame.face_id, frame.depth, seconds


def _steps(args: HiddenArgs, p, results, gpu):
    """The algorithms at work side by side, as an animation."""
    import numpy as np

    from ..animate import write_animation
    from ..hidden.lab import id_colors, step_frames
    from ..io.images import label, opaque

    count = 24
    columns = []
    for name in args.algorithms:
        if name == "gpu":
            frames = [gpu[0]] * count
        else:
            frames = step_frames(name, p, results[name], count)
        columns.append([label(id_colors(f), name) for f in frames])
    images = [opaque(np.hstack([c[k] for c in columns])) for k in range(count)]
    write_animation(images + images[-1:] * 8, args.steps, fps=8)
