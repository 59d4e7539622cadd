"""Comparing shading modes: labelled grids, difference heat maps, error metrics against an
analytic or refined reference, and tessellation sweeps."""

from .._callable import callable_package
from . import metrics
from .comparison import REFERENCES, Comparison, ModeMetrics, compare
from .methods import MethodComparison, compare_methods, compare_shadows, compare_transparency
from .sweeps import patch_sweep, sweep, sweep_plot

__all__ = ["compare", "Comparison", "ModeMetrics", "REFERENCES", "sweep", "sweep_plot",
           "patch_sweep", "metrics", "compare_shadows",
           "compare_transparency", "compare_methods", "MethodComparison"]

callable_package(__name__, compare)  # glshade.compare(...) calls the function, whatever is bound
