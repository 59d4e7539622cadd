"""Numerical tolerances of the geometry code, in one place so they can be read and tuned."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Tolerance", "tol"]


@dataclass
class Tolerance:
    """Relative tolerances (scaled by the size of the data they are applied to).

    Parameters
    ----------
    zero_length : float
        A length below this times the data's size is zero.
    convexity : float
        A cross product below this (relative) is a straight corner.
    merge : float
        Vertices closer than this (relative) are one.
    """

    #: a vector shorter than this times its largest coordinate counts as zero
    zero_length: float = 1e-12
    #: a corner turning back by less than this (relative to squared edge length) is convex
    convexity: float = 1e-12
    #: points closer than this relative to the bounding box size are merged (STL welding)
    merge: float = 1e-9


tol = Tolerance()
