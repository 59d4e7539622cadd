"""Shared timing helpers: series run interleaved in one process, medians reported."""

from __future__ import annotations

import statistics
import time


def interleaved(series: dict, repeats: int = 5) -> dict[str, float]:
    """Median seconds of each callable; one call of each per round, so drift in the
    machine's speed hits every series alike."""
    times: dict[str, list[float]] = {name: [] for name in series}
    for _ in range(repeats):
        for name, fn in series.items():
            t = time.perf_counter()
            fn()
            times[name].append(time.perf_counter() - t)
    return {name: statistics.median(ts) for name, ts in times.items()}


def frame_arguments(doc: str):
    """``--repeats`` and ``--size`` of a frame-time benchmark, parsed (its docstring's first
    paragraph as the description)."""
    import argparse

    parser = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--size", type=int, default=512)
    return parser.parse_args()


def frame_header(renderer, size: int, repeats: int) -> str:
    """The line that says what a frame-time table was measured on."""
    return (f"{renderer.context.detail}, {size}x{size}, Phong, medians of {repeats} "
            "interleaved rounds")


def table(rows: list[tuple], headers: tuple) -> str:
    from glshade.io.tables import format_table

    return format_table(rows, headers)
