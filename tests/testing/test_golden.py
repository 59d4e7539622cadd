"""Golden images: names, collisions, add-missing and update, the results folder, the HTML
summary, RGB and RGBA, and the fingerprint verdict (exact bytes from the same renderer;
edge pixels free and interior pixels held to tolerance from another)."""

import json

import numpy as np
import pytest

from glshade.testing.golden import as_rgba, edge_mask, judge


def _quads():
    """A 16x16 image of two polygons (ids 0 and 1) on a background (-1), and its colours."""
    ids = np.full((16, 16), -1, np.int32)
    ids[3:13, 3:8] = 0
    ids[3:13, 8:13] = 1
    color = np.zeros((16, 16, 4), np.uint8)
    color[..., 3] = 255
    color[ids == 0, :3] = (200, 40, 40)
    color[ids == 1, :3] = (40, 200, 40)
    return ids, color


def test_edge_mask_marks_where_the_id_changes():
    ids, _ = _quads()
    edges = edge_mask(ids)
    # the seam between the polygons and the silhouette are edges; a polygon's middle is not
    assert edges[6, 7] and edges[6, 8] and edges[3, 5] and edges[2, 5]
    assert not edges[7, 5] and not edges[0, 0]
    assert edge_mask(ids, 2)[7, 5 + 1] and not edge_mask(ids, 2)[8, 5]


def test_the_same_renderer_must_give_the_same_bytes():
    ids, color = _quads()
    off = color.copy()
    off[7, 5, 0] += 1  # one level, one pixel
    assert judge(color, color, same_fingerprint=True).ok
    v = judge(off, color, same_fingerprint=True, face_id=ids)
    assert not v.ok and v.differing == 1 and "regression" in v.reason


def test_another_renderer_may_differ_on_edges_but_not_inside():
    ids, color = _quads()
    edge_only = color.copy()
    edge_only[ids == 0] = color[ids == 0]
    edge_only[edge_mask(ids)] = (255, 255, 255, 255)  # every edge pixel wildly different
    v = judge(edge_only, color, same_fingerprint=False, face_id=ids)
    assert v.ok, v.summary()
    assert v.edge_differing == int(edge_mask(ids).sum()) and v.interior_over == 0
    interior = color.copy()
    interior[7, 5, :3] = (255, 255, 255)  # one pixel inside polygon 0
    v = judge(interior, color, same_fingerprint=False, face_id=ids)
    assert not v.ok and v.interior_over == 1 and "regression" in v.reason
    # within max_pixel inside is fine; without an id buffer every pixel is held to it
    small = color.copy()
    small[7, 5, 0] += 3
    assert judge(small, color, same_fingerprint=False, face_id=ids, max_pixel=4).ok
    assert not judge(edge_only, color, same_fingerprint=False).ok


def test_rgb_and_rgba_are_compared_by_what_they_hold():
    _, color = _quads()
    assert judge(color[..., :3], color, same_fingerprint=True).ok  # opaque RGBA == RGB
    see_through = color.copy()
    see_through[..., 3] = 128
    assert not judge(color[..., :3], see_through, same_fingerprint=True).ok
    assert as_rgba(np.ones((2, 2)))[0, 0].tolist() == [255, 255, 255, 255]
    v = judge(color[:8], color, same_fingerprint=True)
    assert not v.ok and "sizes differ" in v.reason


PLUGIN = """
import numpy as np
import pytest
from glshade import Camera, Scene
from glshade.geometry import primitives

def frame(r, color=(0.8, 0.8, 0.8)):
    from glshade import Material
    s = Scene()
    s.add(primitives.cube(), Material(color=color))
    return r.render_frame(s, Camera.look_at([2, 1.5, 3], [0, 0, 0]), "flat")

def test_auto(glshade_renderer, glshade_golden):
    f = frame(glshade_renderer)
    glshade_golden(f)
    glshade_golden(f.color[..., :3])  # the second check of a test: its own name, RGB

class TestGroup:
    def test_param(self, glshade_renderer, glshade_golden):
        glshade_golden(frame(glshade_renderer))

def test_shared_a(glshade_renderer, glshade_golden):
    glshade_golden(frame(glshade_renderer), "shared.png")

def test_shared_b(glshade_renderer, glshade_golden):
    glshade_golden(frame(glshade_renderer), "shared.png")
"""


@pytest.mark.once
def test_plugin_names_collisions_add_missing_update_and_summary(pytester, gl_context):
    backend = gl_context.backend.value
    pytester.makepyfile(test_images=PLUGIN)
    pytester.makeini("[pytest]\nglshade_results = ../out\n")
    run = lambda *a: pytester.runpytest_subprocess("--glshade-backend", backend, *a)  # noqa
    result = run("--glshade-add-missing")
    # names from the node ids; two tests asking for one golden: the second is refused
    result.assert_outcomes(passed=3, failed=1)
    result.stdout.fnmatch_lines(["*golden image shared.png is already checked by "
                                 "test_images.py::test_shared_a*"])
    golden = pytester.path / "golden"
    assert {p.name for p in golden.glob("*.png")} == {
        "test_images.test_auto.png", "test_images.test_auto-2.png",
        "test_images.TestGroup.test_param.png", "shared.png"}
    facts = json.loads((golden / "test_images.test_auto.json").read_text())
    assert facts["backend"] == backend and facts["samples"] == 0 and facts["renderer"]
    # an RGB golden of the same pixels equals the RGBA render (compared by what they hold)
    from PIL import Image

    auto = golden / "test_images.test_auto.png"
    Image.open(auto).convert("RGB").save(auto)
    assert Image.open(auto).mode == "RGB"
    run("-k", "test_auto").assert_outcomes(passed=1)
    # add-missing leaves an existing golden alone (it is checked): a changed one fails
    stamp = (golden / "test_images.TestGroup.test_param.png").stat().st_mtime_ns
    pytester.makepyfile(test_images=PLUGIN.replace("def frame(r, color=(0.8, 0.8, 0.8))",
                                                   "def frame(r, color=(0.8, 0.2, 0.8))"))
    result = run("--glshade-add-missing", "-k", "param")
    result.assert_outcomes(failed=1)
    assert (golden / "test_images.TestGroup.test_param.png").stat().st_mtime_ns == stamp
    out = pytester.path.parent / "out"  # (the ini's results folder)
    page = (out / "index.html").read_text()
    assert "test_images.py::TestGroup::test_param" in page
    assert ('src="test_images.py.TestGroup.test_param/test_images.TestGroup.test_param/'
            'diff.png"') in page
    assert "the same renderer made different bytes" in page and "llvmpipe" in page
    assert not list(pytester.path.rglob("actual.png"))  # nothing in the source tree
    # update rewrites it; then it passes
    run("--glshade-update-golden", "-k", "param").assert_outcomes(passed=1)
    assert (golden / "test_images.TestGroup.test_param.png").stat().st_mtime_ns != stamp
    run("-k", "param").assert_outcomes(passed=1)


def test_plugin_verdict_for_another_renderer(pytester, gl_context):
    """A golden from another renderer (its fingerprint differs): an edge-only change passes
    when the check is given the Frame (its id buffer), an interior change fails."""
    backend = gl_context.backend.value
    pytester.makepyfile(test_images=PLUGIN + '''
from glshade.testing.golden import edge_mask

def test_edges(glshade_renderer, glshade_golden):
    f = frame(glshade_renderer)
    f.color[edge_mask(f.face_id)] = (255, 0, 255, 255)
    glshade_golden(f, "cube.png")

def test_inside(glshade_renderer, glshade_golden):
    f = frame(glshade_renderer)
    inside = (f.face_id >= 0) & ~edge_mask(f.face_id, 3)
    ys, xs = np.nonzero(inside)
    f.color[ys[0], xs[0]] = (255, 0, 255, 255)
    glshade_golden(f, "cube-inside.png")
''')
    run = lambda *a: pytester.runpytest_subprocess("--glshade-backend", backend, *a)  # noqa
    run("--glshade-add-missing", "-k", "test_auto").assert_outcomes(passed=1)
    golden = pytester.path / "golden"
    for name in ("cube", "cube-inside"):
        (golden / f"{name}.png").write_bytes((golden / "test_images.test_auto.png").read_bytes())
        facts = json.loads((golden / "test_images.test_auto.json").read_text())
        facts["renderer"] = "another GPU"
        (golden / f"{name}.json").write_text(json.dumps(facts))
    result = run("-k", "edges or inside")
    result.assert_outcomes(passed=1, failed=1)
    result.stdout.fnmatch_lines(["*cube-inside.png: another renderer, but interior pixels "
                                 "differ beyond tolerance*1 interior pixels over tolerance*"])


BASELINES = '''
import numpy as np
import pytest
from glshade import Camera, Material, Scene
from glshade.geometry import primitives

def frame(r, color):
    s = Scene()
    s.add(primitives.cube(), Material(color=color))
    return r.render_frame(s, Camera.look_at([2, 1.5, 3], [0, 0, 0]), "flat")

def test_two(glshade_renderer, glshade_golden):
    glshade_golden(frame(glshade_renderer, COLOR_A), "a.png")
    glshade_golden(frame(glshade_renderer, COLOR_B), "b.png")
'''


@pytest.mark.once
def test_plugin_baselines_every_failure_report_and_approve(pytester, gl_context):
    """The modes image-test users ask for most: several baselines per golden (passes if
    any does, a failure is judged against the closest); every differing golden of a test
    reported in one run (the second check runs after the first fails); results in a folder
    per node id (two test files of one name in two folders do not share one); a passing
    run rewrites index.html (no stale report); approving from the report's list writes
    the new goldens, and the run passes."""
    import subprocess
    import sys

    backend = gl_context.backend.value
    grey, red = "(0.8, 0.8, 0.8)", "(0.2, 0.2, 0.75)"
    for sub in ("one", "two"):
        pytester.mkpydir(sub)
        (pytester.path / sub / "test_same.py").write_text(
            BASELINES.replace("COLOR_A", grey).replace("COLOR_B", grey))
    results = pytester.path / "results"   # (outside the tests' folders, this test's own)
    run = lambda *a: pytester.runpytest_subprocess(  # noqa: E731
        "--glshade-backend", backend, "--glshade-results", str(results), *a)
    run("--glshade-add-missing").assert_outcomes(passed=2)
    page = (results / "index.html").read_text()
    assert "all 4 golden image checks passed" in page
    # one: an alternative baseline of a.png in navy; the render turns navy: passes by it
    golden = pytester.path / "one" / "golden"
    (pytester.path / "one" / "test_same.py").write_text(
        BASELINES.replace("COLOR_A", red).replace("COLOR_B", grey))
    run("--glshade-update-golden", "one").assert_outcomes(passed=1)
    (golden / "a.png").rename(golden / "a.alt-1.png")
    (golden / "a.json").rename(golden / "a.alt-1.json")
    (pytester.path / "two" / "golden" / "a.png").replace(golden / "a.png")
    (pytester.path / "two" / "golden" / "a.json").replace(golden / "a.json")
    run("one", "-k", "test_two").assert_outcomes(passed=1)
    # both folders' test_two turn blue in a and b: both checks of each fail, all reported
    blue = "(0.2, 0.2, 0.9)"
    for sub in ("one", "two"):
        if sub == "two":
            (pytester.path / "two" / "golden" / "a.png").unlink(missing_ok=True)
            run("--glshade-add-missing", "two").assert_outcomes(passed=1)
        (pytester.path / sub / "test_same.py").write_text(
            BASELINES.replace("COLOR_A", blue).replace("COLOR_B", blue))
    result = run()
    result.assert_outcomes(failed=2)
    result.stdout.fnmatch_lines(["*a.png (closest baseline a.alt-1.png)*", "*b.png:*"])
    found = sorted(p.relative_to(results).as_posix() for p in results.glob("*/*/diff.png"))
    want = ["one_test_same.py.test_two/a/diff.png", "one_test_same.py.test_two/b/diff.png",
            "two_test_same.py.test_two/a/diff.png", "two_test_same.py.test_two/b/diff.png"]
    assert len(found) == 4 and all(f.endswith(w) for f, w in zip(found, want)), found
    page = (results / "index.html").read_text()
    assert "4 of 4 golden image checks differ" in page and page.count("class='approve'") == 4
    # approve two by name, then the rest
    keys = list(json.loads((results / "approve.json").read_text()))
    approve = [sys.executable, "-m", "glshade.testing.approve", str(results)]
    out = subprocess.run(approve + keys[:2], capture_output=True, text=True)
    assert out.returncode == 0 and out.stdout.count("approved:") == 2, out.stderr
    out = subprocess.run(approve + ["nonsense"], capture_output=True, text=True)
    assert out.returncode == 2 and out.stderr.count("\n") == 1 and "no failure" in out.stderr
    assert subprocess.run(approve + ["--all"], capture_output=True).returncode == 0
    run().assert_outcomes(passed=2)
    assert "all 4 golden image checks passed" in (results / "index.html").read_text()


PBR_PLUGIN = """
from glshade import PBRMaterial, Scene, SpotLight, Camera
from glshade.geometry import primitives

ROUGHNESS = 0.35

def test_gold(glshade_renderer, glshade_golden):
    s = Scene()
    s.add(primitives.icosphere(3), PBRMaterial(base_color=(1, 0.77, 0.33), metallic=1.0,
                                              roughness=ROUGHNESS))
    s.add_light(SpotLight((1, 3, 3), (-1, -3, -3), intensity=40, outer_angle=0.6))
    glshade_golden(glshade_renderer.render_frame(s, Camera.look_at([0, 0, 4], [0, 0, 0]),
                                                 "phong"))
"""


@pytest.mark.once
def test_a_pbr_golden_holds_the_materials_factors(pytester, gl_context):
    """glTF's model through the golden check: a changed roughness (a highlight's spread)
    is a regression, the same scene passes."""
    backend = gl_context.backend.value
    pytester.makepyfile(test_pbr=PBR_PLUGIN)
    run = lambda *a: pytester.runpytest_subprocess("--glshade-backend", backend, *a)  # noqa
    run("--glshade-add-missing").assert_outcomes(passed=1)
    run().assert_outcomes(passed=1)
    pytester.makepyfile(test_pbr=PBR_PLUGIN.replace("ROUGHNESS = 0.35", "ROUGHNESS = 0.45"))
    result = run()
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(["*regression*"])
