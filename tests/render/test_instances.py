"""Instances (``Scene.add(mesh, material, instances=(K, 4, 4), colors=(K, 3))``): one
instanced draw gives, to the byte, the picture, polygon ids, instance ids and depth of K
models added one by one -- the oracle is the renderer's own per-model path, which shares
no code with the instanced one past the mesh's buffers (its uniforms against a texture of
rows, its material products against a vectorised copy) -- in every shading mode, with
MSAA, shadows of both kinds, an orthographic camera, attenuated and directional lights,
culling on, off and auto, mirrored instances, and over random placements; and it is one
draw call."""

import dataclasses
import warnings

import moderngl
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st
from scipy.spatial.transform import Rotation

import glshade as g
from glshade.errors import SceneError
from glshade.geometry import primitives as P

pytestmark = pytest.mark.gl

W, H = 120, 90


def placements(k, seed, mirror=True):
    rng = np.random.default_rng(seed)
    t = np.tile(np.eye(4), (k, 1, 1))
    t[:, :3, 3] = rng.uniform(-2.2, 2.2, (k, 3))
    t[:, :3, :3] = Rotation.random(k, random_state=seed).as_matrix() * \
        rng.uniform(0.3, 0.8, (k, 1, 1))
    if mirror:
        t[1::4, :3, 0] *= -1  # (every fourth mirrored: its faces wind the other way)
    return t, rng.uniform(0.05, 1.0, (k, 3))


def pair(mesh, t, colors, material=None, **scene):
    """The same K objects, instanced and one by one."""
    material = material or g.Material(shininess=24)
    a, b = g.Scene(**scene), g.Scene(**scene)
    for s in (a, b):
        s.add(P.plane(12.0), g.Material(color=(0.8, 0.8, 0.8)), translation=(0, -3, 0),
              rotation=g.quaternion.from_axis_angle((1, 0, 0), -np.pi / 2))
    a.add(mesh, material, instances=t, colors=colors, label="part")
    for k in range(len(t)):
        m = material if colors is None else \
            dataclasses.replace(material, color=tuple(float(c) for c in colors[k]))
        b.add(mesh, m, transform=t[k], label="part")
    return a, b


def same(renderer, a, b, camera, mode, **options):
    fa = renderer.render_frame(a, camera, mode, outputs=g.Outputs.ALL, **options)
    fb = renderer.render_frame(b, camera, mode, outputs=g.Outputs.ALL, **options)
    for name in ("color", "face_id", "instance", "semantic", "depth", "normal"):
        x, y = getattr(fa, name), getattr(fb, name)
        assert np.array_equal(x, y, equal_nan=True), \
            f"{mode} {options}: {name} differs at {int((x != y).sum())} values"
    plain_a = renderer.render(a, camera, mode, **options)  # (the colour-only programs)
    assert np.array_equal(plain_a, renderer.render(b, camera, mode, **options))
    return fa


CAMERA = g.Camera.look_at((1.0, 4.0, 8.0), (0, 0, 0), fov_y=55)


@pytest.mark.parametrize("mode", ["flat", "gouraud", "phong", "normals", "depth"])
@pytest.mark.parametrize("samples", [0, 4])
def test_instances_are_the_models_to_the_byte(mode, samples, make_renderer):
    t, colors = placements(16, 1)
    a, b = pair(P.torus(0.6, 0.22, 18, 9), t, colors)
    frame = same(make_renderer(W, H, samples=samples), a, b, CAMERA, mode)
    assert len(np.unique(frame.instance)) > 10  # (the instances were in view)


@pytest.mark.parametrize("shadows", ["exact", "map"])
def test_instances_cast_and_receive_shadows_as_models(shadows, make_renderer):
    t, colors = placements(10, 2)
    a, b = pair(P.icosphere(1, 0.7), t, colors)
    a.add_light(g.PointLight(position=(2.0, 6.0, 3.0), attenuation=(1.0, 0.05, 0.01)))
    b.add_light(g.PointLight(position=(2.0, 6.0, 3.0), attenuation=(1.0, 0.05, 0.01)))
    a.add_light(g.DirectionalLight(direction=(-0.3, -1.0, -0.2), intensity=0.4))
    b.add_light(g.DirectionalLight(direction=(-0.3, -1.0, -0.2), intensity=0.4))
    same(make_renderer(W, H), a, b, CAMERA, "phong", shadows=shadows)


@pytest.mark.parametrize("cull", ["auto", True, False])
def test_instances_cull_as_models(cull, make_renderer):
    """Culling is decided instance by instance (AUTO: a closed mesh wholly beyond the near
    plane): an eye among the instances sees some from inside."""
    t, colors = placements(24, 3)
    a, b = pair(P.box((1.0, 1.0, 1.0)), t, colors)
    eye = g.Camera.look_at(t[0, :3, 3] + (0.05, 0.02, 0.03), (0, 0, 0), near=0.01)
    same(make_renderer(W, H), a, b, eye, "phong", cull=cull)
    ortho = CAMERA.replace(projection="orthographic", height=7.0)
    same(make_renderer(W, H), a, b, ortho, "gouraud", cull=cull)


def test_an_instance_given_another_material_or_hidden_is_drawn_as_such(make_renderer):
    """A model of a group changed after the add (another material, hidden, moved): the
    picture is still the one of the models one by one."""
    t, colors = placements(8, 10)
    a, b = pair(P.icosphere(1, 0.6), t, colors)
    for s in (a, b):
        s.models[3].material = g.Material(color=(0.9, 0.9, 0.1), ks=0.8, shininess=5)
        s.models[5].visible = False
        s.models[6].transform = s.models[6].transform @ np.diag([1.0, 2.0, 1.0, 1.0])
    same(make_renderer(W, H), a, b, CAMERA, "phong")
    a.models[3].material, b.models[3].material = a.models[2].material, b.models[2].material
    a.models[5].visible = b.models[5].visible = True
    same(make_renderer(W, H), a, b, CAMERA, "gouraud")  # (moved: still one draw)


def test_instances_without_colours_and_transparent_ones(make_renderer):
    """No colours: the material's for all. A transparent material: drawn model by model by
    the transparency pass (still the same picture)."""
    t, _ = placements(8, 4, mirror=False)
    a, b = pair(P.icosphere(1, 0.6), t, None)
    same(make_renderer(W, H), a, b, CAMERA, "phong")
    a, b = pair(P.icosphere(1, 0.6), t, None, g.Material(color=(0.2, 0.5, 0.9), opacity=0.5))
    same(make_renderer(W, H), a, b, CAMERA, "phong")


@settings(max_examples=12, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(seed=st.integers(0, 2**16), k=st.integers(2, 40),
       mode=st.sampled_from(["flat", "gouraud", "phong"]))
def test_instances_over_random_placements(seed, k, mode, make_renderer):
    t, colors = placements(k, seed)
    a, b = pair(P.teapot(3), t, colors)
    same(make_renderer(W, H), a, b, CAMERA, mode)


def test_a_group_is_one_draw_call(make_renderer, monkeypatch):
    """The meshes' stage draws K = 200 instances (none mirrored, none seen from inside)
    with one instanced call; added one by one, with 200."""
    calls = []
    original = moderngl.VertexArray.render

    def counted(self, *args, **kwargs):
        calls.append(kwargs.get("instances", 1))
        return original(self, *args, **kwargs)

    t, colors = placements(200, 5, mirror=False)
    t[:, :3, 3] *= 2.0
    a, b = pair(P.icosphere(1, 0.3), t, colors)
    r = make_renderer(W, H)
    r.render(a, CAMERA, "phong")  # (programs compiled, buffers uploaded)
    r.render(b, CAMERA, "phong")
    monkeypatch.setattr(moderngl.VertexArray, "render", counted)
    r.render(a, CAMERA, "phong")
    instanced = list(calls)
    calls.clear()
    r.render(b, CAMERA, "phong")
    culled = r.culled.models  # (instances wholly outside the view are not drawn)
    assert sorted(instanced) == [1, 200 - culled]  # (the floor, then every instance)
    assert len(calls) == 201 - culled


def test_instances_are_objects_of_their_own():
    t, colors = placements(5, 6)
    s = g.Scene()
    s.add(P.box(), g.Material(), label="crate")
    group = s.add(P.icosphere(1), g.Material(), instances=t, colors=colors, label="ball")
    assert len(group) == 5 and list(s.models[1:]) == list(group.models)
    assert [m.instance_id for m in s.models] == [1, 2, 3, 4, 5, 6]
    assert s.labels == {"crate": 1, "ball": 2}
    assert np.array_equal(group.transforms, t)
    assert s.models[3].material.color == tuple(colors[2])


@pytest.mark.parametrize("instances, colors, words", [
    (np.ones((2, 4, 4)), None, "instances[0] is not a finite, invertible matrix"),
    (np.zeros((0, 4, 4)), None, "K >= 1, got shape (0, 4, 4)"),
    (np.eye(4), None, "got shape (4, 4)"),
    (np.tile(np.eye(4), (2, 1, 1)) * [[[1]], [[np.nan]]], None, "instances[1]"),
    (np.tile(np.eye(4), (2, 1, 1)), [[1, 0, 0]], "colors must be (2, 3)"),
    (np.tile(np.eye(4), (2, 1, 1)), [[1, 0, 0], [0, -1, 0]], "colors[1] is (0, -1, 0)"),
    (None, [[1, 0, 0]], "give instances= too"),
])
def test_bad_instances_are_refused_in_one_line(instances, colors, words):
    with pytest.raises(SceneError) as info:
        g.Scene().add(P.box(), instances=instances, colors=colors)
    assert words in str(info.value) and "\n" not in str(info.value)


def test_instances_of_a_solid_are_refused():
    from glshade.solids.leaves import Sphere

    s = g.Scene()
    with pytest.raises(SceneError, match="copies one mesh of one material"):
        s.add(Sphere(1.0), instances=np.tile(np.eye(4), (2, 1, 1)))
    assert not s.models and not s.solids


def test_scene_files_take_instances(tmp_path, make_renderer):
    """``instances = "transforms.npy"`` and a table of matrices, with ``instance_colors``:
    the scene the API makes; a missing file and a wrong shape named in one line."""
    t, colors = placements(6, 7)
    np.save(tmp_path / "t.npy", t)
    np.save(tmp_path / "c.npy", colors)
    table = "[" + ", ".join(str(m.tolist()) for m in t) + "]"
    for key, value in (("instances", '"t.npy"'), ("instances", table)):
        path = tmp_path / "s.toml"
        path.write_text(f'[[mesh]]\nsource = "primitive:torus"\nshininess = 24\n'
                        f'{key} = {value}\ninstance_colors = "c.npy"\n')
        scene = g.load_scene(path).scene
        api = g.Scene()
        api.add(P.torus(), g.Material(shininess=24), instances=t, colors=colors)
        assert len(scene.models) == 6
        r = make_renderer(W, H)
        assert np.array_equal(r.render(scene, CAMERA, "phong"), r.render(api, CAMERA, "phong"))
    path.write_text('[[mesh]]\nsource = "primitive:torus"\ninstances = "none.npy"\n')
    with pytest.raises(g.errors.SceneFormatError, match=r"s.toml:3: .*instances: no such file"):
        g.load_scene(path)
    np.save(tmp_path / "bad.npy", np.eye(4))
    path.write_text('[[mesh]]\nsource = "primitive:torus"\ninstances = "bad.npy"\n')
    with pytest.raises(g.errors.SceneFormatError, match=r"got shape \(4, 4\)"):
        g.load_scene(path)


@settings(max_examples=15, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(azimuth=st.floats(0, 360), elevation=st.floats(-30, 80), distance=st.floats(0.5, 12),
       fov=st.floats(15, 100), instanced=st.booleans())
def test_frustum_culling_never_drops_a_visible_pixel(azimuth, elevation, distance, fov,
                                                      instanced, make_renderer):
    """Culled and unculled frames are the same to the byte (colour, ids, depth) from any
    camera, in or out of a field of 60 parts; what is skipped is counted, and every part
    skipped has no vertex inside the view (numpy's own projection of its vertices)."""
    t, colors = placements(60, 8, mirror=False)
    t[:, :3, 3] *= 2.5
    mesh = P.torus(0.6, 0.22, 12, 6)
    s = g.Scene()
    if instanced:
        s.add(mesh, g.Material(), instances=t, colors=colors)
    else:
        for k in range(len(t)):
            s.add(mesh, g.Material(color=tuple(colors[k])), transform=t[k])
    e, a = np.radians(elevation), np.radians(azimuth)
    eye = distance * np.array([np.cos(e) * np.cos(a), np.sin(e), np.cos(e) * np.sin(a)])
    camera = g.Camera.look_at(eye, eye * 0.2, fov_y=fov, near=0.05, far=40.0)
    r = make_renderer(W, H)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", g.errors.RenderWarning)
        culled = r.render_frame(s, camera, "phong", outputs=g.Outputs.ALL)
        skipped = r.culled.models
        whole = r.render_frame(s, camera, "phong", outputs=g.Outputs.ALL, frustum_cull=False)
        assert r.culled.models == 0
    for name in ("color", "face_id", "instance", "depth"):
        assert np.array_equal(getattr(culled, name), getattr(whole, name)), name
    view_proj = camera.projection_matrix(W / H) @ camera.view_matrix()
    v = np.c_[mesh.vertices, np.ones(mesh.n_vertices)]
    clip = np.einsum("ij,kjl,vl->kvi", view_proj, t, v)  # (K, V, 4)
    w = clip[..., 3:]
    seen = ((np.abs(clip[..., :3]) <= w) & (w > 0)).all(-1).any(1)
    assert skipped <= int((~seen).sum())


@pytest.mark.parametrize("instanced", [True, False])
def test_culling_skips_what_lies_behind(instanced, make_renderer):
    """From inside the field, looking one way through a narrow view, most parts are skipped
    (counted) and the picture is the unculled one."""
    t, colors = placements(60, 9, mirror=False)
    t[:, :3, 3] *= 2.5
    s = g.Scene()
    if instanced:
        s.add(P.icosphere(1, 0.4), g.Material(), instances=t, colors=colors)
    else:
        for k in range(len(t)):
            s.add(P.icosphere(1, 0.4), g.Material(color=tuple(colors[k])), transform=t[k])
    camera = g.Camera.look_at((0, 0, 0), (1, 0, 0), fov_y=30, near=0.05, far=40.0)
    r = make_renderer(W, H)
    culled = r.render_frame(s, camera, "flat", outputs=g.Outputs.ALL)
    assert r.culled.models > 40
    whole = r.render_frame(s, camera, "flat", outputs=g.Outputs.ALL, frustum_cull=False)
    assert np.array_equal(culled.color, whole.color)
    assert np.array_equal(culled.face_id, whole.face_id)
