"""Approve renders as golden images: ``python -m glshade.testing.approve RESULTS [KEY ...]``
(or ``--all``) writes each approved test's saved actual render, with its renderer's facts,
as its golden -- what the results folder's ``index.html`` lists, with a box per image, and
``approve.json`` records (KEY: ``node id::golden name``)."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

__all__ = ["approve", "main"]


def approve(results, keys=None) -> list[str]:
    """Write the actual renders of ``keys`` (all when None) recorded in ``results``'s
    ``approve.json`` as their goldens; the golden paths written.

    Parameters
    ----------
    results : str or Path
        The results folder (holding ``approve.json``).
    keys : list of str or None
        The renders to approve (None: all).
    """
    from PIL import Image

    from ..errors import InputError
    from .golden import write_golden

    manifest_path = Path(results) / "approve.json"
    if not manifest_path.is_file():
        raise InputError(f"{manifest_path}: no such file (a run that found differing "
                         "golden images writes it)")
    manifest = json.loads(manifest_path.read_text(encoding="utf-8"))
    chosen = list(manifest) if keys is None else list(keys)
    unknown = [k for k in chosen if k not in manifest]
    if unknown:
        raise InputError(f"{manifest_path}: no failure {unknown[0]!r}; it lists "
                         + (", ".join(repr(k) for k in manifest) or "none"))
    written = []
    for key in chosen:
        entry = manifest[key]
        with Image.open(entry["actual"]) as im:
            image = im.convert("RGBA")
            write_golden(Path(entry["golden"]), __import__("numpy").asarray(image),
                         entry["facts"])
        written.append(entry["golden"])
    return written


def main(argv=None) -> int:
    """The command: approve the named renders (or ``--all``); 0, or 2 with one line.

    Parameters
    ----------
    argv : list of str or None
        The arguments (None: sys.argv's).
    """
    from ..errors import GlshadeError

    ap = argparse.ArgumentParser(prog="python -m glshade.testing.approve",
                                 description=__doc__.split("\n\n")[0])
    ap.add_argument("results", help="the results folder (holds approve.json)")
    ap.add_argument("keys", nargs="*", help="node id::golden name, as index.html lists them")
    ap.add_argument("--all", action="store_true", help="approve every failure listed")
    a = ap.parse_args(argv)
    if not a.keys and not a.all:
        ap.error("name the renders to approve, or give --all")
    try:
        for path in approve(a.results, None if a.all else a.keys):
            print(f"approved: {path}")
    except GlshadeError as exc:
        print(f"approve: error: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
