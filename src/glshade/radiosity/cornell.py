"""The Cornell box for radiosity: the published geometry (:mod:`glshade.geometry.data.cornell`,
millimetres), the published camera, and RGB approximations of the measured spectral
reflectances and of the light's emission (the values common renderers use)."""

from __future__ import annotations

import numpy as np

from ..geometry.data.cornell import CORNELL_PARTS
from ..geometry.primitives import cornell_parts

__all__ = ["CORNELL_PARTS", "CORNELL_MATERIALS", "CORNELL_CAMERA", "cornell_parts",
           "cornell_scene"]

_WHITE = (0.725, 0.71, 0.68)
#: (reflectance rho_d, emission) per part: RGB approximations of the published spectra
CORNELL_MATERIALS = {
    "floor": (_WHITE, (0, 0, 0)), "ceiling": (_WHITE, (0, 0, 0)),
    "back_wall": (_WHITE, (0, 0, 0)), "short_block": (_WHITE, (0, 0, 0)),
    "tall_block": (_WHITE, (0, 0, 0)),
    "red_wall": ((0.63, 0.065, 0.05), (0, 0, 0)),
    "green_wall": ((0.14, 0.45, 0.091), (0, 0, 0)),
    "light": ((0.78, 0.78, 0.78), (17.0, 12.0, 4.0)),
}

#: eye, target, up and vertical field of view (35 mm lens, 25 mm film: 39.31 degrees)
CORNELL_CAMERA = {"eye": (278.0, 273.0, -800.0), "target": (278.0, 273.0, -799.0),
                  "up": (0.0, 1.0, 0.0), "fov_y": float(np.degrees(2 * np.arctan(12.5 / 35)))}


def cornell_scene():
    """The box as a Scene (a model per part, with reflectance and emission) and its
    published Camera."""
    from ..scene import Camera, Material, Scene

    scene = Scene(ambient=(0.0, 0.0, 0.0))
    for name, mesh in cornell_parts().items():
        rho, emission = CORNELL_MATERIALS[name]
        scene.add(mesh, Material(color=rho, kd=1.0, ka=0.0, ks=0.0, reflectance=rho,
                                 emission=emission), name=name)
    c = CORNELL_CAMERA
    camera = Camera.look_at(c["eye"], c["target"], up=c["up"], fov_y=c["fov_y"],
                            near=10.0, far=3000.0)
    return scene, camera
