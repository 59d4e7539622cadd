"""What a scene and its TraceOptions compile to, read without a GL context: the path
tracer's program source is made apart from its GL object (program_defines)."""

import re
import struct

import numpy as np
import pytest

from glshade.errors import OptionError
from glshade.modes import Accel
from glshade.pathtrace import TraceOptions, TraceScene
from glshade.radiosity import cornell_scene
from glshade.render.passes.pathtrace import program_defines


def _defines(accel, options, storage=False, controls=None):
    scene, _ = cornell_scene()
    ts = TraceScene.from_scene(scene)
    data, layout = ts.tables()
    return ts, program_defines(ts, data, layout, accel, options, storage=storage,
                               controls=controls, most_emitters=16)


def test_the_flat_program_holds_every_triangle_exactly():
    """accel FLAT compiles each triangle's rows as float bits; decoded, they are the
    scene's corners (p0, p1 - p0, p2 - p0), to the last bit of float32."""
    ts, defines = _defines(Accel.FLAT, TraceOptions())
    named = dict(d.split(" ", 1) for d in defines if " " in d)
    n = len(ts.triangles)
    assert named["FLAT_TRIANGLES"] == str(n) and "HIERARCHY" not in defines
    bits = [int(b) for b in re.findall(r"uintBitsToFloat\((\d+)u\)", named["FLAT_ROWS"])]
    rows = np.array([struct.unpack("<f", struct.pack("<I", b))[0] for b in bits],
                    np.float32).reshape(n, 3, 3)
    tri = ts.triangles  # (float64; the table holds them in the hierarchy's order)
    want = np.stack([tri[:, 0], tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]], 1)
    want = want.astype(np.float32).reshape(n, 9)

    def ordered(a):
        return a[np.lexsort(a.T[::-1])]

    assert np.array_equal(ordered(rows.reshape(n, 9)), ordered(want))
    assert named["FLAT_TESTS"].split() == [f"FLAT_TEST({k})" for k in range(n)]


@pytest.mark.parametrize("options, storage, expect, absent", [
    (TraceOptions(), False, {"HIERARCHY", "MIS"}, {"STORAGE_WALK", "LOW_DISCREPANCY"}),
    (TraceOptions(sampler="sobol", mis=False), True,
     {"HIERARCHY", "STORAGE_WALK", "GLSL_430", "LOW_DISCREPANCY"}, {"MIS"}),
    (TraceOptions(coherent=True), False, {"COHERENT_TILE uvec2(4u, 2u)"}, set()),
    (TraceOptions(coherent=(8, 4)), False, {"COHERENT_TILE uvec2(8u, 4u)"}, set()),
])
def test_each_option_is_one_define(options, storage, expect, absent):
    _, defines = _defines(Accel.BVH, options, storage)
    assert expect <= set(defines) and not absent & set(defines)
    assert not any(d.startswith("FLAT_") for d in defines)


def test_the_cornell_box_compiles_its_one_light_in_and_no_point_lights():
    _, defines = _defines(Accel.BVH, TraceOptions(), controls=8)
    assert "LIGHTS 0" in defines and "EMITTERS" in defines and "CONTROL 8" in defines
    assert sum(d.startswith("EMITTER_PICK ") for d in defines) == 1


@pytest.mark.parametrize("field, value, words", [
    ("accel", "octree", "accel must be 'auto', 'bvh', 'flat' or 'hybrid', got 'octree'"),
    ("sampler", 3, "sampler must be 'pcg' or 'sobol', got 3"),
    ("mis", "yes", "mis must be True or False, got 'yes'"),
    ("coherent", (0, 2), "coherent must be True, False or a block's"),
    ("max_depth", 0, "max_depth must be a whole number >= 1, got 0"),
    ("max_depth", 2_000_000, "max_depth must be at most 1,000,000"),
    ("storage", "on", "storage must be True, False or None"),
    ("seed", 1, "TraceOptions has no seed: its fields are accel, coherent, kernel, "
               "lobe_sampling, max_depth"),
    ("lobe_sampling", "cosine", "lobe_sampling must be 'visible-normals', 'normals' or "
                                "'uniform', got 'cosine'"),
])
def test_a_bad_option_is_refused_when_the_value_is_made(field, value, words):
    with pytest.raises(OptionError) as raised:
        TraceOptions.of(**{field: value})
    assert str(raised.value).startswith(words)


def test_past_the_compiled_in_thresholds_a_program_is_no_scene_s_numbers():
    """A driver's shader cache serves every scene whose program source is the same: past
    the triangles and emitters compiled in (where the speed guide measured them faster),
    two scenes of other sizes, places, colours and model counts compile to one source (a
    scene's kinds of surface -- glossy or not, emitting or not -- are switches: they do)."""
    from glshade import Material, Scene
    from glshade.geometry import primitives as P
    from glshade.render.passes.pathtrace import MAX_CONTROL_MODELS

    def defines(scene):
        ts = TraceScene.from_scene(scene)
        data, layout = ts.tables()
        return program_defines(ts, data, layout, Accel.BVH, TraceOptions(), storage=True,
                               controls=MAX_CONTROL_MODELS, most_emitters=0)

    a, _ = cornell_scene()
    b, _ = cornell_scene()
    b.add(P.icosphere(3), Material(color=(0.2, 0.7, 0.4), kd=0.6, ks=0.0),
          translation=(0.3, 0.2, 0.1), scale=0.15)
    b.add(P.cube(), Material(color=(0.9, 0.1, 0.1), kd=0.5, ks=0.0), translation=(-0.2, 0.1, 0.3),
          scale=0.1)
    assert len(b.models) == len(a.models) + 2
    assert defines(a) == defines(b)
    c = Scene()  # (nothing alike but a light and the kind of surface)
    c.add(P.cube(), Material(color=(0.5, 0.5, 0.5), kd=0.7, ks=0.0,
                             emission=(2.0, 2.0, 2.0)))
    c.add(P.plane(5.0), Material(color=(0.8, 0.8, 0.8), kd=0.8, ks=0.0),
          translation=(0, -1, 0))
    assert defines(c) == defines(a)
