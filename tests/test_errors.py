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
