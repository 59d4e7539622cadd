"""The command line's grammar: subcommands, their options and help."""

from __future__ import annotations

import argparse
import dataclasses

from .._version import __version__
from ..errors import EXIT_USAGE
from ..options import DEFAULT_SIZE
from ..scene import Camera, Material
from . import commands as c
from . import hidden as hidden_command
from . import radiosity as radiosity_command
from . import validators as v

__all__ = ["build_parser", "add_render_options"]


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, exit 2, like every other bad input
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message}\n")


def _defaults(cls) -> dict:
    return {f.name: f.default for f in dataclasses.fields(cls)}


def add_render_options(p: argparse.ArgumentParser) -> None:
    """Options shared by render, view and compare. An option left out is None here: its
    default is decided where the value is used (scene file, then the dataclasses), and the
    help text quotes those defaults."""
    mat, cam = _defaults(Material), _defaults(Camera)
    w, h = DEFAULT_SIZE
    p.add_argument("--size", type=v.size, metavar="WxH",
                   help=f"image size (default: the scene file's, else {w}x{h})")
    p.add_argument("--samples", type=v.samples, help="MSAA samples, 0 = off (default 4)")
    p.add_argument("--eye", type=v.vec3, metavar="X,Y,Z", help="camera position "
                   "(default: auto framing)")
    p.add_argument("--target", type=v.vec3, metavar="X,Y,Z", help="point looked at")
    p.add_argument("--fov", type=v.fov, help=f"vertical field of view in degrees "
                   f"(default {cam['fov_y']:g})")
    p.add_argument("--light", type=v.vec3, action="append", metavar="X,Y,Z",
                   help="a point light (repeat for more; default: a headlight at the eye)")
    p.add_argument("--color", type=v.vec3, metavar="R,G,B", help="material colour, linear "
                   f"0..1 (default {','.join(f'{c:g}' for c in mat['color'])})")
    p.add_argument("--background", type=v.vec3, metavar="R,G,B", help="default black")
    for name, what in (("ka", "ambient"), ("kd", "diffuse"), ("ks", "specular")):
        p.add_argument(f"--{name}", type=v.unit_float, help=f"{what} coefficient "
                       f"(default {mat[name]:g})")
    p.add_argument("--shininess", type=v.nonnegative_float,
                   help=f"specular exponent n (default {mat['shininess']:g})")
    p.add_argument("--crease", type=v.degrees, metavar="DEG", help="keep edges sharper than "
                   "DEG degrees sharp in smooth shading (CAD parts; default: all smooth)")
    p.add_argument("--backend", choices=["auto", "egl", "osmesa"], default="auto")
    p.add_argument("--srgb", action="store_true", default=None,
                   help="encode the linear result as sRGB")


def add_executor_options(p: argparse.ArgumentParser, default_jobs: str = "the number of "
                         "cores", what: str = "items") -> None:
    """Where the work runs: local worker processes or a Dask cluster."""
    p.add_argument("--jobs", type=v.count, help=f"local worker processes rendering {what} "
                   f"(default: {default_jobs}); with --scheduler local, the workers started")
    p.add_argument("--scheduler", type=v.scheduler, metavar="ADDRESS",
                   help="render on a Dask cluster: tcp://HOST:PORT of a running scheduler, "
                   "or 'local' to start one here (needs pip install 'glshade[distributed]')")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="glshade", description="Classic shading on the GPU, headless or in a "
                     "window; and the geometry that goes with it.")
    parser.add_argument("--version", action="version", version=f"glshade {__version__}")
    parser.add_argument("--debug", action="store_true", help="show tracebacks on errors")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True
    p = sub.add_parser("info", help="print counts, polygon sizes, bounds and area of a mesh "
                       "(or what a scene file holds)")
    p.add_argument("mesh", metavar="MESH|SCENE", help="a mesh file (.obj .off .ply .stl), "
                   "primitive:NAME[:ARGS] (e.g. primitive:icosphere:3), solid:TEXT or a scene "
                   "file (.toml)")
    p.add_argument("--json", action="store_true", help="machine-readable output")
    p.set_defaults(func=c.info)

    p = sub.add_parser("render", help="render a mesh headless to an image")
    p.add_argument("mesh", metavar="MESH", help="a mesh file or primitive:NAME[:ARGS]")
    p.add_argument("-o", "--output", required=True, type=v.image_output,
                   help="output image (.png; .jpg, .webp ... by extension)")
    p.add_argument("--mode", type=v.mode, default=None,
                   help="flat, gouraud, phong, normals, depth or radiosity (default phong, or the "
                   "scene file's)")
    p.add_argument("-q", "--quiet", action="store_true")
    p.add_argument("--time", type=float, help="with a scene file: the moment on its camera "
                   "path (seconds)")
    add_render_options(p)
    p.set_defaults(func=c.render)

    p = sub.add_parser("animate", help="render a scene file's camera path, or a turntable "
                       "round a mesh, to GIF, PNG, MP4 or frames")
    p.add_argument("scene", metavar="SCENE.toml|MESH", help="a scene file with a camera path, "
                   "or a mesh (a turn round it: 4 s unless --frames or --duration)")
    p.add_argument("-o", "--output", required=True, help="out.gif, out.png (APNG), out.mp4 "
                   "or a folder/ for PNG frames")
    p.add_argument("--fps", type=v.positive_float, help="frames per second (default: the "
                   "scene's, else 30)")
    length = p.add_mutually_exclusive_group()
    length.add_argument("--duration", type=v.nonnegative_float, help="seconds of path to render")
    length.add_argument("--frames", type=v.count, help="number of frames")
    p.add_argument("--mode", type=v.mode, help="shading mode (default: the scene's)")
    p.add_argument("--modes", type=v.modes, help="several modes side by side, e.g. "
                   "flat,gouraud,phong")
    add_executor_options(p)
    p.add_argument("--size", type=v.size, metavar="WxH", help="frame size (default: the "
                   "scene's)")
    p.add_argument("--samples", type=v.samples, help="MSAA samples (default: the scene's)")
    p.add_argument("--backend", choices=["auto", "egl", "osmesa"], default="auto")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar or summary")
    p.set_defaults(func=c.animate)

    p = sub.add_parser("compare", help="flat, Gouraud and Phong side by side, with errors "
                       "against a reference")
    p.add_argument("mesh", metavar="MESH", help="a mesh file, primitive:NAME[:ARGS] or a "
                   "scene file (.toml)")
    p.add_argument("-o", "--output", required=True, type=v.image_output,
                   help="output image: the grid (or the plot, with --sweep)")
    p.add_argument("--modes", type=v.modes, default="flat,gouraud,phong",
                   help="comma-separated modes (default flat,gouraud,phong)")
    p.add_argument("--diff", action="store_true", help="add a row of difference heat maps")
    p.add_argument("--reference", default="analytic", help="analytic (sphere primitives), "
                   "phong-fine, or an image file (default analytic)")
    p.add_argument("--json", help="write the metrics as JSON")
    p.add_argument("--csv", help="write the metrics as CSV")
    p.add_argument("--sweep", action="store_true", help="error of each mode against "
                   "tessellation level of a sphere primitive")
    p.add_argument("--levels", type=v.levels, default=list(range(0, 7)),
                   help="levels for --sweep, e.g. 0..6")
    add_executor_options(p, default_jobs="1", what="--sweep levels")
    add_render_options(p)
    p.set_defaults(func=c.compare)

    p = sub.add_parser("batch", help="render every mesh of folders or globs to images "
                       "(and depth/normal/id arrays), resumably, locally or on Dask")
    p.add_argument("inputs", nargs="+", metavar="INPUT", help="mesh files, folders (searched "
                   "recursively) or globs such as 'data/**/*.ply'")
    p.add_argument("-o", "--output", required=True, metavar="OUTDIR",
                   help="output folder: REL.MODE.png per mesh (and REL.npz), manifest.csv")
    p.add_argument("--modes", type=v.modes, default="phong", help="comma-separated modes "
                   "(default phong)")
    p.add_argument("--outputs", type=v.outputs, default="color", help="color, and any of "
                   "depth, normal, face_id (saved per view in REL.npz); default color")
    p.add_argument("--views", type=v.count, default=1, help="N views around each mesh "
                   "(REL.vK.MODE.png; default 1)")
    p.add_argument("--overwrite", action="store_true", help="render again the meshes whose "
                   "outputs exist (default: keep them, so a rerun resumes)")
    add_executor_options(p, what="meshes")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar or summary")
    add_render_options(p)
    p.set_defaults(func=c.batch, size=None)

    radiosity_command.add_parser(sub, v)
    hidden_command.add_parser(sub, v)

    p = sub.add_parser("view", help="explore a mesh in a window (keys: h)")
    p.add_argument("mesh", metavar="MESH", help="a mesh file, primitive:NAME[:ARGS] or a "
                   "scene file (.toml)")
    p.add_argument("--mode", type=v.mode, help="initial shading mode (default phong)")
    p.add_argument("--compare", action="store_true", help="flat | gouraud | phong side by "
                   "side")
    p.add_argument("--screenshot", metavar="PATH", help="save the window's pixels after "
                   "--frames frames and exit")
    p.add_argument("--frames", type=v.count, help="draw this many frames, then exit")
    p.add_argument("--hidden", action="store_true", help=argparse.SUPPRESS)
    add_render_options(p)
    p.set_defaults(func=c.view)

    p = sub.add_parser("doctor", help="say which GL backends work and what they are")
    p.add_argument("--backend", choices=["auto", "egl", "osmesa"], default="auto")
    p.set_defaults(func=c.doctor)
    return parser
