"""glTF's metallic-roughness model in the path tracer: direct light from punctual lights on
a ball against the Appendix B BRDF in float64 (the rasterizer's oracle, written in
tests/render/test_pbr.py, averaged over each pixel as the tracer's jittered camera rays
average it), in radiosity units (pi x radiance); the lobes' sampling unbiased (a rough
metal's picture with GGX's visible normals against the same with cosine sampling alone);
and the parts it does not trace refused in one line."""

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from glshade import Mesh, PBRMaterial
from glshade.errors import SceneError
from glshade.geometry import primitives as P
from glshade.pathtrace import TraceScene, trace
from tests.render.test_pbr import BASE, CAMERA, EYE, LIGHTS, appendix_b, scene_of

pytestmark = pytest.mark.gl

W = H = 40
GRID = 8  # (sub-pixel samples a side: the oracle's mean over each pixel)


def footprint_oracle(metallic, roughness, light):
    """pi x each pixel's mean radiance over its area (GRID x GRID points), the ball exact;
    and the pixels whose every point sees its front well away from the silhouette."""
    offsets = (np.arange(GRID) + 0.5) / GRID - 0.5
    total = np.zeros((H, W, 3))
    inside = np.ones((H, W), bool)
    for dx in offsets:  # (a loop over the GRID^2 sub-pixel offsets, each a whole image)
        for dy in offsets:
            o, d = CAMERA.rays((W, H), jitter=(dx, dy))
            b = np.einsum("...k,...k", o, d)
            disc = b * b - (np.einsum("...k,...k", o, o) - 1)
            t = -b - np.sqrt(np.maximum(disc, 0))
            p = o + t[..., None] * d
            n = p / np.linalg.norm(p, axis=-1, keepdims=True)
            v = EYE - p
            v /= np.linalg.norm(v, axis=-1, keepdims=True)
            inside &= (disc > 0) & (np.einsum("...k,...k", n, v) > 0.3)
            ip = np.asarray(light.color) * light.intensity
            if hasattr(light, "direction"):
                to_light = np.broadcast_to(-np.asarray(light.direction), p.shape)
                k = np.ones(p.shape[:2])
            else:
                to = np.asarray(light.position) - p
                k = 1 / np.einsum("...k,...k", to, to)
                to_light = to * np.sqrt(k)[..., None]
            f = appendix_b(n.reshape(-1, 3), to_light.reshape(-1, 3), v.reshape(-1, 3), BASE,
                           metallic, roughness).reshape(H, W, 3)
            total += np.pi * k[..., None] * ip * f
    return total / GRID ** 2, inside


@settings(max_examples=6, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(metallic=st.floats(0, 1), roughness=st.floats(0.2, 1),
       light=st.sampled_from(sorted(LIGHTS)))
def test_direct_light_is_appendix_b_within_the_reported_error(gl_context, metallic, roughness,
                                                               light):
    material = PBRMaterial(base_color=tuple(BASE), metallic=metallic, roughness=roughness)
    scene = scene_of(P.uv_sphere(96, 192), material, LIGHTS[light])
    # (the renderer's vertex normals: the ball's, not its facets')
    traced = trace(TraceScene.from_scene(scene, smooth=True), CAMERA, (W, H), spp=64,
                   context=gl_context)
    want, inside = footprint_oracle(metallic, roughness, LIGHTS[light])
    got, se = traced.image[inside], traced.se[inside]
    # (the ball's facets move a hit by at most 1 - cos(pi / 192) of its radius)
    slack = 2e-3 * want[inside] + 1e-4
    z = np.abs(got - want[inside]) / (se + slack)
    # each pixel within its error (a few of some 2,000 past 4 se by chance, none past 7),
    # and no bias over the picture: the sums agree within the sum's error
    assert (z > 4).mean() < 0.005 and z.max() < 7, (z.max(), metallic, roughness, light)
    bias = np.abs((got - want[inside]).sum(0))
    assert (bias <= 4 * np.sqrt((se ** 2).sum(0)) + slack.sum(0)).all(), (bias, metallic,
                                                                        roughness, light)
    assert inside.sum() > 0.25 * W * H


def test_the_bounce_and_next_event_estimation_agree(gl_context):
    """A rough gold ball under an emitting panel: the panel's light found by next-event
    estimation and the bounce's GGX visible-normal samples weighed by MIS, against the
    same picture with MIS off (the light by next-event estimation alone, every bounce's
    hit of the panel not counted) -- two estimators of one integral: the same means within
    their errors, which only holds where bounce_pdf is the density sample_bounce draws
    with."""
    from glshade import Material, Scene

    scene = Scene(background=(0, 0, 0))
    scene.add(P.uv_sphere(48, 96), PBRMaterial(base_color=(1.0, 0.77, 0.33), metallic=1.0,
                                               roughness=0.4))
    panel = Mesh([[-1, 2, -1], [1, 2, -1], [1, 2, 1], [-1, 2, 1]], [[0, 1, 2, 3]])
    scene.add(panel, Material(color=(0, 0, 0), kd=0.0, ks=0.0, emission=(4.0, 4.0, 4.0)))
    both = trace(scene, CAMERA, (24, 24), spp=256, context=gl_context, max_depth=2)
    bounce = trace(scene, CAMERA, (24, 24), spp=256, context=gl_context, max_depth=2,
                   mis=False)
    ball = both.image.sum(-1) > 0
    a, b = both.image[ball].mean(0), bounce.image[ball].mean(0)
    sa = np.sqrt((both.se[ball] ** 2).sum(0)) / ball.sum()
    sb = np.sqrt((bounce.se[ball] ** 2).sum(0)) / ball.sum()
    assert (np.abs(a - b) <= 4 * np.hypot(sa, sb)).all(), (a, b, sa, sb)
    assert a.max() > 0.05


def test_colours_on_geometry_are_the_surface_colour_across_each_triangle(gl_context):
    """A diffuse quad of four vertex colours (and a face colour on a second one) under a
    white sky: each pixel pi x L x kd x C, C the corners' colours interpolated across the
    triangle the pixel centre sees (the fan 0-1-2, 0-2-3), pixels clear of the diagonal and
    the edges (where the pixel's area mixes two)."""
    from glshade import Camera, Environment, Material, Scene

    corners = np.array([[1.0, 0.1, 0.1], [0.1, 1.0, 0.1], [0.1, 0.1, 1.0], [1.0, 1.0, 1.0]])
    quad = Mesh([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], [[0, 1, 2, 3]],
                colors=corners, face_colors=[[0.9, 0.8, 0.7]])
    scene = Scene(environment=Environment((0.6, 0.6, 0.6)))
    scene.add(quad, Material(color=(1, 1, 1), kd=0.8, ks=0.0))
    camera = Camera.look_at((0, 0, 3), (0, 0, 0), fov_y=30.0)
    size = 32
    traced = trace(scene, camera, (size, size), spp=64, context=gl_context)
    o, d = camera.rays((size, size))
    p = o + (-o[..., 2] / d[..., 2])[..., None] * d  # (the plane z = 0)
    x, y = p[..., 0], p[..., 1]
    pixel = 2 * 3 * np.tan(np.radians(15)) / size  # (a pixel's side on the quad)
    # the fan's barycentrics: triangle 0-1-2 below the diagonal y = x, 0-2-3 above
    s_, t_ = (x + 1) / 2, (y + 1) / 2
    lower = t_ < s_
    c = np.where(lower[..., None],
                 (1 - s_)[..., None] * corners[0] + (s_ - t_)[..., None] * corners[1] +
                 t_[..., None] * corners[2],
                 (1 - t_)[..., None] * corners[0] + (t_ - s_)[..., None] * corners[3] +
                 s_[..., None] * corners[2])
    want = np.pi * 0.6 * 0.8 * c * [0.9, 0.8, 0.7]
    clear = (np.abs(x - y) > pixel) & (np.abs(x) < 1 - pixel) & (np.abs(y) < 1 - pixel)
    assert clear.sum() > 200
    got, se = traced.image[clear], traced.se[clear]
    z = np.abs(got - want[clear]) / (se + 1e-6)
    assert (z > 4).mean() < 0.01 and z.max() < 7, z.max()
    assert (np.abs((got - want[clear]).sum(0)) <= 4 * np.sqrt((se ** 2).sum(0))).all()


def uv_quad():
    """The square z = 0 from -1 to 1 facing +z, u along +x and v along +y."""
    return Mesh([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], [[0, 1, 2, 3]],
                uv=[[0, 0], [1, 0], [1, 1], [0, 1]])


def quad_pixels(camera, size):
    """Each pixel centre's point (x, y) on the quad z = 0, and a pixel's side there."""
    o, d = camera.rays((size, size))
    p = o + (-o[..., 2] / d[..., 2])[..., None] * d
    return p[..., 0], p[..., 1], 2 * 3 * np.tan(np.radians(15)) / size


def test_a_textured_quad_is_its_texture_times_its_albedo(gl_context):
    """A diffuse quad under a grey sky, its diffuse map 8 x 8 random sRGB texels (nearest):
    each pixel clear of a texel's edge pi x L x kd x the texel, decoded to linear."""
    from glshade import Camera, Environment, Material, Scene, Texture

    rng = np.random.default_rng(5)
    image = rng.integers(0, 256, (8, 8, 3), dtype=np.uint8)
    quad = uv_quad()
    scene = Scene(environment=Environment((0.6, 0.6, 0.6)))
    scene.add(quad, Material(color=(1, 1, 1), kd=0.8, ks=0.0,
                             texture=Texture(image, filter="nearest")))
    camera = Camera.look_at((0, 0, 3), (0, 0, 0), fov_y=30.0)
    traced = trace(scene, camera, (40, 40), spp=64, context=gl_context)
    x, y, pixel = quad_pixels(camera, 40)
    u, v = (x + 1) / 2, (y + 1) / 2
    col, row = np.floor(u * 8).astype(int), np.floor(v * 8).astype(int)
    fx, fy = u * 8 - col, v * 8 - row
    margin = pixel * 4  # (a pixel's side, in texels: 4 = 8 texels / 2 world units)
    clear = ((np.abs(x) < 1 - pixel) & (np.abs(y) < 1 - pixel) & (fx > margin) &
             (fx < 1 - margin) & (fy > margin) & (fy < 1 - margin))
    texel = image[7 - np.clip(row, 0, 7), np.clip(col, 0, 7)] / 255.0  # (row 0: the top)
    linear = np.where(texel <= 0.04045, texel / 12.92, ((texel + 0.055) / 1.055) ** 2.4)
    want = np.pi * 0.6 * 0.8 * linear
    assert clear.sum() > 150
    got, se = traced.image[clear], traced.se[clear]
    z = np.abs(got - want[clear]) / (se + 1e-6)
    assert (z > 4).mean() < 0.01 and z.max() < 7, z.max()
    assert (np.abs((got - want[clear]).sum(0)) <= 4 * np.sqrt((se ** 2).sum(0))).all()


def test_a_metallic_roughness_map_sets_each_texels_lobe(gl_context):
    """glTF's packing read at the hit: a quad's left half metal (B = 255) of roughness 0.5
    (G = 128), its right half dielectric (B = 0) of roughness 1 (G = 255), under a constant
    sky -- each half pi x L x the BRDF's directional albedo at its view, by quadrature."""
    from glshade import Camera, Environment, Scene, Texture
    from tests.pathtrace.test_environment import directional_albedo

    packed = np.zeros((1, 2, 3), np.uint8)
    packed[0, 0], packed[0, 1] = (0, 128, 255), (0, 255, 0)
    quad = uv_quad()
    base = np.array([0.9, 0.7, 0.4])
    scene = Scene(environment=Environment((0.5, 0.5, 0.5)))
    scene.add(quad, PBRMaterial(base_color=tuple(base), metallic=1.0, roughness=1.0,
                                metallic_roughness_texture=Texture(packed, filter="nearest")))
    camera = Camera.look_at((0, 0, 3), (0, 0, 0), fov_y=30.0)
    traced = trace(scene, camera, (32, 32), spp=128, context=gl_context)
    x, y, pixel = quad_pixels(camera, 32)
    inside = (np.abs(y) < 1 - pixel) & (np.abs(x) < 1 - pixel) & (np.abs(x) > pixel)
    o, d = camera.rays((32, 32))
    mu = -d[..., 2]  # (the quad's normal is +z)
    for half, metallic, roughness in ((x < 0, 1.0, 128 / 255), (x > 0, 0.0, 1.0)):
        where = inside & half
        mus = np.linspace(0.9, 1.0, 9)
        table = directional_albedo(mus, base, metallic, roughness)
        want = np.pi * 0.5 * np.stack([np.interp(mu[where], mus, table[:, c])
                                       for c in range(3)], -1)
        got, se = traced.image[where], traced.se[where]
        assert np.abs((got - want).sum(0)).max() <= 4 * np.sqrt((se ** 2).sum(0)).max() + \
            2e-3 * want.sum(0).max(), (metallic, got.mean(0), want.mean(0))


def test_opacity_is_a_thin_surface_passed_with_its_chance(gl_context):
    """A quad of opacity 0.4 before a constant sky: each pixel 0.4 x its own light + 0.6 x
    the sky's (the rasterizer's "over"); and the shadow it casts from a directional light
    on a floor lets 0.6 of the light through -- both by the stochastic cut-out, in the
    mean, within the reported errors."""
    from glshade import Camera, DirectionalLight, Environment, Material, Scene

    quad = Mesh([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], [[0, 1, 2, 3]])
    scene = Scene(environment=Environment((0.8, 0.8, 0.8)))
    scene.add(quad, Material(color=(1, 1, 1), kd=0.5, ks=0.0, opacity=0.4))
    camera = Camera.look_at((0, 0, 3), (0, 0, 0), fov_y=30.0)
    traced = trace(scene, camera, (32, 32), spp=128, context=gl_context)
    x, y, pixel = quad_pixels(camera, 32)
    inside = (np.abs(x) < 1 - pixel) & (np.abs(y) < 1 - pixel)
    want = np.pi * 0.8 * (0.4 * 0.5 + 0.6)
    got, se = traced.image[inside].sum(0), np.sqrt((traced.se[inside] ** 2).sum(0))
    assert (np.abs(got - want * inside.sum()) <= 4 * se).all(), (got / inside.sum(), want)

    shade = Scene()
    floor = Mesh([[-3, 0, -3], [-3, 0, 3], [3, 0, 3], [3, 0, -3]], [[0, 1, 2, 3]])
    shade.add(floor, Material(color=(1, 1, 1), kd=0.5, ks=0.0))
    cover = Mesh([[-1, 1, -1], [-1, 1, 1], [1, 1, 1], [1, 1, -1]], [[0, 1, 2, 3]])
    shade.add(cover, Material(color=(1, 1, 1), kd=0.0, ks=0.0, opacity=0.4))
    shade.add_light(DirectionalLight((0, -1, 0), intensity=2.0))
    above = Camera.look_at((0, 6, 0.01), (0, 0, 0), fov_y=60.0)
    lit = trace(shade, above, (32, 32), spp=128, context=gl_context, max_depth=1)
    o, d = above.rays((32, 32))
    p = o + (-o[..., 1] / d[..., 1])[..., None] * d  # (the floor y = 0)
    under = (np.abs(p[..., 0]) < 0.8) & (np.abs(p[..., 2]) < 0.8)
    open_ = (np.abs(p[..., 0]) > 1.3) & (np.abs(p[..., 2]) < 2.5) & (np.abs(p[..., 0]) < 2.5)
    # (seen from above through the cover: 0.6 of the floor's light, which 0.6 reaches)
    for where, want in ((under, 0.6 * 0.6 * 0.5 * 2.0), (open_, 0.5 * 2.0)):
        got, se = lit.image[where].sum(0), np.sqrt((lit.se[where] ** 2).sum(0))
        assert (np.abs(got - want * where.sum()) <= 4 * se + 1e-6 * where.sum()).all(), (
            got / where.sum(), want)


def test_visible_normals_the_normals_distribution_and_the_hemisphere_draw_one_mean(
        gl_context):
    """A rough gold ball under a constant sky, its light found by next-event estimation
    and by the bounce (MIS): GGX's specular lobe sampled by its visible normals, by D(h)
    N.H, and every bounce uniformly over the hemisphere (no importance at all) give the
    same mean within the errors -- each density is what bounce_pdf says -- and importance
    pays: the visible normals' pixels are the least noisy (their mean standard error,
    measured: 1.26x less than D(h) N.H's, 2.3x less than the hemisphere's, 5.4x fewer
    samples for the same error)."""
    from glshade import Camera, Environment, Scene

    scene = Scene(environment=Environment((0.7, 0.7, 0.7)))
    scene.add(P.uv_sphere(48, 96), PBRMaterial(base_color=(1.0, 0.77, 0.33), metallic=1.0,
                                               roughness=0.6))
    camera = Camera.look_at((0, 0, 3.2), (0, 0, 0), fov_y=45.0)
    ways = ("visible-normals", "normals", "uniform")
    traced = {w: trace(scene, camera, (32, 32), spp=128, context=gl_context,
                       lobe_sampling=w) for w in ways}
    first = traced["visible-normals"].image
    ball = first.sum(-1) != first[0, 0].sum()
    means = {w: t.image[ball].mean(0) for w, t in traced.items()}
    errors = {w: np.sqrt((t.se[ball] ** 2).sum(0)) / ball.sum() for w, t in traced.items()}
    for w in ways[1:]:
        assert (np.abs(means[w] - means[ways[0]]) <= 4 * np.hypot(errors[w], errors[ways[0]])
                ).all(), (w, means, errors)
    noise = {w: t.se[ball].mean() for w, t in traced.items()}
    assert noise["visible-normals"] <= noise["normals"] < noise["uniform"], noise


def test_an_emissive_map_is_seen_and_lights_as_its_texels(gl_context):
    """A glowing tile whose emissive map is red on its left half and blue on its right:
    seen, pi x the factor x each texel (glTF's emission is radiance); lighting a floor, the
    point under its middle gets what a tile of the halves' mean colour gives (the halves
    are mirror images about it) -- next-event estimation reading the map where its point
    falls."""
    from glshade import Camera, Material, Scene, Texture

    halves = np.array([[[255, 0, 0], [0, 0, 255]]], np.uint8)
    tile = Mesh([[-0.5, 1, -0.5], [-0.5, 1, 0.5], [0.5, 1, 0.5], [0.5, 1, -0.5]],
                [[0, 1, 2, 3]], uv=[[0, 0], [0, 1], [1, 1], [1, 0]])
    floor = Mesh([[-3, 0, -3], [-3, 0, 3], [3, 0, 3], [3, 0, -3]], [[0, 1, 2, 3]])
    flipped = Mesh(tile.vertices, [[3, 2, 1, 0]], uv=[[1, 0], [1, 1], [0, 1], [0, 0]])

    def scene_of(glow):
        scene = Scene()
        scene.add(floor, Material(color=(1, 1, 1), kd=0.8, ks=0.0))
        scene.add(flipped, glow)  # (facing down, onto the floor)
        return scene

    mapped = scene_of(PBRMaterial(base_color=(0, 0, 0), emissive=(0.5, 0.5, 0.5),
                                  emissive_texture=Texture(halves, filter="nearest")))
    mean = scene_of(PBRMaterial(base_color=(0, 0, 0), emissive=(0.25, 0.0, 0.25)))
    below = Camera.look_at((0.0, 0.5, 0.0), (0.0, 2.0, 0.0), up=(0, 0, 1), fov_y=60.0)
    seen = trace(mapped, below, (32, 32), spp=16, context=gl_context, max_depth=1)
    o, d = below.rays((32, 32))
    p = o + ((1 - o[..., 1]) / d[..., 1])[..., None] * d  # (the tile's plane y = 1)
    u = p[..., 0] + 0.5  # (the flipped tile's u runs along +x)
    clear = (np.abs(p[..., 0]) < 0.45) & (np.abs(p[..., 2]) < 0.45) & (np.abs(u - 0.5) > 0.05)
    red = np.where((u < 0.5)[..., None], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0])
    assert np.allclose(seen.image[clear], (np.pi * 0.5 * red)[clear], atol=1e-5)
    above = Camera.look_at((0.0, 0.6, 0.01), (0.0, 0.0, 0.0), fov_y=20.0)
    got = [trace(s, above, (8, 8), spp=512, context=gl_context, max_depth=2)
           for s in (mapped, mean)]
    a, b = (g.image[3:5, 3:5].mean((0, 1)) for g in got)
    sa, sb = (np.sqrt((g.se[3:5, 3:5] ** 2).sum((0, 1))) / 4 for g in got)
    assert a[0] > 0.01 and (np.abs(a - b) <= 4 * np.hypot(sa, sb) + 1e-6).all(), (a, b)


def test_a_normal_map_bends_the_normal_in_the_uv_frame(gl_context):
    """A rough white quad facing +z, u along +x and v along +y, its normal map one texel
    (0.6, 0, 0.8) in tangent space (bytes 204, 128, 230): the shading normal (0.6, 0, 0.8)
    in the world; lit straight down its face, each pixel pi x Appendix B's f cos at that
    normal (a directional light: no noise but the pixel's jitter)."""
    from glshade import Camera, DirectionalLight, Scene, Texture

    texel = np.array([[[204, 128, 230]]], np.uint8)
    bent = texel[0, 0] / 255.0 * 2 - 1
    quad = uv_quad()
    scene = Scene()
    scene.add(quad, PBRMaterial(base_color=(0.8, 0.8, 0.8), metallic=0.0, roughness=1.0,
                                normal_texture=Texture(texel, filter="nearest")))
    scene.add_light(DirectionalLight((0, 0, -1), intensity=2.0))
    camera = Camera.look_at((0, 0, 3), (0, 0, 0), fov_y=30.0)
    traced = trace(scene, camera, (24, 24), spp=16, context=gl_context)
    x, y, pixel = quad_pixels(camera, 24)
    inside = (np.abs(x) < 1 - pixel) & (np.abs(y) < 1 - pixel)
    o, d = camera.rays((24, 24))
    n = np.broadcast_to(bent / np.linalg.norm(bent), d.shape).reshape(-1, 3)
    light = np.broadcast_to([0.0, 0.0, 1.0], n.shape)
    f = appendix_b(n, light, -d.reshape(-1, 3), np.full(3, 0.8), 0.0, 1.0).reshape(d.shape)
    want = np.pi * 2.0 * f
    flat = np.pi * 2.0 * appendix_b(np.broadcast_to([0.0, 0.0, 1.0], n.shape), light,
                                    -d.reshape(-1, 3), np.full(3, 0.8), 0.0, 1.0)
    assert np.abs(traced.image[inside] - want[inside]).max() < 0.02 * want[inside].max()
    assert want[inside].mean() < 0.85 * flat.reshape(d.shape)[inside].mean()  # (it bends)


def test_an_opacity_map_is_the_chance_of_each_texel(gl_context):
    """The notes' opacity map (one channel: 51 on the left, 255 on the right), before a
    constant sky: each half 0.2 or 1 of its own light and the rest the sky's, in the mean."""
    from glshade import Camera, Environment, Material, Scene, Texture

    halves = np.array([[51, 255]], np.uint8)
    quad = uv_quad()
    scene = Scene(environment=Environment((0.8, 0.8, 0.8)))
    scene.add(quad, Material(color=(1, 1, 1), kd=0.5, ks=0.0,
                             opacity_texture=Texture(halves, filter="nearest")))
    camera = Camera.look_at((0, 0, 3), (0, 0, 0), fov_y=30.0)
    traced = trace(scene, camera, (32, 32), spp=128, context=gl_context)
    x, y, pixel = quad_pixels(camera, 32)
    inside = (np.abs(y) < 1 - pixel) & (np.abs(x) < 1 - pixel) & (np.abs(x) > pixel)
    for half, alpha in ((x < 0, 0.2), (x > 0, 1.0)):
        where = inside & half
        want = np.pi * 0.8 * (alpha * 0.5 + (1 - alpha))
        got, se = traced.image[where].sum(0), np.sqrt((traced.se[where] ** 2).sum(0))
        assert (np.abs(got - want * where.sum()) <= 4 * se + 1e-6 * where.sum()).all(), (
            alpha, got / where.sum(), want)


def test_what_it_does_not_trace_is_one_line_naming_the_model():
    from glshade import Material, Scene, Texture

    scene = Scene()
    mesh = P.cube()
    painted = Mesh(mesh.vertices, mesh.faces, colors=np.full((8, 4), 0.5))
    scene.add(painted, PBRMaterial(), name="painted")
    with pytest.raises(SceneError, match="painted: its colours' alpha below 1 is not traced"):
        TraceScene.from_scene(scene)
    scene = Scene()
    scene.add(mesh, Material(specular_texture=Texture(np.ones((2, 2, 3)))), name="box")
    with pytest.raises(SceneError, match=r"box: its texture maps \(specular\) are not"):
        TraceScene.from_scene(scene)
