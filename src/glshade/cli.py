"""The ``glshade`` command line tool.

Exit status: 0 on success; 2 for bad input (arguments, or an input file that is missing
or malformed), reported in one line on stderr; 1 for a failure of the environment (no GL
context, an output that cannot be written), also one line. ``--debug`` shows tracebacks.
Heavy imports happen inside the subcommands, so ``--help`` needs no GL.
"""

from __future__ import annotations

import argparse
import json
import sys

from ._version import __version__

__all__ = ["main"]

EXIT_OK, EXIT_ENVIRONMENT, EXIT_USAGE = 0, 1, 2


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, exit 2, like every other bad input
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message}\n")


def _load(spec: str):
    """A mesh from a file path or a ``primitive:NAME[:ARGS]`` spec."""
    from .geometry import primitives
    from .io import load_mesh

    if spec.startswith("primitive:"):
        return primitives.from_spec(spec)
    return load_mesh(spec)


def mesh_summary(mesh) -> dict:
    """Counts, polygon sizes, bounds and area of a mesh, as plain JSON-able data."""
    import numpy as np

    sizes, counts = np.unique(mesh.face_sizes, return_counts=True)
    return {
        "name": mesh.name,
        "vertices": mesh.n_vertices,
        "faces": mesh.n_faces,
        "edges": mesh.n_edges,
        "polygon_sizes": {int(k): int(c) for k, c in zip(sizes, counts)},
        "bounds": {"min": mesh.bounds[0].tolist(), "max": mesh.bounds[1].tolist()},
        "total_area": mesh.total_area,
        "degenerate_faces": int(len(mesh.degenerate_faces)),
        "euler_characteristic": mesh.n_vertices - mesh.n_edges + mesh.n_faces,
        "signed_volume": mesh.signed_volume(),
    }


def _cmd_info(args) -> int:
    mesh = _load(args.mesh)
    info = mesh_summary(mesh)
    info["source"] = args.mesh
    if args.json:
        print(json.dumps(info, indent=2))
        return EXIT_OK
    lo, hi = info["bounds"]["min"], info["bounds"]["max"]
    rows = [
        ("source", args.mesh),
        ("vertices", f"{info['vertices']:,}"),
        ("faces", f"{info['faces']:,}"),
        ("edges", f"{info['edges']:,}"),
        ("V - E + F", str(info["euler_characteristic"])),
        ("bounding box", f"[{', '.join(f'{x:.4g}' for x in lo)}] .. "
                         f"[{', '.join(f'{x:.4g}' for x in hi)}]"),
        ("total area", f"{info['total_area']:.6g}"),
        ("signed volume", f"{info['signed_volume']:.6g}"),
        ("degenerate faces", str(info["degenerate_faces"])),
    ]
    width = max(len(k) for k, _ in rows)
    for k, v in rows:
        print(f"{k:<{width}}  {v}")
    print("polygon sizes:")
    total = max(info["faces"], 1)
    for k, c in info["polygon_sizes"].items():
        bar = "#" * max(1, round(40 * c / total))
        print(f"  {k:>4}-gon  {c:>10,}  {bar}")
    return EXIT_OK


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="glshade", description="Classic shading on the GPU, headless or in a "
                     "window; and the geometry that goes with it.")
    parser.add_argument("--version", action="version", version=f"glshade {__version__}")
    parser.add_argument("--debug", action="store_true", help="show tracebacks on errors")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True
    p = sub.add_parser("info", help="print counts, polygon sizes, bounds and area of a mesh")
    p.add_argument("mesh", metavar="MESH", help="a mesh file (.obj .off .ply .stl) or "
                   "primitive:NAME[:ARGS], e.g. primitive:icosphere:3")
    p.add_argument("--json", action="store_true", help="machine-readable output")
    p.set_defaults(func=_cmd_info)
    return parser


def main(argv: list[str] | None = None) -> int:
    from .errors import GlshadeError

    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except GlshadeError as exc:
        if args.debug:
            raise
        code = EXIT_USAGE if isinstance(exc, ValueError) else EXIT_ENVIRONMENT
        print(f"glshade: error: {exc}", file=sys.stderr)
        return code
    except OSError as exc:  # cannot write an output, disk full, ...
        if args.debug:
            raise
        print(f"glshade: error: {exc}", file=sys.stderr)
        return EXIT_ENVIRONMENT
    except KeyboardInterrupt:
        print("glshade: interrupted", file=sys.stderr)
        return 130
