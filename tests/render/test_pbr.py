"""glTF's metallic-roughness model (PBRMaterial) against the BRDF of the glTF 2.0
specification's Appendix B written out here in float64 numpy: Phong at every pixel centre
of a finely tessellated sphere (the ray met with the exact sphere, its exact normal),
Gouraud as the BRDF at a coarse sphere's vertices interpolated barycentrically, flat as the
BRDF once at each polygon's centre -- under directional and point lights, over metallic
and roughness from 0 to 1 (hypothesis), within 2/255 (linear) away from the silhouette."""

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from glshade import Camera, DirectionalLight, Mesh, PointLight, Scene
from glshade.errors import SceneError
from glshade.geometry import primitives as P
from glshade.scene.pbr import PBRMaterial
from tests.oracle.neighbours import inside_regions

pytestmark = pytest.mark.gl

W = H = 80
EYE = np.array([0.6, 0.9, 3.6])
CAMERA = Camera.look_at(eye=tuple(EYE), target=(0.0, 0.0, 0.0), fov_y=38.0)
AMBIENT = np.array([0.05, 0.04, 0.03])
BASE = np.array([0.9, 0.55, 0.3])
KA = 0.2  # (PBRMaterial's default: the notes' ambient coefficient)
LIGHTS = {"directional": DirectionalLight(direction=(-0.4, -0.7, -0.6), intensity=2.5,
                                          color=(1.0, 0.95, 0.9)),
          "point": PointLight(position=(1.8, 2.4, 2.2), intensity=14.0)}


def appendix_b(n, to_light, v, base, metallic, roughness):
    """f(l, v) N.L, the specification's formulas, float64, per row."""
    nl = np.einsum("ij,ij->i", n, to_light)
    nv = np.maximum(np.einsum("ij,ij->i", n, v), 1e-4)
    h = to_light + v
    h /= np.linalg.norm(h, axis=1, keepdims=True)
    nh = np.maximum(np.einsum("ij,ij->i", n, h), 0)
    vh = np.maximum(np.einsum("ij,ij->i", v, h), 0)
    alpha = roughness ** 2
    a2 = alpha ** 2
    f0 = 0.04 * (1 - metallic) + base * metallic
    fresnel = f0 + (1 - f0) * ((1 - vh) ** 5)[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = np.pi * (nh ** 2 * (a2 - 1) + 1) ** 2
        dist = np.where(denom > 0, a2 / np.where(denom > 0, denom, 1.0), 0.0)
        nlc = np.maximum(nl, 0)
        vis = 0.5 / (nlc * np.sqrt(nv ** 2 * (1 - a2) + a2) + nv * np.sqrt(nlc ** 2 * (1 - a2)
                                                                          + a2))
    diffuse = (1 - fresnel) * (1 - metallic) * base / np.pi
    f = diffuse + fresnel * (dist * vis)[:, None]
    return np.where((nl > 0)[:, None], f * nl[:, None], 0.0)


def radiance(p, n, base, metallic, roughness, light):
    """Outgoing radiance at points ``p`` with normals ``n``: the light through the BRDF
    (lux, or candela / d^2) plus ka x the ambient x base colour."""
    v = EYE - p
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    ip = np.asarray(light.color) * light.intensity
    if isinstance(light, DirectionalLight):
        l = np.broadcast_to(-np.asarray(light.direction), p.shape)  # noqa: E741
        k = np.ones(len(p))
    else:
        to = np.asarray(light.position) - p
        d2 = np.einsum("ij,ij->i", to, to)
        l = to / np.sqrt(d2)[:, None]  # noqa: E741
        k = 1 / d2
    return KA * AMBIENT * base + k[:, None] * ip * appendix_b(n, l, v, base, metallic,
                                                              roughness)


def scene_of(mesh, material, light):
    s = Scene(ambient=tuple(AMBIENT), background=(0, 0, 0))
    s.add(mesh, material)
    s.add_light(light)
    return s


def sphere_hits():
    """Pixel rays met with the exact unit sphere: ``(hit (H, W), p (H, W, 3))``."""
    o, d = CAMERA.rays((W, H))
    b = np.einsum("...k,...k", o, d)
    c = np.einsum("...k,...k", o, o) - 1
    disc = b * b - c
    t = -b - np.sqrt(np.maximum(disc, 0))
    return disc > 0, o + t[..., None] * d


@settings(max_examples=10, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(metallic=st.floats(0, 1), roughness=st.floats(0, 1),
       light=st.sampled_from(sorted(LIGHTS)))
def test_phong_is_appendix_b_at_every_pixel(make_renderer, metallic, roughness, light):
    sphere = P.uv_sphere(96, 192)
    material = PBRMaterial(base_color=tuple(BASE), metallic=metallic, roughness=roughness)
    r = make_renderer(W, H, samples=0)
    got = r.render_frame(scene_of(sphere, material, LIGHTS[light]), CAMERA, "phong",
                         color_dtype="f4").color[..., :3]
    hit, p = sphere_hits()
    n = p / np.linalg.norm(p, axis=-1, keepdims=True)
    v = EYE - p
    v /= np.linalg.norm(v, axis=-1, keepdims=True)
    away = hit & (np.einsum("...k,...k", n, v) > 0.25)  # (away from the silhouette)
    want = np.clip(radiance(p[away], n[away], BASE, metallic, roughness, LIGHTS[light]), 0, 1)
    diff = np.abs(got[away] - want)
    # (a mirror-like highlight is a few pixels whose normal the tessellation still bends:
    # at roughness below 0.1 the 99.5th percentile holds the bound)
    bound = np.quantile(diff, 0.995) if roughness < 0.1 else diff.max()
    assert bound <= 2 / 255, (bound * 255, metallic, roughness, light)
    assert away.sum() > 0.3 * W * H


def triangle_hits(mesh):
    """Each pixel's nearest triangle of ``mesh`` (-1: none) and its barycentrics."""
    o, d = CAMERA.rays((W, H))
    o, d = o.reshape(-1, 3), d.reshape(-1, 3)
    corners = mesh.vertices[mesh.triangles[0]]
    p0, e1, e2 = corners[:, 0], corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
    best = np.full(len(o), np.inf)
    which = np.full(len(o), -1)
    bary = np.zeros((len(o), 3))
    for s in range(0, len(o), 256):
        dd, oo = d[s:s + 256, None], o[s:s + 256, None]
        pv = np.cross(dd, e2)
        det = np.einsum("rtk,tk->rt", pv, e1)
        with np.errstate(divide="ignore", invalid="ignore"):
            sv = oo - p0
            u = np.einsum("rtk,rtk->rt", sv, pv) / det
            qv = np.cross(sv, e1)
            w = np.einsum("rtk,rtk->rt", dd, qv) / det
            t = np.einsum("rtk,tk->rt", qv, e2) / det
        ok = (u >= 0) & (w >= 0) & (u + w <= 1) & (t > 0)
        t = np.where(ok, t, np.inf)
        k = t.argmin(1)
        rows = np.arange(len(k))
        found = np.isfinite(t[rows, k])
        which[s:s + 256] = np.where(found, k, -1)
        best[s:s + 256] = t[rows, k]
        bary[s:s + 256] = np.stack([1 - u[rows, k] - w[rows, k], u[rows, k], w[rows, k]], 1)
    return which.reshape(H, W), bary.reshape(H, W, 3)


@pytest.mark.parametrize("light", sorted(LIGHTS))
@pytest.mark.parametrize("mode", ["gouraud", "flat"])
def test_gouraud_and_flat_evaluate_it_where_the_notes_model_is(make_renderer, mode, light):
    """Gouraud: the BRDF at each vertex (its own normal and view), interpolated; flat: once
    a polygon, at its centre with its Newell normal."""
    sphere = P.uv_sphere(12, 24)
    mesh = Mesh(sphere.vertices, sphere.faces)  # (normals: unit positions, computed here)
    metallic, roughness = 0.3, 0.45
    material = PBRMaterial(base_color=tuple(BASE), metallic=metallic, roughness=roughness)
    r = make_renderer(W, H, samples=0)
    got = r.render_frame(scene_of(mesh, material, LIGHTS[light]), CAMERA, mode,
                         color_dtype="f4").color[..., :3]
    which, bary = triangle_hits(mesh)
    tri, owner = mesh.triangles
    seen = which >= 0
    inside = inside_regions(which if mode == "gouraud" else np.where(seen, owner[which], -1))
    inside &= seen
    if mode == "gouraud":
        v = mesh.vertices
        normals = v / np.linalg.norm(v, axis=1, keepdims=True)  # (a sphere's vertex normals)
        at_vertices = np.clip(radiance(v, normals, BASE, metallic, roughness, LIGHTS[light]),
                              0, None)
        want = np.einsum("hwc,hwck->hwk", bary, at_vertices[tri[np.maximum(which, 0)]])
    else:
        faces = [np.asarray(f) for f in sphere.faces]
        centres = np.array([mesh.vertices[f].mean(0) for f in faces])
        newell = np.array([np.cross(mesh.vertices[f], mesh.vertices[np.roll(f, -1)]).sum(0)
                           for f in faces])
        newell /= np.linalg.norm(newell, axis=1, keepdims=True)
        per_polygon = radiance(centres, newell, BASE, metallic, roughness, LIGHTS[light])
        want = per_polygon[owner[np.maximum(which, 0)]]
    want = np.clip(want, 0, 1)
    diff = np.abs(got - want)[inside]
    assert inside.sum() > 400
    assert diff.max() <= 2 / 255, (mode, light, diff.max() * 255)


def test_emission_and_vertex_colours_take_their_places(make_renderer):
    """The emissive colour adds as it is; a mesh's colours multiply the base colour (here,
    a dark light: the ambient term alone, ka Ia x base x C)."""
    sphere = P.uv_sphere(12, 24)
    colors = np.random.default_rng(1).uniform(0.2, 1, (sphere.n_vertices, 3))
    mesh = Mesh(sphere.vertices, sphere.faces, colors=colors)
    dark = DirectionalLight(direction=(0, -1, 0), intensity=0.0)
    r = make_renderer(W, H, samples=0)
    material = PBRMaterial(base_color=tuple(BASE), emissive=(0.1, 0.2, 0.05))
    frame = r.render_frame(scene_of(mesh, material, dark), CAMERA, "flat", color_dtype="f4")
    polygons = frame.face_id[frame.face_id >= 0]
    got = frame.color[..., :3][frame.face_id >= 0]
    means = np.array([colors[np.asarray(f)].mean(0) for f in sphere.faces])
    want = KA * AMBIENT * BASE * means[polygons] + (0.1, 0.2, 0.05)
    assert np.abs(got - want).max() <= 1e-5


def test_bad_factors_are_refused_naming_them():
    with pytest.raises(SceneError, match="metallic must be in"):
        PBRMaterial(metallic=1.5)
    with pytest.raises(SceneError, match="roughness must be a non-negative"):
        PBRMaterial(roughness=-0.1)
    with pytest.raises(SceneError, match="base_color must be 3 numbers in"):
        PBRMaterial(base_color=(2, 0, 0))


def test_a_scene_file_gives_a_mesh_glTFs_material(tmp_path):
    from glshade import load_scene
    from glshade.errors import SceneFormatError

    (tmp_path / "gold.toml").write_text(
        '[[mesh]]\nsource = "primitive:uv_sphere"\n'
        'pbr = { base_color = [0.9, 0.6, 0.2], metallic = 1.0, roughness = 0.3 }\n')
    (model,) = load_scene(tmp_path / "gold.toml").scene.models
    assert model.material == PBRMaterial(base_color=(0.9, 0.6, 0.2), metallic=1.0,
                                         roughness=0.3)
    (tmp_path / "both.toml").write_text(
        '[[mesh]]\nsource = "primitive:uv_sphere"\nks = 0.5\npbr = { metallic = 1.0 }\n')
    with pytest.raises(SceneFormatError, match=r"both.toml:\d+: \[\[mesh\]\] 1 key 'pbr' and "
                                               r"'ks' are two lighting models"):
        load_scene(tmp_path / "both.toml")
    (tmp_path / "odd.toml").write_text(
        '[[mesh]]\nsource = "primitive:uv_sphere"\npbr = { sheen = 1.0 }\n')
    with pytest.raises(SceneFormatError, match="unknown factor 'sheen'"):
        load_scene(tmp_path / "odd.toml")


def _quad_hits(vertices, faces, uv):
    """Per pixel: the triangle hit (-1: none), the hit point and its barycentrics."""
    o, d = CAMERA.rays((W, H))
    o, d = o.reshape(-1, 3), d.reshape(-1, 3)
    which = np.full(len(o), -1)
    bary = np.zeros((len(o), 3))
    for k, f in enumerate(faces):
        p0, p1, p2 = vertices[f]
        e1, e2 = p1 - p0, p2 - p0
        pv = np.cross(d, e2)
        det = pv @ e1
        s = o - p0
        u = (s * pv).sum(1) / det
        q = np.cross(s, e1)
        w = (d * q).sum(1) / det
        hit = (u >= 0) & (w >= 0) & (u + w <= 1) & ((q @ e2) / det > 0)
        which[hit] = k
        bary[hit] = np.stack([1 - u - w, u, w], 1)[hit]
    return which.reshape(H, W), bary.reshape(H, W, 3)


@pytest.mark.parametrize("mode", ["phong", "gouraud", "flat"])
def test_maps_are_read_where_the_scheme_lights(make_renderer, mode):
    """glTF's maps (a 3x3 base colour map, a metallic-roughness map, nearest texels) are
    read at the pixel (Phong), the vertices (Gouraud), a polygon's centre (flat), and the
    BRDF evaluated there with them, against Appendix B here."""
    from glshade import Texture

    vertices = np.array([[-1.2, -0.9, 0.3], [1.1, -1.0, -0.2], [1.0, 1.0, -0.4],
                         [-1.1, 0.9, 0.1]])
    uv = np.array([[0.02, 0.03], [0.97, 0.01], [0.98, 0.99], [0.01, 0.96]])
    faces = np.array([[0, 1, 2], [0, 2, 3]])
    mesh = Mesh(vertices, faces, uv=uv[faces.ravel()])
    rng = np.random.default_rng(8)
    base_texels = rng.integers(30, 250, (3, 3, 3)).astype(np.uint8)
    mr_texels = np.zeros((3, 3, 3), np.uint8)
    mr_texels[..., 1] = rng.integers(60, 250, (3, 3))   # roughness (G)
    mr_texels[..., 2] = rng.integers(0, 256, (3, 3))    # metallic (B)
    material = PBRMaterial(base_color=(0.9, 0.8, 1.0), metallic=0.8, roughness=0.9,
                           base_color_texture=Texture(base_texels, filter="nearest"),
                           metallic_roughness_texture=Texture(mr_texels, filter="nearest"))
    light = LIGHTS["directional"]
    r = make_renderer(W, H, samples=0)
    got = r.render_frame(scene_of(mesh, material, light), CAMERA, mode,
                         color_dtype="f4").color[..., :3]

    def decode(c):
        c = c / 255.0
        return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)

    def at(uvs, points, normal):
        """The model's radiance at ``points`` with the maps read at ``uvs``."""
        i = np.clip((uvs[:, 0] * 3).astype(int), 0, 2)
        j = 2 - np.clip((uvs[:, 1] * 3).astype(int), 0, 2)  # (row 0 is the image's top)
        base = np.array([0.9, 0.8, 1.0]) * decode(base_texels[j, i].astype(float))
        metallic = 0.8 * mr_texels[j, i, 2] / 255.0
        roughness = 0.9 * mr_texels[j, i, 1] / 255.0
        n = np.broadcast_to(normal, points.shape)
        out = np.empty((len(points), 3))
        for k in range(len(points)):  # (one texel's factors at a time: a handful of values)
            out[k] = radiance(points[k:k + 1], n[k:k + 1], base[k], metallic[k],
                              roughness[k], light)[0]
        return out

    which, bary = _quad_hits(vertices, faces, uv)
    normal = np.cross(vertices[1] - vertices[0], vertices[2] - vertices[0])
    normal /= np.linalg.norm(normal)
    normal = normal if normal @ (EYE - vertices[0]) > 0 else -normal
    seen = which >= 0
    tri_uv = uv[faces[np.maximum(which, 0)]]
    tri_p = vertices[faces[np.maximum(which, 0)]]
    pixel_uv = np.einsum("hwc,hwck->hwk", bary, tri_uv)
    if mode == "phong":
        p = np.einsum("hwc,hwck->hwk", bary, tri_p)[seen]
        want = at(pixel_uv[seen], p, normal)
        texel = np.where(seen, (pixel_uv[..., 0] * 3).astype(int) * 3 +
                         (pixel_uv[..., 1] * 3).astype(int), -1)
        inside = inside_regions(texel)[seen]
    elif mode == "gouraud":
        corners = at(uv, vertices, normal)
        want = np.einsum("hwc,hwck->hwk", bary, corners[faces[np.maximum(which, 0)]])[seen]
        inside = inside_regions(which)[seen]
    else:
        centres = np.array([uv[f].mean(0) for f in faces])
        middles = np.array([vertices[f].mean(0) for f in faces])
        per_face = at(centres, middles, normal)
        want = per_face[which[seen]]
        inside = inside_regions(which)[seen]
    diff = np.abs(got[seen] - np.clip(want, 0, 1))[inside]
    assert inside.sum() > 500
    assert diff.max() <= 2 / 255, (mode, diff.max() * 255)


def test_compare_draws_the_schemes_in_glTFs_model_too(make_renderer):
    """``compare(..., modes=["phong", "pbr-phong"])``: the second tile is the scene in glTF's
    model -- the Material as PBRMaterial.like makes it (base = C, metallic 0, roughness from
    n by alpha^2 = 2 / (n + 2)), a directional light x pi -- against Appendix B here."""
    from glshade import compare

    n = 24.0
    color = np.array([0.7, 0.5, 0.3])
    scene = Scene(ambient=tuple(AMBIENT), background=(0, 0, 0))
    scene.add(P.uv_sphere(96, 192), g_material(color, n))
    light = DirectionalLight(direction=(-0.4, -0.7, -0.6), intensity=0.8)
    scene.add_light(light)
    r = make_renderer(W, H, samples=0)
    result = compare(scene, CAMERA, ["phong", "pbr-phong"], renderer=r, diff=False,
                     size=(W, H))
    got = result.images["pbr-phong"].astype(float) / 255
    hit, p = sphere_hits()
    normals = p / np.linalg.norm(p, axis=-1, keepdims=True)
    v = EYE - p
    v /= np.linalg.norm(v, axis=-1, keepdims=True)
    away = hit & (np.einsum("...k,...k", normals, v) > 0.25)
    roughness = (2 / (n + 2)) ** 0.25
    scaled = DirectionalLight(direction=light.direction, intensity=0.8 * np.pi)
    want = np.clip(radiance(p[away], normals[away], color, 0.0, roughness, scaled), 0, 1)
    assert np.abs(got[away][:, :3] - want).max() <= 3 / 255
    assert [m.mode for m in result.metrics] == ["phong", "pbr-phong"]


def g_material(color, n):
    from glshade import Material

    return Material(color=tuple(color), shininess=n)


@pytest.mark.parametrize("mode", ["phong", "flat"])
def test_a_normal_map_bends_the_normal_in_the_uv_frame(make_renderer, mode):
    """A square whose normal map holds one tilted normal everywhere (tangent space: x along
    increasing u, y along increasing v): lit as a surface with that normal -- Appendix B here
    with n = 0.48 t + 0.36 b + 0.8 N -- at every pixel (Phong), once at the centre (flat)."""
    from glshade import Texture

    tilt = np.array([0.48, 0.36, 0.8])
    texel = np.round((tilt * 0.5 + 0.5) * 255).astype(np.uint8)
    normal_map = Texture(np.broadcast_to(texel, (4, 4, 3)).copy(), filter="nearest")
    vertices = np.array([[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [1.0, 1.0, 0.0],
                         [-1.0, 1.0, 0.0]])
    uv = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    mesh = Mesh(vertices, [[0, 1, 2, 3]], uv=uv)
    material = PBRMaterial(base_color=tuple(BASE), metallic=0.2, roughness=0.5,
                           normal_texture=normal_map)
    light = LIGHTS["directional"]
    r = make_renderer(W, H, samples=0)
    frame = r.render_frame(scene_of(mesh, material, light), CAMERA, mode, color_dtype="f4")
    decoded = texel / 255.0 * 2 - 1  # (what the 8-bit map holds)
    bent = decoded.astype(float)  # (the square's u runs along x, v along y, N is z)
    bent /= np.linalg.norm(bent)
    o, d = CAMERA.rays((W, H))
    p = o + (-o[..., 2] / d[..., 2])[..., None] * d
    seen = (frame.face_id == 0) & inside_regions(frame.face_id)
    if mode == "phong":
        points = p[seen]
    else:
        points = np.zeros((1, 3))  # (the square's centre)
    n = np.broadcast_to(bent, points.shape)
    want = radiance(points, n, BASE, 0.2, 0.5, light)
    got = frame.color[..., :3][seen]
    assert seen.sum() > 500
    assert np.abs(got - np.clip(want, 0, 1)).max() <= 2 / 255
