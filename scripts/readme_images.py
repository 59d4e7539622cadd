"""Render the README's pictures with glshade itself: the teapot in flat, Gouraud and Phong
shading, side by side. Run: ``.venv/bin/python scripts/readme_images.py``."""

from pathlib import Path

import numpy as np

import glshade
from glshade.scene import default_camera
from glshade.compare import sweep, sweep_plot
from glshade.geometry import primitives
from glshade import Renderer
from glshade.scene import Material, PointLight, Scene

DOCS = Path(__file__).resolve().parent.parent / "docs"


def main() -> None:
    DOCS.mkdir(exist_ok=True)
    scene = Scene(background=(0.12, 0.12, 0.14))
    scene.add(primitives.teapot(3), Material(color=(0.85, 0.55, 0.3), ks=0.5, shininess=40))
    camera = default_camera(scene, 4 / 3)
    scene.add_light(PointLight(tuple(camera.position + 6 * camera.up - 3 * camera.right)))
    with Renderer(400, 300, samples=4) as r:
        tiles = [r.render(scene, camera, mode) for mode in
                 ("flat", "gouraud", "phong")]
    glshade.save_image(np.hstack(tiles), DOCS / "teapot-modes.png")
    print(DOCS / "teapot-modes.png")

    # the comparison grid of a coarse sphere against the exact one, and the sweep
    sphere = Scene()
    sphere.add(primitives.icosphere(2), Material(color=(0.9, 0.75, 0.6), ks=0.5, shininess=30))
    sphere.add_light(PointLight((3.0, 4.0, 5.0)))
    cam = glshade.Camera.look_at([0.4, 0.6, 3.3], [0, 0, 0], fov_y=40)
    result = glshade.compare(sphere, cam, size=(200, 200), diff=True)
    glshade.save_image(result.image, DOCS / "compare-sphere.png")
    rows = sweep(primitives.icosphere, range(0, 7))
    glshade.save_image(sweep_plot(rows, ["flat", "gouraud", "phong"]), DOCS / "sweep.png")
    print(result.table())
    cornell()
    csg()


def csg() -> None:
    """The sample CSG part with a mesh through it, and its octree at two depths."""
    from glshade.octree import Octree
    from glshade.io.scenefile import load_scene

    sf = load_scene(DOCS.parent / "assets/scenes/csg-part.toml")
    camera = sf.path.at(sf.path.start)
    solid = sf.scene.solids[0].solid
    tiles = []
    with Renderer(360, 270, samples=4) as r:
        tiles.append(r.render(sf.scene, camera, "phong"))
        for depth in (4, 6):
            s = Scene(background=(0.12, 0.12, 0.14))
            s.add(Octree.from_solid(solid, depth).to_mesh("inside+boundary"),
                  Material(color=(0.8, 0.55, 0.3)))
            s.add_light(PointLight((4.0, 6.0, 5.0)))
            tiles.append(r.render(s, camera, "flat"))
    glshade.save_image(np.hstack(tiles), DOCS / "csg-octree.png")
    print(DOCS / "csg-octree.png")


def cornell() -> None:
    """The Cornell box by radiosity (progressive refinement to 99% shot), beside the
    convergence plot."""
    from glshade.radiosity import cornell_scene, solve
    from glshade.radiosity.plot import convergence_plot

    scene, camera = cornell_scene()
    solution = solve(scene, 50.0, until=0.01)
    with Renderer(360, 360, samples=4) as r:
        image = r.render(solution.scene(), camera, "radiosity", srgb=True)[..., :3]
    plot = convergence_plot(solution.history, "progressive refinement: unshot energy (log)",
                            size=(520, 360), target=0.01)
    glshade.save_image(np.hstack([image, plot]), DOCS / "cornell-radiosity.png")
    print(DOCS / "cornell-radiosity.png", solution.unshot_fraction, len(solution.history) - 1)


if __name__ == "__main__":
    main()
