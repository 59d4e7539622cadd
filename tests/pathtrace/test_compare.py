"""The path tracer as compare's reference: in the same units as the raster modes, so where
the local model is the whole story (direct light, no interreflection, no ambient, a diffuse
surface) the heat map is flat, and where it is not the difference is the light it leaves out."""

import numpy as np
import pytest

from glshade.compare import compare
from glshade.geometry import primitives
from glshade.modes import Outputs
from glshade.pathtrace import TraceScene, trace
from glshade.scene import Camera, DirectionalLight, Material, Scene

pytestmark = pytest.mark.gl


def _lit(mesh, ks=0.0):
    scene = Scene(ambient=(0.0, 0.0, 0.0))
    scene.add(mesh, Material(color=(0.9, 0.8, 0.7), ka=0.0, kd=0.8, ks=ks, shininess=20.0))
    scene.add_light(DirectionalLight(direction=(-0.4, -0.7, -0.6), intensity=1.0))
    return scene


CAMERA = Camera.look_at((2.2, 1.6, 2.6), (0.0, 0.0, 0.0), fov_y=40.0, near=0.5, far=10.0)


@pytest.mark.parametrize("mesh, mode", [(primitives.cube(), "phong"),
                                        (primitives.uv_sphere(24, 48), "phong"),
                                        (primitives.uv_sphere(24, 48), "gouraud")])
def test_direct_diffuse_light_is_what_the_raster_modes_draw(make_renderer, mesh, mode):
    """A convex diffuse object under one directional light: the path-traced reference
    (shaded with the renderer's interpolated vertex normals) equals Phong's picture to
    about one 8-bit level, and Gouraud's to its interpolation error."""
    r = make_renderer(96, 96, samples=0)
    result = compare(_lit(mesh), CAMERA, (mode,), "pathtrace", renderer=r, size=(96, 96),
                     spp=16)
    m = result.metrics[0]
    assert result.reference_kind == "path traced (16 spp)"
    assert m.pixels > 2000 and m.mean_abs < (1.5 if mode == "phong" else 3.0), m


def test_the_path_tracer_adds_the_light_the_local_model_leaves_out(make_renderer):
    """Inside a box open to the light the walls light each other: the path-traced
    reference is brighter than Phong's direct light (the side walls, edge-on to the light,
    get none of it)."""
    from glshade import Mesh

    box = primitives.cube().flipped()
    open_box = Mesh(box.vertices, [f for f, c in zip(box.faces, box.face_centroids)
                                   if c[2] < 0.4])  # (no wall behind the camera)
    scene = _lit(open_box)
    scene.lights = [DirectionalLight(direction=(0.0, 0.0, -1.0))]
    cam = Camera.look_at((0.0, 0.0, 0.45), (0.0, 0.0, -1.0), fov_y=70.0, near=0.01, far=5.0)
    r = make_renderer(64, 64, samples=0)
    result = compare(scene, cam, ("phong",), "pathtrace", renderer=r, size=(64, 64), spp=64)
    ours, theirs = result.images["phong"].astype(float), result.reference.astype(float)
    assert (theirs - ours)[8:56, 8:56].mean() > 5  # (interreflection, 8-bit levels)


def test_smooth_shading_normals_follow_the_renderer(gl_context):
    """With smooth=True a sphere's shading is the interpolated normals' (no facets): on a
    coarse sphere, neighbouring pixels differ far less than with the flat triangles."""
    scene = _lit(primitives.uv_sphere(8, 16))
    flat = trace(TraceScene.from_scene(scene), CAMERA, (64, 64), spp=4, context=gl_context,
                 progress=False)
    smooth = trace(TraceScene.from_scene(scene, smooth=True), CAMERA, (64, 64), spp=4,
                   context=gl_context, progress=False)

    def constant(image):
        """The share of lit neighbours with equal values: a flat facet under a directional
        light is one value (no noise: no other surface), smooth normals vary everywhere."""
        lum = image.mean(-1)
        inside = (lum[:, 1:] > 0.05) & (lum[:, :-1] > 0.05)
        return (np.abs(np.diff(lum, axis=1))[inside] < 1e-5).mean()

    assert constant(flat.image) > 0.4 and constant(smooth.image) < 0.05, (
        constant(flat.image), constant(smooth.image))


def test_a_csg_solid_is_traced_by_the_raster_pass_s_own_ray_casting(make_renderer):
    """A convex CSG solid (a box and a sphere intersected) under a directional light: the
    path tracer's direct light (the exact normals of csg.glsl, its hits the raster pass's)
    equals Phong's picture of it away from the silhouette. Over a floor, its shadow is
    darker than Phong draws it (the raster has no shadows)."""
    from glshade.solids import Box, Sphere

    solid = Box((1.6, 1.6, 1.6)) & Sphere(1.0)
    matte = Material(color=(0.9, 0.8, 0.7), ka=0.0, kd=0.8, ks=0.0)
    alone = Scene(ambient=(0.0, 0.0, 0.0))
    alone.add(solid, matte)
    alone.add_light(DirectionalLight(direction=(-0.4, -0.7, -0.6)))
    r = make_renderer(96, 96, samples=0)
    result = compare(alone, CAMERA, ("phong",), "pathtrace", renderer=r, size=(96, 96),
                     spp=16)
    m = result.metrics[0]
    assert m.pixels > 1500 and m.mean_abs < 2.5, m

    floor = primitives.plane(6.0)
    scene = _lit(floor)
    scene.models[0].transform = np.array([[1, 0, 0, 0], [0, 0, 1, -1.0], [0, -1, 0, 0],
                                          [0, 0, 0, 1.0]])  # (y = -1, facing up)
    scene.add(solid, matte)
    result = compare(scene, CAMERA, ("phong",), "pathtrace", renderer=r, size=(96, 96),
                     spp=16)
    frame = r.render_frame(scene, CAMERA, "phong", outputs=Outputs.FACE_ID)
    on_floor = frame.face_id == 0
    ours, theirs = result.images["phong"].astype(float), result.reference.astype(float)
    assert ((theirs - ours)[on_floor].mean(-1) < -20).sum() > 30  # (its shadow, in view)


def test_two_solids_or_an_emitting_solid_are_refused():
    from glshade.errors import SceneError
    from glshade.solids import Sphere

    scene = _lit(primitives.cube())
    scene.add(Sphere(1.0), Material(emission=(1, 1, 1)), name="lamp")
    with pytest.raises(SceneError, match="lamp: a CSG solid cannot emit"):
        TraceScene.from_scene(scene)
    scene = _lit(primitives.cube())
    scene.add(Sphere(1.0))
    scene.add(Sphere(0.5))
    with pytest.raises(SceneError, match=r"one CSG solid, the scene has 2: make them one"):
        TraceScene.from_scene(scene)
