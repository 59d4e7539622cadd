"""Render the README's pictures with glshade itself: the teapot in flat, Gouraud and Phong
shading, side by side. Run: ``.venv/bin/python scripts/readme_images.py``."""

from pathlib import Path

import numpy as np

import glshade
from glshade.camera import default_camera
from glshade.geometry import primitives
from glshade import Renderer
from glshade.scene import Material, PointLight, Scene

DOCS = Path(__file__).resolve().parent.parent / "docs"


def main() -> None:
    DOCS.mkdir(exist_ok=True)
    scene = Scene(background=(0.12, 0.12, 0.14))
    scene.add(primitives.teapot(3), Material(color=(0.85, 0.55, 0.3), ks=0.5, shininess=40))
    camera = default_camera(scene.bounds(), 4 / 3)
    scene.add_light(PointLight(tuple(camera.position + 6 * camera.up - 3 * camera.right)))
    with Renderer(400, 300, samples=4) as r:
        tiles = [r.render(scene, camera, mode) for mode in
                 ("flat", "gouraud", "phong")]
    glshade.save_image(np.hstack(tiles), DOCS / "teapot-modes.png")
    print(DOCS / "teapot-modes.png")


if __name__ == "__main__":
    main()
