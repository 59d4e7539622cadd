"""The notebook viewer in a real browser: a JupyterLab server started here (no display: the
kernel renders headless), Debian's headless Chromium driven by selenium opens a notebook,
runs it, drags on the widget, presses a mode key, picks and splits the view; after each
gesture the canvas's pixels equal glshade's own headless render of the view the widget
reports, made in this process.
Every server and browser started here is stopped afterwards."""

import base64
import io
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import time
import urllib.request

import nbformat
import numpy as np
import pytest
from PIL import Image

from tests.conftest import BACKEND

pytestmark = pytest.mark.browser
CHROMIUM, CHROMEDRIVER = shutil.which("chromium"), shutil.which("chromedriver")
SIZE = (240, 180)
CELLS = [
    "import glshade\n"
    "from glshade.geometry import primitives\n"
    "from glshade.notebook import view\n"
    "scene = glshade.Scene()\n"
    "scene.add(primitives.torus(), glshade.Material(color=(0.8, 0.5, 0.3), ks=0.4))\n"
    f"w = view(scene, size={SIZE}, pick=True, trace_samples=4)\n"
    "w",
]


def _needs(what: str, found) -> None:
    if not found:
        if os.environ.get("CI"):
            pytest.fail(f"{what} is missing in CI (scripts/setup.sh installs it)")
        pytest.skip(f"{what} is not installed")


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture
def lab(tmp_path):
    """A JupyterLab server on a free port, serving a notebook with the viewer; stopped
    (with its kernels: its whole process group) afterwards."""
    _needs("jupyterlab", shutil.which("jupyter-lab", path=os.path.dirname(sys.executable)))
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell(c) for c in CELLS]
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                                 "language": "python"}
    nbformat.write(nb, tmp_path / "viewer.ipynb")
    port, token = _free_port(), "glshade-test"
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    env.update(GLSHADE_BACKEND=BACKEND, JUPYTER_CONFIG_DIR=str(tmp_path / "config"),
               JUPYTER_RUNTIME_DIR=str(tmp_path / "runtime"))
    log = open(tmp_path / "lab.log", "w")
    server = subprocess.Popen(
        [sys.executable, "-m", "jupyterlab", "--no-browser", "--allow-root",
         f"--port={port}", "--ip=127.0.0.1", f"--IdentityProvider.token={token}",
         f"--ServerApp.root_dir={tmp_path}", "--LabApp.expose_app_in_browser=True",
         "--ServerApp.open_browser=False"],
        env=env, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
    url = f"http://127.0.0.1:{port}"
    try:
        deadline = time.monotonic() + 90
        while True:
            try:
                urllib.request.urlopen(f"{url}/api/status?token={token}", timeout=2)
                break
            except OSError as exc:
                if server.poll() is not None or time.monotonic() > deadline:
                    raise RuntimeError("JupyterLab did not start: "
                                       + (tmp_path / "lab.log").read_text()[-2000:]) from exc
                time.sleep(0.3)
        yield f"{url}/lab/tree/viewer.ipynb?token={token}"
    finally:
        try:
            os.killpg(server.pid, signal.SIGTERM)
            server.wait(timeout=20)
        except (subprocess.TimeoutExpired, ProcessLookupError):
            os.killpg(server.pid, signal.SIGKILL)
            server.wait()
        log.close()


@pytest.fixture
def browser(tmp_path):
    """Headless Chromium through chromedriver (both Debian's: no download), quit after."""
    _needs("chromium", CHROMIUM)
    _needs("chromedriver", CHROMEDRIVER)
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                "--no-first-run", "--disable-background-networking", "--disable-sync",
                "--disable-component-update", "--disable-quic", "--window-size=1400,1000",
                f"--user-data-dir={tmp_path / 'chromium'}"):
        options.add_argument(arg)
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    try:
        yield driver
    finally:
        driver.quit()


def wait_for(driver, script: str, timeout: float = 120.0):
    """Poll a JavaScript expression until it is truthy."""
    deadline = time.monotonic() + timeout
    while True:
        value = driver.execute_script(f"return !!({script});")
        if value:
            return value
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out waiting for {script}")
        time.sleep(0.25)


CANVAS = "document.querySelector('.glshade-viewer canvas')"


def settled(driver, after: int) -> tuple[int, dict, np.ndarray]:
    """The widget once its frames stop coming (newer than revision ``after``): the revision,
    the view it reports and the canvas's pixels (RGB)."""
    wait_for(driver, f"{CANVAS} && +{CANVAS}.dataset.revision > {after}")
    last, still = None, 0
    while still < 3:  # (three polls in a row with no new frame)
        time.sleep(0.3)
        now = driver.execute_script(f"return {CANVAS}.dataset.revision;")
        still = still + 1 if now == last else 0
        last = now
    view = json.loads(driver.execute_script(
        "return document.querySelector('.glshade-viewer').dataset.view;"))
    url = driver.execute_script(f"return {CANVAS}.toDataURL('image/png');")
    png = base64.b64decode(url.split(",", 1)[1])
    pixels = np.asarray(Image.open(io.BytesIO(png)).convert("RGB"))
    return int(last), view, pixels


def headless(view: dict, mode: str, around=None):
    """glshade's own render of the widget's view, in this process: ``(image (H, W, 3),
    polygon ids (H, W), {(x, y): pick} for the 3x3 pixels around ``around``)``."""
    import glshade
    from glshade.geometry import primitives
    from glshade.notebook import camera_from_view

    scene = glshade.Scene()
    scene.add(primitives.torus(), glshade.Material(color=(0.8, 0.5, 0.3), ks=0.4))
    camera = camera_from_view(view)
    r = glshade.Renderer(*SIZE, samples=4, backend=BACKEND)
    try:
        image = r.render(scene, camera, mode)[..., :3]
        ids = r.render_frame(scene, camera, mode).face_id
        picks = {}
        if around is not None:
            for dy in (-1, 0, 1):
                for dx in (-1, 0, 1):
                    x, y = around[0] + dx, around[1] + dy
                    picks[x, y] = r.pick(scene, camera, x + 0.5, y + 0.5)
        return image, ids, picks
    finally:
        r.close()


def test_the_widget_in_a_browser_shows_glshades_pixels_after_each_gesture(lab, browser):
    from selenium.webdriver.common.action_chains import ActionChains

    browser.get(lab)
    wait_for(browser, "window.jupyterapp && window.jupyterapp.shell.currentWidget "
                      "&& window.jupyterapp.shell.currentWidget.sessionContext "
                      "&& window.jupyterapp.shell.currentWidget.sessionContext.session "
                      "&& window.jupyterapp.shell.currentWidget.sessionContext.session.kernel")
    browser.execute_script("window.jupyterapp.commands.execute('notebook:run-all-cells');")
    revision, start, pixels = settled(browser, 0)
    expected, _, _ = headless(start, "phong")
    assert pixels.shape == (SIZE[1], SIZE[0], 3)
    assert (pixels == expected).all()  # the first frame: glshade's render, pixel for pixel
    assert len(np.unique(pixels.reshape(-1, 3), axis=0)) > 50  # (a lit torus, not blank)

    canvas = browser.execute_script(f"return {CANVAS};")
    drag = ActionChains(browser).move_to_element_with_offset(canvas, -50, -10).click_and_hold()
    for _ in range(4):
        drag = drag.move_by_offset(20, 8)
    drag.release().perform()
    revision, turned, pixels = settled(browser, revision)
    assert not np.allclose(turned["orientation"], start["orientation"])  # the drag turned it
    expected, _, _ = headless(turned, "phong")
    assert (pixels == expected).all()

    browser.execute_script("arguments[0].focus();", canvas)  # (focus without a click)
    ActionChains(browser).send_keys("1").perform()  # key 1: flat
    revision, flat_view, pixels = settled(browser, revision)
    expected, ids, _ = headless(flat_view, "flat")
    assert flat_view == turned and (pixels == expected).all()

    # a click on a polygon well inside its silhouette: the widget names what glshade's pick
    # names there (at that pixel, or a neighbour: the browser may round the click's place)
    pad = np.pad(ids, 2, constant_values=-2)
    inside = [(int(x), int(y)) for y, x in np.argwhere(ids >= 0)
              if (pad[y:y + 5, x:x + 5] == ids[y, x]).all()]
    x, y = inside[len(inside) // 2]
    _, _, picks = headless(flat_view, "flat", around=(x, y))
    ActionChains(browser).move_to_element_with_offset(
        canvas, x - SIZE[0] // 2, y - SIZE[1] // 2).click().perform()
    wait_for(browser, "document.querySelector('.glshade-status').textContent"
                      ".startsWith('pick: polygon')", timeout=60)
    status = browser.execute_script(
        "return document.querySelector('.glshade-status').textContent;")
    assert f"polygon {ids[y, x]} at" in status
    assert status in {f"pick: {p}" for p in picks.values()}, (status, picks[x, y])

    # the split compare: phong left of the middle, normals right of it
    from selenium.webdriver.support.ui import Select

    Select(browser.find_element("css selector", ".glshade-compare")).select_by_value("normals")
    revision, split_view, pixels = settled(browser, revision)
    left, _, _ = headless(split_view, "flat")
    right, _, _ = headless(split_view, "normals")
    half = SIZE[0] // 2
    assert (pixels[:, :half] == left[:, :half]).all()
    assert (pixels[:, half:] == right[:, half:]).all()

    # the trace button: the path tracer's picture, refined to trace_samples, then resting
    browser.find_element("css selector", ".glshade-trace").click()
    wait_for(browser, "document.querySelector('.glshade-status').textContent"
                      ".includes('path tracing, 4 samples a pixel (done')", timeout=120)
