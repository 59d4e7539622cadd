"""The Cornell box's geometry from its published measurements (Cornell University Program
of Computer Graphics, "Cornell Box Data"), in millimetres: walls face into the room, the
blocks face outward, the light faces down. The light is lowered 0.5 mm below the ceiling
(in the data it lies in the ceiling's plane, where the two would z-fight). Materials and the
camera are in :mod:`glshade.radiosity.cornell`."""

from __future__ import annotations

import numpy as np

from .merge import concatenate
from .mesh import Mesh

__all__ = ["CORNELL_PARTS", "cornell_parts", "cornell_box_mm"]

CENTER = np.array([278.0, 274.4, 279.6])
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

def cornell_parts() -> dict[str, Mesh]:
    """Each part as a Mesh of quads, oriented (walls inward, blocks outward, light down)."""
    out = {}
    for name, quads in CORNELL_PARTS.items():
        q = np.array(quads, dtype=np.float64)
        if name == "light":
            q[..., 1] -= LIGHT_DROP
        v = q.reshape(-1, 3)
        f = np.arange(len(v)).reshape(-1, 4)
        n = np.cross(q[:, 2] - q[:, 0], q[:, 3] - q[:, 1])  # (diagonals: planar quads)
        if name.endswith("block"):
            toward = q.mean(1) - q.reshape(-1, 3).mean(0)  # outward from the block
        elif name == "light":
            toward = np.tile([0.0, -1.0, 0.0], (len(q), 1))
        else:
            toward = CENTER - q.mean(1)  # into the room
        flip = np.einsum("ij,ij->i", n, toward) < 0
        f[flip] = f[flip][:, ::-1]
        out[name] = Mesh(v, f, name=name).weld()
    return out


def cornell_box_mm() -> Mesh:
    """The whole box as one mesh, each part a named group."""
    parts = cornell_parts()
    m = concatenate(parts.values(), parts.keys())
    m.name = "cornell_box_mm"
    return m
