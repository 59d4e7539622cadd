"""CPU renderers in numpy: the lighting twin of the GLSL and analytic ray casting (the
hidden-surface algorithms will live here). No GL."""

from .lighting import light_intensity
from .raycast import has_analytic_surfaces, pixel_rays, raycast_scene

__all__ = ["light_intensity", "pixel_rays", "raycast_scene", "has_analytic_surfaces"]
