"""The numpy twins of the GPU's passes, in float64, for the tests and the references of
``compare``: what a pass computes, written a second way so the two check each other. No GL.

- :mod:`.lighting`: the lighting formula of ``shaders/include/lighting.glsl`` and its
  sRGB encoding (``srgb.glsl``).
- :mod:`.raycast`: the analytic reference -- exact surfaces ray cast and lit by that
  formula -- through :meth:`glshade.Camera.rays` (``rays.glsl``).
- :mod:`.csg`: the CSG pass's twin, Roth's ray casting of a solid (``include/csg/``).

The hidden-surface algorithms are a chapter of their own (:mod:`glshade.hidden`), and the
path tracer's twin lives with it (:mod:`glshade.pathtrace.twin`).
"""

from .lighting import light_intensity
from .raycast import has_analytic_surfaces, pixel_rays, raycast_scene

__all__ = ["light_intensity", "pixel_rays", "raycast_scene", "has_analytic_surfaces"]
