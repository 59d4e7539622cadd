"""Program variants: the flat-constant Phong programs a software rasterizer gets for large
triangles draw the same pictures as the uniform ones a GPU gets."""

import numpy as np
import pytest

from glshade import Camera
from glshade.geometry import primitives as P
from glshade.modes import ShadingMode
from glshade.render.programs import FLAT_CONSTANTS_PIXELS, ProgramKey, flat_constants_fit
from glshade.scene import DirectionalLight, Material, PointLight, Scene

CAMERA = Camera.look_at([0.6, 0.9, 3.0], [0, 0, 0], fov_y=45.0)
MAT = Material(color=(0.9, 0.6, 0.3), ka=0.2, kd=0.6, ks=0.5, shininess=24)
LIGHT_SETS = {
    "directional": [DirectionalLight((-1.0, -1.0, -1.0))],
    "three kinds": [PointLight((2.0, 3.0, 4.0), color=(1.0, 0.8, 0.6)),
                    PointLight((-2.0, 1.0, 2.0), intensity=0.6, attenuation=(1.0, 0.1, 0.05)),
                    DirectionalLight((0.5, -1.0, -0.3), color=(0.3, 0.5, 1.0))],
    "eight attenuated": [PointLight((np.cos(a) * 3, 1.0, np.sin(a) * 3), intensity=0.3,
                                    attenuation=(1.0, 0.05, 0.01))
                         for a in np.linspace(0, 2 * np.pi, 8, endpoint=False)],
}


def scene_with(lights):
    s = Scene(ambient=(0.8, 0.9, 1.0))
    s.add(P.icosphere(2), MAT)  # 320 triangles: large ones, at 224x224
    s.add(P.plane(4.0), Material(color=(0.4, 0.7, 0.5), ks=0.3, shininess=8),
          transform=np.array([[1, 0, 0, 0], [0, 0, 1, -1.0], [0, -1, 0, 0], [0, 0, 0, 1.0]]))
    for light in lights:
        s.add_light(light)
    return s


@pytest.mark.parametrize("lights", list(LIGHT_SETS), ids=list(LIGHT_SETS))
@pytest.mark.parametrize("camera", ["perspective", "orthographic"])
def test_flat_constants_draw_what_uniforms_draw(make_renderer, lights, camera):
    scene = scene_with(LIGHT_SETS[lights])
    cam = CAMERA if camera == "perspective" else CAMERA.replace(projection="orthographic")
    r = make_renderer(224, 224)
    assert 320 * FLAT_CONSTANTS_PIXELS <= 224 * 224
    frames = {}
    for flat in (False, True):
        r.flat_constants = flat
        for cull in ("auto", False):  # (the open plane is two-sided either way)
            frames[flat, cull] = r.render_frame(scene, cam, "phong", color_dtype="f4",
                                                cull_back_faces=cull)
            frames[flat, cull, "plain"] = r.render(scene, cam, "phong", cull_back_faces=cull)
    for key in [("auto",), (False,)]:
        a, b = frames[(False, *key)], frames[(True, *key)]
        assert (a.face_id >= 0).mean() > 0.3  # a real picture
        np.testing.assert_allclose(b.color, a.color, atol=2e-6)
        np.testing.assert_array_equal(b.face_id, a.face_id)
        np.testing.assert_array_equal(b.depth, a.depth)
        np.testing.assert_allclose(b.normal, a.normal, atol=1e-6)
        plain = np.abs(frames[(True, *key, "plain")].astype(int) -
                       frames[(False, *key, "plain")].astype(int))
        assert plain.max() <= 1 and (plain > 0).mean() < 1e-3

    # the flat variant was really drawn where it fits this GL's varyings, and only there
    used = {k.flat_constants for k in r.shaders.compiled if k.mode is ShadingMode.PHONG}
    n = len(LIGHT_SETS[lights])
    kinds = ("ATTENUATED",) * n if lights == "eight attenuated" else ("POINT",) * n
    fits = flat_constants_fit(ShadingMode.PHONG, False, kinds, r.meshes.max_varyings)
    assert used == ({False, True} if fits else {False})


def test_flat_constants_only_for_large_triangles(make_renderer):
    """Small triangles keep the uniforms: their setup would cost more than it saves."""
    scene = scene_with(LIGHT_SETS["directional"])
    r = make_renderer(64, 64)
    r.flat_constants = True
    r.render(scene, CAMERA, "phong")
    flat = {k.flat_constants: k for k in r.shaders.compiled if k.mode is ShadingMode.PHONG}
    assert set(flat) == {False, True}  # the sphere's program, and the two-triangle plane's
    assert flat[True].two_sided and not flat[False].two_sided  # (the plane is open)


def test_flat_constants_are_for_phong_only_and_counted_in_varyings():
    phong, gouraud = ShadingMode.PHONG, ShadingMode.GOURAUD
    # position and normal, ambient and n, then 3 vectors a light (4 with attenuation)
    assert flat_constants_fit(phong, False, ("DIRECTIONAL",), 6)
    assert not flat_constants_fit(phong, True, ("DIRECTIONAL",), 6)  # + the world normal
    assert flat_constants_fit(phong, False, ("POINT",) * 4, 15)  # GL 3.3's minimum
    assert not flat_constants_fit(phong, False, ("POINT", "ATTENUATED") * 2, 15)
    assert not flat_constants_fit(gouraud, False, ("POINT",), 32)
    assert "FLAT_CONSTANTS" in ProgramKey(phong, flat_constants=True).defines()
    assert "FLAT_CONSTANTS" not in ProgramKey(gouraud, flat_constants=True).defines()
    assert "FLAT_CONSTANTS" not in ProgramKey(phong).defines()


def test_a_new_scene_of_the_same_kind_compiles_nothing(make_renderer):
    """Programs are compiled from what a draw needs (mode, light kinds, outputs), never from
    a scene's numbers: a second scene with other meshes, materials, light places and colours
    and the same kinds of lights draws with the programs the first compiled -- one source,
    which a driver's shader cache serves across processes too."""
    r = make_renderer(32, 32)
    r.render_frame(scene_with(LIGHT_SETS["three kinds"]), CAMERA, "phong")
    compiled = []
    make = r.ctx.program
    r.ctx.program = lambda *a, **k: compiled.append(1) or make(*a, **k)
    try:
        other = Scene(ambient=(0.1, 0.3, 0.2))
        other.add(P.uv_sphere(9, 17), Material(color=(0.1, 0.2, 0.9), ks=0.9, shininess=90),
                  translation=(0.4, 0.1, -0.3))
        other.add(P.cube(), Material(color=(0.7, 0.7, 0.1), kd=0.3), scale=0.4)
        for light in (PointLight((-3.0, 2.0, 1.0), color=(0.2, 1.0, 0.4)),
                      PointLight((1.0, -2.0, 5.0), intensity=2.0, attenuation=(1.0, 0.3, 0.2)),
                      DirectionalLight((-0.2, -1.0, 0.6))):
            other.add_light(light)
        r.render_frame(other, Camera.look_at([2.0, 1.0, 3.0], [0, 0, 0]), "phong")
        assert compiled == []
        other.add_light(PointLight((0.0, 4.0, 0.0)))  # (another light: another program)
        r.render_frame(other, Camera.look_at([2.0, 1.0, 3.0], [0, 0, 0]), "phong")
        assert compiled
    finally:
        r.ctx.program = make
