"""The ``glshade`` command line tool.

Exit status: 0 on success; 2 for bad input (arguments, or an input file that is missing
or malformed), reported in one line on stderr; 1 for a failure of the environment (no GL
context, an output that cannot be written), also one line. ``--debug`` shows tracebacks.
Heavy imports happen inside the subcommands, so ``--help`` needs no GL.
"""

from __future__ import annotations

import argparse
import json
import math
import re
import sys

import numpy as np

from ._version import __version__

__all__ = ["main"]

EXIT_OK, EXIT_ENVIRONMENT, EXIT_USAGE = 0, 1, 2
DEFAULT_SIZE = (800, 600)


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


def topology_summary(mesh) -> dict:
    """Euler's formula and the validity checks of the mesh's winged-edge structure."""
    from .geometry.brep import WingedEdge

    w = WingedEdge.from_mesh(mesh, strict=False)
    out = w.euler().as_dict()
    out["problems"] = w.report.message() or None
    return out


def _cmd_info(args) -> int:
    mesh = _load(args.mesh)
    info = mesh_summary(mesh)
    info["source"] = args.mesh
    info["topology"] = topology_summary(mesh)
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
    t = info["topology"]
    print("topology (winged edge):")
    print("     V       E       F     H    C    G  closed  manifold  oriented  boundary loops")
    g = "?" if t["G"] is None else t["G"]
    print(f"  {t['V']:>4} {t['E']:>7} {t['F']:>7} {t['H']:>5} {t['C']:>4} {g:>4}  "
          f"{'yes' if t['closed'] else 'no':>6}  {'yes' if t['manifold'] else 'no':>8}  "
          f"{'yes' if t['oriented'] else 'no':>8}  {t['boundary_loops']:>14}")
    print(f"  Euler's formula {'holds' if t['euler_holds'] else 'does NOT hold'}: "
          f"{t['formula']}")
    if t["problems"]:
        print(f"  problems: {t['problems']}")
    return EXIT_OK


def _size(text: str) -> tuple[int, int]:
    m = re.fullmatch(r"\s*(\d+)\s*[xX]\s*(\d+)\s*", text)
    if not m or int(m.group(1)) < 1 or int(m.group(2)) < 1 or max(map(int, m.groups())) > 16384:
        raise argparse.ArgumentTypeError(f"expected WIDTHxHEIGHT such as 800x600 (1..16384), "
                                         f"got {text!r}")
    return int(m.group(1)), int(m.group(2))


def _vec3(text: str) -> tuple[float, float, float]:
    try:
        values = tuple(float(v) for v in text.split(","))
    except ValueError:
        values = ()
    if len(values) != 3 or not all(map(math.isfinite, values)):
        raise argparse.ArgumentTypeError(f"expected three numbers x,y,z such as 1,2.5,-3, got "
                                         f"{text!r}")
    return values


def _count(text: str) -> int:
    if not text.strip().isdigit() or int(text) < 1:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 1 such as 4, got "
                                         f"{text!r}")
    return int(text)


def _unit_float(text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        v = float("nan")
    if not (0 <= v <= 1):
        raise argparse.ArgumentTypeError(f"expected a number in [0, 1] such as 0.5, got {text!r}")
    return v


def _positive_float(text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        v = float("nan")
    if not (v >= 0 and math.isfinite(v)):
        raise argparse.ArgumentTypeError(f"expected a non-negative number such as 32, got "
                                         f"{text!r}")
    return v


def _mode(text: str):
    from .modes import ShadingMode

    try:
        return ShadingMode(text.lower())
    except ValueError:
        choices = ", ".join(m.value for m in ShadingMode)
        raise argparse.ArgumentTypeError(f"unknown mode {text!r}; choose one of {choices}") \
            from None


def build_scene(mesh, args):
    """A one-mesh scene and camera from the render options (shared with the viewer)."""
    from .camera import Camera, default_camera
    from .scene import Material, PointLight, Scene

    width, height = args.size
    scene = Scene(background=args.background)
    scene.add(mesh, Material(color=args.color, ka=args.ka, kd=args.kd, ks=args.ks,
                             shininess=args.shininess))
    if args.eye is not None or args.target is not None:
        eye = args.eye if args.eye is not None else (0.0, 0.0, 5.0)
        target = args.target if args.target is not None else tuple(scene.bounds().mean(0))
        b = scene.bounds()
        reach = float(np.linalg.norm(b[1] - b[0])) + float(np.linalg.norm(np.subtract(eye,
                                                                                      target)))
        camera = Camera.look_at(eye, target, fov_y=args.fov, near=reach * 1e-3, far=reach * 2)
    else:
        camera = default_camera(scene.bounds(), width / height, fov_y=args.fov)
    if args.light:
        for position in args.light:
            scene.add_light(PointLight(position))
    else:
        # a key light above and to the left of the camera
        distance = float(np.linalg.norm(camera.position - scene.bounds().mean(0)))
        position = camera.position + distance * (0.8 * camera.up - 0.5 * camera.right)
        scene.add_light(PointLight(tuple(position)))
    return scene, camera


def _cmd_render(args) -> int:
    from .image import save_image
    from .render.renderer import Renderer

    if args.mesh.lower().endswith(".toml"):
        from .scenefile import load_scene

        sf = load_scene(args.mesh)
        scene = sf.scene
        settings = sf.settings
        # options given on the command line win over the scene file's settings
        width, height = args.size or (settings.width, settings.height)
        mode = args.mode or settings.mode
        samples = settings.samples if args.samples is None else args.samples
        srgb = args.srgb or settings.srgb
        camera = sf.path.at(sf.path.start if args.time is None else args.time)
        polygons = sum(m.mesh.n_faces for m in scene.models)
    else:
        if args.time is not None:
            raise GlshadeErrorUsage("--time needs a scene file (.toml) with a camera path")
        args.size = args.size or DEFAULT_SIZE
        mesh = _load(args.mesh)
        scene, camera = build_scene(mesh, args)
        (width, height), srgb = args.size, args.srgb
        mode = args.mode or _mode("phong")
        samples = 4 if args.samples is None else args.samples
        polygons = mesh.n_faces
    with Renderer(width, height, samples=samples, backend=args.backend) as renderer:
        image = renderer.render(scene, camera, mode, srgb=srgb)
    save_image(image, args.output)
    if not args.quiet:
        print(f"{args.output}: {width}x{height} {mode.value}, {polygons:,} polygons "
              f"({renderer.backend})")
    return EXIT_OK


def _cmd_animate(args) -> int:
    import os

    from .animate import animate, output_format
    from .scenefile import load_scene

    output_format(args.output)  # a bad extension fails before any rendering
    sf = load_scene(args.scene)
    st = sf.settings
    fps = args.fps or st.fps
    duration = args.duration if args.duration is not None else st.duration
    if args.frames is not None:
        frames = args.frames
    elif duration:
        frames = max(1, int(round(duration * fps)))
    else:
        frames = 1
    size = args.size or (st.width, st.height)
    modes = [m.value for m in args.modes] if args.modes else [(args.mode or st.mode).value]
    jobs = args.jobs or os.cpu_count() or 1
    n = animate(sf.scene, sf.path, frames, modes=modes, output=args.output, fps=fps,
                size=size, samples=st.samples if args.samples is None else args.samples,
                srgb=st.srgb, jobs=jobs, backend=args.backend,
                progress=None if not args.quiet else False)
    if not args.quiet:
        print(f"{args.output}: {n} frames, {size[0]}x{size[1]}, {fps:g} fps, "
              f"{'/'.join(modes)}, {jobs} job{'s' if jobs > 1 else ''}")
    return EXIT_OK


def _levels(text: str) -> list[int]:
    m = re.fullmatch(r"\s*(\d+)\s*\.\.\s*(\d+)\s*", text)
    if m and int(m.group(1)) <= int(m.group(2)) <= 8:
        return list(range(int(m.group(1)), int(m.group(2)) + 1))
    try:
        values = [int(v) for v in text.split(",")]
    except ValueError:
        values = []
    if not values or min(values) < 0 or max(values) > 8:
        raise argparse.ArgumentTypeError(f"expected levels such as 0..6 or 1,3,5 (0 to 8), got "
                                         f"{text!r}")
    return values


def _modes(text: str):
    return [_mode(t.strip()) for t in text.split(",") if t.strip()] or \
        [_mode("")]  # an empty list reports the choices


def _cmd_compare(args) -> int:
    from .comparison import compare, sweep, sweep_plot
    from .geometry import primitives
    from .image import save_image

    modes = [m.value for m in args.modes]
    if args.sweep:
        spec = args.mesh.removeprefix("primitive:").split(":")[0]
        if spec not in ("icosphere", "uv_sphere"):
            raise GlshadeErrorUsage("--sweep needs a sphere primitive: primitive:icosphere or "
                                    "primitive:uv_sphere")
        make = primitives.icosphere if spec == "icosphere" else \
            (lambda k: primitives.uv_sphere(4 * 2**k, 8 * 2**k))
        rows = sweep(make, args.levels, modes=modes, size=args.size, backend=args.backend)
        head = "level  faces     " + "  ".join(f"{m:>9}" for m in modes) + \
            "   " + "  ".join(f"{'peak ' + m:>13}" for m in modes)
        print("mean |error| against the analytic sphere (8-bit units) and the brightest "
              "pixel (the reference's: %.1f)" % rows[0][modes[0]].reference_peak)
        print(head)
        for r in rows:
            print(f"{r['level']:>5}  {r['faces']:>8,}  " +
                  "  ".join(f"{r[m].mean_abs:>9.3f}" for m in modes) + "   " +
                  "  ".join(f"{r[m].peak:>13.1f}" for m in modes))
        save_image(sweep_plot(rows, modes), args.output)
        if args.json:
            from ._atomic import atomic_write

            with atomic_write(args.json, "w") as f:
                json.dump([{"level": r["level"], "faces": r["faces"],
                            **{m: r[m].__dict__ for m in modes}} for r in rows], f, indent=2)
        print(f"plot: {args.output}")
        return EXIT_OK
    if args.mesh.lower().endswith(".toml"):
        from .scenefile import load_scene

        sf = load_scene(args.mesh)
        scene, camera = sf.scene, sf.camera
    else:
        scene, camera = build_scene(_load(args.mesh), args)
    result = compare(scene, camera, modes, args.reference, size=args.size, diff=args.diff,
                     backend=args.backend)
    save_image(result.image, args.output)
    print(result.table())
    if args.json:
        result.write_json(args.json)
    if args.csv:
        result.write_csv(args.csv)
    print(f"grid: {args.output}")
    return EXIT_OK


class GlshadeErrorUsage(ValueError):
    """Bad combination of arguments (exit 2)."""


def _cmd_view(args) -> int:
    from .viewer.window import Viewer

    if args.mesh.lower().endswith(".toml"):
        from .scenefile import load_scene

        sf = load_scene(args.mesh)
        scene, camera = sf.scene, sf.camera
    else:
        scene, camera = build_scene(_load(args.mesh), args)
    with Viewer(scene, camera, size=args.size, mode=args.mode, samples=args.samples,
                compare=args.compare, visible=not args.hidden) as viewer:
        if args.screenshot:
            viewer.run(args.frames)
            viewer.screenshot(args.screenshot)
        else:
            viewer.run(args.frames)
    return EXIT_OK


def _cmd_doctor(args) -> int:
    from .render.context import create_context, probe_backends

    ok = True
    try:
        with create_context(args.backend) as ctx:
            info = ctx.info
        print(f"backend chosen     {info['backend']}")
        for key in ("vendor", "renderer", "version", "max_samples", "max_texture_size"):
            print(f"{key.replace('_', ' '):<18} {info[key]}")
    except Exception as exc:  # report, then go on to the per-backend probe
        ok = False
        print(f"backend chosen     none: {exc}")
    print("backends:")
    for name, status in probe_backends().items():
        print(f"  {name:<8} {status}")
    return EXIT_OK if ok else EXIT_ENVIRONMENT


def add_render_options(p: argparse.ArgumentParser) -> None:
    """Options shared by render, view and compare."""
    p.add_argument("--size", type=_size, default=DEFAULT_SIZE, metavar="WxH",
                   help="image size (default 800x600)")
    p.add_argument("--samples", type=int, default=4, help="MSAA samples, 0 = off (default 4)")
    p.add_argument("--eye", type=_vec3, metavar="X,Y,Z", help="camera position "
                   "(default: auto framing)")
    p.add_argument("--target", type=_vec3, metavar="X,Y,Z", help="point looked at")
    p.add_argument("--fov", type=float, default=45.0, help="vertical field of view, degrees")
    p.add_argument("--light", type=_vec3, action="append", metavar="X,Y,Z",
                   help="a point light (repeat for more; default: one above the camera)")
    p.add_argument("--color", type=_vec3, default=(0.8, 0.8, 0.8), metavar="R,G,B",
                   help="material colour, linear 0..1")
    p.add_argument("--background", type=_vec3, default=(0.0, 0.0, 0.0), metavar="R,G,B")
    p.add_argument("--ka", type=_unit_float, default=0.2, help="ambient coefficient")
    p.add_argument("--kd", type=_unit_float, default=0.7, help="diffuse coefficient")
    p.add_argument("--ks", type=_unit_float, default=0.3, help="specular coefficient")
    p.add_argument("--shininess", type=_positive_float, default=32.0,
                   help="specular exponent n")
    p.add_argument("--backend", choices=["auto", "egl", "osmesa"], default="auto")
    p.add_argument("--srgb", action="store_true", help="encode the linear result as sRGB")


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

    p = sub.add_parser("render", help="render a mesh headless to an image")
    p.add_argument("mesh", metavar="MESH", help="a mesh file or primitive:NAME[:ARGS]")
    p.add_argument("-o", "--output", required=True, help="output image (.png)")
    p.add_argument("--mode", type=_mode, default=None,
                   help="flat, gouraud, phong, normals or depth (default phong, or the "
                   "scene file's)")
    p.add_argument("-q", "--quiet", action="store_true")
    p.add_argument("--time", type=float, help="with a scene file: the moment on its camera "
                   "path (seconds)")
    add_render_options(p)
    # unset size and samples fall back to the scene file's, else the defaults
    p.set_defaults(func=_cmd_render, size=None, samples=None)

    p = sub.add_parser("animate", help="render a scene file's camera path to GIF, PNG, MP4 "
                       "or frames")
    p.add_argument("scene", metavar="SCENE.toml")
    p.add_argument("-o", "--output", required=True, help="out.gif, out.png (APNG), out.mp4 "
                   "or a folder/ for PNG frames")
    p.add_argument("--fps", type=_positive_float, help="frames per second (default: the "
                   "scene's, else 30)")
    length = p.add_mutually_exclusive_group()
    length.add_argument("--duration", type=_positive_float, help="seconds of path to render")
    length.add_argument("--frames", type=_count, help="number of frames")
    p.add_argument("--mode", type=_mode, help="shading mode (default: the scene's)")
    p.add_argument("--modes", type=_modes, help="several modes side by side, e.g. "
                   "flat,gouraud,phong")
    p.add_argument("--jobs", type=_count, help="worker processes (default: the number of "
                   "cores)")
    p.add_argument("--size", type=_size, metavar="WxH", help="frame size (default: the "
                   "scene's)")
    p.add_argument("--samples", type=int, help="MSAA samples (default: the scene's)")
    p.add_argument("--backend", choices=["auto", "egl", "osmesa"], default="auto")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar or summary")
    p.set_defaults(func=_cmd_animate)

    p = sub.add_parser("compare", help="flat, Gouraud and Phong side by side, with errors "
                       "against a reference")
    p.add_argument("mesh", metavar="MESH", help="a mesh file, primitive:NAME[:ARGS] or a "
                   "scene file (.toml)")
    p.add_argument("-o", "--output", required=True, help="output image: the grid (or the "
                   "plot, with --sweep)")
    p.add_argument("--modes", type=_modes, default="flat,gouraud,phong",
                   help="comma-separated modes (default flat,gouraud,phong)")
    p.add_argument("--diff", action="store_true", help="add a row of difference heat maps")
    p.add_argument("--reference", default="analytic", help="analytic (sphere primitives), "
                   "phong-fine, or an image file (default analytic)")
    p.add_argument("--json", help="write the metrics as JSON")
    p.add_argument("--csv", help="write the metrics as CSV")
    p.add_argument("--sweep", action="store_true", help="error of each mode against "
                   "tessellation level of a sphere primitive")
    p.add_argument("--levels", type=_levels, default=list(range(0, 7)),
                   help="levels for --sweep, e.g. 0..6")
    add_render_options(p)
    p.set_defaults(func=_cmd_compare, size=(256, 256), samples=0)

    p = sub.add_parser("view", help="explore a mesh in a window (keys: h)")
    p.add_argument("mesh", metavar="MESH", help="a mesh file, primitive:NAME[:ARGS] or a "
                   "scene file (.toml)")
    p.add_argument("--mode", type=_mode, default="phong", help="initial shading mode")
    p.add_argument("--compare", action="store_true", help="flat | gouraud | phong side by "
                   "side")
    p.add_argument("--screenshot", metavar="PATH", help="save the window's pixels after "
                   "--frames frames and exit")
    p.add_argument("--frames", type=_count, help="draw this many frames, then exit")
    p.add_argument("--hidden", action="store_true", help=argparse.SUPPRESS)
    add_render_options(p)
    p.set_defaults(func=_cmd_view)

    p = sub.add_parser("doctor", help="say which GL backends work and what they are")
    p.add_argument("--backend", choices=["auto", "egl", "osmesa"], default="auto")
    p.set_defaults(func=_cmd_doctor)
    return parser


def main(argv: list[str] | None = None) -> int:
    from .errors import GlshadeError

    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except (GlshadeError, GlshadeErrorUsage) as exc:
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
