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
tests that would share a golden are refused. Several baselines: ``NAME.alt-1.png``,
``NAME.alt-2.png`` ... beside ``NAME.png`` are accepted too (a render passes if any does;
a failure is reported against the closest). Every check of a test runs: the test fails
after its body with every golden that differs, not at the first. Each run that checks
goldens writes ``index.html`` in the results folder -- the failures (actual, expected,
difference, facts; a folder per test node id) with an approve box each, or that all
passed -- and ``approve.json``, from which ``python -m glshade.testing.approve DIR
[NAME ...]`` writes the approved renders as the new goldens. Options:

- ``--glshade-add-missing``: write the goldens that do not exist (the rest are checked).
- ``--glshade-update-golden``: rewrite every golden the run checks.
- ``--glshade-results DIR`` (or ``glshade_results = "DIR"`` in the ini file, relative to
  the root): where failure images and ``index.html`` go; default: pytest's temporary folder
  (never the source tree). The summary line at the end of the run names it.
"""

from __future__ import annotations

import glob
import html
import json
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pytest

from glshade.testing import node_folder, safe_name

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
    config.stash[_CHECKS] = []


def pytest_sessionstart(session):
    """The results folder is known from the start (assert_images_close's failures go there
    too, before any golden has failed)."""
    if session.config.getoption("--glshade-results") or \
            session.config.getini("glshade_results"):
        _results(session.config)


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
    """``tests/test_a.py::TestB::test_c[x]`` -> ``test_a.TestB.test_c[x]``: a file name.

    Parameters
    ----------
    nodeid : str
        A pytest node id.
    """
    file, _, rest = nodeid.partition("::")
    parts = [Path(file).stem, *rest.split("::")] if rest else [Path(file).stem]
    return safe_name(".".join(p for p in parts if p))


@dataclass
class _Failure:
    nodeid: str
    name: str
    folder: Path
    summary: str
    golden_facts: dict | None
    facts: dict
    golden: Path        # where an approved render goes (the golden's own path)
    baseline: Path      # the baseline it was judged against (the closest)


_ITEM_FAILURES = pytest.StashKey[list]()  # one test's golden failures (messages)
_CHECKS = pytest.StashKey[list]()         # golden checks run this session (one per check)


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
        from glshade.testing.golden import fingerprint, write_golden

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
        config.stash[_CHECKS].append(name)
        if update or (add_missing and not path.exists()):
            write_golden(path, color, facts)
            return
        if not path.exists():
            pytest.fail(f"no golden image {path}; run pytest with --glshade-add-missing to "
                        "write the missing ones (or --glshade-update-golden to rewrite all)",
                        pytrace=False)
        verdict, baseline, expected, golden_facts = _closest(path, color, facts, face_id,
                                                             max_mean, max_pixel, edge_width)
        if verdict.ok:
            return
        out = _results(config) / node_folder(request.node.nodeid) / safe_name(Path(name).stem)
        _save_failure(out, color, expected, verdict)
        config.stash[_FAILURES].append(_Failure(request.node.nodeid, name, out,
                                                verdict.summary(), golden_facts, facts, path,
                                                baseline))
        shown = name if baseline == path else f"{name} (closest baseline {baseline.name})"
        request.node.stash.setdefault(_ITEM_FAILURES, []).append(
            f"{shown}: {verdict.summary()}. Saved actual.png, expected.png and diff.png in "
            f"{out}")

    return check


def _closest(path: Path, color, facts, face_id, max_mean, max_pixel, edge_width):
    """The verdict against ``path`` or any of its ``.alt-K`` baselines: the first that
    passes, else the closest (fewest interior pixels over, then the least mean)."""
    from glshade.testing.golden import judge, read_golden

    baselines = [path] + sorted(path.parent.glob(f"{glob.escape(path.stem)}.alt-*.png"))
    best = None
    for baseline in baselines:
        expected, golden_facts = read_golden(baseline)
        same = golden_facts is not None and all(golden_facts.get(k) == facts.get(k)
                                                for k in facts)
        verdict = judge(color, expected, same_fingerprint=same, face_id=face_id,
                        max_mean=max_mean, max_pixel=max_pixel, edge_width=edge_width)
        found = (verdict, baseline, expected, golden_facts)
        if verdict.ok:
            return found
        if best is None or (verdict.interior_over, verdict.mean) < \
                (best[0].interior_over, best[0].mean):
            best = found
    assert best is not None
    return best


@pytest.hookimpl(wrapper=True)
def pytest_runtest_call(item):
    """After the test's body: fail with every golden check that differed (each was
    checked; the first did not stop the rest)."""
    result = yield
    failures = item.stash.get(_ITEM_FAILURES, [])
    if failures:
        pytest.fail("\n".join(failures), pytrace=False)
    return result


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
    """Write this run's report (a run that checked goldens rewrites it: never stale)."""
    checks = session.config.stash.get(_CHECKS, [])
    if not checks:
        return
    from glshade.atomic import atomic_write

    failures = session.config.stash.get(_FAILURES, [])
    folder = _results(session.config)
    rows = []
    for f in failures:
        rel = os.path.relpath(f.folder, folder)
        key = f"{f.nodeid}::{f.name}"
        images = "".join(f'<td><img src="{html.escape(rel)}/{n}.png" alt="{n}"><br>{n}</td>'
                         for n in ("actual", "expected", "diff"))
        facts = html.escape(f"render: {f.facts}\ngolden ({f.baseline.name}): "
                            f"{f.golden_facts}")
        rows.append(f"<tr><td><label><input type='checkbox' class='approve' "
                    f"value='{html.escape(key, quote=True)}'> approve</label><br>"
                    f"<b>{html.escape(f.nodeid)}</b><br>{html.escape(f.name)}<br>"
                    f"{html.escape(f.summary)}<pre>{facts}</pre></td>{images}</tr>")
    head = (f"{len(failures)} of {len(checks)} golden image checks differ" if failures
            else f"all {len(checks)} golden image checks passed")
    command = f"python -m glshade.testing.approve {folder}"
    script = ("<script>function cmd(){var k=[...document.querySelectorAll('.approve:checked')]"
              ".map(function(b){return \"'\"+b.value.replace(/'/g,\"'\\\\''\")+\"'\"});"
              f"document.getElementById('cmd').textContent={json.dumps(command)}+"
              "(k.length?' '+k.join(' '):' --all')}"
              "document.addEventListener('change',cmd);cmd()</script>")
    page = ("<!doctype html><meta charset='utf-8'><title>glshade golden images</title>"
            "<style>img{image-rendering:pixelated;max-width:320px}td{vertical-align:top;"
            "padding:6px}pre{white-space:pre-wrap;font-size:small}</style>"
            f"<h1>{html.escape(head)}</h1>"
            + (f"<p>Tick the renders to approve, then run (writes them as the goldens):</p>"
               f"<pre id='cmd'></pre><table>{''.join(rows)}</table>{script}" if failures
               else ""))
    with atomic_write(folder / "index.html", "w") as out:
        out.write(page)
    manifest = {f"{f.nodeid}::{f.name}": {"golden": str(f.golden),
                                          "actual": str(f.folder / "actual.png"),
                                          "facts": f.facts} for f in failures}
    with atomic_write(folder / "approve.json", "w") as out:
        json.dump(manifest, out, indent=2, default=str)


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    failures = config.stash.get(_FAILURES, [])
    if failures:
        terminalreporter.write_line(f"glshade: {len(failures)} golden image(s) differ; "
                                    f"see {_results(config) / 'index.html'}")


__all__ = ["golden_name", "glshade_renderer", "glshade_golden"]
