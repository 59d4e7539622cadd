"""``glshade dataset``: a BOP or COCO data set rendered from a scene file."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..errors import EXIT_OK
from .arguments import DatasetArgs

__all__ = ["dataset"]


def dataset(args: DatasetArgs) -> int:
    """Render the views and write the data set; one summary line."""
    from .. import dataset as ds
    from ..render.context import create_context
    from .validators import check_outputs

    check_outputs({}, {"the data set": args.output})  # (before any work)
    if args.images == "raster" and (args.spp is not None or args.until is not None):
        from ..errors import UsageError

        raise UsageError(f"--{'spp' if args.spp is not None else 'until'} is for --images "
                         "pathtrace")
    context = create_context(args.backend.value, args.device)
    common: dict[str, Any] = {
        "views": args.views, "size": args.size,
        "samples": 4 if args.samples is None else args.samples,
        "progress": False if args.quiet else None, "context": context,
        "jobs": args.jobs or 1, "scheduler": args.scheduler,
        "images": args.images, "spp": args.spp, "until": args.until}
    try:
        if args.format == "bop":
            where = ds.write_bop(args.scene, args.output, depth_scale=args.depth_scale,
                                 units=args.units, **common)
        else:
            where = ds.write_coco(args.scene, args.output, **common)
    finally:
        context.release()
    if not args.quiet:
        print(f"{args.views:,} views of {Path(args.scene).name} as {args.format.upper()} in "
              f"{where}")
    return EXIT_OK
