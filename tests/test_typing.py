"""The public API is typed: a type checker (mypy) passes on src/ and on a user's file written
as the README writes the API, and it sees real types, not ``Any`` (an assertion of a wrong
type fails). The user's file also runs."""

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
USER = ROOT / "tests" / "typing" / "user_api.py"


def _mypy(*paths) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "mypy", "--no-error-summary", *map(str, paths)],
                          capture_output=True, text=True, cwd=ROOT)


@pytest.mark.slow
def test_the_package_and_a_users_file_type_check():
    out = _mypy(ROOT / "src" / "glshade", USER)
    assert out.returncode == 0, out.stdout + out.stderr


@pytest.mark.slow
def test_the_checker_sees_real_types(tmp_path):
    """Were the lazy names Any, every assert_type below would pass silently."""
    wrong = tmp_path / "wrong.py"
    wrong.write_text(
        "from typing_extensions import assert_type\nimport glshade\n"
        "r = glshade.Renderer(8, 8)\n"
        "assert_type(r.render(glshade.Scene(), glshade.Camera()), str)\n"
        "assert_type(glshade.load_mesh('x.obj'), int)\n"
        "assert_type(glshade.brep.WingedEdge, int)\n")
    out = _mypy(wrong)
    assert out.returncode == 1
    assert out.stdout.count("[assert-type]") == 3, out.stdout


@pytest.mark.gl
def test_the_users_file_runs():
    out = subprocess.run([sys.executable, str(USER)], capture_output=True, text=True, cwd=ROOT)
    assert out.returncode == 0, out.stderr
