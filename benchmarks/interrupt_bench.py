"""Ctrl-C at random moments: how every command ends, and how long it takes to, with the
machine loaded (a busy loop on every core) or not. A command must end 0 (it had finished)
or 130 in one line within a second or two, at any moment: imports, the GL context, shader
compiles, passes, the write. Reported per command: the ends seen and the time from the
interrupt to the process's exit (median, 99th percentile, worst).

Run: ``.venv/bin/python benchmarks/interrupt_bench.py [--tries 100] [--load]``.
"""

from __future__ import annotations

import argparse
import multiprocessing
import os
import random
import signal
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _timing import table  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
COMMANDS = {
    "pathtrace": ["pathtrace", "assets/scenes/cornell-box.toml", "--spp", "1000000",
                  "--size", "32x32", "-q"],
    "render": ["render", "primitive:teapot", "--size", "96x72"],
    "radiosity": ["radiosity", "assets/scenes/cornell-box.toml", "--size", "32x32", "-q"],
    "batch": ["batch", "assets/teapot.obj", "--views", "64", "--size", "64x48", "--jobs",
              "1", "-q"],
}


def _busy() -> None:
    while True:
        pass


def one(command: list[str], delay: float, folder: Path) -> tuple[str, float]:
    """Start ``command``, interrupt it after ``delay`` s; (how it ended, seconds to exit)."""
    out = folder / ("out" if command[0] == "batch" else "out.png")
    proc = subprocess.Popen([sys.executable, "-m", "glshade", *command, "-o", str(out)],
                            cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            text=True)
    time.sleep(delay)
    sent = time.perf_counter()
    proc.send_signal(signal.SIGINT)
    try:
        _, err = proc.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        return "no end in 60 s", 60.0
    took = time.perf_counter() - sent
    lines = err.strip().splitlines()
    if proc.returncode in (0, 130) and len(lines) <= 1 and "Traceback" not in err:
        return str(proc.returncode), took
    if (lines[-1:] == ["KeyboardInterrupt"] and "glshade" not in err) or \
            (proc.returncode == -signal.SIGINT and not lines):  # (before Python's handler)
        return "the interpreter's start", took
    return f"{proc.returncode}: {lines[-1][:60] if lines else ''}", took


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--tries", type=int, default=100, help="interrupts a command")
    ap.add_argument("--most", type=float, default=3.0, help="latest moment, seconds")
    ap.add_argument("--load", action="store_true", help="a busy loop on every core")
    ap.add_argument("--commands", default=",".join(COMMANDS))
    args = ap.parse_args()
    signal.signal(signal.SIGINT, signal.SIG_DFL)  # (as a terminal's Ctrl-C would find it)
    load = [multiprocessing.Process(target=_busy, daemon=True)
            for _ in range(os.cpu_count() or 1)] if args.load else []
    for p in load:
        p.start()
    rng = random.Random(0)
    rows = []
    try:
        for name in args.commands.split(","):
            ends: Counter = Counter()
            took = []
            for _ in range(args.tries):
                with tempfile.TemporaryDirectory() as folder:
                    end, seconds = one(COMMANDS[name], rng.uniform(0.0, args.most),
                                       Path(folder))
                ends[end] += 1
                took.append(seconds)
            t = np.array(took)
            rows.append((name, args.tries, ", ".join(f"{k} x{v}" for k, v in ends.items()),
                         f"{np.median(t):.2f}", f"{np.percentile(t, 99):.2f}",
                         f"{t.max():.2f}"))
    finally:
        for p in load:
            p.terminate()
    print(f"Ctrl-C at moments uniform in [0, {args.most:g}] s"
          f"{', every core busy' if args.load else ''}")
    print(table(rows, ("command", "tries", "ends", "median s", "p99 s", "worst s")))


if __name__ == "__main__":
    main()
