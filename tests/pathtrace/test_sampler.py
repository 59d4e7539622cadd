"""The path tracer's low-discrepancy sampler (Owen-scrambled Sobol pairs, random.glsl)
against properties that share nothing with its construction: the first 2^m points of a
pair are a (0, m, 2)-net (every elementary interval of area 2^-m holds exactly one, counted
in numpy), pairs and pixels are not copies of each other, and on the Cornell box the same
samples leave less error against a long render than independent random numbers do; and
multiple importance sampling leaves less error on a glossy floor -- while the furnace
(tests/pathtrace/test_sweeps.py) shows the answer unbiased either way."""

import numpy as np
import pytest

from glshade.geometry import primitives
from glshade.pathtrace import trace
from glshade.scene import Material

pytestmark = [pytest.mark.gl]

POINTS, PAIRS = 256, 12

FRAGMENT = """#version 330 core
#define LOW_DISCREPANCY
#include "random.glsl"
uniform uint u_pixel_seed;
out vec4 color;
void main() {
    g_pixel_seed = u_pixel_seed;
    uint k = uint(gl_FragCoord.x), pair = uint(gl_FragCoord.y);
    color = vec4(sobol_pair(k, pair), 0.0, 1.0);
}
"""
VERTEX = """#version 330 core
void main() {
    vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
    gl_Position = vec4(p, 0.0, 1.0);
}
"""


def sobol_points(gl_context, seeds) -> dict:
    """``{seed: (PAIRS, POINTS, 2)}``: sample k of each dimension pair of a pixel seeded
    ``seed``, as the shader makes them."""
    import tempfile
    from pathlib import Path

    from glshade.render.shaders import assemble

    ctx = gl_context.ctx
    with tempfile.TemporaryDirectory() as folder:
        probe = Path(folder) / "probe.frag"
        probe.write_text(FRAGMENT)
        frag, _ = assemble(str(probe))  # (its #include found among glshade's shaders)
    prog = ctx.program(vertex_shader=VERTEX, fragment_shader=frag)
    tex = ctx.texture((POINTS, PAIRS), 4, dtype="f4")
    fbo = ctx.framebuffer([tex])
    vao = ctx.vertex_array(prog, [])
    out = {}
    try:
        fbo.use()
        ctx.viewport = (0, 0, POINTS, PAIRS)
        for seed in seeds:
            prog["u_pixel_seed"].value = seed
            vao.render(vertices=3)
            data = np.frombuffer(fbo.read(components=4, dtype="f4"), np.float32)
            out[seed] = data.reshape(PAIRS, POINTS, 4)[..., :2].astype(np.float64)
    finally:
        gl_context.rest()  # (never release the bound framebuffer)
        for obj in (vao, fbo, tex, prog):
            obj.release()
    return out


def is_net(points: np.ndarray, m: int) -> bool:
    """Whether ``2^m`` points fill each elementary interval of every shape 2^-a x 2^-b,
    a + b = m, exactly once."""
    for a in range(m + 1):
        cells = np.floor(points[:, 0] * 2**a) * 2 ** (m - a) + \
            np.floor(points[:, 1] * 2 ** (m - a))
        if len(np.unique(cells)) != 2**m:
            return False
    return True


def test_each_pair_is_a_net_at_every_power_of_two(gl_context):
    points = sobol_points(gl_context, (1, 77, 2))
    for seed in (1, 77):
        pts = points[seed]
        assert ((pts >= 0) & (pts < 1)).all()
        for pair in range(PAIRS):
            for m in range(1, 9):
                assert is_net(pts[pair, :2**m], m), (seed, pair, m)
        # a shuffled order: sample k is not the same point in every pair or pixel
        assert len({tuple(pts[p, 0]) for p in range(PAIRS)}) == PAIRS
    assert not np.allclose(points[2][0], points[1][0])  # (nor in every pixel)


def test_a_random_point_set_is_no_net():
    """(The test's own check: independent uniform points are almost never a net.)"""
    rng = np.random.default_rng(0)
    assert not is_net(rng.random((256, 2)), 8)


def test_the_same_samples_leave_less_error(gl_context):
    from glshade.radiosity import cornell_scene

    scene, camera = cornell_scene()
    scene.add(primitives.icosphere(1), Material(color=(0.75, 0.75, 0.75), kd=0.9, ks=0.0),
              scale=90.0, translation=(280.0, 90.0, 280.0))
    size = (24, 24)
    reference = trace(scene, camera, size, spp=2048, seed=99, context=gl_context,
                      progress=False).image[..., :3]
    errors = {}
    for sampler in ("pcg", "sobol"):
        rms = []
        for seed in range(3):
            img = trace(scene, camera, size, spp=16, seed=seed, context=gl_context,
                        progress=False, sampler=sampler).image[..., :3]
            rms.append(np.sqrt(np.mean((img - reference) ** 2)))
        errors[sampler] = float(np.mean(rms))
    assert errors["sobol"] < 0.9 * errors["pcg"], errors


def test_mis_leaves_less_error_on_a_glossy_floor(gl_context):
    """Multiple importance sampling: the area light's reflection in a glossy floor is found
    better by the bounce than by next-event estimation; weighing both leaves less error
    (away from the light's own pixels) than next-event estimation alone -- and the furnace
    sweep shows both unbiased."""
    import glshade as g
    from glshade.radiosity import cornell_scene

    scene, camera = cornell_scene()
    scene.add(primitives.plane(400.0),
              Material(color=(0.2, 0.2, 0.2), kd=0.2, ks=0.75, shininess=400.0),
              translation=(278, 1.0, 280),
              rotation=g.quaternion.from_axis_angle((1, 0, 0), -np.pi / 2))
    size = (48, 48)
    reference = trace(scene, camera, size, spp=1024, seed=99, context=gl_context,
                      progress=False, sampler="sobol").image[..., :3]
    keep = reference.max(-1) < 2.0  # (not the light itself)
    errors = {}
    for mis in (False, True):
        rms = []
        for seed in range(3):
            img = trace(scene, camera, size, spp=16, seed=seed, context=gl_context,
                        progress=False, mis=mis).image[..., :3]
            rms.append(np.sqrt(np.mean((img - reference)[keep] ** 2)))
        errors[mis] = float(np.mean(rms))
    assert errors[True] < 0.95 * errors[False], errors


def test_an_unknown_sampler_is_named(gl_context):
    from glshade.errors import OptionError
    from glshade.radiosity import cornell_scene

    scene, camera = cornell_scene()
    with pytest.raises(OptionError, match="sampler must be 'pcg' or 'sobol'"):
        trace(scene, camera, (4, 4), spp=1, context=gl_context, progress=False,
              sampler="halton")
