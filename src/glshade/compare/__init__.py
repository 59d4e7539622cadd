"""Comparing shading modes: labelled grids, difference heat maps, error metrics against an
analytic or refined reference, and tessellation sweeps."""

from .._callable import callable_package
from . import metrics
from .comparison import REFERENCES, Comparison, ModeMetrics, compare
from .shadows import ShadowComparison, compare_shadows
from .sweeps import patch_sweep, sweep, sweep_plot

__all__ = ["compare", "Comparison", "ModeMetrics", "REFERENCES", "sweep", "sweep_plot",
           "patch_sweep", "metrics", "compare_shadows", "ShadowComparison"]

callable_package(__name__, compare)  # glshade.compare(...) calls the function, whatever is bound
