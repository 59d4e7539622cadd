"""Patches drawn by the renderer: a closed patch model leaves no hole inside its silhouette
at mixed levels; the teapot's exact normals (checked here by finite differences of a
power-basis evaluation) against the averaged ones of its quad mesh; and Phong shading with
exact normals nearer a fine reference than with averaged ones."""

import numpy as np
import pytest
from scipy import ndimage
from scipy.spatial import cKDTree

from glshade import Camera, Mesh, Scene
from glshade import patches as G
from glshade.geometry import primitives
from tests.patches.test_patches import power_basis

pytestmark = pytest.mark.gl
SIZE = (200, 150)


@pytest.mark.parametrize("name, tolerance", [("sphere", 0.02), ("cone", 0.01),
                                              ("cylinder", 0.05)])
def test_a_closed_patch_model_has_no_hole_inside_its_silhouette(name, tolerance,
                                                                make_renderer):
    tess = G.tessellate(G.named(name), tolerance=tolerance)
    scene = Scene()
    scene.add(tess.mesh)
    r = make_renderer(*SIZE)
    for eye in ((2.5, 1.5, 3.0), (0.3, 3.5, 0.2), (-3.0, -1.0, 1.0)):
        ids = r.render_frame(scene, Camera.look_at(eye, (0, 0, 0)), "flat").face_id
        drawn = ids >= 0
        assert drawn.sum() > 2000
        assert (ndimage.binary_fill_holes(drawn) == drawn).all(), (name, eye)


def exact_normals_fd(points, u, v, h=1e-6):
    """Unit normals by central differences of the test's own evaluation, a little inside
    the patch where a side collapses (its limit, to within the offset)."""
    u = np.clip(u, 1e-4, 1 - 1e-4)
    v = np.clip(v, 1e-4, 1 - 1e-4)
    w = np.ones(points.shape[:3])
    su = power_basis(points, w, u + h, v) - power_basis(points, w, u - h, v)
    sv = power_basis(points, w, u, v + h) - power_basis(points, w, u, v - h)
    n = np.cross(su, sv)
    return n / np.linalg.norm(n, axis=-1, keepdims=True)


def test_the_teapots_averaged_normals_against_its_exact_ones():
    """glshade.patches' exact normals equal this test's finite-difference ones, and the
    quad mesh's averaged normals (primitives.teapot, 8 quads a patch side) are off by about
    a degree typically, several at the 95th percentile and almost 40 where the lid's rim
    turns sharply."""
    t = G.teapot()
    k = 8
    s = np.arange(k + 1) / k
    uu, vv = [x.ravel() for x in np.meshgrid(s, s, indexing="ij")]
    exact = t.normals(uu, vv)  # (32, 81, 3)
    fd = exact_normals_fd(t.points, uu, vv)
    assert np.degrees(np.arccos(np.clip(np.einsum("pki,pki->pk", exact, fd), -1, 1))).max() \
        < 0.1
    mesh = primitives.teapot(k)
    pts = t.evaluate(uu, vv)
    # each sample's mesh vertex: among its own patch's (the primitive's faces are patch
    # by patch, k x k each; where the handle and spout touch the body they keep their own)
    patch_of_corner = mesh.corner_face // (k * k)
    averaged = np.empty_like(exact)
    for p in range(len(t)):
        own = np.unique(mesh.face_indices[patch_of_corner == p])
        distance, near = cKDTree(mesh.vertices[own]).query(pts[p])
        assert distance.max() < 1e-9
        averaged[p] = mesh.vertex_normals[own[near]]
    angle = np.degrees(np.arccos(np.clip(np.einsum("pki,pki->pk", averaged, exact), -1, 1)))
    print(f"median {np.median(angle):.2f}, 95th {np.percentile(angle, 95):.1f}, max "
          f"{angle.max():.0f} degrees")
    assert 0.5 < np.median(angle) < 1.5
    assert 5 < np.percentile(angle, 95) < 11
    assert 30 < angle.max() < 45


def test_phong_with_exact_normals_is_nearer_the_reference_than_with_averaged(make_renderer):
    coarse = G.tessellate(G.teapot(), 6)
    averaged = Mesh(coarse.mesh.vertices, coarse.mesh.faces)  # (the same mesh, averaged)
    fine = G.tessellate(G.teapot(), 64).mesh
    camera = Camera.look_at((4.5, 3.5, 6.0), (0, 1.2, 0))
    r = make_renderer(*SIZE)
    images, ids = {}, {}
    for name, mesh in (("exact", coarse.mesh), ("averaged", averaged), ("fine", fine)):
        scene = Scene()
        scene.add(mesh)
        frame = r.render_frame(scene, camera, "phong")
        images[name] = frame.color[..., :3].astype(float)
        ids[name] = frame.face_id >= 0
    both = ids["exact"] & ids["averaged"] & ids["fine"]
    err = {k: np.abs(images[k] - images["fine"])[both].mean() for k in ("exact", "averaged")}
    assert both.sum() > 5000
    assert err["exact"] < 0.7 * err["averaged"], err


def test_the_patch_sweep_puts_exact_normals_below_averaged_ones(make_renderer, tmp_path):
    import json

    from glshade.compare import patch_sweep
    from tests.conftest import BACKEND, glshade

    rows = patch_sweep(G.named("teapot"), levels=(3, 6, 12), modes=("phong",),
                       renderer=make_renderer(160, 160), reference_level=48)
    exact = [r["phong exact"].mean_abs for r in rows]
    averaged = [r["phong averaged"].mean_abs for r in rows]
    assert all(e < a for e, a in zip(exact, averaged)), (exact, averaged)
    assert exact[0] > exact[1] > exact[2]  # (finer is nearer)
    out = tmp_path / "sweep.png"
    r = glshade("compare", "patches:torus", "--sweep", "--levels", "2,4", "--modes", "phong",
                "-o", str(out), "--json", str(tmp_path / "s.json"), "--size", "96x96",
                "--backend", BACKEND)
    assert r.returncode == 0, r.stderr
    data = json.loads((tmp_path / "s.json").read_text())
    assert [d["level"] for d in data] == [2, 4] and "phong exact" in data[0]
    assert out.stat().st_size > 0
