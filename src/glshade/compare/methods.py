"""Methods side by side -- shadows (``compare --shadows exact,map``) or transparency
(``compare --transparency exact,weighted,blend``): each method's picture, its difference
from the first method's as a heat map, and the numbers -- the mean difference, the fraction
of drawn pixels that differ by more than a level, and the frame time."""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ..modes import Shadows, Transparency
from ..options import DrawOptions, RenderConfig

__all__ = ["MethodComparison", "compare_shadows", "compare_transparency", "compare_methods"]


@dataclass
class MethodComparison:
    """``methods`` of ``option`` in order (the first is the reference); per method its
    ``colors`` ``(H, W, 4) uint8``, ``visibility`` ``(H, W, L)`` (shadows; None for off)
    and ``seconds`` a frame; ``drawn`` ``(H, W)`` the pixels measured (those a surface
    covers for shadows; the whole picture for transparency).

    Parameters
    ----------
    methods : tuple of str
        The values compared, in order; the first is the reference.
    option : str
        The drawing option compared (``"shadows"``, ``"transparency"``).
    colors : dict
        Each method's picture, ``(H, W, 4)`` uint8.
    visibility : dict
        Each method's ``(H, W, L)`` light visibility (shadows; None for off).
    seconds : dict
        Each method's time a frame.
    drawn : ndarray or None
        ``(H, W)`` bool: the pixels measured.
    """

    methods: tuple[str, ...]
    option: str = "shadows"
    colors: dict = field(default_factory=dict)
    visibility: dict = field(default_factory=dict)
    seconds: dict = field(default_factory=dict)
    drawn: np.ndarray | None = None

    @property
    def reference(self) -> str:
        return self.methods[0]

    def disagreement(self, method: str) -> float:
        """The fraction of drawn pixels whose colour differs from the reference's by more
        than one 8-bit level (where a light's visibility differs but its term is zero --
        the side turned away from it -- nothing shows, and nothing is counted).

        Parameters
        ----------
        method : str
            One of the methods.
        """
        diff = np.abs(self.colors[method][..., :3].astype(int) -
                      self.colors[self.reference][..., :3].astype(int)).max(-1)
        drawn = self.drawn if self.drawn is not None else np.ones(diff.shape, bool)
        return float((diff > 1)[drawn].mean()) if drawn.any() else 0.0

    def mean_difference(self, method: str) -> float:
        """The mean absolute colour difference from the reference over the drawn pixels, in
        8-bit units.

        Parameters
        ----------
        method : str
            One of the methods.
        """
        diff = np.abs(self.colors[method][..., :3].astype(int) -
                      self.colors[self.reference][..., :3].astype(int)).max(-1)
        return float(diff[self.drawn].mean()) if self.drawn is not None and \
            self.drawn.any() else 0.0

    def table(self) -> str:
        from ..io.tables import format_table

        rows = [(m, f"{self.seconds[m] * 1000:.1f}",
                 "-" if m == self.reference else f"{self.mean_difference(m):.3f}",
                 "-" if m == self.reference else f"{self.disagreement(m):.3%}")
                for m in self.methods]
        return format_table(rows, (self.option, "ms a frame", f"mean |diff| vs {self.reference}",
                                   "pixels that differ (> 1 level)"))

    @property
    def image(self) -> np.ndarray:
        """The renders in a labelled row, and under them each method's difference from the
        reference as a heat map (its scale: the largest difference, at least 1)."""
        from ..io.images import heatmap, labelled_row

        top = labelled_row({f"{self.option} {m} ({self.seconds[m] * 1000:.0f} ms)": self.colors[m]
                            for m in self.methods})
        diffs = {m: np.abs(self.colors[m][..., :3].astype(int) -
                           self.colors[self.reference][..., :3].astype(int)).max(-1)
                 for m in self.methods}
        vmax = max(1.0, max(float(d.max()) for d in diffs.values()))
        bottom = labelled_row({
            (f"{self.reference}: the reference" if m == self.reference else
             f"|{m} - {self.reference}|, {self.disagreement(m):.2%} differ"):
            heatmap(d, vmax) for m, d in diffs.items()})
        return np.vstack([top, bottom])


def compare_methods(scene, camera, option: str, methods, options=None,
                    config: RenderConfig | None = None, renderer=None) -> MethodComparison:
    """Draw ``scene`` once per value of the draw option ``option`` ("shadows" or
    "transparency"; the first value is the reference) with the same ``options`` otherwise;
    each timed on a third draw (the first two build the BVH, the maps and the programs).

    Parameters
    ----------
    scene : Scene
        What to draw.
    camera : Camera
        From where.
    option : str
        The drawing option compared (``"shadows"``, ``"transparency"``).
    methods : sequence of str
        The values compared, the first the reference.
    options : DrawOptions, ShadingMode, str or None
        The rest of how it is drawn.
    config : RenderConfig or None
        Size, MSAA samples, backend (None: the defaults).
    renderer : Renderer or None
        A renderer to draw with (None: one made here).
    """
    from ..render.renderer import Renderer

    parse = {"shadows": Shadows.parse, "transparency": Transparency.parse}[option]
    chosen = tuple(parse(m).value for m in methods)
    if len(chosen) < 2:
        raise ValueError(f"comparing {option} needs two or more methods")
    base = DrawOptions.of(options)
    own = renderer is None
    r = renderer or Renderer(config=config or RenderConfig(samples=0))
    out = MethodComparison(chosen, option)
    try:
        for m in chosen:
            o = base.replace(**{option: m})
            frame = r.render_frame(scene, camera, o)
            r.render(scene, camera, o)  # (the colour-only programs compiled: then timed)
            start = time.perf_counter()
            r.render(scene, camera, o)
            out.seconds[m] = time.perf_counter() - start
            out.colors[m] = frame.color
            out.visibility[m] = frame.visibility
            assert frame.face_id is not None
            # (the pixels measured: where a surface is; transparent ones write no id)
            out.drawn = frame.face_id >= 0 if option == "shadows" else \
                np.ones(frame.face_id.shape, bool)
    finally:
        if own:
            r.close()
    return out


def compare_shadows(scene, camera, methods=("exact", "map"), options=None,
                    config: RenderConfig | None = None, renderer=None) -> MethodComparison:
    """:func:`compare_methods` of the shadow methods (the first is the reference).

    Parameters
    ----------
    scene : Scene
        What to draw.
    camera : Camera
        From where.
    methods : sequence of str
        The values compared, the first the reference.
    options : DrawOptions, ShadingMode, str or None
        The rest of how it is drawn.
    config : RenderConfig or None
        Size, MSAA samples, backend (None: the defaults).
    renderer : Renderer or None
        A renderer to draw with (None: one made here).
    """
    return compare_methods(scene, camera, "shadows", methods, options, config, renderer)


def compare_transparency(scene, camera, methods=("exact", "weighted", "blend"), options=None,
                         config: RenderConfig | None = None,
                         renderer=None) -> MethodComparison:
    """:func:`compare_methods` of the transparency methods (the first is the reference).

    Parameters
    ----------
    scene : Scene
        What to draw.
    camera : Camera
        From where.
    methods : sequence of str
        The values compared, the first the reference.
    options : DrawOptions, ShadingMode, str or None
        The rest of how it is drawn.
    config : RenderConfig or None
        Size, MSAA samples, backend (None: the defaults).
    renderer : Renderer or None
        A renderer to draw with (None: one made here).
    """
    return compare_methods(scene, camera, "transparency", methods, options, config,
                           renderer)

