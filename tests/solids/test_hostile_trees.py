"""Hostile CSG trees through the command line: each refused with exit 2 and one line that
names the problem -- no traceback, no hang, nothing written."""

import subprocess
import sys

import pytest

CHAIN = " | ".join(f"sphere(0.2).move({i * 0.05}, 0, 0)" for i in range(1100))
CASES = {
    "nearly singular matrix": ("sphere(1).transform([[1,0,0,0],[0,1,0,0],[1,1,1e-17,0],"
                               "[0,0,0,1]])", "singular"),
    "half-space offset nan": ("box(2) & halfspace([0, 1, 0], nan)", "number"),
    "sphere(1e300)": ("sphere(1e300)", "out of range"),
    "box(1e300)": ("box(1e300)", "out of range"),
    "a translation of 1e300": ("sphere(1).move(1e300, 0, 0)", "too large"),
    "a tiny size": ("cylinder(1e-20, 1)", "out of range"),
    "more leaves than the cap": (CHAIN, "1,024"),
    "parentheses 300 deep": ("(" * 300 + "sphere(1)" + ")" * 300, "nested"),
}


@pytest.mark.parametrize("case", CASES.values(), ids=CASES.keys())
def test_hostile_trees_exit_2_with_one_line(case, tmp_path):
    text, words = case
    out = tmp_path / "x.png"
    run = subprocess.run([sys.executable, "-m", "glshade", "render", f"solid:{text}", "-o",
                          str(out), "--size", "64x48"], capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 2, run.stderr
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and words in lines[0], run.stderr
    assert "Traceback" not in run.stderr and not out.exists()


def test_info_on_a_large_tree_is_quick_and_complete():
    """300 leaves: the octree's depth follows the cell budget; leaves, depth, volume with
    its error, bounds and the time are printed."""
    text = " | ".join(f"sphere(0.3).move({i * 0.1}, 0, 0)" for i in range(300))
    run = subprocess.run([sys.executable, "-m", "glshade", "info", f"solid:{text}"],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    out = run.stdout
    assert "300 leaves" in out and "levels deep" in out and "+-" in out
    assert "bounding box  [-0.3, -0.3, -0.3] .. [30.2, 0.3, 0.3]" in out
    assert "characters)" in out  # (the long source is shortened)


def test_a_tree_too_deep_to_rebalance_is_refused():
    """Operators that alternate cannot be regrouped: past MAX_DEPTH, a GeometryError that
    says how to fix it (never Python's RecursionError later)."""
    from glshade.errors import GeometryError
    from glshade.solids import Sphere
    from glshade.solids.tree import MAX_DEPTH

    s = Sphere(1)
    with pytest.raises(GeometryError, match=f"the limit is {MAX_DEPTH}: group them"):
        for i in range(2 * MAX_DEPTH):
            s = (s | Sphere(1).translated((i * 0.01, 0, 0))) if i % 2 else s & Sphere(5)
