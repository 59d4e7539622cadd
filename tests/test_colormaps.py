"""One id palette: the frame's id tile, the hidden-surface lab's pictures and its results'
thumbnails colour a polygon alike."""

from types import SimpleNamespace

import numpy as np

from glshade.display import buffers_image
from glshade.colormaps import BACKGROUND_ID_COLOR, id_colors
from glshade.hidden import HiddenResult


def test_ids_get_distinct_colours_and_the_background_its_own():
    ids = np.arange(-1, 400).reshape(1, -1)
    rgb = id_colors(ids)
    assert tuple(rgb[0, 0]) == BACKGROUND_ID_COLOR
    neighbours = np.abs(rgb[0, 2:].astype(int) - rgb[0, 1:-1].astype(int)).sum(-1)
    assert neighbours.min() > 30  # (ids next to each other never look alike)
    assert len({tuple(c) for c in rgb[0, 1:]}) == 400


def test_every_picture_of_ids_uses_the_one_palette():
    ids = np.array([[-1, 0, 1], [2, 3, -1]])
    frame = SimpleNamespace(color=np.zeros((2, 3, 4), np.uint8), depth=None, normal=None,
                            face_id=ids)
    assert (buffers_image(frame)[:, 3:] == id_colors(ids)).all()
    result = HiddenResult("zbuffer", ids.astype(np.int32), np.where(ids >= 0, 1.0, np.inf))
    html = result._repr_html_()
    import base64
    import io
    import re

    from PIL import Image

    data = base64.b64decode(re.search(r"base64,([^\"]+)", html).group(1))
    shown = np.asarray(Image.open(io.BytesIO(data)).convert("RGB"))
    assert (shown == id_colors(ids)).all()
