"""The rendering equation solved a second way: a progressive Monte Carlo path tracer on the
GPU beside radiosity (which solves only its diffuse restriction), and a numpy twin for small
scenes that shares nothing with it but the scene.

The notes (23.1) write the rendering equation I(x, x') = E(x, x') + integral of rho(x, x',
x'') I(x', x'') dx''; radiosity keeps only diffuse reflection. The path tracer keeps the
lighting model's specular lobe too (made energy-conserving), so the two can be held against
each other on diffuse scenes (they must agree) and a student can see what the restriction
costs on glossy ones. Conventions (units, BRDF, lights): :mod:`glshade.pathtrace.scene`.

>>> from glshade.radiosity.cornell import cornell_scene
>>> from glshade import pathtrace
>>> scene, camera = cornell_scene()
>>> result = pathtrace.trace(scene, camera, size=(64, 64), spp=16, progress=False)
>>> result.image.shape
(64, 64, 3)
"""

from ..options import TraceOptions
from .progressive import PathTraced, PathTracer, relative_error, trace
from .scene import TraceScene

__all__ = ["trace", "TraceOptions", "PathTracer", "PathTraced", "TraceScene", "relative_error"]
