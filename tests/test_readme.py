"""The README's Python example runs as written (in a temporary folder, with the names it
leaves to the reader filled in), whatever glshade modules were imported before it."""

import re
import subprocess
import sys

import pytest

from tests.conftest import ROOT

pytestmark = pytest.mark.gl


def test_the_readme_python_example_runs(tmp_path):
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    code = re.search(r"```python\n(.*?)```", text, re.S).group(1)
    assert "glshade.compare(" in code and "glshade.animate(" in code
    (tmp_path / "path.toml").write_text("[[keyframe]]\ntime = 0.0\neye = [0.0, 1.0, 5.0]\n"
                                        "target = [0.0, 0.0, 0.0]\n")
    prelude = (f"import os\nos.chdir({str(tmp_path)!r})\n"
               "import glshade.compare.metrics, glshade.animate.writers  # the packages first\n"
               f"ROOT = {str(ROOT)!r}\n"
               "q0, q1, t = [0, 0, 0, 1.0], [0, 1, 0, 0.0], 0.3\n")
    code = code.replace('"assets/', 'ROOT + "/assets/').replace("jobs=2)", "jobs=2, size=(64, 48))")
    r = subprocess.run([sys.executable, "-c", prelude + code], capture_output=True, text=True,
                       cwd=tmp_path, timeout=300)
    assert r.returncode == 0, r.stderr
    assert "against the phong-fine reference" in r.stdout
    assert (tmp_path / "teapot.png").stat().st_size > 0
    assert (tmp_path / "thumbs" / "teapot.v01.phong.png").stat().st_size > 0
    assert (tmp_path / "orbit.gif").stat().st_size > 0
