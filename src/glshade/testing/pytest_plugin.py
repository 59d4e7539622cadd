"""pytest plugin: headless rendering and golden images in other projects' tests.

Fixtures:

- ``glshade_renderer``: one headless Renderer (256x256, no MSAA) for the whole session;
  a clear failure naming every backend tried when no GL context can be made.
- ``glshade_golden``: ``glshade_golden(image_or_frame, name=None, *, renderer=None,
  max_mean=0.5, max_pixel=4)`` compares with ``golden/NAME.png`` beside the test file,
  judged as :mod:`glshade.testing.golden` says (the same renderer: identical bytes;
  another: interior pixels within tolerance, edge pixels free when a Frame gives its id
  buffer).

Golden names come from the test's node id (``test_file.TestClass.test_name[param].png``;
a second check in one test adds ``-2``, ``-3`` ...); an explicit ``name`` still works. Two
tests that would share a golden are refused. Options:

- ``--glshade-add-missing``: write the goldens that do not exist (the rest are checked).
- ``--glshade-update-golden``: rewrite every golden the run checks.
- ``--glshade-results DIR`` (or ``glshade_results = "DIR"`` in the ini file, relative to
  the root): where failure images and ``index.html`` go; default: pytest's temporary folder
  (never the source tree). The summary line at the end of the run names it.
"""

from __future__ import annotations

import html
import os
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest

_REGISTRY = pytest.StashKey[dict]()  # golden path -> node id that checks it
_FAILURES = pytest.StashKey[list]()  # what index.html lists
_RESULTS = pytest.StashKey[Path]()


def pytest_addoption(parser):
    from glshade.modes import HEADLESS_BACKENDS

    group = parser.getgroup("glshade")
    group.addoption("--glshade-update-golden", action="store_true", default=False,
                    help="rewrite the golden images of every glshade_golden check run")
    group.addoption("--glshade-add-missing", action="store_true", default=False,
                    help="write the golden images that do not exist yet; check the others")
    group.addoption("--glshade-results", metavar="DIR", default=None,
                    help="folder for failure images and index.html (default: pytest's "
                    "temporary folder)")
    group.addoption("--glshade-backend", default="auto", choices=HEADLESS_BACKENDS,
                    help="GL backend for glshade_renderer: " + ", ".join(HEADLESS_BACKENDS))
    parser.addini("glshade_results", "folder for glshade's failure images and index.html "
                  "(relative to the root)", default="")


def pytest_configure(config):
    config.stash[_REGISTRY] = {}
    config.stash[_FAILURES] = []


def _results(config) -> Path:
    """The results folder, made on first use (and told to glshade.testing)."""
    if _RESULTS not in config.stash:
        given = config.getoption("--glshade-results") or config.getini("glshade_results")
        if given:
            folder = Path(given)
            if not folder.is_absolute():
                folder = Path(config.rootpath) / folder
        else:
            folder = config._tmp_path_factory.getbasetemp() / "glshade-results"
        folder.mkdir(parents=True, exist_ok=True)
        config.stash[_RESULTS] = folder
        os.environ["GLSHADE_RESULTS"] = str(folder)  # (assert_images_close's failures too)
    return config.stash[_RESULTS]


@pytest.fixture(scope="session")
def glshade_renderer(request):
    from glshade.errors import ContextError
    from glshade.render.renderer import Renderer

    try:
        renderer = Renderer(256, 256, samples=0,
                            backend=request.config.getoption("--glshade-backend"))
    except ContextError as exc:
        pytest.fail(f"glshade_renderer: no headless OpenGL context.\n{exc}", pytrace=False)
    yield renderer
    renderer.close()


def golden_name(nodeid: str) -> str:
    """``tests/test_a.py::TestB::test_c[x]`` -> ``test_a.TestB.test_c[x]``: a file name."""
    file, _, rest = nodeid.partition("::")
    parts = [Path(file).stem, *rest.split("::")] if rest else [Path(file).stem]
    return re.sub(r"[^A-Za-z0-9_.\-\[\]]+", "_", ".".join(p for p in parts if p))


@dataclass
class _Failure:
    nodeid: str
    name: str
    folder: Path
    summary: str
    golden_facts: dict | None
    facts: dict


@pytest.fixture
def glshade_golden(request):
    config = request.config
    update = config.getoption("--glshade-update-golden")
    add_missing = config.getoption("--glshade-add-missing")
    folder = Path(request.node.fspath).parent / "golden"
    registry = config.stash[_REGISTRY]
    calls = [0]

    def check(image: Any, name: str | None = None, *, renderer: Any = None,
              max_mean: float = 0.5, max_pixel: float = 4.0, edge_width: int = 1) -> None:
        from glshade.testing.golden import fingerprint, judge, read_golden, write_golden

        calls[0] += 1
        if name is None:
            name = golden_name(request.node.nodeid) + \
                (f"-{calls[0]}" if calls[0] > 1 else "") + ".png"
        elif not name.lower().endswith(".png"):
            name += ".png"
        path = (folder / name).resolve()
        owner = registry.setdefault(str(path), request.node.nodeid)
        if owner != request.node.nodeid:
            pytest.fail(f"golden image {name} is already checked by {owner}: two tests cannot "
                        "share a golden (give one of them another name)", pytrace=False)
        color = getattr(image, "color", image)
        face_id = getattr(image, "face_id", None)
        if renderer is None:
            renderer = request.getfixturevalue("glshade_renderer")
        facts = fingerprint(renderer)
        if update or (add_missing and not path.exists()):
            write_golden(path, color, facts)
            return
        if not path.exists():
            pytest.fail(f"no golden image {path}; run pytest with --glshade-add-missing to "
                        "write the missing ones (or --glshade-update-golden to rewrite all)",
                        pytrace=False)
        expected, golden_facts = read_golden(path)
        same = golden_facts is not None and all(golden_facts.get(k) == facts.get(k)
                                                for k in facts)
        verdict = judge(color, expected, same_fingerprint=same, face_id=face_id,
                        max_mean=max_mean, max_pixel=max_pixel, edge_width=edge_width)
        if verdict.ok:
            return
        out = _results(config) / re.sub(r"[^A-Za-z0-9_.\-\[\]]+", "_", Path(name).stem)
        _save_failure(out, color, expected, verdict)
        config.stash[_FAILURES].append(_Failure(request.node.nodeid, name, out,
                                                verdict.summary(), golden_facts, facts))
        pytest.fail(f"{name}: {verdict.summary()}. Saved actual.png, expected.png and "
                    f"diff.png in {out}", pytrace=False)

    return check


def _save_failure(out: Path, actual, expected, verdict) -> None:
    from glshade.testing.golden import as_rgba
    from glshade.io.images import heatmap, save_image

    out.mkdir(parents=True, exist_ok=True)
    save_image(as_rgba(actual), out / "actual.png")
    save_image(as_rgba(expected), out / "expected.png")
    if verdict.diff.size:
        save_image(heatmap(verdict.diff, max(float(verdict.diff.max()), 1.0)),
                   out / "diff.png")


def pytest_sessionfinish(session, exitstatus):
    failures = session.config.stash.get(_FAILURES, [])
    if not failures:
        return
    folder = _results(session.config)
    rows = []
    for f in failures:
        rel = os.path.relpath(f.folder, folder)
        images = "".join(f'<td><img src="{html.escape(rel)}/{n}.png" alt="{n}"><br>{n}</td>'
                         for n in ("actual", "expected", "diff"))
        facts = html.escape(f"render: {f.facts}\ngolden: {f.golden_facts}")
        rows.append(f"<tr><td><b>{html.escape(f.nodeid)}</b><br>{html.escape(f.name)}<br>"
                    f"{html.escape(f.summary)}<pre>{facts}</pre></td>{images}</tr>")
    page = ("<!doctype html><meta charset='utf-8'><title>glshade golden images</title>"
            "<style>img{image-rendering:pixelated;max-width:320px}td{vertical-align:top;"
            "padding:6px}pre{white-space:pre-wrap;font-size:small}</style>"
            f"<h1>{len(failures)} golden image(s) differ</h1><table>{''.join(rows)}</table>")
    (folder / "index.html").write_text(page, encoding="utf-8")


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    failures = config.stash.get(_FAILURES, [])
    if failures:
        terminalreporter.write_line(f"glshade: {len(failures)} golden image(s) differ; "
                                    f"see {_results(config) / 'index.html'}")


__all__ = ["golden_name", "glshade_renderer", "glshade_golden"]
