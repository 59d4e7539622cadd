"""The Cornell box's geometry from its published measurements (Cornell University Program
of Computer Graphics, "Cornell Box Data"), in millimetres: walls face into the room, the
blocks face outward, the light faces down. The light is lowered 0.5 mm below the ceiling
(in the data it lies in the ceiling's plane, where the two would z-fight). Materials and the
camera are in :mod:`glshade.radiosity.cornell`; the meshes are built by
:func:`glshade.geometry.primitives.cornell_parts`."""

from __future__ import annotations

__all__ = ["CORNELL_PARTS", "CENTER", "LIGHT_DROP"]

#: the room's centre (mm), which the walls face
CENTER = (278.0, 274.4, 279.6)
#: mm the light hangs below the ceiling's plane
LIGHT_DROP = 0.5

#: quads (each 4 corners, mm) of every part, as published
CORNELL_PARTS = {
    "floor": [[[552.8, 0, 0], [0, 0, 0], [0, 0, 559.2], [549.6, 0, 559.2]]],
    "light": [[[343.0, 548.8, 227.0], [343.0, 548.8, 332.0], [213.0, 548.8, 332.0],
               [213.0, 548.8, 227.0]]],
    "ceiling": [[[556.0, 548.8, 0], [556.0, 548.8, 559.2], [0, 548.8, 559.2],
                 [0, 548.8, 0]]],
    "back_wall": [[[549.6, 0, 559.2], [0, 0, 559.2], [0, 548.8, 559.2],
                   [556.0, 548.8, 559.2]]],
    "green_wall": [[[0, 0, 559.2], [0, 0, 0], [0, 548.8, 0], [0, 548.8, 559.2]]],
    "red_wall": [[[552.8, 0, 0], [549.6, 0, 559.2], [556.0, 548.8, 559.2],
                  [556.0, 548.8, 0]]],
    "short_block": [
        [[130.0, 165.0, 65.0], [82.0, 165.0, 225.0], [240.0, 165.0, 272.0],
         [290.0, 165.0, 114.0]],
        [[290.0, 0, 114.0], [290.0, 165.0, 114.0], [240.0, 165.0, 272.0],
         [240.0, 0, 272.0]],
        [[130.0, 0, 65.0], [130.0, 165.0, 65.0], [290.0, 165.0, 114.0], [290.0, 0, 114.0]],
        [[82.0, 0, 225.0], [82.0, 165.0, 225.0], [130.0, 165.0, 65.0], [130.0, 0, 65.0]],
        [[240.0, 0, 272.0], [240.0, 165.0, 272.0], [82.0, 165.0, 225.0], [82.0, 0, 225.0]]],
    "tall_block": [
        [[423.0, 330.0, 247.0], [265.0, 330.0, 296.0], [314.0, 330.0, 456.0],
         [472.0, 330.0, 406.0]],
        [[423.0, 0, 247.0], [423.0, 330.0, 247.0], [472.0, 330.0, 406.0], [472.0, 0, 406.0]],
        [[472.0, 0, 406.0], [472.0, 330.0, 406.0], [314.0, 330.0, 456.0], [314.0, 0, 456.0]],
        [[314.0, 0, 456.0], [314.0, 330.0, 456.0], [265.0, 330.0, 296.0], [265.0, 0, 296.0]],
        [[265.0, 0, 296.0], [265.0, 330.0, 296.0], [423.0, 330.0, 247.0], [423.0, 0, 247.0]]],
}
