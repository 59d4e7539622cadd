"""Comparing shading modes: labelled grids, difference heat maps, error metrics against an
analytic or refined reference, and tessellation sweeps."""

import sys as _sys
import types as _types

from . import metrics
from .comparison import REFERENCES, Comparison, ModeMetrics, compare
from .sweep import sweep, sweep_plot

__all__ = ["compare", "Comparison", "ModeMetrics", "REFERENCES", "sweep", "sweep_plot",
           "metrics"]


class _Callable(_types.ModuleType):
    """``glshade.compare(...)`` is the function (the README's API) even after this package,
    which shares its name, has been imported and bound in its place: calling the package
    calls :func:`compare`."""

    def __call__(self, *args, **kwargs):
        return compare(*args, **kwargs)


_sys.modules[__name__].__class__ = _Callable
