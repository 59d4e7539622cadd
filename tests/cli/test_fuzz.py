"""Hostile input to the commands (hypothesis, derandomized in CI; the failing example is
printed): every option of render, pathtrace, compare, radiosity, hidden, animate, batch
and info given values from the edges -- zero, negative, huge (past 2^31 and 2^63), not
finite, not a number, empty -- and inputs that are not meshes. Every run ends with status
0, 1 or 2; a failure says one line on stderr, with no traceback and no numpy repr, and
leaves nothing in the output folder; a success writes only its outputs there."""

import re

import pytest

from tests.conftest import BACKEND, glshade, require

require("hypothesis", "property-based sweeps are part of the test extra")
from hypothesis import HealthCheck, given, settings, strategies as st  # noqa: E402

pytestmark = [pytest.mark.gl, pytest.mark.once]

HOSTILE = ["0", "-1", "1e400", "nan", "inf", "-inf", "99999999999999999999", "2147483648",
           "abc", "", "0.5", "1e-320"]
SIZES = ["0x0", "1x1", "65536x2", "99999999999x1", "axb", "-4x4", "16x16"]

#: command -> (its fixed arguments, {option: values to try}); -o goes into the test's folder
COMMANDS = {
    "render": (["primitive:cube", "--size", "16x16"],
               {"--fov": HOSTILE, "--size": SIZES, "--crease": HOSTILE,
                "--shininess": HOSTILE, "--eye": ["1,2", "nan,0,0", "1e400,0,0", "0,0,0"]}),
    "pathtrace": (["assets/scenes/cornell-box.toml", "--size", "16x16", "--spp", "1"],
                  {"--spp": HOSTILE, "--max-depth": HOSTILE, "--exposure": HOSTILE,
                   "--until": HOSTILE, "--size": SIZES, "--seed": HOSTILE,
                   "--sampler": ["sobol", "SOBOL", "", "halton"]}),
    "compare": (["primitive:icosphere:1", "--size", "32x32"],
                {"--size": SIZES, "--scale": HOSTILE, "--fov": HOSTILE,
                 "--reference": ["nope", "pathtrace", "", "analytic"]}),
    "radiosity": (["assets/scenes/cornell-box.toml", "--size", "16x16", "--patch-size",
                   "200", "--iterations", "2"],
                  {"--patch-size": HOSTILE, "--iterations": HOSTILE, "--until": HOSTILE,
                   "--hemicube": HOSTILE, "--exposure": HOSTILE}),
    "hidden": (["primitive:cube", "--size", "16x16"],
               {"--size": SIZES, "--algorithm": ["bsp", "nope", ""], "--fov": HOSTILE}),
    "animate": (["primitive:cube", "--size", "16x16", "--frames", "2", "--jobs", "1", "-q"],
                {"--frames": HOSTILE, "--fps": HOSTILE, "--duration": HOSTILE,
                 "--size": SIZES}),
    "batch": (["assets/teapot.obj", "--size", "16x16", "--jobs", "1", "-q"],
              {"--views": HOSTILE, "--size": SIZES, "--samples": HOSTILE,
               "--crease": HOSTILE}),
}
#: what each command is told to write (-o) in the test's folder; the rest write out.png
OUTPUT = {"animate": "out.gif", "batch": "out"}
INPUTS = ["/dev/null", "assets", "missing.obj", "assets/README.md"]


def _check(done, out_dir, outputs):
    err = done.stderr.strip()
    assert done.returncode in (0, 1, 2), (done.returncode, err)
    assert "Traceback" not in done.stderr, err
    assert not re.search(r"np\.\w+\(|array\(\[", done.stderr), err  # (plain numbers)
    left = sorted(p.name for p in out_dir.iterdir())
    if done.returncode:
        assert len(err.splitlines()) == 1, err
        assert left == [], left
    else:
        assert set(left) <= set(outputs), left


@settings(max_examples=80, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data())
def test_hostile_options_end_well(data, tmp_path_factory):
    command = data.draw(st.sampled_from(sorted(COMMANDS)), label="command")
    fixed, options = COMMANDS[command]
    option = data.draw(st.sampled_from(sorted(options)), label="option")
    value = data.draw(st.sampled_from(options[option]), label="value")
    out_dir = tmp_path_factory.mktemp("out")
    out = out_dir / OUTPUT.get(command, "out.png")
    args = [command, *fixed, option, value, "-o", str(out), "--backend", BACKEND]
    outputs = {"out.png", "out-convergence.png", "out.gif", "out"}
    _check(glshade(*args, timeout=300), out_dir, outputs)


@pytest.mark.parametrize("source", INPUTS)
@pytest.mark.parametrize("command", ["render", "info", "compare", "hidden"])
def test_inputs_that_are_not_meshes_end_in_one_line(command, source, tmp_path):
    out_dir = tmp_path / "out"
    out_dir.mkdir()
    args = [command, source] + (["-o", str(out_dir / "out.png")] if command != "info" else [])
    done = glshade(*args, "--size", "16x16") if command != "info" else glshade(*args)
    assert done.returncode == 2, done.stderr
    _check(done, out_dir, set())


@pytest.mark.parametrize("command", ["render", "pathtrace", "hidden", "compare"])
@pytest.mark.parametrize("bad", ["missing folder", "a folder", "empty"])
def test_an_output_that_cannot_be_written_is_refused_before_any_work(command, bad, tmp_path):
    """Every command that writes an image checks its output first (it rendered, then met
    a raw OS error: 'cannot write .: Device or resource busy' for -o '')."""
    fixed, _ = COMMANDS[command]
    output = {"missing folder": str(tmp_path / "no" / "x.png"), "a folder": str(tmp_path),
              "empty": ""}[bad]
    done = glshade(command, *fixed, "-o", output, "--backend", BACKEND)
    assert done.returncode == 2 and done.stderr.count("\n") == 1, done.stderr
    assert "cannot write" not in done.stderr and "Traceback" not in done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == []
