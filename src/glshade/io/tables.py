"""Plain-text tables for the command line, the comparison metrics and the benchmarks."""

from __future__ import annotations

__all__ = ["format_table"]


def format_table(rows, headers) -> str:
    """Columns padded to fit, a rule under the header; the first column left-aligned, the
    others (numbers) right-aligned.

    Parameters
    ----------
    rows : sequence of tuple
        The rows.
    headers : tuple of str
        The columns' names.
    """
    text = [[str(c) for c in row] for row in [headers, *rows]]
    widths = [max(len(r[i]) for r in text) for i in range(len(headers))]
    out = ["  ".join(c.ljust(w) for c, w in zip(text[0], widths)),
           "  ".join("-" * w for w in widths)]
    out += ["  ".join(c.rjust(w) if i else c.ljust(w) for i, (c, w) in enumerate(zip(r, widths)))
            for r in text[1:]]
    return "\n".join(out)
