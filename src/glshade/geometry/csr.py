"""Faces as one flat index array plus offsets (CSR layout), built from what users hand in:
an ``(F, k)`` array or a list of index sequences of any lengths."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from ..errors import GeometryError

__all__ = ["faces_to_csr"]


def faces_to_csr(faces) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """Accept an (F, k) array or a sequence of index sequences; return (indices, offsets).

    Parameters
    ----------
    faces : array_like or sequence
        ``(F, k)`` indices, or a sequence of index sequences.
    """
    if isinstance(faces, np.ndarray) or (
        isinstance(faces, Sequence) and faces and not isinstance(faces[0], (Sequence, np.ndarray))
    ):
        arr = np.asarray(faces)
        if arr.ndim != 2:
            raise GeometryError(
                f"faces must be an (F, k) array or a list of index sequences, got shape {arr.shape}"
            )
        f, k = arr.shape
        return _integer_indices(arr.ravel()), np.arange(f + 1, dtype=np.int64) * k
    faces = list(faces)
    sizes = np.fromiter((len(f) for f in faces), dtype=np.int64, count=len(faces))
    offsets = np.zeros(len(faces) + 1, dtype=np.int64)
    np.cumsum(sizes, out=offsets[1:])
    try:
        flat = np.array([i for f in faces for i in f])
    except (TypeError, ValueError) as exc:
        raise GeometryError(f"face indices must be integers: {exc}") from None
    return _integer_indices(flat.reshape(-1)), offsets


def _integer_indices(values: np.ndarray) -> NDArray[np.int64]:
    """Face indices as int64; a float that is not a whole number (1.5, nan) is an error
    naming it, never truncated."""
    if values.size == 0 or np.issubdtype(values.dtype, np.integer):
        return values.astype(np.int64)
    if values.dtype.kind not in "fb" and values.dtype != object:
        raise GeometryError(f"face indices must be integers, got dtype {values.dtype}")
    try:
        v = values.astype(np.float64)
    except (TypeError, ValueError):
        raise GeometryError("face indices must be integers") from None
    bad = ~np.isfinite(v) | (v != np.round(v)) | (np.abs(v) > 2**53)
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise GeometryError(f"face index {float(v[i]):g} (position {i} of the flat index "
                            "list) is not a whole number")
    return v.astype(np.int64)
