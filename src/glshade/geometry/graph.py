"""Small vectorized graph helpers shared by the mesh and B-Rep code."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["component_labels", "cycle_labels"]

Int = NDArray[np.int64]


def component_labels(n: int, a: Int, b: Int) -> Int:
    """Connected-component label (the smallest member) of n nodes joined by pairs (a, b):
    min-label propagation with pointer jumping, as many rounds as the widest component
    needs (no Python loop over nodes).

    Parameters
    ----------
    n : int
        The nodes.
    a, b : ndarray
        ``(E,)`` the pairs joined.
    """
    labels = np.arange(n)
    if len(a) == 0:
        return labels
    while True:
        m = np.minimum(labels[a], labels[b])
        new = labels.copy()
        np.minimum.at(new, a, m)
        np.minimum.at(new, b, m)
        new = new[new]
        if np.array_equal(new, labels):
            return labels
        labels = new


def cycle_labels(nxt: Int) -> Int:
    """Label of each element of a permutation's cycles: the smallest index in its cycle
    (pointer doubling, log2(n) rounds).

    Parameters
    ----------
    nxt : ndarray
        ``(n,)`` a permutation: each element's successor.
    """
    label = np.arange(len(nxt))
    jump = nxt.copy()
    for _ in range(max(1, int(np.ceil(np.log2(max(len(nxt), 2)))) + 1)):
        label = np.minimum(label, label[jump])
        jump = jump[jump]
    return label
