"""The command line's grammar: every subcommand, its options and help, in one place. Each
subcommand names its command function (``func``) and the typed value its arguments become
(``arguments``, :mod:`.arguments`); the commands live in :mod:`.commands`, :mod:`.info`,
:mod:`.hidden` and :mod:`.radiosity`."""

from __future__ import annotations

import argparse
import dataclasses

from .._version import __version__
from ..errors import EXIT_USAGE
from ..modes import HEADLESS_BACKENDS
from ..options import DEFAULT_SIZE, HEMICUBE_RESOLUTION
from ..scene import Camera, Material
from . import arguments as a
from . import commands as c
from . import hidden as hidden_command
from . import dataset as dataset_command
from . import pathtrace as pathtrace_command
from . import radiosity as radiosity_command
from . import validators as v

__all__ = ["build_parser", "add_render_options"]


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, exit 2, like every other bad input
        self.exit(EXIT_USAGE, f"{self.prog}: error: {message}\n")


def _examples(*lines: str) -> dict:
    """An epilog of examples for a subcommand's --help (kept as written)."""
    return {"epilog": "examples:\n" + "\n".join(f"  {line}" for line in lines),
            "formatter_class": argparse.RawDescriptionHelpFormatter}


def add_backend(add) -> None:
    """The --backend, --device and --require-gpu options, through ``add`` (a parser's
    ``add_argument``)."""
    add("--backend", choices=HEADLESS_BACKENDS, default="auto",
        help="where the GL context comes from: auto (EGL, else OSMesa), egl or "
        "osmesa (default auto; GLSHADE_BACKEND overrides auto)")
    add("--device", metavar="INDEX|NAME", default=None,
        help="the EGL device, by index or a part of its name (glshade doctor "
        "lists them; as GLSHADE_EGL_DEVICE)")
    add("--require-gpu", action="store_true",
        help="refuse a software rasterizer (llvmpipe): exit 2 naming what was found "
        "(as GLSHADE_REQUIRE_GPU=1, for this run and its workers)")


def add_quiet(p: argparse.ArgumentParser, what: str = "no summary line") -> None:
    p.add_argument("-q", "--quiet", action="store_true", help=what)


MESH_HELP = ("a mesh file (.obj .off .ply .stl; glTF and others with glshade[formats]), "
             "primitive:NAME[:ARGS] (e.g. primitive:icosphere:3), solid:TEXT (a CSG tree, "
             "e.g. \"solid:box(2) - sphere(1.2)\"), patches:NAME (Bezier patches: teapot, "
             "sphere, cylinder, cone, torus) or a scene file (.toml)")


def _defaults(cls) -> dict:
    return {f.name: f.default for f in dataclasses.fields(cls)}


class _Refused(argparse.Action):
    """An option of the raster modes that a command does not apply: its parser refuses it
    with the reason (never accepted and ignored)."""

    def __init__(self, option_strings, dest, reason: str = "", **kwargs):
        kwargs.pop("type", None)
        super().__init__(option_strings, dest, nargs=kwargs.pop("nargs", None), **kwargs)
        self.reason = reason

    def __call__(self, parser, namespace, values, option_string=None):
        parser.error(f"{option_string} {self.reason}")


#: the raster modes' options the path tracer does not apply, and why
NOT_TRACED = {
    "--samples": "is an option of the raster modes; the path tracer antialiases by its "
                 "samples (--spp)",
    "--edges": "is an option of the raster modes; the path tracer draws no edges",
    "--shadows": "is an option of the raster modes; the path tracer's shadows are always "
                 "exact",
    "--opacity": "is an option of the raster modes; the path tracer's surfaces are opaque",
    "--transparency": "is an option of the raster modes; the path tracer's surfaces are "
                      "opaque",
    "--texture-filter": "is an option of the raster modes; the path tracer samples no "
                        "textures",
}


def add_render_options(p: argparse.ArgumentParser, size_default: str | None = None,
                       refused: dict[str, str] | None = None) -> None:
    """Options shared by render, view, compare and batch. An option left out is None here:
    its default is decided where the value is used (scene file, then the dataclasses), and
    the help text quotes those defaults. ``refused``: options the command does not apply,
    by name, with the reason its parser gives when one is used."""
    refused = refused or {}

    def add(*names, **kwargs):
        if names[0] not in refused:
            return p.add_argument(*names, **kwargs)
        flag = kwargs.get("action") == "store_true"
        return p.add_argument(*names, action=_Refused, reason=refused[names[0]],
                              help=argparse.SUPPRESS, nargs=0 if flag else None, default=None)

    _render_options(add, size_default)


def _render_options(add, size_default: str | None) -> None:
    """add_render_options' options, each through ``add`` (``add_argument``'s signature)."""
    mat, cam = _defaults(Material), _defaults(Camera)
    w, h = DEFAULT_SIZE
    add("--size", type=v.size, metavar="WxH",
        help=f"image size (default: the scene file's, else "
        f"{size_default or f'{w}x{h}'})")
    add("--samples", type=v.samples, help="MSAA samples, 0 = off (default 4)")
    add("--eye", type=v.vec3, metavar="X,Y,Z", help="camera position "
        "(default: auto framing)")
    add("--target", type=v.vec3, metavar="X,Y,Z", help="point looked at")
    add("--fov", type=v.fov, help=f"vertical field of view in degrees "
        f"(default {cam['fov_y']:g})")
    add("--light", type=v.vec3, action="append", metavar="X,Y,Z",
        help="a point light (repeat for more; default: a headlight at the eye)")
    add("--color", type=v.vec3, metavar="R,G,B", help="material colour, linear "
        f"0..1 (default {','.join(f'{c:g}' for c in mat['color'])})")
    add("--background", type=v.vec3, metavar="R,G,B", help="default black")
    for name, what in (("ka", "ambient"), ("kd", "diffuse"), ("ks", "specular")):
        add(f"--{name}", type=v.unit_float, help=f"{what} coefficient "
            f"(default {mat[name]:g})")
    add("--shininess", type=v.nonnegative_float,
        help=f"specular exponent n (default {mat['shininess']:g})")
    add("--opacity", type=v.unit_float, help="the mesh's opacity, 0..1 (below 1: "
        "transparent; default 1)")
    add("--texture-filter", type=v.texture_filter, metavar="nearest|linear|mipmap",
        help="how textures are sampled: the nearest texel, bilinear, or trilinear "
        "between mipmap levels (default: linear, or the scene file's)")
    add("--transparency", type=v.transparency, metavar="exact|weighted|blend",
        help="how transparent surfaces are composited: exact (per-pixel lists, "
        "sorted), weighted (McGuire-Bavoil) or blend (drawing order); default: "
        "the scene's, else exact; compare takes several, e.g. exact,weighted,blend")
    add("--tolerance", type=v.positive_float, metavar="T", help="patches:NAME: "
        "tessellate to within T world units of the exact surface (default: a "
        "thousandth of its size)")
    add("--crease", type=v.degrees, metavar="DEG", help="keep edges sharper than "
        "DEG degrees sharp in smooth shading (CAD parts; default: all smooth)")
    add("--view", type=v.view, metavar="NAME", help="a named view, framed: " +
        ", ".join(v.VIEW_CHOICES) + " (default: from the front-right, above)")
    add("--ortho", action="store_true", help="parallel (orthographic) projection")
    add("--edges", action="store_true", default=None, help="draw the polygons' "
        "edges over the picture (their boundaries, not the triangles')")
    add_shadows(add)
    add_backend(add)
    add("--srgb", action="store_true", default=None,
        help="encode the linear result as sRGB")


def add_shadows(add) -> None:
    """The --shadows option, through ``add`` (a parser's ``add_argument``)."""
    add("--shadows", type=v.shadows, metavar="off|exact|map",
        help="cast shadows: exact (a ray from each pixel's point to each light), "
        "map (shadow maps, PCF) or off (default: the scene's, else off); compare "
        "takes two or more, e.g. exact,map, and shows their difference")


def add_executor_options(p: argparse.ArgumentParser, default_jobs: str = "the number of "
                         "cores", what: str = "items") -> None:
    """Where the work runs: local worker processes or a Dask cluster."""
    p.add_argument("--jobs", type=v.count, help=f"local worker processes rendering {what} "
                   f"(default: {default_jobs}); with --scheduler local, the workers started")
    p.add_argument("--scheduler", type=v.scheduler, metavar="ADDRESS",
                   help="render on a Dask cluster: tcp://HOST:PORT of a running scheduler, "
                   "or 'local' to start one here (needs pip install 'glshade[distributed]')")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of every command."""
    parser = _Parser(prog="glshade", description="Classic shading on the GPU, headless or in a "
                     "window; and the geometry that goes with it.")
    parser.add_argument("--version", action="version", version=f"glshade {__version__}")
    parser.add_argument("--debug", action="store_true", help="show tracebacks on errors")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True
    for add in (add_info, add_render, add_animate, add_compare, add_batch, add_radiosity,
                add_pathtrace, add_hidden, add_view, add_dataset, add_doctor):
        add(sub)
    return parser


def add_info(sub) -> None:
    p = sub.add_parser("info", help="print counts, polygon sizes, bounds and area of a mesh "
                       "(or what a scene file holds)",
                       **_examples("glshade info assets/teapot.obj",
                                   "glshade info \"solid:box(2) - cylinder(0.5, 3)\" --json",
                                   "glshade info assets/scenes/cornell-box.toml"))
    p.add_argument("mesh", metavar="MESH|SCENE", help=MESH_HELP)
    p.add_argument("--json", action="store_true", help="machine-readable output")
    p.add_argument("--tolerance", type=v.positive_float, metavar="T", help="patches:NAME: "
                   "the tolerance whose adaptive triangle count is reported (default: a "
                   "thousandth of its size)")
    p.set_defaults(func=c.info, arguments=a.InfoArgs)


def add_render(sub) -> None:
    p = sub.add_parser("render", help="render a mesh, solid or scene headless to an image",
                       **_examples("glshade render assets/teapot.obj -o teapot.png --mode gouraud",
                                   "glshade render primitive:torus -o t.png --size 256x256 "
                                   "--samples 0",
                                   "glshade render \"solid:box(2) - sphere(1.2)\" -o part.png",
                                   "glshade render assets/scenes/teapot-orbit.toml -o f.png "
                                   "--time 1.5"))
    p.add_argument("mesh", metavar="MESH|SCENE", help=MESH_HELP)
    p.add_argument("-o", "--output", required=True, type=v.image_output,
                   help="output image (.png; .jpg, .webp ... by extension)")
    p.add_argument("--mode", type=v.mode, default=None,
                   help="flat, gouraud, phong, normals, depth or radiosity (default phong, or the "
                   "scene file's)")
    add_quiet(p)
    p.add_argument("--time", type=float, help="with a scene file: the moment on its camera "
                   "path (seconds)")
    add_render_options(p)
    p.set_defaults(func=c.render, arguments=a.RenderCommandArgs)


def add_animate(sub) -> None:
    p = sub.add_parser("animate", help="render a scene file's camera path, or a turntable "
                       "round a mesh, to GIF, PNG, MP4 or frames",
                       **_examples("glshade animate assets/scenes/teapot-orbit.toml -o orbit.gif",
                                   "glshade animate primitive:teapot -o spin.png --frames 48 "
                                   "--modes flat,gouraud,phong --jobs 2"))
    p.add_argument("scene", metavar="SCENE.toml|MESH", help="a scene file with a camera path, "
                   "or a mesh (a turn round it: 4 s unless --frames or --duration)")
    p.add_argument("-o", "--output", required=True, help="out.gif, out.png (APNG), out.mp4 "
                   "or a folder/ for PNG frames")
    p.add_argument("--fps", type=v.fps, help="frames per second (default: the "
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
    add_shadows(p.add_argument)
    add_backend(p.add_argument)
    add_quiet(p, "no progress bar or summary")
    p.set_defaults(func=c.animate, arguments=a.AnimateArgs)


def add_compare(sub) -> None:
    p = sub.add_parser("compare", help="flat, Gouraud and Phong side by side, with errors "
                       "against a reference",
                       **_examples("glshade compare primitive:icosphere:2 -o grid.png --diff",
                                   "glshade compare assets/teapot.obj -o grid.png --reference "
                                   "phong-fine --json m.json",
                                   "glshade compare primitive:icosphere --sweep --levels 0..6 "
                                   "-o sweep.png"))
    p.add_argument("mesh", metavar="MESH|SCENE", help=MESH_HELP)
    p.add_argument("-o", "--output", required=True, type=v.image_output,
                   help="output image: the grid (or the plot, with --sweep)")
    p.add_argument("--modes", type=v.compare_modes, default="flat,gouraud,phong",
                   help="comma-separated modes (default flat,gouraud,phong); pbr-flat, "
                   "pbr-gouraud, pbr-phong: the scheme with the scene's materials in glTF's "
                   "metallic-roughness model, to compare the two lighting models")
    p.add_argument("--diff", action=argparse.BooleanOptionalAction, default=True,
                   help="a row of difference heat maps under the renders, each with its "
                   "mean, max, PSNR and SSIM (default on; --no-diff: the renders alone)")
    p.add_argument("--reference", default="auto", help="auto (analytic where the mesh knows "
                   "its exact surface, as sphere primitives do, else phong-fine), analytic, "
                   "phong-fine, pathtrace (the rendering equation: interreflection, the "
                   "energy-conserving Phong lobe; --spp), or an image file (default auto)")
    p.add_argument("--spp", type=v.count, default=64, metavar="N", help="samples a pixel of "
                   "--reference pathtrace (default 64)")
    p.add_argument("--patch-size", type=v.positive_float, metavar="S", help="the radiosity "
                   "mode's patches, about S a side (scene units; default: a 24th of the "
                   "diagonal)")
    p.add_argument("--scale", type=v.positive_float, help="the heat maps' top, in 8-bit "
                   "units (default: the 99th percentile of the errors off the silhouette)")
    p.add_argument("--save-tiles", metavar="DIR", help="also write each mode's image, the "
                   "reference and the pixels measured (MODE-mask.png) into DIR")
    p.add_argument("--json", help="write the metrics as JSON")
    p.add_argument("--csv", help="write the metrics as CSV")
    p.add_argument("--sweep", action="store_true", help="error of each mode against "
                   "tessellation level of a sphere primitive")
    p.add_argument("--levels", type=v.levels, default=None,
                   help="levels for --sweep, e.g. 0..6 (spheres: subdivisions 0 to 8, "
                   "default 0..6; patches: tessellation levels 1 to 512, default "
                   "2,3,4,6,8,12,16)")
    add_executor_options(p, default_jobs="1", what="--sweep levels")
    add_render_options(p, size_default="%dx%d per cell" % c.COMPARE_DEFAULTS.size)
    p.set_defaults(func=c.compare, arguments=a.CompareArgs)


def add_batch(sub) -> None:
    p = sub.add_parser("batch", help="render every mesh of folders or globs to images "
                       "(and depth/normal/id arrays), resumably, locally or on Dask",
                       **_examples("glshade batch assets/ -o thumbs --views 2 --jobs 2",
                                   "glshade batch 'data/**/*.ply' -o out --outputs depth,normal "
                                   "--scheduler local"))
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
    add_quiet(p, "no progress bar or summary")
    add_render_options(p, size_default="256x256")
    p.set_defaults(func=c.batch, arguments=a.BatchArgs)


def add_view(sub) -> None:
    p = sub.add_parser("view", help="explore a mesh in a window (keys: h)",
                       **_examples("glshade view assets/teapot.obj",
                                   "glshade view primitive:teapot --compare",
                                   "glshade view assets/scenes/csg-part.toml --mode gouraud"))
    p.add_argument("mesh", metavar="MESH|SCENE", help=MESH_HELP)
    p.add_argument("--mode", type=v.mode, help="initial shading mode (default phong)")
    p.add_argument("--compare", action="store_true", help="flat | gouraud | phong side by "
                   "side")
    p.add_argument("--screenshot", metavar="PATH", help="save the window's pixels after "
                   "--frames frames and exit")
    p.add_argument("--frames", type=v.count, help="draw this many frames, then exit")
    p.add_argument("--pick", action="store_true", help="print the polygon, point, normal and "
                   "depth under a click")
    p.add_argument("--hidden", action="store_true", help=argparse.SUPPRESS)
    add_render_options(p)
    p.set_defaults(func=c.view, arguments=a.ViewArgs)


def add_doctor(sub) -> None:
    p = sub.add_parser("doctor", help="say which GL backends work and what they are")
    add_backend(p.add_argument)
    p.set_defaults(func=c.doctor, arguments=a.DoctorArgs)


def add_radiosity(sub) -> None:
    p = sub.add_parser("radiosity", help="solve a scene's diffuse interreflection (hemicube "
                       "form factors on the GPU) and render it",
                       **_examples("glshade radiosity assets/scenes/cornell-box.toml -o box.png",
                                   "glshade radiosity assets/scenes/cornell-box.toml -o box.png "
                                   "--patch-size 50 --steps steps.gif"))
    p.add_argument("scene", metavar="SCENE.toml", help="a scene file whose materials give "
                   "emission (e.g. assets/scenes/cornell-box.toml)")
    p.add_argument("-o", "--output", required=True, type=v.image_output,
                   help="the image (.png)")
    p.add_argument("--patch-size", type=v.positive_float, metavar="S", help="cut polygons "
                   "into patches of about S (scene units; default: a 24th of the diagonal)")
    p.add_argument("--hemicube", type=v.hemicube, default=HEMICUBE_RESOLUTION, metavar="N",
                   help="hemicube resolution, the top face's pixels a side (default "
                   f"{HEMICUBE_RESOLUTION})")
    p.add_argument("--method", type=v.radiosity_method, default="progressive",
                   help="progressive refinement (default), gauss-seidel gathering over the "
                   "full matrix (small scenes), or monte-carlo light tracing (no form "
                   "factors: the independent check; --particles)")
    p.add_argument("--particles", type=v.count, default=200_000, metavar="N",
                   help="light particles of --method monte-carlo (default 200,000)")
    stop = p.add_mutually_exclusive_group()
    stop.add_argument("--until", type=v.fraction, default=0.01, metavar="F",
                      help="stop when the unshot fraction of the emitted energy is below F "
                      "(default 0.01)")
    stop.add_argument("--iterations", type=v.count, metavar="N", help="stop after N shots "
                      "(progressive) or N sweeps (Gauss-Seidel)")
    p.add_argument("--steps", metavar="OUT", help="also animate the solution at work, the "
                   "energy shot so far (.gif, .png, .mp4 or a folder/)")
    p.add_argument("--plot", metavar="PNG", type=v.image_output, help="convergence plot "
                   "(default: OUTPUT's name with -convergence.png)")
    p.add_argument("--exposure", type=v.positive_float, help="scale of radiosity to display "
                   "(default: the brightest lit surface shows as white)")
    p.add_argument("--no-ambient", action="store_true", help="show only the energy shot so "
                   "far (no ambient estimate of the rest)")
    p.add_argument("--seed", type=v.seed, default=0, help="of the hemicubes' random turns "
                   "(a whole number >= 0; default 0)")
    p.add_argument("--size", type=v.size, metavar="WxH", help="image size (default: the "
                   "scene's)")
    p.add_argument("--samples", type=v.samples, help="MSAA samples (default: the scene's)")
    p.add_argument("--srgb", action="store_true", default=None, help="encode as sRGB")
    add_backend(p.add_argument)
    add_quiet(p, "no progress bar or summary")
    p.set_defaults(func=radiosity_command.radiosity, arguments=a.RadiosityArgs)


def add_dataset(sub) -> None:
    p = sub.add_parser("dataset", help="render a data set for vision code with exact ground "
                       "truth: BOP (poses, masks, depth) or COCO (instance masks as RLE)",
                       **_examples("glshade dataset assets/scenes/spheres.toml -o spheres-bop "
                                   "--views 50 --format bop --units m",
                                   "glshade dataset scene.toml -o coco --views 20 --format "
                                   "coco --size 640x480"))
    p.add_argument("scene", metavar="SCENE", help="a scene file; [[mesh]] label = \"...\" "
                   "names each object's class (default: its name)")
    p.add_argument("-o", "--output", required=True, help="the data set's folder (made if "
                   "missing; views already written there are kept)")
    p.add_argument("--views", type=v.count, default=1, metavar="N", help="cameras on a "
                   "sphere around the scene, or the scene file's key-framed path sampled N "
                   "times (default 1)")
    p.add_argument("--format", choices=("bop", "coco"), default="bop",
                   help="bop (the BOP toolkit's layout: poses in mm, 16-bit depth, full and "
                   "visible masks) or coco (one instances JSON; needs glshade[vision])")
    p.add_argument("--size", type=v.size, metavar="WxH", help="image size (default: the "
                   "scene file's [render] size, else 640x480)")
    p.add_argument("--samples", type=v.samples, help="MSAA samples of the colour images "
                   "(default 4; masks and depth are exact either way)")
    p.add_argument("--images", choices=("raster", "pathtrace"), default="raster",
                   help="the colour images rasterized (default) or path traced (masks, "
                   "depth and poses the exact raster ones of the same cameras)")
    stop = p.add_mutually_exclusive_group()
    stop.add_argument("--spp", type=v.count, metavar="N", help="--images pathtrace: samples "
                      "a pixel (default 64)")
    stop.add_argument("--until", type=v.fraction, metavar="F", help="--images pathtrace: "
                      "trace each image until its RMS standard error is F of its mean")
    p.add_argument("--depth-scale", type=v.positive_float, default=1.0, metavar="S",
                   help="BOP: a depth pixel times S is millimetres (default 1)")
    p.add_argument("--units", choices=("m", "mm"), default="m", help="what a scene unit is "
                   "(BOP files hold mm; default m)")
    add_backend(p.add_argument)
    add_executor_options(p, "1: this process", "the views")
    add_quiet(p, "no progress bar or summary")
    p.set_defaults(func=dataset_command.dataset, arguments=a.DatasetArgs)


def add_pathtrace(sub) -> None:
    p = sub.add_parser("pathtrace", help="solve the rendering equation by Monte Carlo path "
                       "tracing on the GPU (diffuse and Phong reflection, progressive)",
                       **_examples("glshade pathtrace assets/scenes/cornell-box.toml -o box.png "
                                   "--spp 256",
                                   "glshade pathtrace cornell-box -o box.png --until 0.02"))
    p.add_argument("scene", metavar="SCENE|MESH", help="a scene file (emitting materials or "
                   "lights), or a mesh lit by a headlight: " + MESH_HELP)
    p.add_argument("-o", "--output", required=True, type=v.image_output,
                   help="the image (.png)")
    stop = p.add_mutually_exclusive_group()
    stop.add_argument("--spp", type=v.count, metavar="N", help="samples (paths) a pixel "
                      "(default 64)")
    stop.add_argument("--until", type=v.fraction, metavar="F", help="trace until the "
                      "pixels' RMS standard error is F of the image's mean (e.g. 0.01)")
    p.add_argument("--seed", type=v.seed, default=0, help="of the random numbers (a whole "
                   "number >= 0; default 0: the same picture every run)")
    p.add_argument("--max-depth", type=v.count, default=None, metavar="N",
                   help="vertices a path may have (default: no limit; Russian roulette "
                   "ends paths, so the picture is the rendering equation's)")
    p.add_argument("--exposure", type=v.positive_float, help="scale of radiosity units to "
                   "display (default: the brightest lit surface shows as white)")
    p.add_argument("--no-lights", action="store_true", help="only emitting surfaces give "
                   "light (the scene's lights left out, as radiosity sees it)")
    p.add_argument("--sampler", choices=("pcg", "sobol"), default="pcg",
                   help="the paths' random numbers: pcg (independent, default) or sobol "
                   "(Owen-scrambled Sobol points at the first three vertices: less error for "
                   "the same samples; the error printed and --until's is figured from the "
                   "first samples' mean against the rest's)")
    p.add_argument("--kernel", choices=("auto", "fragment", "compute"), default="auto",
                   help="the program a pass runs: a fragment program or a compute kernel "
                   "(GL 4.3; the same numbers); auto (default) measures both on first use "
                   "and keeps the faster for this GL")
    p.add_argument("--streams", type=v.count, metavar="S", help="invocations sharing "
                   "each pixel's samples, 1 to 64 (default: one on a software renderer, else "
                   "enough to fill a large GPU: a small picture has too few pixels for its "
                   "cores; the same picture to rounding)")
    p.add_argument("--coherent", action="store_true", help="blocks of 4x2 pixels draw the "
                   "same random numbers, so their rays run together (faster on a large mesh; "
                   "each pixel as noisy, the noise in blocks)")
    p.add_argument("--control", action="store_true", help="solve the scene's radiosity "
                   "and use each model's indirect irradiance as a control variate at Russian "
                   "roulette (unbiased; less error where light bounces a lot)")
    p.add_argument("--adaptive", action="store_true", help="--spp is the mean: a pilot "
                   "from another seed measures each pixel's spread and the samples go where "
                   "it is (unbiased; less error for the same paths)")
    p.add_argument("--no-mis", action="store_true", help="count emission found by a "
                   "bounce only at the first vertex (next-event estimation alone after it), "
                   "not weighed against next-event estimation by multiple importance "
                   "sampling (the default)")
    add_render_options(p, refused=NOT_TRACED)
    add_quiet(p, "no progress bar or summary")
    p.set_defaults(func=pathtrace_command.pathtrace, arguments=a.PathtraceArgs)


def add_hidden(sub) -> None:
    p = sub.add_parser("hidden", help="the classic hidden-surface algorithms side by side, "
                       "checked against the GPU z-buffer",
                       **_examples("glshade hidden primitive:teapot:4 -o grid.png --steps "
                                   "steps.gif",
                                   "glshade hidden assets/lprism.obj -o g.png --algorithms "
                                   "scanline,bsp,gpu"))
    p.add_argument("mesh", metavar="MESH|SCENE", help=MESH_HELP)
    p.add_argument("-o", "--output", required=True, type=v.image_output,
                   help="the grid of id images and disagreement maps (.png)")
    p.add_argument("--algorithms", type=v.algorithms, default=list(v.ALGORITHM_CHOICES),
                   help="comma-separated, from " + ", ".join(v.ALGORITHM_CHOICES) +
                   " (default: all)")
    p.add_argument("--steps", metavar="OUT.gif", help="also animate the algorithms at work")
    p.add_argument("--size", type=v.size, metavar="WxH", help="image size (default 256x256)")
    p.add_argument("--eye", type=v.vec3, metavar="X,Y,Z",
                   help="camera position (default: auto framing)")
    p.add_argument("--target", type=v.vec3, metavar="X,Y,Z", help="point looked at")
    p.add_argument("--fov", type=v.fov, help="vertical field of view in degrees")
    add_backend(p.add_argument)
    p.set_defaults(func=hidden_command.hidden, arguments=a.HiddenArgs)
