"""One hierarchy: every error a user can cause is an InputError (exit status 2), every
failure of the environment an EnvironmentFailure (exit status 1)."""

import pytest

from glshade import errors as E


@pytest.mark.parametrize("cls", [E.GeometryError, E.TopologyError, E.MeshFormatError,
                                 E.SceneFormatError, E.PathFormatError, E.OutputError,
                                 E.UsageError, E.ComparisonError, E.OptionError,
                                 E.SceneError])
def test_user_errors_exit_2(cls):
    exc = cls("f.obj", "bad") if cls is E.MeshFormatError else cls("bad")
    assert isinstance(exc, (E.InputError, ValueError))
    assert E.exit_status(exc) == 2


@pytest.mark.parametrize("cls", [E.ContextError, E.ShaderError, E.VideoUnavailable,
                                 E.DisplayError])
def test_environment_failures_exit_1(cls):
    assert isinstance(cls("x"), RuntimeError)
    assert E.exit_status(cls("x")) == 1
    assert E.exit_status(OSError("disk full")) == 1


def test_errors_carry_their_facts():
    exc = E.MeshFormatError("a.off", "face 3 is short", line=7)
    assert (exc.path, exc.line, str(exc)) == ("a.off", 7, "a.off:7: face 3 is short")
    assert E.PathFormatError("k.toml: keyframe 2: bad", keyframe=2).keyframe == 2


def test_every_error_class_lives_in_errors_py():
    import ast
    from pathlib import Path

    import glshade

    root = Path(glshade.__file__).parent
    elsewhere = []
    for path in root.rglob("*.py"):
        if path.name == "errors.py":
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ClassDef) and any(
                    getattr(b, "id", getattr(b, "attr", "")).endswith(("Error", "Exception"))
                    for b in node.bases):
                elsewhere.append(f"{path.relative_to(root)}: {node.name}")
    assert elsewhere == []


def test_errors_survive_pickling_from_worker_processes():
    import pickle

    for exc in (E.MeshFormatError("a.off", "bad", line=3), E.PathFormatError.at("p", 2, "x"),
                E.SettingError("samples", "too many"), E.GeometryError("plain")):
        back = pickle.loads(pickle.dumps(exc))
        assert type(back) is type(exc) and str(back) == str(exc)
        assert back.__dict__ == exc.__dict__


# ------------------------------------------------------------------ the table, through the CLI

#: (arguments, environment changes, exit status, words the one line must hold)
CLI_TABLE = [
    (["render", "primitive:cube", "-o", "x.png", "--backend", "vulkan"], {}, 2,
     "invalid choice: 'vulkan'"),
    (["render", "primitive:cube", "-o", "x.png"], {"GLSHADE_BACKEND": "vulkan"}, 2,
     "GLSHADE_BACKEND: unknown backend 'vulkan'; choose one of auto, egl, osmesa"),
    (["render", "primitive:cube", "-o", "x.png", "--size", "0x5"], {}, 2,
     "size must be whole pixels from 1 to 16384"),
    (["render", "primitive:cube", "-o", "x.png", "--samples", "3"], {}, 2,
     "samples (MSAA) must be 0 (off) or a power of two"),
    (["render", "primitive:cube", "-o", "x.png", "--mode", "toon"], {}, 2,
     "unknown shading mode 'toon'"),
    (["render", "primitive:cube", "-o", "x.png", "--fov", "200"], {}, 2,
     "the field of view must be from 0.0001 to under 180 degrees"),
    (["radiosity", "assets/scenes/cornell-box.toml", "-o", "x.png", "--method", "jacobi"], {},
     2, "unknown radiosity method 'jacobi'; choose one of progressive, gauss-seidel"),
    (["hidden", "primitive:cube", "-o", "x.png", "--algorithms", "painter"], {}, 2,
     "unknown algorithm painter"),
    (["view", "primitive:cube"], {"DISPLAY": None, "WAYLAND_DISPLAY": None}, 1, "no display"),
]


@pytest.mark.parametrize("args, env, status, words", CLI_TABLE,
                         ids=[" ".join(a[:1] + a[3:] or a) for a, *_ in CLI_TABLE])
def test_each_kind_of_fault_has_its_exit_status_and_one_line(args, env, status, words,
                                                             tmp_path):
    """Bad input (a mistyped backend, size, sample count, mode, method) exits 2; the machine's
    lack (no display) exits 1; each with one line naming the argument, and no output."""
    import os
    import subprocess
    import sys
    from pathlib import Path

    root = Path(__file__).resolve().parent.parent
    environ = {k: v for k, v in os.environ.items() if k not in env}
    environ.update({k: v for k, v in env.items() if v is not None})
    args = [str(root / a) if a.startswith("assets/") else a for a in args]
    out = subprocess.run([sys.executable, "-m", "glshade", *args], capture_output=True,
                         text=True, env=environ, cwd=tmp_path)
    assert out.returncode == status, out.stderr
    assert words in out.stderr, out.stderr
    assert len(out.stderr.strip().splitlines()) == 1, out.stderr
    assert not (tmp_path / "x.png").exists()


@pytest.mark.parametrize("call, kind", [
    (lambda g: g.Renderer(8, 8, backend="vulkan"), "OptionError"),
    (lambda g: g.RenderConfig(0, 8), "OptionError"),
    (lambda g: g.RenderConfig(8, 8, samples=3), "OptionError"),
    (lambda g: g.DrawOptions(mode="toon"), "OptionError"),
    (lambda g: g.DrawOptions(cull="sometimes"), "OptionError"),
    (lambda g: g.Camera(fov_y=0), "SceneError"),
    (lambda g: g.Camera(projection="fisheye"), "OptionError"),
    (lambda g: g.CameraPath([g.Keyframe(0.0, (0, 0, 3), (0, 0, 0, 1))],
                            orientation_interp="bezier"), "OptionError"),
    (lambda g: g.Mesh([[0, 0], [1, 0]], [[0, 1, 0]]), "GeometryError"),
])
def test_the_api_raises_the_kind_of_each_fault(call, kind):
    """The same faults in the API: an option is an OptionError, a scene value a SceneError,
    a shape a GeometryError -- all InputErrors (exit 2), none of them another's."""
    import glshade

    with pytest.raises(E.InputError) as info:
        call(glshade)
    assert type(info.value).__name__ == kind, repr(info.value)
    assert E.exit_status(info.value) == 2
