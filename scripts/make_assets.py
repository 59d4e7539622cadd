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


def main() -> None:
    ASSETS.mkdir(exist_ok=True)
    save_mesh(primitives.teapot(6), ASSETS / "teapot.obj")
    save_mesh(primitives.torus(1.0, 0.35, 24, 12), ASSETS / "torus.off")
    save_mesh(l_prism(), ASSETS / "lprism.obj")
    for p in sorted(ASSETS.glob("*.*")):
        print(p.name, p.stat().st_size)


if __name__ == "__main__":
    main()
