"""What one hidden-surface algorithm of the lab found: the polygon id and depth at every
pixel, with its counts and time (the GPU renderer's conventions: see
:mod:`glshade.hidden.view`)."""

from __future__ import annotations

from typing import Any

from dataclasses import dataclass, field

import numpy as np

__all__ = ["HiddenResult"]


@dataclass
class HiddenResult:
    """What one algorithm produced: ``face_id (H, W) int32`` (-1 background), ``depth
    (H, W) float32`` (inf background), its ``counters`` and the ``seconds`` it took.

    Parameters
    ----------
    name : str
        The algorithm.
    face_id : ndarray
        ``(H, W)`` int32 polygon ids, -1 background.
    depth : ndarray
        ``(H, W)`` float32 view depth, inf background.
    counters : dict
        What the algorithm counted (tests, splits, fragments ...).
    seconds : float
        The time it took.
    steps : list
        Snapshots of its work, for animations.
    painted : object
        The painter's order, where it has one.
    """

    name: str
    face_id: np.ndarray
    depth: np.ndarray
    counters: dict = field(default_factory=dict)
    seconds: float = 0.0
    steps: list = field(default_factory=list)  # (label, face_id) snapshots, for teaching
    #: the object-space algorithms' paint order (depth sort, BSP), for their steps
    painted: Any = None

    def __repr__(self) -> str:
        h, w = self.face_id.shape
        return (f"<HiddenResult {self.name} {w}x{h}: {self.seconds:.3g} s, "
                f"{int((self.face_id >= 0).sum()):,} pixels drawn>")

    def _repr_html_(self) -> str:
        """In a notebook: the polygon ids it found, and its counters."""
        from ..display import facts_html
        from ..colormaps import id_colors

        facts = [f"{k}: {v:,}" if isinstance(v, int) else f"{k}: {v}"
                 for k, v in self.counters.items()]
        return facts_html(repr(self), facts, id_colors(self.face_id))
