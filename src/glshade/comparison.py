"""Comparing shading modes: a labelled grid, difference heat maps, and the numbers.

``compare(scene, camera)`` renders each mode and a reference -- the exact surface ray-cast
with the same lighting formula (``"analytic"``, for sphere primitives), a Phong render of
the mesh refined by Phong tessellation (``"phong-fine"``), or an image you supply -- and
measures each mode against it on the pixels both cover.
"""

from __future__ import annotations

import csv
import io
import json
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from . import metrics
from ._table import format_table
from ._atomic import atomic_write
from .camera import Camera
from .errors import ComparisonError
from .geometry.subdivide import phong_tessellate
from .modes import ShadingMode
from .scene import Scene

__all__ = ["compare", "sweep", "Comparison", "ModeMetrics", "heatmap", "REFERENCES"]

REFERENCES = ("analytic", "phong-fine")
LABEL_HEIGHT = 22

# a perceptually ordered ramp (dark blue -> purple -> orange -> pale yellow)
_RAMP = np.array([[0, 0, 4], [40, 11, 84], [101, 21, 110], [159, 42, 99], [212, 72, 66],
                  [245, 125, 21], [250, 193, 39], [252, 255, 164]], float)


def heatmap(values, vmax: float) -> np.ndarray:
    """Map ``(H, W)`` values in ``[0, vmax]`` to RGB uint8 through the ramp."""
    t = np.clip(np.asarray(values, float) / max(vmax, 1e-12), 0, 1) * (len(_RAMP) - 1)
    i = np.minimum(t.astype(int), len(_RAMP) - 2)
    f = (t - i)[..., None]
    return ((1 - f) * _RAMP[i] + f * _RAMP[i + 1] + 0.5).astype(np.uint8)


@dataclass
class ModeMetrics:
    """How far one mode is from the reference, in 8-bit units (PSNR in dB)."""

    mode: str
    mean_abs: float
    max_abs: float
    rmse: float
    psnr: float
    ssim: float
    mach_band: float
    peak: float            # brightest luminance (the specular highlight)
    reference_peak: float
    pixels: int


@dataclass
class Comparison:
    """The grid image, the per-mode metrics and the images they came from."""

    image: np.ndarray
    metrics: list[ModeMetrics]
    images: dict = field(repr=False, default_factory=dict)
    reference: np.ndarray | None = field(repr=False, default=None)
    reference_kind: str = ""

    def table(self) -> str:
        head = ("mode", "mean", "max", "RMSE", "PSNR dB", "SSIM", "Mach band", "peak/ref")
        rows = [(m.mode, f"{m.mean_abs:.3f}", f"{m.max_abs:.1f}", f"{m.rmse:.3f}",
                 f"{m.psnr:.2f}", f"{m.ssim:.4f}", f"{m.mach_band:.2f}",
                 f"{m.peak:.1f}/{m.reference_peak:.1f}") for m in self.metrics]
        return (f"against the {self.reference_kind} reference, 8-bit units\n"
                + format_table(rows, head))

    def as_dicts(self) -> list[dict]:
        return [asdict(m) for m in self.metrics]

    def write_json(self, path) -> None:
        with atomic_write(path, "w") as f:
            json.dump({"reference": self.reference_kind, "modes": self.as_dicts()}, f,
                      indent=2, default=lambda x: None)

    def write_csv(self, path) -> None:
        rows = self.as_dicts()
        with atomic_write(path, "w") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)

    def _repr_png_(self) -> bytes:
        from PIL import Image

        buf = io.BytesIO()
        Image.fromarray(self.image).save(buf, format="PNG")
        return buf.getvalue()


def _font(size: int = 14):
    from PIL import ImageFont

    try:
        return ImageFont.load_default(size=size)
    except TypeError:  # Pillow < 10.1
        return ImageFont.load_default()


def _label(tile: np.ndarray, text: str, background=(24, 24, 28)) -> np.ndarray:
    from PIL import Image, ImageDraw

    h, w = tile.shape[:2]
    band = Image.new("RGB", (w, LABEL_HEIGHT), background)
    draw = ImageDraw.Draw(band)
    font = _font(14)
    width = draw.textlength(text, font=font)
    draw.text(((w - width) / 2, 3), text, fill=(235, 235, 235), font=font)
    return np.vstack([np.asarray(band), tile[..., :3]])


def _colour_bar(height: int, vmax: float) -> np.ndarray:
    from PIL import Image, ImageDraw

    width = 64
    ramp = heatmap(np.linspace(vmax, 0, height)[:, None].repeat(14, 1), vmax)
    img = Image.new("RGB", (width, height), (24, 24, 28))
    img.paste(Image.fromarray(ramp), (4, 0))
    draw = ImageDraw.Draw(img)
    font = _font(11)
    draw.text((21, 0), f"{vmax:.3g}", fill=(235, 235, 235), font=font)
    draw.text((21, height // 2 - 6), f"{vmax / 2:.3g}", fill=(235, 235, 235), font=font)
    draw.text((21, height - 13), "0", fill=(235, 235, 235), font=font)
    draw.text((21, height - 28), "|err|", fill=(180, 180, 180), font=font)
    return np.asarray(img)


def _reference(scene, camera, kind, renderer, size):
    from .raycast import raycast_scene

    w, h = size
    if isinstance(kind, (str, Path)) and str(kind) == "analytic":
        color, mask = raycast_scene(scene, camera, w, h)
        bg = np.asarray(scene.background[:3])
        return np.where(mask[..., None], color, bg) * 255, mask, "analytic"
    if isinstance(kind, (str, Path)) and str(kind) == "phong-fine":
        fine = Scene(scene.ambient, scene.background)
        for m in scene.models:
            if m.visible:
                fine.add(phong_tessellate(m.mesh, 6), m.material, m.transform)
        fine.lights = list(scene.lights)
        frame = renderer.render_frame(fine, camera, "phong", color_dtype="f4")
        return frame.color[..., :3] * 255.0, frame.face_id >= 0, "phong-fine"
    if isinstance(kind, (str, Path)):
        from PIL import Image

        path = Path(kind)
        if not path.is_file():
            raise ComparisonError(f"reference {str(kind)!r} is neither {' nor '.join(REFERENCES)} "
                               "nor an image file")
        kind = np.asarray(Image.open(path).convert("RGB"))
        label = path.name
    else:
        label = "given image"
    img = np.asarray(kind, dtype=np.float64)
    if img.shape[:2] != (h, w):
        raise ComparisonError(f"the reference image is {img.shape[1]}x{img.shape[0]}, the "
                           f"comparison {w}x{h}")
    if img.max() <= 1.0:
        img = img * 255
    bg = np.asarray(scene.background[:3]) * 255
    mask = np.abs(img[..., :3] - bg).max(-1) > 1
    return img[..., :3], mask, label


def compare(scene: Scene, camera: Camera, modes=("flat", "gouraud", "phong"),
            reference="analytic", *, size=(256, 256), diff: bool = True, renderer=None,
            backend="auto") -> Comparison:
    """Render ``modes`` and a reference; return the labelled grid and the metrics.

    ``reference``: "analytic" (sphere primitives, ray-cast exactly), "phong-fine" (Phong on
    a Phong-tessellated copy of each mesh), an image path or an ``(H, W, 3)`` array. No MSAA:
    every pixel is one sample, like the reference.
    """
    from .render.renderer import Renderer

    modes = [ShadingMode.parse(m) for m in modes]
    if not modes:
        raise ComparisonError("compare needs at least one mode")
    w, h = size
    own = renderer is None
    r = renderer or Renderer(w, h, samples=0, backend=backend)
    try:
        if (r.width, r.height) != (w, h):
            raise ComparisonError(f"the renderer is {r.width}x{r.height}, size asks {w}x{h}")
        ref, ref_mask, ref_kind = _reference(scene, camera, reference, r, size)
        frames = {m: r.render_frame(scene, camera, m, color_dtype="f4") for m in modes}
    finally:
        if own:
            r.close()
    results, images, errors = [], {}, {}
    ref_lum = metrics.luminance(ref)
    for m, f in frames.items():
        img = f.color[..., :3].astype(np.float64) * 255
        mask = ref_mask & (f.face_id >= 0)
        images[m.value] = img
        errors[m.value] = np.where(mask, metrics.abs_error(img, ref), 0.0)
        results.append(ModeMetrics(
            mode=m.value, mean_abs=metrics.mae(img, ref, mask),
            max_abs=metrics.max_error(img, ref, mask), rmse=metrics.rmse(img, ref, mask),
            psnr=metrics.psnr(img, ref, mask), ssim=metrics.ssim(img, ref, mask),
            mach_band=metrics.mach_band_strength(img, f.face_id, ref),
            peak=float(metrics.luminance(img)[mask].max(initial=0)),
            reference_peak=float(ref_lum[ref_mask].max(initial=0)), pixels=int(mask.sum())))
    grid = _grid(images, ref, ref_kind, errors if diff else None)
    return Comparison(grid, results, images, ref, ref_kind)


def _grid(images: dict, ref: np.ndarray, ref_kind: str, errors: dict | None) -> np.ndarray:
    def u8(a):
        return np.clip(a + 0.5, 0, 255).astype(np.uint8)

    top = [_label(u8(img), name) for name, img in images.items()]
    top.append(_label(u8(ref), f"reference: {ref_kind}"))
    rows = [np.hstack(top)]
    if errors is not None:
        vmax = max(max(float(e.max()) for e in errors.values()), 1.0)
        bottom = [_label(heatmap(e, vmax), f"|{name} - reference|")
                  for name, e in errors.items()]
        bar = _colour_bar(bottom[0].shape[0] - LABEL_HEIGHT, vmax)
        pad = np.full((LABEL_HEIGHT, bar.shape[1], 3), 24, np.uint8)
        tile_w = top[-1].shape[1]
        key = np.hstack([np.vstack([pad, bar]),
                         np.full((bottom[0].shape[0], tile_w - bar.shape[1], 3), 24, np.uint8)])
        rows.append(np.hstack([*bottom, key]))
    grid = np.vstack(rows)
    return np.dstack([grid, np.full(grid.shape[:2], 255, np.uint8)])


def sweep(make_mesh, levels, camera: Camera | None = None, modes=("flat", "gouraud", "phong"),
          *, material=None, lights=None, size=(192, 192), backend="auto",
          renderer=None) -> list[dict]:
    """Error of each mode against the analytic reference for each tessellation level:
    ``[{"level": k, "faces": F, "flat": ModeMetrics, ...}, ...]``."""
    from contextlib import nullcontext

    from .render.renderer import Renderer
    from .scene import Material, PointLight

    rows = []
    owned = renderer is None
    with (Renderer(size[0], size[1], samples=0, backend=backend) if owned
          else nullcontext(renderer)) as r:
        for k in levels:
            mesh = make_mesh(k)
            scene = Scene()
            scene.add(mesh, material or Material(color=(0.9, 0.75, 0.6), ks=0.5, shininess=30))
            for light in lights or [PointLight((3.0, 4.0, 5.0))]:
                scene.add_light(light)
            cam = camera or Camera.look_at([0.4, 0.6, 3.3], [0, 0, 0], fov_y=40)
            c = compare(scene, cam, modes, "analytic", size=size, diff=False, renderer=r)
            row = {"level": k, "faces": mesh.n_faces}
            row.update({m.mode: m for m in c.metrics})
            rows.append(row)
    return rows


def sweep_plot(rows: list[dict], modes, metric: str = "mean_abs", size=(640, 420)) -> np.ndarray:
    """A log-scale line plot of ``metric`` against level, drawn with Pillow."""
    from PIL import Image, ImageDraw

    colors = {"flat": (230, 120, 60), "gouraud": (90, 170, 240), "phong": (120, 220, 120),
              "normals": (200, 200, 200), "depth": (160, 160, 160)}
    w, h = size
    left, right, top, bottom = 70, 20, 40, 50
    img = Image.new("RGB", (w, h), (250, 250, 250))
    d = ImageDraw.Draw(img)
    font, small = _font(14), _font(11)
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
    d.text((w / 2 - 60, h - 22), "tessellation level", fill=(30, 30, 30), font=font)
    d.text((left, 10), f"{metric.replace('_', ' ')} error vs the analytic sphere (8-bit, log)",
           fill=(30, 30, 30), font=font)
    for i, m in enumerate(modes):
        pts = [px(r["level"], getattr(r[m], metric)) for r in rows]
        d.line(pts, fill=colors.get(m, (0, 0, 0)), width=3)
        for x, y in pts:
            d.ellipse([x - 3, y - 3, x + 3, y + 3], fill=colors.get(m, (0, 0, 0)))
        d.text((w - right - 90, top + 8 + 16 * i), m, fill=colors.get(m, (0, 0, 0)), font=font)
    return np.asarray(img)
