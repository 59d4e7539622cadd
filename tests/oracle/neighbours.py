"""Which pixels are well inside a region: all eight neighbours carry the same label (a
triangle, a polygon id), so a pixel on an edge -- where a half-pixel shift changes what the
pixel shows -- is left out of an exact comparison."""

import numpy as np


def inside_regions(labels: np.ndarray, outside: int = -2) -> np.ndarray:
    """``(H, W)`` bool: the label equals each of its eight neighbours' (the image's border
    counts as ``outside``, a label no pixel has)."""
    h, w = labels.shape
    pad = np.pad(labels, 1, constant_values=outside)
    inside = np.ones(labels.shape, bool)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            inside &= pad[1 + dy:h + 1 + dy, 1 + dx:w + 1 + dx] == labels
    return inside
