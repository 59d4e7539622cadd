"""pytest plugin: headless rendering in other projects' tests.

Fixtures:

- ``glshade_renderer``: one headless Renderer (256x256, no MSAA) for the whole session;
  a clear failure naming every backend tried when no GL context can be made.
- ``glshade_golden``: ``glshade_golden(image, "name.png", max_mean=0.5, max_pixel=4)``
  compares with ``golden/name.png`` beside the test file; ``--glshade-update-golden``
  (re)writes the golden images instead.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest


def pytest_addoption(parser):
    group = parser.getgroup("glshade")
    group.addoption("--glshade-update-golden", action="store_true", default=False,
                    help="write the images glshade_golden is given as the new golden images")
    from glshade.modes import HEADLESS_BACKENDS

    group.addoption("--glshade-backend", default="auto", choices=HEADLESS_BACKENDS,
                    help="GL backend for glshade_renderer: " + ", ".join(HEADLESS_BACKENDS))


@pytest.fixture(scope="session")
def glshade_renderer(request):
    from glshade.errors import ContextError
    from glshade.render.renderer import Renderer

    try:
        renderer = Renderer(256, 256, samples=0,
                            backend=request.config.getoption("--glshade-backend"))
    except ContextError as exc:
        pytest.fail(f"glshade_renderer: no headless OpenGL context.\n{exc}", pytrace=False)
    yield renderer
    renderer.close()


@pytest.fixture
def glshade_golden(request):
    update = request.config.getoption("--glshade-update-golden")
    folder = Path(request.node.fspath).parent / "golden"

    def check(image, name: str, max_mean: float = 0.5, max_pixel: float = 4.0) -> None:
        from PIL import Image

        from glshade.io.images import save_image
        from glshade.testing import assert_images_close

        path = folder / name
        if update:
            folder.mkdir(parents=True, exist_ok=True)
            save_image(image, path)
            return
        if not path.exists():
            pytest.fail(f"no golden image {path}; run pytest with --glshade-update-golden to "
                        "write it", pytrace=False)
        expected = np.asarray(Image.open(path))
        assert_images_close(image, expected, max_mean=max_mean, max_pixel=max_pixel)

    return check
