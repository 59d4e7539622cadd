"""A frame's pipeline: ``Renderer.draw`` is its list of stages, each keeping one protocol,
none receiving the renderer; every per-draw decision is made once, in the DrawState."""

import ast
import inspect
import itertools
from pathlib import Path

import numpy as np
import pytest

import glshade
from glshade import Camera, DirectionalLight, Material, Outputs, Scene
from glshade.geometry import primitives
from glshade.render.passes import Stage, run

pytestmark = pytest.mark.gl

PASSES = Path(glshade.__file__).parent / "render" / "passes"
ORDER = ["EnvironmentPass", "ShadowPass", "MeshPass", "PatchPass", "CsgPass", "PointPass",
         "LinePass", "TransparencyPass", "EdgePass"]
PROTOCOL = {"wanted": ["state"], "prepare": ["state"], "draw": ["state", "id_base"],
            "finish": ["state"]}

#: the shadow scene: a floor (z = 0), a sphere of radius R at height H above its centre,
#: a light straight down -- its shadow is the disk of radius R under the sphere
R, H, SIZE = 1.0, 1.6, 48
EYE, LOOK = np.array([0.0, -5.0, 6.0]), np.array([0.0, 0.0, 0.5])


def test_draw_is_its_list_of_stages(make_renderer):
    r = make_renderer(16, 16)
    assert [type(s).__name__ for s in r.stages] == ORDER
    assert all(isinstance(s, Stage) for s in r.stages)


@pytest.mark.parametrize("name", ORDER)
def test_each_stage_keeps_the_protocol(make_renderer, name):
    """Its methods take what the protocol says -- the state, and the first free id -- and
    nothing of the renderer's."""
    r = make_renderer(16, 16)
    [stage] = [s for s in r.stages if type(s).__name__ == name]
    for method, params in PROTOCOL.items():
        got = list(inspect.signature(getattr(stage, method)).parameters)
        assert got == params, (name, method, got)


def test_no_pass_receives_or_imports_the_renderer():
    """No function in render/passes takes a renderer or an owner, and no pass module
    imports the renderer's module: what a stage needs is handed to it when it is made."""
    found = []
    for path in sorted(PASSES.glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                names = {a.arg for a in node.args.args + node.args.kwonlyargs}
                if names & {"renderer", "owner"}:
                    found.append(f"{path.name}:{node.lineno} {node.name}")
            elif isinstance(node, ast.ImportFrom) and "renderer" in (node.module or ""):
                found.append(f"{path.name}:{node.lineno} imports {node.module}")
    assert found == []


def everything() -> Scene:
    """A scene every stage but the patches' has work in: shadow-casting meshes, a
    transparent one, a CSG solid, a point cloud and a polyline."""
    from glshade import PointCloud, Polyline
    from glshade.solids import Sphere

    scene = shadow_scene()
    scene.add(primitives.plane(1.0), Material(color=(0.2, 0.4, 0.9), opacity=0.5),
              translation=(1.8, 0.0, 0.5))
    scene.add(Sphere(0.5).translated((-1.8, 0.0, 0.6)))
    scene.add(PointCloud([[0.0, -1.8, 0.5], [0.3, -1.8, 0.5]], radius=0.2))
    scene.add(Polyline([[-1.0, 1.8, 0.3], [0.0, 1.8, 0.5], [1.0, 1.8, 0.3]], width=3))
    return scene


def test_the_stages_run_in_order_and_pass_the_ids_on(make_renderer, monkeypatch):
    """Every stage prepares before the target is bound, then each draws in turn with the
    id the one before it returned, then each finishes: recorded on a real draw. A solid
    casts, so the shadows go through a G-buffer, drawn by the opaque stages alone (inside
    the shadow stage's prepare)."""
    r = make_renderer(32, 32)
    calls, depth = [], [0]
    for stage in r.stages:
        for method in PROTOCOL:
            real, label = getattr(stage, method), f"{type(stage).__name__}.{method}"

            def spy(*args, _real=real, _name=label):
                depth[0] += 1
                try:
                    out = _real(*args)
                finally:
                    depth[0] -= 1
                calls.append((depth[0], _name, args[1:], out))
                return out

            monkeypatch.setattr(stage, method, spy)
    scene = everything()
    r.render(scene, Camera.look_at(EYE, LOOK, up=(0, 0, 1)), "phong", shadows="exact",
             edges=True)
    top = [(n, args, out) for d, n, args, out in calls if d == 0]
    inner = [n for d, n, _, _ in calls if d == 1]
    wanted = [n.split(".")[0] for n, _, out in top if n.endswith("wanted") and out]
    # (no patch model, no sky: those stages not wanted)
    assert wanted == [n for n in ORDER if n not in ("PatchPass", "EnvironmentPass")]
    phases = [n.split(".")[1] for n, _, _ in top if not n.endswith("wanted")]
    assert phases == ["prepare"] * 7 + ["draw"] * 7 + ["finish"] * 7
    opaque = ["MeshPass", "CsgPass", "PointPass", "LinePass"]
    assert [n for n in inner if not n.endswith("wanted")] == [
        f"{stage}.{phase}" for phase in ("prepare", "draw", "finish") for stage in opaque]
    draws = [(n, args, out) for n, args, out in top if n.endswith(".draw")]
    assert draws[0][1] == (0,)
    for (_, _, before), (_, args, _) in zip(draws, draws[1:]):
        assert args == (before,)  # (each stage's first id is the last one's return)
    # the meshes' ids: the floor's quad, the sphere's triangles, the transparent quad;
    # then the solid's leaf, the cloud's two points, the polyline's two segments
    n_mesh = sum(m.mesh.n_faces for m in scene.models)
    assert [out for *_, out in draws] == [0, n_mesh, n_mesh + 1, n_mesh + 3, n_mesh + 5,
                                          n_mesh + 5, n_mesh + 5]


def shadow_scene(model: str = "notes") -> Scene:
    """A floor and a ball over it, lit from above: in the notes' model, or in glTF's with
    every map on the floor (a grey base colour map, a flat normal map ...)."""
    scene = Scene(ambient=(0.1, 0.1, 0.1), background=(0, 0, 0))
    if model == "notes":
        floor, ball = Material(color=(0.8, 0.8, 0.8), ks=0.0), Material(color=(0.8, 0.3, 0.3))
    else:
        grey = glshade.Texture(np.full((4, 4, 3), 230, np.uint8))
        flat = glshade.Texture(np.broadcast_to(np.array([128, 128, 255], np.uint8),
                                               (4, 4, 3)).copy())
        floor = glshade.PBRMaterial(base_color=(0.8, 0.8, 0.8), metallic=0.0, roughness=0.9,
                                    base_color_texture=grey, metallic_roughness_texture=grey,
                                    occlusion_texture=grey, emissive_texture=grey,
                                    normal_texture=flat)
        ball = glshade.PBRMaterial(base_color=(0.8, 0.3, 0.3), metallic=0.5, roughness=0.4)
    scene.add(primitives.plane(8.0), floor)
    scene.add(primitives.icosphere(3, R), ball, translation=(0.0, 0.0, H))
    scene.add_light(DirectionalLight(direction=(0.0, 0.0, -1.0),
                                     intensity=1.0 if model == "notes" else 3.0))
    return scene


def floor_truth(camera: Camera, size: int):
    """Per pixel, from the camera's pinhole alone: whether its centre's ray meets the floor
    first (not the sphere's ball, with a margin), and whether that point lies in the
    sphere's shadow disk -- undecided within 12% of the disk's rim (the icosphere's facets
    fall inside the true sphere)."""
    j, i = np.mgrid[0:size, 0:size] + 0.5
    t = np.tan(np.radians(camera.fov_y) / 2)
    d = np.stack([(2 * i / size - 1) * t, (1 - 2 * j / size) * t, -np.ones_like(i)], -1)
    d = d @ camera.rotation.T
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    o = camera.position
    hit = (-o[2] / d[..., 2])[..., None] * d + o  # (the floor z = 0)
    centre = np.array([0.0, 0.0, H])
    along = (centre - o) @ d.reshape(-1, 3).T
    miss = np.linalg.norm(o + along.reshape(size, size, 1) * d - centre, axis=-1)
    floor = (d[..., 2] < 0) & (np.abs(hit[..., :2]) < 3.9).all(-1) & (miss > 1.1 * R)
    rim = np.hypot(hit[..., 0], hit[..., 1])
    return floor & (rim < 0.88 * R), floor & (rim > 1.12 * R)


@pytest.mark.parametrize("model", ["notes", "pbr"])
@pytest.mark.parametrize("samples", [0, 4])
def test_every_combination_of_outputs_shadows_wireframe_transparency(make_renderer,
                                                                      samples, model):
    """The fault of a rule written twice (``render_frame(shadows="exact", wireframe=True)``
    raised AttributeError on a fresh renderer and returned the previous frame's visibility
    after a shadowed one): every combination, one renderer drawing them in turn, against
    the floor's shadow disk computed from the camera alone -- in either lighting model."""
    r = make_renderer(SIZE, SIZE, samples=samples)
    camera = Camera.look_at(EYE, LOOK, up=(0, 0, 1))
    shade, lit = floor_truth(camera, SIZE)
    assert shade.sum() > 20 and lit.sum() > 200
    for outputs, shadows, wireframe, transparency in itertools.product(
            [Outputs.COLOR, Outputs.ALL], ["off", "exact", "map"], [False, True],
            [None, "exact", "blend"]):
        scene = shadow_scene(model)
        if transparency:  # (in front of the shadow: transparent surfaces cast none)
            glass = Material(color=(0.2, 0.4, 0.9), opacity=0.3) if model == "notes" else \
                glshade.PBRMaterial(base_color=(0.2, 0.4, 0.9), opacity=0.3)
            scene.add(primitives.plane(8.0), glass, translation=(0.0, 0.0, 0.05))
        case = (outputs, shadows, wireframe, transparency)
        frame = r.render_frame(scene, camera, "phong", outputs=outputs, shadows=shadows,
                               wireframe=wireframe, transparency=transparency or "exact")
        if shadows == "off" or wireframe:
            assert frame.visibility is None, case
            continue
        v = frame.visibility[..., 0]
        assert (v[shade] < 0.05).all() and (v[lit] > 0.95).all(), case
        grey = frame.color[..., :3].astype(float).mean(-1)
        assert grey[shade].mean() < 0.5 * grey[lit].mean(), case


def test_a_stage_list_runs_on_its_own(make_renderer):
    """``run`` drives any list of stages: the meshes alone draw the opaque surfaces and
    return their ids -- the pipeline needs no renderer."""
    from glshade.render.state import DrawState

    r = make_renderer(SIZE, SIZE)
    from glshade.render.target import OffscreenTarget

    scene = shadow_scene()
    camera = Camera.look_at(EYE, LOOK, up=(0, 0, 1)).with_planes(scene.bounds)
    with OffscreenTarget(r.context, SIZE, SIZE) as target:
        state = DrawState.of(target, scene, camera, glshade.DrawOptions.of("flat"))
        r.context.make_current()
        run(r.ctx, [r.meshes], state)
        alone = target.read_color()
    whole = r.render(scene, camera, "flat")
    assert np.array_equal(alone, whole)
