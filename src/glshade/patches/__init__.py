"""Parametric patches (the notes' B-Reps whose faces are surfaces): Bezier and rational
Bezier curves and tensor-product patches of any degree over mass-points (:mod:`.bezier`),
the exact quadrics as rational patches (:mod:`.quadrics`), the classic patch data sets
(:mod:`.files`: Newell's teapot), patches as a B-Rep with Euler's formula (:mod:`.surface`) and
crack-free tessellation with exact normals, uniform or to an error bound
(:mod:`.tessellation`). Pure numpy: nothing here imports GL.
"""

from .bezier import PatchSet, bernstein, curve_point, de_casteljau
from .files import parse_patches, read_patches, teapot, write_patches
from .quadrics import cone, cylinder, revolve, sphere, torus
from .surface import PatchSurface
from .tessellation import Tessellation, flatness_levels, tessellate

__all__ = ["PatchSet", "bernstein", "curve_point", "de_casteljau", "PatchSurface",
           "Tessellation", "tessellate", "flatness_levels", "revolve", "sphere", "cylinder",
           "cone", "torus", "teapot", "read_patches", "parse_patches", "write_patches",
           "named"]


def named(name: str) -> PatchSurface:
    """A named patch model: "teapot", "sphere", "cylinder", "cone" or "torus".

    Parameters
    ----------
    name : str
        ``"teapot"``, ``"sphere"``, ``"cylinder"``, ``"cone"`` or ``"torus"``.
    """
    from ..errors import InputError

    makers = {"teapot": teapot, "sphere": sphere, "cylinder": cylinder, "cone": cone,
              "torus": torus}
    if name not in makers:
        raise InputError(f"unknown patch model {name!r}; choose one of "
                         f"{', '.join(makers)}")
    return PatchSurface(makers[name](), name)
