"""Outputs that cannot be written: one line naming the output asked for (not a temporary
file), exit status 1, and nothing left behind."""

import resource
import subprocess
import sys

import pytest

from tests.conftest import BACKEND, ROOT

pytestmark = pytest.mark.gl


def limited(limit_bytes, *args):
    """The command line with files capped at ``limit_bytes`` (a disk that fills up)."""
    def cap():
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit_bytes, limit_bytes))

    return subprocess.run([sys.executable, "-m", "glshade", *args], capture_output=True,
                          text=True, cwd=ROOT, timeout=120, preexec_fn=cap)


@pytest.mark.parametrize("name, extra", [
    ("out.png", ("render", "assets/teapot.obj", "--size", "200x150")),
    ("out.gif", ("animate", "assets/scenes/spheres.toml", "--frames", "3", "--size",
                 "120x90", "-q")),
    ("out.mp4", ("animate", "assets/scenes/spheres.toml", "--frames", "12", "--size",
                 "120x90", "-q", "--jobs", "1")),
    ("frames/", ("animate", "assets/scenes/spheres.toml", "--frames", "3", "--size",
                 "120x90", "-q")),
])
def test_a_full_disk_names_the_output_and_leaves_nothing(tmp_path, name, extra):
    out = tmp_path / name
    r = limited(2000, *extra[:2], "-o", str(out), *extra[2:], "--backend", BACKEND)
    assert r.returncode == 1, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"glshade: error: cannot write {out}"), \
        r.stderr
    assert ".part" not in r.stderr
    assert list(tmp_path.iterdir()) == []


def test_an_output_in_a_missing_folder(tmp_path):
    out = tmp_path / "no" / "such" / "x.png"
    r = limited(10**9, "render", "primitive:cube", "-o", str(out), "--size", "16x16",
                "--backend", BACKEND)
    assert r.returncode == 2  # (checked before any work: a path given wrong)
    assert r.stderr.strip() == (f"glshade: error: {out}: the folder {out.parent} does not "
                                "exist")


@pytest.mark.parametrize("command", [("render", "primitive:cube"),
                                     ("compare", "primitive:icosphere:1"),
                                     ("hidden", "primitive:cube"),
                                     ("radiosity", "assets/scenes/cornell-box.toml")])
def test_an_output_that_is_not_an_image_is_refused_before_any_work(tmp_path, command):
    out = tmp_path / "out.pgn"  # (a typo)
    r = limited(10**9, *command, "-o", str(out), "--backend", BACKEND)
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and f"{out}: '.pgn' is not an image extension" in lines[0], r.stderr
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("name, magic", [("a.jpg", b"\xff\xd8"), ("a.webp", b"RIFF"),
                                         ("a", b"\x89PNG")])
def test_the_image_format_follows_the_extension(tmp_path, name, magic):
    out = tmp_path / name
    r = limited(10**9, "render", "primitive:cube", "-o", str(out), "--size", "16x16", "-q",
                "--backend", BACKEND)
    assert r.returncode == 0, r.stderr
    assert out.read_bytes().startswith(magic)


@pytest.mark.parametrize("command, output, words", [
    (("animate", "primitive:cube", "--frames", "2"), "{tmp}/no/x.gif", "does not exist"),
    (("animate", "primitive:cube", "--frames", "2"), "{tmp}/taken.txt/", "is a file, not a "
     "folder"),
    (("animate", "primitive:cube", "--frames", "2"), "", "-o: an empty file name"),
    (("batch", "assets/teapot.obj"), "{tmp}/taken.txt", "is a file, not a folder"),
    (("batch", "assets/teapot.obj"), "{tmp}/no/out", "does not exist"),
])
def test_animate_and_batch_check_their_outputs_first(tmp_path, command, output, words):
    """The commands that write many files check where before the first frame or mesh."""
    (tmp_path / "taken.txt").write_text("mine")
    r = limited(10**9, *command, "-o", output.replace("{tmp}", str(tmp_path)), "-q",
                "--backend", BACKEND)
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and words in r.stderr, r.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["taken.txt"]
