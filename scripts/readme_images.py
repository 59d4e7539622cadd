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
    axes()
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


def axes() -> None:
    """The vision guide's picture: OpenCV's camera axes beside glshade's (OpenGL's), and
    OpenCV's pixel convention (integer coordinates at pixel centres)."""
    from PIL import Image, ImageDraw

    from glshade.io.images import font

    w, h = 720, 260
    img = Image.new("RGB", (w, h), (30, 30, 34))
    d = ImageDraw.Draw(img)
    big, small = font(16), font(13)
    red, green, blue, grey = (235, 90, 80), (110, 200, 110), (110, 150, 245), (200, 200, 200)

    def arrow(x0, y0, x1, y1, colour, name):
        d.line([(x0, y0), (x1, y1)], fill=colour, width=4)
        v = np.array([x1 - x0, y1 - y0], float)
        v /= np.linalg.norm(v)
        n = np.array([-v[1], v[0]])
        tip = np.array([x1, y1], float)
        d.polygon([tuple(tip + 10 * v), tuple(tip + 7 * n), tuple(tip - 7 * n)], fill=colour)
        d.text((x1 + 16 * v[0] + 12 * abs(v[1]) - 4, y1 + 12 * v[1] - 8), name, fill=colour,
               font=big)

    def panel(cx, title, y_down, into):
        d.text((cx - 110, 14), title, fill=grey, font=big)
        oy = 118
        arrow(cx, oy, cx + 90, oy, red, "x")
        arrow(cx, oy, cx, oy + (66 if y_down else -66), green, "y")
        d.ellipse([cx - 13, oy - 13, cx + 13, oy + 13], outline=blue, width=3)
        if into:  # (z into the picture: a cross)
            d.line([cx - 8, oy - 8, cx + 8, oy + 8], fill=blue, width=3)
            d.line([cx - 8, oy + 8, cx + 8, oy - 8], fill=blue, width=3)
        else:  # (z out of the picture, towards you: a dot)
            d.ellipse([cx - 4, oy - 4, cx + 4, oy + 4], fill=blue)
        d.text((cx - 110, 222), "z " + ("forward: the camera looks along +z" if into else
                                        "back: the camera looks down -z"),
               fill=blue, font=small)

    panel(130, "OpenCV (K, R, t): x_cam = R X + t", True, True)
    panel(380, "glshade Camera (OpenGL's axes)", False, False)
    # the pixel convention: a 3x2 grid, centres at integers
    gx, gy, s = 560, 60, 44
    for i in range(3):
        for j in range(2):
            d.rectangle([gx + i * s, gy + j * s, gx + (i + 1) * s, gy + (j + 1) * s],
                        outline=grey)
            c = (gx + i * s + s / 2, gy + j * s + s / 2)
            d.ellipse([c[0] - 3, c[1] - 3, c[0] + 3, c[1] + 3], fill=red)
    d.text((gx + s / 2 - 14, gy + s / 2 + 5), "(0, 0)", fill=red, font=small)
    d.text((gx - 40, gy - 22), "(-0.5, -0.5)", fill=grey, font=small)
    d.text((gx - 20, gy + 2 * s + 12), "pixel centres at integer (u, v):", fill=grey,
           font=small)
    d.text((gx - 20, gy + 2 * s + 30), "column floor(u + 0.5),", fill=grey, font=small)
    d.text((gx - 20, gy + 2 * s + 48), "row floor(v + 0.5)", fill=grey, font=small)
    img.save(DOCS / "vision-axes.png")
    print(DOCS / "vision-axes.png")


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
