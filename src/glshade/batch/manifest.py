"""``manifest.csv``: one row per input (what it became, or why it did not), written
atomically; an earlier run's manifest lends its rows to the inputs a rerun keeps."""

from __future__ import annotations

import csv
import dataclasses
import io
from pathlib import Path

from ..atomic import atomic_write
from .worker import Row

__all__ = ["write_manifest", "read_manifest", "COLUMNS"]

COLUMNS = ("input", "status", "polygons", "seconds", "outputs", "message", "renderer")


def write_manifest(rows: list[Row], path) -> None:
    """Outputs are written relative to the manifest's folder, so the folder can move.

    Parameters
    ----------
    rows : list of Row
        The rows.
    path : str or Path
        The manifest file.
    """
    import os

    base = Path(path).resolve().parent
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(COLUMNS)
    for r in rows:
        w.writerow([r.input, r.status, "" if r.polygons is None else r.polygons,
                    "" if r.seconds is None else f"{r.seconds:.4f}",
                    # (forward slashes: a manifest written on Windows reads everywhere)
                    ";".join(os.path.relpath(o, base).replace(os.sep, "/")
                             for o in r.outputs),
                    r.message, r.renderer])
    # (file names are bytes: one that is not UTF-8 is written back as the bytes it was)
    with atomic_write(path, "w", encoding="utf-8", errors="surrogateescape") as f:
        f.write(buf.getvalue())


def read_manifest(path) -> dict[str, Row]:
    """The rows of an earlier manifest by input (empty if there is none, or it is not ours).

    Parameters
    ----------
    path : str or Path
        The manifest file.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8", errors="surrogateescape")
    except (OSError, UnicodeDecodeError):
        return {}
    rows = {}
    reader = csv.DictReader(io.StringIO(text))
    if tuple(reader.fieldnames or ()) not in (COLUMNS, COLUMNS[:-1]):  # (older: no renderer)
        return {}
    for d in reader:
        try:
            rows[d["input"]] = Row(d["input"], d["status"],
                                   int(d["polygons"]) if d["polygons"] else None,
                                   float(d["seconds"]) if d["seconds"] else None,
                                   # (Windows reads either separator)
                                   tuple(str(path.parent.resolve() / x)
                                         for x in d["outputs"].split(";") if x),
                                   d["message"], d.get("renderer") or "")
        except (ValueError, TypeError):
            continue
    return rows


def kept(task, earlier: dict[str, Row]) -> Row:
    """The row of an input whose outputs all exist already."""
    old = earlier.get(task.input)
    row = Row(task.input, "exists", outputs=task.outputs,
              message="outputs exist; kept (--overwrite to render again)")
    if old is not None and old.status in ("ok", "exists"):
        row = dataclasses.replace(row, polygons=old.polygons, seconds=old.seconds,
                                  renderer=old.renderer)
    return row
