"""How each shading mode's error falls as a sphere is tessellated more finely (against the
analytic sphere), or a patch model (against a fine tessellation with exact normals, with
exact and with averaged normals): the numbers and a log-scale plot drawn with Pillow."""

from __future__ import annotations

import numpy as np

from ..io.images import font
from ..options import RenderConfig
from ..scene import Camera, Material, PointLight, Scene, default_camera
from .comparison import compare

__all__ = ["sweep", "sweep_plot", "patch_sweep", "SweepLevel", "icosphere_level",
           "uv_sphere_level"]

#: a sweep's tiles: small, one sample per pixel like the analytic reference
SWEEP_CONFIG = RenderConfig(192, 192, samples=0)


def sweep(make_mesh, levels, camera: Camera | None = None, modes=("flat", "gouraud", "phong"),
          *, material=None, lights=None, size=None, backend=None,
          config: RenderConfig | None = None, renderer=None, jobs: int = 1,
          scheduler: str | None = None, progress=None) -> list[dict]:
    """Error of each mode against the analytic reference for each tessellation level:
    ``[{"level": k, "faces": F, "flat": ModeMetrics, ...}, ...]``. Levels render in
    ``jobs`` worker processes or on a Dask ``scheduler`` (then ``make_mesh`` must be
    picklable: a module-level function or a ``functools.partial`` of one). ``config`` (or
    ``size``, ``backend``): what each worker's Renderer is built with (192x192, no MSAA).
    ``progress``: a bar (a notebook's widget, a terminal's line), None to decide by where
    output goes, False for none, or an object with ``update()``.

    Parameters
    ----------
    make_mesh : callable
        ``make_mesh(level) -> Mesh`` (picklable for workers).
    levels : iterable of int
        The tessellation levels.
    camera : Camera or None
        From where (None: the default framing).
    modes : sequence of str
        The shading modes measured.
    material : Material or None
        The meshes' material.
    lights : list or None
        The lights (None: the default).
    size : (int, int) or None
        Width and height (default 192x192).
    backend : str or None
        The headless backend.
    config : RenderConfig or None
        What each worker's renderer is built with.
    renderer : Renderer or None
        A renderer to draw with, in this process.
    jobs : int
        Worker processes.
    scheduler : str or None
        A Dask scheduler's address, or ``"local"``.
    progress : bool, tqdm-like or None
        The progress bar (None: where output goes decides; False: none).
    """
    config = RenderConfig.of(config, size=size, backend=backend, base=SWEEP_CONFIG)
    args = (make_mesh, camera, tuple(modes), material, lights, config)
    if renderer is not None:
        worker = SweepLevel(*args, renderer=renderer)
        return [worker(k) for k in levels]
    from ..parallel import as_progress, make_executor

    levels = list(levels)
    executor = make_executor(SweepLevel, args, jobs, items=len(levels), scheduler=scheduler)
    bar, owned = as_progress(progress, len(levels), "levels")
    rows = []
    try:
        for row in executor.map(levels):
            rows.append(row)
            if bar is not None:
                bar.update()
    finally:
        if owned:
            bar.close()
    return rows


class SweepLevel:
    """A worker: the row of one tessellation level (its own renderer unless given one).

    Parameters
    ----------
    make_mesh : callable
        ``make_mesh(level) -> Mesh``.
    camera : Camera or None
        From where.
    modes : sequence of str
        The shading modes.
    material : Material or None
        The meshes' material.
    lights : list or None
        The lights.
    config : RenderConfig
        What its renderer is built with.
    renderer : Renderer or None
        A renderer to draw with (None: its own).
    """

    def __init__(self, make_mesh, camera, modes, material, lights, config: RenderConfig,
                 renderer=None):
        from ..render.renderer import Renderer

        self.make_mesh, self.modes, self.size = make_mesh, modes, config.size
        self.camera = camera or Camera.look_at([0.4, 0.6, 3.3], [0, 0, 0], fov_y=40)
        self.material = material or Material(color=(0.9, 0.75, 0.6), ks=0.5, shininess=30)
        self.lights = lights or [PointLight((3.0, 4.0, 5.0))]
        self.owned = renderer is None
        self.renderer = renderer or Renderer(config=config)

    def __call__(self, k: int) -> dict:
        mesh = self.make_mesh(k)
        scene = Scene()
        scene.add(mesh, self.material)
        for light in self.lights:
            scene.add_light(light)
        c = compare(scene, self.camera, self.modes, "analytic", size=self.size, diff=False,
                    renderer=self.renderer)
        row = {"level": k, "faces": mesh.n_faces}
        row.update({m.mode: m for m in c.metrics})
        return row

    def close(self):
        if self.owned:
            self.renderer.close()


def icosphere_level(k: int):
    """The icosphere of subdivision level ``k`` (a picklable ``make_mesh``).

    Parameters
    ----------
    k : int
        The subdivision level.
    """
    from ..geometry import primitives

    return primitives.icosphere(k)


def uv_sphere_level(k: int):
    """A UV sphere with ``4 * 2**k`` stacks and ``8 * 2**k`` slices.

    Parameters
    ----------
    k : int
        The level: ``4 * 2**k`` stacks.
    """
    from ..geometry import primitives

    return primitives.uv_sphere(4 * 2**k, 8 * 2**k)


#: the series' colours in a sweep plot (others: the palette, in turn)
SERIES_COLORS = {"flat": (230, 120, 60), "gouraud": (90, 170, 240), "phong": (120, 220, 120),
                 "normals": (200, 200, 200), "depth": (160, 160, 160)}
PALETTE = [(40, 150, 60), (230, 120, 60), (60, 110, 220), (190, 70, 170), (120, 120, 120),
           (200, 170, 40)]


def sweep_plot(rows: list[dict], modes, metric: str = "mean_abs", size=(640, 420),
               title: str = "error vs the analytic sphere") -> np.ndarray:
    """A log-scale line plot of ``metric`` of each series (``modes``: the rows' keys)
    against level, drawn with Pillow.

    Parameters
    ----------
    rows : list of dict
        :func:`sweep`'s rows.
    modes : sequence of str
        The series drawn (the rows' keys).
    metric : str
        The ModeMetrics field plotted.
    size : (int, int)
        The plot's width and height in pixels.
    title : str
        Its title.
    """
    from PIL import Image, ImageDraw

    colors = {m: SERIES_COLORS.get(m, PALETTE[i % len(PALETTE)]) for i, m in enumerate(modes)}
    w, h = size
    left, right, top, bottom = 70, 20, 40, 50
    img = Image.new("RGB", (w, h), (250, 250, 250))
    d = ImageDraw.Draw(img)
    face, small = font(14), font(11)
    values = [max(getattr(r[m], metric), 1e-3) for r in rows for m in modes]
    lo, hi = np.floor(np.log10(min(values))), np.ceil(np.log10(max(values)))
    hi = max(hi, lo + 1)
    levels = [r["level"] for r in rows]
    x0, x1 = min(levels), max(levels) if max(levels) > min(levels) else min(levels) + 1

    def px(level, value):
        x = left + (level - x0) / (x1 - x0) * (w - left - right)
        y = top + (hi - np.log10(max(value, 1e-3))) / (hi - lo) * (h - top - bottom)
        return x, y

    d.rectangle([left, top, w - right, h - bottom], outline=(120, 120, 120))
    for e in range(int(lo), int(hi) + 1):
        _, y = px(x0, 10.0**e)
        d.line([left, y, w - right, y], fill=(225, 225, 225))
        d.text((8, y - 7), f"1e{e}", fill=(60, 60, 60), font=small)
    for level in levels:
        x, _ = px(level, 10**lo)
        d.text((x - 4, h - bottom + 6), str(level), fill=(60, 60, 60), font=small)
    d.text((w / 2 - 60, h - 22), "tessellation level", fill=(30, 30, 30), font=face)
    d.text((left, 10), f"{metric.replace('_', ' ')} {title} (8-bit, log)",
           fill=(30, 30, 30), font=face)
    for i, m in enumerate(modes):
        pts = [px(r["level"], getattr(r[m], metric)) for r in rows]
        d.line(pts, fill=colors.get(m, (0, 0, 0)), width=3)
        for x, y in pts:
            d.ellipse([x - 3, y - 3, x + 3, y + 3], fill=colors.get(m, (0, 0, 0)))
        label_w = d.textlength(m, font=face)
        d.text((w - right - 10 - label_w, top + 8 + 16 * i), m,
               fill=colors.get(m, (0, 0, 0)), font=face)
    return np.asarray(img)


#: the tessellation levels a patch sweep draws unless told
PATCH_SWEEP_LEVELS = (2, 3, 4, 6, 8, 12, 16)


def patch_sweep(surface, camera: Camera | None = None, levels=PATCH_SWEEP_LEVELS,
                modes=("gouraud", "phong"), *, reference_level: int = 96, size=(256, 256),
                material=None, renderer=None, backend=None, progress=None) -> list[dict]:
    """Shading error of a patch model's tessellations against an exact per-pixel reference
    (Phong on a ``reference_level`` tessellation with exact normals), per level: each of
    ``modes`` with the patches' exact normals and with normals averaged over the welded mesh
    (the notes' formula). Rows ``{"level", "faces", "<mode> exact": ModeMetrics,
    "<mode> averaged": ModeMetrics}``, in 8-bit units.

    Parameters
    ----------
    surface : PatchSurface or PatchSet
        The patches.
    camera : Camera or None
        From where (None: the default framing).
    levels : sequence of int
        The tessellation levels measured.
    modes : sequence of str
        The shading modes.
    reference_level : int
        The reference's tessellation level.
    size : (int, int)
        Width and height.
    material : Material or None
        The surface's material.
    renderer : Renderer or None
        A renderer to draw with.
    backend : str or None
        The headless backend of one made here.
    progress : bool, tqdm-like or None
        The progress bar (None: where output goes decides; False: none).
    """
    from ..geometry.mesh import Mesh
    from ..parallel import as_progress
    from ..patches import PatchSurface, tessellate
    from ..render.renderer import Renderer

    surface = surface if isinstance(surface, PatchSurface) else PatchSurface(surface)
    material = material or Material(color=(0.85, 0.55, 0.3), ks=0.5, shininess=40)
    owned = renderer is None
    r = renderer or Renderer(int(size[0]), int(size[1]), samples=0, backend=backend or "auto")
    bar, own_bar = as_progress(progress, len(levels) + 1, "levels")
    try:
        def scene_of(mesh):
            scene = Scene()
            scene.add(mesh, material)
            scene.add_light(PointLight((5.0, 7.0, 8.0)))
            return scene

        fine = scene_of(tessellate(surface, reference_level).mesh)
        camera = camera or default_camera(fine.bounds, r.width / r.height)
        reference = r.render(fine, camera, "phong")[..., :3]
        if bar is not None:
            bar.update()
        rows = []
        for k in levels:
            tess = tessellate(surface, int(k))
            exact = scene_of(tess.mesh)
            averaged = scene_of(Mesh(tess.mesh.vertices, tess.mesh.faces).weld())
            row: dict = {"level": int(k), "faces": tess.n_triangles}
            for kind, scene in (("exact", exact), ("averaged", averaged)):
                c = compare(scene, camera, modes, reference, diff=False, renderer=r,
                            size=(r.width, r.height))
                row.update({f"{m.mode} {kind}": m for m in c.metrics})
            rows.append(row)
            if bar is not None:
                bar.update()
        return rows
    finally:
        if own_bar:
            bar.close()
        if owned:
            r.close()
