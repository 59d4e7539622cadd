"""Comparing shading modes: a labelled grid, difference heat maps, and the numbers.

``compare(scene, camera)`` renders each mode and a reference -- the exact surface ray-cast
with the same lighting formula (``"analytic"``, for sphere primitives), a Phong render of
the mesh refined by Phong tessellation (``"phong-fine"``), or an image you supply; by
default (``"auto"``) the analytic one where every mesh knows its exact surface, else
phong-fine -- and measures each mode against it on the pixels both cover.

What is measured is what is shown: each mode's 8-bit image against the 8-bit reference
(:meth:`Comparison.save_tiles` writes them and the pixels measured, so the numbers can be
recomputed from the files). The heat maps share one scale: by default the
``HEAT_PERCENTILE``-th percentile of the errors away from the silhouette, over every mode
(silhouette pixels -- within a pixel of where a mode's or the reference's coverage ends --
are where a tessellation legitimately differs most; they are counted apart and drawn in
``SILHOUETTE_COLOR``), or a fixed ``scale``; larger errors saturate. Each heat map carries
its mode's mean and max error, PSNR and SSIM.
"""

from __future__ import annotations

import csv
import io
import json
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from ..atomic import atomic_write
from ..errors import ComparisonError
from ..geometry.merge import detect_crease
from ..geometry.subdivide import phong_tessellate
from ..io.images import (
    BACKGROUND, LABEL_HEIGHT, colour_bar, heatmap, label, labelled_row, opaque,
)
from ..io.tables import format_table
from ..modes import Outputs, ShadingMode
from ..options import DrawOptions, RenderConfig
from ..scene import Camera, Scene
from . import metrics

__all__ = ["compare", "Comparison", "ModeMetrics", "REFERENCES"]

REFERENCES = ("auto", "analytic", "phong-fine", "pathtrace")
#: the heat maps' scale by default: this percentile of the errors off the silhouette
HEAT_PERCENTILE = 99.0
#: how silhouette pixels show in the heat maps (they are not on the error scale)
SILHOUETTE_COLOR = (200, 60, 200)

@dataclass
class ModeMetrics:
    """How far one mode is from the reference, in 8-bit units (PSNR in dB).

    Parameters
    ----------
    mode : str
        The shading mode measured.
    mean_abs, max_abs, rmse : float
        The mean, largest and root-mean-square absolute difference from the reference.
    psnr : float
        Peak signal-to-noise ratio in dB.
    ssim : float
        Structural similarity.
    mach_band : float
        Mach-band strength across polygon edges.
    peak, reference_peak : float
        The brightest level of the mode's picture and of the reference's.
    pixels : int
        The pixels measured.
    silhouette : int
        The pixels left out at the silhouette (where coverage differs).
    """

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
    silhouette: int = 0    # of the pixels, those on the silhouette (shown apart)


@dataclass
class Comparison:
    """The grid image, the per-mode metrics and the images they came from.

    Parameters
    ----------
    image : ndarray
        ``(H, W, 4)`` uint8 the grid: each mode's picture and heat map.
    metrics : list of ModeMetrics
        Each mode's numbers against the reference.
    images : dict
        Each mode's picture, by name.
    reference : ndarray or None
        The reference picture.
    reference_kind : str
        What the reference is (``"phong-fine"``, ``"analytic"``, ``"pathtrace"`` ...).
    reference_crease : float or None
        The crease angle the reference was drawn with.
    masks : dict
        Each mode's pixels its numbers are over, by name.
    scale : float
        The heat maps' full scale (the largest difference shown).
    """

    image: np.ndarray
    metrics: list[ModeMetrics]
    images: dict = field(repr=False, default_factory=dict)
    reference: np.ndarray | None = field(repr=False, default=None)
    reference_kind: str = ""
    #: the crease angle (degrees) the phong-fine reference kept hard, found from the
    #: meshes' own edges (None: smooth, or another reference)
    reference_crease: float | None = None
    masks: dict = field(repr=False, default_factory=dict)
    scale: float = 0.0     # the heat maps' (8-bit units)

    def save_tiles(self, folder) -> None:
        """Write what was measured: ``MODE.png`` per mode, ``reference.png`` and
        ``MODE-mask.png`` (white: the pixels each mode's numbers are over).

        Parameters
        ----------
        folder : str or Path
            Where the tiles go (made if missing).
        """
        from ..io.images import save_image

        out = Path(folder)
        out.mkdir(parents=True, exist_ok=True)
        for name, img in self.images.items():
            save_image(img, out / f"{name}.png")
            save_image((self.masks[name] * 255).astype(np.uint8)[..., None].repeat(3, 2),
                       out / f"{name}-mask.png")
        if self.reference is not None:
            save_image(self.reference, out / "reference.png")

    def table(self) -> str:
        head = ("mode", "mean", "max", "RMSE", "PSNR dB", "SSIM", "Mach band", "peak/ref")
        rows = [(m.mode, f"{m.mean_abs:.3f}", f"{m.max_abs:.1f}", f"{m.rmse:.3f}",
                 f"{m.psnr:.2f}", f"{m.ssim:.4f}", f"{m.mach_band:.2f}",
                 f"{m.peak:.1f}/{m.reference_peak:.1f}") for m in self.metrics]
        return (f"against the {self.reference_kind} reference{self._crease_note()}, 8-bit "
                f"units\n" + format_table(rows, head))

    def _crease_note(self) -> str:
        c = self.reference_crease
        return "" if c is None else f" (edges sharper than {c:.3g}° kept hard)"

    def as_dicts(self) -> list[dict]:
        return [asdict(m) for m in self.metrics]

    def write_json(self, path) -> None:
        """Write the metrics as JSON (atomically).

        Parameters
        ----------
        path : str or Path
            Where.
        """
        with atomic_write(path, "w") as f:
            json.dump({"reference": self.reference_kind, "crease": self.reference_crease,
                       "modes": self.as_dicts()}, f, indent=2, default=lambda x: None)

    def write_csv(self, path) -> None:
        """Write the metrics as CSV, a row a mode (atomically).

        Parameters
        ----------
        path : str or Path
            Where.
        """
        rows = self.as_dicts()
        with atomic_write(path, "w") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)

    def __repr__(self) -> str:
        h, w = self.image.shape[:2]
        best = min(self.metrics, key=lambda m: m.mean_abs) if self.metrics else None
        closest = f"; closest {best.mode} (mean {best.mean_abs:.3g})" if best else ""
        return (f"<Comparison of {', '.join(m.mode for m in self.metrics)} against the "
                f"{self.reference_kind} reference: {w}x{h} grid{closest}>")

    def _repr_html_(self) -> str:
        """In a notebook: the grid and each mode's numbers."""
        from ..display import facts_html

        facts = [f"{m.mode}: mean {m.mean_abs:.3g}, max {m.max_abs:.0f}, PSNR {m.psnr:.1f} dB,"
                 f" SSIM {m.ssim:.3f}, Mach band {m.mach_band:.2f}" for m in self.metrics]
        return facts_html(repr(self), facts, self.image)

    def _repr_png_(self) -> bytes:
        from PIL import Image

        buf = io.BytesIO()
        Image.fromarray(self.image).save(buf, format="PNG")
        return buf.getvalue()


def reference_image(scene, camera, kind, renderer, size, options, spp=64):
    """The picture a comparison measures the modes against: ``(image (H, W, 3) floats in
    0..255, mask (H, W) bool of the pixels it covers, its name as the summary says it, the
    crease angle used in degrees or None)``.

    Parameters
    ----------
    scene, camera
        What is seen and from where.
    kind
        A reference's name (``phong-fine``, ``analytic``, ``pathtrace``, ...) or an
        image file's path.
    renderer
        The Renderer the raster references draw with.
    size
        ``(width, height)`` in pixels.
    options
        The DrawOptions the compared modes share.
    spp
        Samples a pixel of a path-traced reference.
    """
    from ..cpu.raycast import raycast_scene

    w, h = size
    if isinstance(kind, (str, Path)) and str(kind) == "pathtrace":
        from ..cpu.lighting import encode_srgb
        from ..pathtrace import TraceScene, trace

        traced = trace(TraceScene.from_scene(scene, camera=camera, smooth=True), camera, size,
                       spp=spp, context=renderer.context, progress=False)
        assert traced.coverage is not None
        mask = traced.coverage > 0.5
        color = np.clip(traced.image, 0, 1)
        if options.srgb:
            color = encode_srgb(color)
        bg = np.asarray(scene.background[:3])
        return np.where(mask[..., None], color, bg) * 255, mask, f"path traced ({spp} spp)", \
            None
    if isinstance(kind, (str, Path)) and str(kind) == "analytic":
        color, mask = raycast_scene(scene, camera, w, h)
        bg = np.asarray(scene.background[:3])
        return np.where(mask[..., None], color, bg) * 255, mask, "analytic", None
    if isinstance(kind, (str, Path)) and str(kind) == "phong-fine":
        # hard edges stay hard: a flat-faced part's creases are split first (the angle
        # each mesh's own edges suggest), else the curved refinement rounds the part off
        fine = Scene(scene.ambient, scene.background)
        creases = []
        for m in scene.models:
            if m.visible:
                crease = detect_crease(m.mesh)
                mesh = m.mesh if crease is None else m.mesh.split_creases(crease)
                creases.append(crease)
                fine.add(phong_tessellate(mesh, 6), m.material, m.transform)
        fine.lights = list(scene.lights)
        fine.clouds, fine.lines = list(scene.clouds), list(scene.lines)  # (no facets)
        frame = renderer.render_frame(fine, camera, options.replace(mode=ShadingMode.PHONG),
                                      outputs=Outputs.FACE_ID, color_dtype="f4")
        found = [c for c in creases if c is not None]
        return frame.color[..., :3] * 255.0, frame.face_id >= 0, "phong-fine", \
            (min(found) if found else None)
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
    return img[..., :3], mask, label, None


#: what compare renders with unless told: small tiles, one sample per pixel like its references
COMPARE_CONFIG = RenderConfig(256, 256, samples=0)


#: compare's prefix for a scheme drawn in glTF's lighting model ("pbr-phong"): each of the
#: scene's notes' Materials as its nearest PBRMaterial (PBRMaterial.like)
PBR_PREFIX = "pbr-"


def compare_mode(text) -> tuple[str, ShadingMode, bool]:
    """One of compare's modes: ``(label, scheme, in glTF's model)`` -- a shading mode by
    name, or a scheme prefixed ``pbr-``: the scene drawn in glTF's metallic-roughness model
    (its notes' Materials as :meth:`PBRMaterial.like <glshade.PBRMaterial.like>` makes
    them), so that the two lighting models are compared as the schemes are.

    Parameters
    ----------
    text : str or ShadingMode
        ``"phong"``, ``"pbr-phong"`` ...
    """
    name = text.value if isinstance(text, ShadingMode) else str(text).strip()
    pbr = name.startswith(PBR_PREFIX)
    mode = ShadingMode.parse(name[len(PBR_PREFIX):] if pbr else name)
    if pbr and mode not in (ShadingMode.FLAT, ShadingMode.GOURAUD, ShadingMode.PHONG):
        raise ComparisonError(f"{PBR_PREFIX} takes a shading scheme (flat, gouraud or phong), "
                              f"not {mode.value}")
    return (PBR_PREFIX + mode.value if pbr else mode.value), mode, pbr


def in_gltfs_model(scene: Scene, camera: Camera) -> Scene:
    """A copy of ``scene`` in glTF's lighting model: its meshes' notes' Materials their
    nearest glTF equivalents (:meth:`PBRMaterial.like <glshade.PBRMaterial.like>`), and its
    lights (the headlight where it has none) in glTF's units, scaled so that each gives
    where it first meets the scene what it gives in the notes' model: glTF's diffuse lobe is
    albedo / pi and a point or spot light's candela fall off as 1 / d^2, the notes'
    intensity does neither -- so x pi, and x d^2 at the distance d from the light to the
    nearest point of the scene's bounding box (its centre's, for a light inside it).

    Parameters
    ----------
    scene : Scene
        The scene.
    camera : Camera
        The camera (the headlight's place).
    """
    import copy
    import dataclasses

    from ..modes import LightingModel
    from ..scene.lights import DirectionalLight
    from ..scene.pbr import PBRMaterial

    out = copy.copy(scene)
    out.models = [dataclasses.replace(m, material=PBRMaterial.like(m.material))
                  if m.material.lighting is LightingModel.NOTES else m for m in scene.models]
    box = np.asarray(scene.bounds, np.float64) if scene.models else np.zeros((2, 3))
    lights = []
    for light in scene.lights_for(camera):
        scale = np.pi
        if not isinstance(light, DirectionalLight):
            at = np.asarray(light.position, np.float64)
            d2 = float(np.sum((at - np.clip(at, box[0], box[1])) ** 2))
            scale *= d2 if d2 > 0 else float(np.sum((at - box.mean(0)) ** 2))
        lights.append(dataclasses.replace(light, intensity=light.intensity * scale))
    out.lights = lights
    return out


def compare(scene: Scene, camera: Camera, modes=("flat", "gouraud", "phong"),
            reference="auto", *, size=None, diff: bool = True, renderer=None,
            backend=None, options: DrawOptions | None = None,
            config: RenderConfig | None = None, scale: float | None = None,
            spp: int = 64, scenes: dict | None = None) -> Comparison:
    """Render ``modes`` and a reference; return the labelled grid and the metrics.

    ``reference``: "auto" (analytic where every mesh knows its exact surface, else
    phong-fine), "analytic" (sphere primitives, ray-cast exactly), "phong-fine" (Phong on
    a Phong-tessellated copy of each mesh), "pathtrace" (the rendering equation by path
    tracing, ``spp`` samples a pixel: interreflection instead of the ambient term, the
    Phong lobe energy-conserving; in the same units as the modes, so the heat maps show
    what the local model leaves out), an image path or an ``(H, W, 3)`` array.
    ``scale``: the heat maps' top in 8-bit units (default: the module's percentile). No MSAA:
    every pixel is one sample, like the reference. ``options`` are the draw options every
    mode shares (its mode is replaced by each of ``modes``). ``config`` (or ``size``,
    ``backend``): the renderer made when none is given (default 256x256; ``samples`` 0).
    ``scenes``: a scene per mode to draw instead of ``scene`` (the ``radiosity`` mode's is
    a solution's, :meth:`~glshade.radiosity.Solution.scene`: at exposure 1 its pixels are
    radiosities, the path-traced reference's units).

    Parameters
    ----------
    scene : Scene
        What to draw.
    camera : Camera
        From where.
    modes : sequence of str
        The shading modes measured; ``"pbr-flat"``, ``"pbr-gouraud"``, ``"pbr-phong"``: the
        scheme with the scene's Materials in glTF's model (:func:`compare_mode`).
    reference : str or ndarray
        ``"auto"``, ``"analytic"``, ``"phong-fine"``, ``"pathtrace"``, an image path or an
        ``(H, W, 3)`` array.
    size : (int, int) or None
        Width and height (default 256x256).
    diff : bool
        Add each mode's heat map of its difference.
    renderer : Renderer or None
        A renderer to draw with (None: one made here).
    backend : str or None
        The headless backend of one made here.
    options : DrawOptions or None
        The draw options every mode shares.
    config : RenderConfig or None
        What a renderer made here is built with.
    scale : float or None
        The heat maps' top in 8-bit units (None: a percentile).
    spp : int
        The path-traced reference's samples a pixel.
    scenes : dict or None
        A scene a mode draws instead (a radiosity solution's).
    """
    from ..render.renderer import Renderer

    parsed = [compare_mode(m) for m in modes]
    if not parsed:
        raise ComparisonError("compare needs at least one mode")
    config = RenderConfig.of(config, size=size, backend=backend, base=COMPARE_CONFIG)
    if config.samples:
        raise ComparisonError(f"compare draws one sample per pixel, like its references: "
                              f"config.samples must be 0, got {config.samples}")
    size = w, h = config.size
    own = renderer is None
    r = renderer or Renderer(config=config)
    try:
        if (r.width, r.height) != (w, h):
            raise ComparisonError(f"the renderer is {r.width}x{r.height}, size asks {w}x{h}")
        base = DrawOptions.of(options)
        if isinstance(reference, str) and reference == "auto":
            from ..cpu.raycast import has_analytic_surfaces

            reference = "analytic" if has_analytic_surfaces(scene) else "phong-fine"
        ref, ref_mask, ref_kind, crease = reference_image(scene, camera, reference, r, size, base,
                                                     spp)
        drawn = {ShadingMode.parse(k): v for k, v in (scenes or {}).items()}
        gltf = in_gltfs_model(scene, camera) if any(pbr for _, _, pbr in parsed) else scene
        frames = {label: r.render_frame(gltf if pbr else drawn.get(m, scene), camera,
                                        base.replace(mode=m), outputs=Outputs.FACE_ID,
                                        color_dtype="f4")
                  for label, m, pbr in parsed}
    finally:
        if own:
            r.close()
    results, images, errors, masks, silhouettes = [], {}, {}, {}, {}
    ref = _u8(ref)  # (what is measured is what is shown: the 8-bit images)
    ref_lum = metrics.luminance(ref)
    for m, f in frames.items():
        img = _u8(f.color[..., :3] * 255.0)
        assert f.face_id is not None  # (asked for)
        covered = f.face_id >= 0
        mask = ref_mask & covered
        # the silhouette: within a pixel of where the mode's or the reference's coverage ends
        silhouette = mask & (metrics.edge_mask(covered.astype(np.int8)) |
                             metrics.edge_mask(ref_mask.astype(np.int8)))
        images[m], masks[m], silhouettes[m] = img, mask, silhouette
        errors[m] = np.where(mask, metrics.abs_error(img, ref), 0.0)
        results.append(ModeMetrics(
            mode=m, mean_abs=metrics.mae(img, ref, mask),
            max_abs=metrics.max_error(img, ref, mask), rmse=metrics.rmse(img, ref, mask),
            psnr=metrics.psnr(img, ref, mask), ssim=metrics.ssim(img, ref, mask),
            mach_band=metrics.mach_band_strength(img, f.face_id, ref),
            peak=float(metrics.luminance(img)[mask].max(initial=0)),
            reference_peak=float(ref_lum[ref_mask].max(initial=0)), pixels=int(mask.sum()),
            silhouette=int(silhouette.sum())))
    if scale is None:
        inner = np.concatenate([errors[k][masks[k] & ~silhouettes[k]] for k in errors])
        scale = float(np.percentile(inner, HEAT_PERCENTILE)) if inner.size else 1.0
    elif not float(scale) > 0:
        raise ComparisonError(f"scale must be a positive number of 8-bit units, got {scale!r}")
    scale = max(float(scale), 1.0)
    grid = _grid(images, ref, ref_kind, errors if diff else None, silhouettes, results, scale)
    return Comparison(grid, results, images, ref, ref_kind, crease, masks, scale)


def _u8(image: np.ndarray) -> np.ndarray:
    return np.clip(np.asarray(image, np.float64) + 0.5, 0, 255).astype(np.uint8)


def _grid(images: dict, ref: np.ndarray, ref_kind: str, errors: dict | None,
          silhouettes: dict, results: list, scale: float) -> np.ndarray:
    """Each mode and the reference under their labels; below, each mode's error heat map
    (silhouette pixels in SILHOUETTE_COLOR) under its numbers, and the colour bar's key in
    the reference's column."""
    tiles = dict(images)
    tiles[f"reference: {ref_kind}"] = ref
    top = labelled_row(tiles)[..., :3]
    rows = [top]
    if errors is not None:
        bottom = []
        for m in results:
            heat = heatmap(errors[m.mode], scale)
            heat[silhouettes[m.mode]] = SILHOUETTE_COLOR
            psnr = "inf" if m.psnr == float("inf") else f"{m.psnr:.1f}"
            tile = label(label(heat, f"PSNR {psnr} dB, SSIM {m.ssim:.3f}"),
                         f"{m.mode}: mean {m.mean_abs:.2f}, max {m.max_abs:.0f}")
            bottom.append(tile)
        h = bottom[0].shape[0]
        bar = colour_bar(h - 2 * LABEL_HEIGHT, scale)
        key = np.full((h, max(ref.shape[1], bar.shape[1]), 3), BACKGROUND, np.uint8)
        key[2 * LABEL_HEIGHT:, :bar.shape[1]] = bar
        key = label(key[LABEL_HEIGHT:], "silhouette: magenta")
        rows.append(np.hstack([*bottom, key]))
    width = max(r.shape[1] for r in rows)  # (small tiles: the key is wider than a tile)
    padded = []
    for r in rows:
        wide = np.full((r.shape[0], width, 3), BACKGROUND, np.uint8)
        wide[:, :r.shape[1]] = r
        padded.append(wide)
    return opaque(np.vstack(padded))
