"""Constructive solid geometry, the notes' solid-modelling chapter: binary trees whose leaves
are primitive solids and whose nodes are booleans or nonsingular affine transforms, with
Roth's ray casting as the numpy reference.

- :mod:`.tree`: the node (:class:`Solid`, its operators ``| & -`` and transforms), the
  booleans and Roth's event lists; written below the leaves, so no import circle can form.
- :mod:`.leaves`: :class:`Sphere`, :class:`Box`, :class:`Cylinder`, :class:`Cone`,
  :class:`Torus`, :class:`HalfSpace`.
- :mod:`.text`: the text syntax of scene files and ``solid:TEXT`` (:func:`parse_solid`).

- :mod:`.encoding`: a tree as the arrays the GPU's ray casting pass
  (:mod:`glshade.render.passes.csg`) reads; :mod:`.proxy`: the screen polygon it draws.

Octrees of solids are in :mod:`glshade.octree`; the numpy twin of the GPU's ray casting in
:mod:`glshade.cpu.csg`.

    from glshade.solids import Box, Sphere
    part = Box(2) - Sphere(1.2)
    part.volume()          # (estimate, standard error)
"""

from .leaves import Box, Cone, Cylinder, HalfSpace, Sphere, Torus
from .text import parse_solid
from .tree import Difference, Events, Intersection, Solid, Transformed, Union

__all__ = ["Solid", "Sphere", "Box", "Cylinder", "Cone", "Torus", "HalfSpace", "Union",
           "Intersection", "Difference", "Transformed", "Events", "parse_solid"]
