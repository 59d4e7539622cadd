"""Every numeric field of a scene file, swept from 1e-320 to 1e308 and through NaN, inf and
-inf (TOML writes all three): the file loads and draws a picture, or loading or drawing
raises one GlshadeError line that names the file's place -- never a traceback, a numpy
repr (np.float64(...), array(...)) or a RuntimeWarning printed on the way."""

import math
import warnings

import pytest

from tests.conftest import require

require("hypothesis", "property-based sweeps are part of the test extra")

from hypothesis import example, given, settings, strategies as st  # noqa: E402

from glshade import GlshadeError, load_scene  # noqa: E402

BASE = """[render]
size = [16, 12]
{render}
[[mesh]]
source = "primitive:cube"
{mesh}
[[light]]
{light}
[camera]
{camera}
"""
DEFAULTS = {"render": "", "mesh": "",
            "light": "position = [2.0, 3.0, 4.0]", "camera": "eye = [3.0, 2.0, 4.0]\n"
            "target = [0.0, 0.0, 0.0]"}

#: each numeric field: its table and how a value v is written there (one component of a
#: vector, one entry of a matrix, a whole number where the field is one)
FIELDS = {
    "render.samples": ("render", "samples = {i}"),
    "render.size": ("render", "size = [{i}, 12]"),
    "render.fps": ("render", "fps = {v}"), "render.duration": ("render", "duration = {v}"),
    "render.background": ("render", "background = [{v}, 0.1, 0.1]"),
    "render.ambient": ("render", "ambient = [{v}, 0.2, 0.2]"),
    **{f"mesh.{k}": ("mesh", f"{k} = {{v}}") for k in
       ("ka", "kd", "ks", "shininess", "crease", "opacity", "scale")},
    **{f"mesh.{k}": ("mesh", f"{k} = [{{v}}, 0.5, 0.5]") for k in
       ("color", "translation", "emission", "reflectance", "ambient", "diffuse", "specular",
        "scale")},
    "mesh.rotation": ("mesh", "rotation = [{v}, 0.0, 0.0, 1.0]"),
    "mesh.transform": ("mesh", "transform = [[{v}, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], "
                               "[0, 0, 0, 1]]"),
    "mesh.transform w": ("mesh", "transform = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], "
                                 "[0, 0, 0, {v}]]"),
    "light.position": ("light", "position = [{v}, 3.0, 4.0]"),
    "light.color": ("light", "position = [2.0, 3.0, 4.0]\ncolor = [{v}, 1.0, 1.0]"),
    "light.intensity": ("light", "position = [2.0, 3.0, 4.0]\nintensity = {v}"),
    "light.attenuation": ("light", "position = [2.0, 3.0, 4.0]\nattenuation = [1.0, {v}, 0.0]"),
    "light.direction": ("light", 'type = "directional"\ndirection = [{v}, -1.0, -1.0]'),
    "camera.eye": ("camera", "eye = [{v}, 2.0, 4.0]\ntarget = [0.0, 0.0, 0.0]"),
    "camera.target": ("camera", "eye = [3.0, 2.0, 4.0]\ntarget = [{v}, 0.0, 0.0]"),
    "camera.up": ("camera", "eye = [3.0, 2.0, 4.0]\ntarget = [0.0, 0.0, 0.0]\n"
                            "up = [{v}, 1.0, 0.0]"),
    "camera.fov_y": ("camera", "eye = [3.0, 2.0, 4.0]\ntarget = [0.0, 0.0, 0.0]\nfov_y = {v}"),
    "camera.near": ("camera", "eye = [3.0, 2.0, 4.0]\ntarget = [0.0, 0.0, 0.0]\nnear = {v}"),
    "camera.far": ("camera", "eye = [3.0, 2.0, 4.0]\ntarget = [0.0, 0.0, 0.0]\nfar = {v}"),
}

EDGES = [1e-320, 5e-324, 1e-300, 1e-30, 1e-7, 0.0, -0.0, -1.0, 0.5, 1.0, 7.0, 1e7, 1e30,
         1e300, 1e308, -1e308, math.nan, math.inf, -math.inf]
VALUES = st.sampled_from(EDGES) | st.floats(allow_nan=True, allow_infinity=True)


def _toml(v: float) -> str:
    if math.isnan(v):
        return "nan"
    if math.isinf(v):
        return "inf" if v > 0 else "-inf"
    return repr(float(v))


def _text(field: str, value: float) -> str:
    table, line = FIELDS[field]
    whole = int(value) if math.isfinite(value) and abs(value) < 1e18 else 10 ** 30
    parts = dict(DEFAULTS)
    parts[table] = line.format(v=_toml(value), i=whole)
    return BASE.format(**parts)


def _draws_or_says_one_line(tmp_path, renderer, field, value):
    path = tmp_path / "s.toml"
    path.write_text(_text(field, value))
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)  # (numpy's own words never leak)
        warnings.filterwarnings("ignore", category=UserWarning)  # (RenderWarning: blank)
        try:
            made = load_scene(path)
            image = renderer.render(made.scene, made.camera, made.settings.options)
        except GlshadeError as exc:
            said = str(exc)
            assert "\n" not in said and "np.float" not in said and "array(" not in said, said
            assert len(said) < 400, said
            return "refused"
    assert image.shape == (12, 16, 4)
    return "drawn"


@pytest.mark.parametrize("field", sorted(FIELDS))
@pytest.mark.parametrize("value", [1e-320, 1e308, math.nan, -math.inf])
def test_each_field_at_the_edges(tmp_path, make_renderer, field, value):
    _draws_or_says_one_line(tmp_path, make_renderer(16, 12), field, value)


@settings(max_examples=150)
@given(field=st.sampled_from(sorted(FIELDS)), value=VALUES)
@example(field="light.position", value=4.253529459746671e38)  # (past float32: overflowed)
def test_any_number_in_any_field(tmp_path_factory, gl_context, field, value):
    from glshade import Renderer

    with Renderer(16, 12, samples=0, context=gl_context) as renderer:
        _draws_or_says_one_line(tmp_path_factory.mktemp("n"), renderer, field, value)
