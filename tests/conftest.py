"""Shared fixtures. GL: one context per test run, made through create_context.

Where no context can be made the GL tests skip with the collected error text on a
developer's machine, but FAIL when ``CI`` or ``GLSHADE_REQUIRE_GL`` is set, so CI can never
go green by skipping the renderer. ``GLSHADE_TEST_BACKEND`` picks the backend (the README's
test command runs the GL tests with egl, then the backend tier with native held to 4.1
core as a Mac's is -- ``GLSHADE_TEST_TIER=4.1`` says the context must be one -- and the
tests of every pass's code with osmesa: the Makefile says which).
"""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from glshade.errors import ContextError

pytest_plugins = ["pytester"]

try:  # property-based sweeps: derandomized in CI (the same examples every run), printed
    from hypothesis import HealthCheck, settings

    settings.register_profile("ci", derandomize=True, deadline=None, print_blob=True,
                              suppress_health_check=[HealthCheck.too_slow])
    settings.register_profile("dev", deadline=None,
                              suppress_health_check=[HealthCheck.too_slow])
    settings.load_profile("ci" if os.environ.get("CI") else
                          os.environ.get("HYPOTHESIS_PROFILE", "dev"))
except ImportError:  # (the test extra installs it; tests that use it say so)
    pass

BACKEND = os.environ.get("GLSHADE_TEST_BACKEND", "egl")
ROOT = Path(__file__).resolve().parents[1]


def _interrupts_as_from_a_terminal() -> None:
    """The Ctrl-C tests send SIGINT to glshade (in this process and in the commands they
    start): a suite started in the background (a shell's ``make test &``, nohup) inherits
    SIGINT ignored, Python then installs no handler, every process it starts ignores it
    too, and those tests fail for the shell's reason, not glshade's. Each test process
    takes SIGINT as a terminal would give it (its children then start with the default)."""
    import signal

    if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
        signal.signal(signal.SIGINT, signal.default_int_handler)


_interrupts_as_from_a_terminal()


def glshade(*args, timeout=120, **kwargs):
    """Run the command line tool in a subprocess from the repository root."""
    return subprocess.run([sys.executable, "-m", "glshade", *args], capture_output=True,
                          text=True, cwd=ROOT, timeout=timeout, **kwargs)


def require(module: str, why: str):
    """``pytest.importorskip`` for what the test extra installs: a skip on a developer's
    machine that lacks it, a failure when ``CI`` is set (CI must never pass by skipping)."""
    import importlib

    try:
        return importlib.import_module(module)
    except ImportError as exc:
        if os.environ.get("CI"):
            pytest.fail(f"{module} is missing in CI ({why}): {exc}", pytrace=False)
        pytest.skip(f"{module} is not installed ({why})", allow_module_level=True)


def closing_factory(build):
    """For a fixture: yield a function that builds objects, and close them all afterwards."""
    made = []

    def make(*args, **kwargs):
        made.append(build(*args, **kwargs))
        return made[-1]

    yield make
    for obj in made:
        obj.close()


@pytest.fixture
def spawn():
    """``subprocess.Popen`` for a test that signals or kills what it starts: each process
    leads its own group, and the group is killed when the test ends, however it ends -- a
    test that fails before its process exits (a long trace, an animation's workers) would
    leave it running and take a core from every test after it."""
    import signal

    started = []

    def start(*args, **kwargs):
        kwargs.setdefault("start_new_session", True)
        started.append(subprocess.Popen(*args, **kwargs))
        return started[-1]

    yield start
    for proc in started:
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):  # (the group has ended)
            pass
        proc.wait()


@pytest.fixture(scope="session")
def gl_context():
    from glshade.render.context import create_context

    try:
        ctx = create_context(BACKEND)
    except ContextError as exc:
        if os.environ.get("CI") or os.environ.get("GLSHADE_REQUIRE_GL"):
            pytest.fail(f"no GL context in CI ({BACKEND}): {exc}", pytrace=False)
        pytest.skip(f"no GL context ({BACKEND}): {exc}")
    expected = os.environ.get("GLSHADE_TEST_TIER")
    if expected and ctx.features.tier != expected:  # (a tier's pass never runs on another)
        found = ctx.features
        ctx.release()
        pytest.fail(f"GLSHADE_TEST_TIER={expected}, and the context is tier {found.tier} "
                    f"(OpenGL {found.version_text}): the driver ignored the overrides",
                    pytrace=False)
    yield ctx
    ctx.release()


@pytest.fixture(autouse=True)
def gl_error_check(request):
    """The GL error flag is clean before and after every GL test."""
    if "gl_context" not in request.fixturenames:
        yield
        return
    context = request.getfixturevalue("gl_context")
    context.make_current()  # (a test that made contexts of its own may have left another)
    ctx = context.ctx
    assert ctx.error == "GL_NO_ERROR", "GL error left by an earlier test"
    yield
    context.make_current()
    assert ctx.error == "GL_NO_ERROR"


@pytest.fixture
def make_renderer(gl_context):
    """Renderers of any size on the shared context, closed after the test."""
    from glshade.render.renderer import Renderer

    yield from closing_factory(lambda width=64, height=64, samples=0:
                               Renderer(width, height, samples=samples, context=gl_context))


#: folders whose GL tests prove what does not depend on the backend -- the command line,
#: files, processes, pytest plugins: the OSMesa pass leaves them out (marked ``once``)
ONCE_FOLDERS = ("tests/batch/", "tests/animate/", "tests/testing/", "tests/cli/")
#: the tests of what a GL context's backend can change -- its version, extensions, sample
#: counts, framebuffers, compute and tessellation stages: every pass of the renderer and
#: the path tracer's and tessellation's programs, each against its oracle. The 4.1 tier
#: runs these (marked ``backend``; the Makefile's BACKEND_TESTS lists the same files), the
#: OSMesa pass those of them that run every pass's code once (its OSMESA_TESTS); the
#: chapters that draw through them (hidden surfaces, radiosity, compare, notebooks ...)
#: prove their own numbers once, on EGL.
BACKEND_PATHS = ("tests/render/", "tests/pathtrace/test_pathtrace.py",
                 "tests/patches/test_gpu_tessellation.py")


def pytest_collection_modifyitems(items):
    """Every test that draws (through the shared context, or a subprocess marked ``gl``) is
    a GL test: ``make test`` runs them again on OSMesa with ``-m gl``, but for those of the
    ONCE_FOLDERS and the README's blocks (which the EGL pass runs)."""
    for item in items:
        path = str(item.fspath).replace("\\", "/")
        if "tests/render/" in path or "gl_context" in getattr(item, "fixturenames", ()):
            item.add_marker(pytest.mark.gl)
        if any(folder in path for folder in ONCE_FOLDERS) or path.endswith("tests/test_readme.py"):
            item.add_marker(pytest.mark.once)
        # (a test there that draws through no shared context -- a refusal before any
        # drawing, a numpy oracle's own check, a subprocess that names its backends -- proves
        # the same on every pass: it runs once)
        if any(part in path for part in BACKEND_PATHS) and \
                "gl_context" in getattr(item, "fixturenames", ()):
            item.add_marker(pytest.mark.backend)


@pytest.fixture
def rng():
    return np.random.default_rng(12345)


class DaskCluster:
    """A real Dask cluster on 127.0.0.1: a ``dask scheduler`` and ``dask worker`` processes
    (single-threaded, no nanny, so that killing one kills its work)."""

    def __init__(self, folder: Path, workers: int = 2):
        import json
        import time

        self.folder, self.workers = folder, []
        file = folder / "scheduler.json"
        dask = str(Path(sys.executable).with_name("dask"))
        self.scheduler = subprocess.Popen(
            [dask, "scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
             "--scheduler-file", str(file)], cwd=folder, stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL)
        deadline = time.time() + 60
        while not file.exists() or not file.read_text().strip():
            assert self.scheduler.poll() is None and time.time() < deadline, \
                "the dask scheduler did not start"
            time.sleep(0.1)
        time.sleep(0.2)
        self.address = json.loads(file.read_text())["address"]
        for _ in range(workers):
            self.start_worker()
        self.wait_for(workers)

    def start_worker(self) -> subprocess.Popen:
        dask = str(Path(sys.executable).with_name("dask"))
        env = {**os.environ, "GLSHADE_TEST_BACKEND": BACKEND}
        proc = subprocess.Popen([dask, "worker", self.address, "--nthreads", "1",
                                 "--no-nanny", "--no-dashboard", "--local-directory",
                                 str(self.folder)], cwd=self.folder, env=env,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.workers.append(proc)
        return proc

    def wait_for(self, n: int) -> None:
        from distributed import Client

        with Client(self.address, timeout="30s") as client:
            client.wait_for_workers(n, timeout=60)

    def close(self) -> None:
        for p in [*self.workers, self.scheduler]:
            p.kill()
            p.wait(timeout=30)


@pytest.fixture(scope="session")
def dask_cluster(tmp_path_factory):
    try:
        import distributed  # noqa: F401
    except ImportError as exc:  # in the test extra: missing in CI is a failure, not a skip
        if os.environ.get("CI"):
            pytest.fail(f"the distributed extra is missing in CI: {exc}", pytrace=False)
        pytest.skip(f"the distributed extra is missing: {exc}")
    cluster = DaskCluster(tmp_path_factory.mktemp("dask"))
    yield cluster
    cluster.close()
