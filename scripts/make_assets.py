"""Regenerate the sample meshes in assets/ from glshade's own primitives (same licence as
the code). Run with `make assets`."""

from pathlib import Path

import numpy as np

from glshade import Mesh, save_mesh
from glshade.geometry import primitives

ASSETS = Path(__file__).resolve().parent.parent / "assets"


def l_prism() -> Mesh:
    """An L-shaped prism: two concave hexagon caps and six quad sides."""
    outline = np.array([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]], float)
    n = len(outline)
    bottom = np.c_[outline[:, 0], np.zeros(n), outline[:, 1]]
    top = bottom + [0, 1, 0]
    v = np.vstack([bottom, top])
    sides = [[i, n + i, n + (i + 1) % n, (i + 1) % n] for i in range(n)]
    return Mesh(v, [list(range(n)), [n + i for i in reversed(range(n))], *sides], name="lprism")


def cornell_box() -> None:
    """assets/cornell/*.obj (the published box, one file per part) and the scene file
    assets/scenes/cornell-box.toml with its materials and camera."""
    from glshade.geometry.primitives import cornell_parts
    from glshade.radiosity.cornell import CORNELL_CAMERA, CORNELL_MATERIALS

    (ASSETS / "cornell").mkdir(exist_ok=True)
    lines = ["# The Cornell box from its published measurements (millimetres), lit by its",
             "# light alone: `glshade radiosity assets/scenes/cornell-box.toml -o box.png`.",
             "# Reflectances and emission are RGB approximations of the measured spectra.",
             "[render]", "size = [512, 512]", 'mode = "radiosity"', "srgb = true",
             "ambient = [0.0, 0.0, 0.0]", ""]
    for name, mesh in cornell_parts().items():
        save_mesh(mesh, ASSETS / "cornell" / f"{name}.obj")
        rho, emission = CORNELL_MATERIALS[name]
        lines += ["[[mesh]]", f'name = "{name}"', f'source = "../cornell/{name}.obj"',
                  f"reflectance = {list(rho)}", f"color = {list(rho)}", "kd = 1.0",
                  "ka = 0.0", "ks = 0.0"]
        if any(emission):
            lines.append(f"emission = {[float(x) for x in emission]}")
        lines.append("")
    c = CORNELL_CAMERA
    lines += ["[camera]", f"eye = {list(c['eye'])}", f"target = {list(c['target'])}",
              f"fov_y = {round(c['fov_y'], 4)}", "near = 10.0", "far = 3000.0"]
    (ASSETS / "scenes" / "cornell-box.toml").write_text("\n".join(lines) + "\n")


def main() -> None:
    ASSETS.mkdir(exist_ok=True)
    save_mesh(primitives.teapot(6), ASSETS / "teapot.obj")
    save_mesh(primitives.torus(1.0, 0.35, 24, 12), ASSETS / "torus.off")
    save_mesh(l_prism(), ASSETS / "lprism.obj")
    cornell_box()
    for p in sorted(ASSETS.glob("*.*")):
        print(p.name, p.stat().st_size)


if __name__ == "__main__":
    main()
