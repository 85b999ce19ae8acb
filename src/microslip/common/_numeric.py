"""Small numerical helpers shared by the references (private)."""

from __future__ import annotations

import numpy as np


def invert_increasing(f, y, lo, hi, iterations: int = 64):
    """Solve ``f(x) = y`` for an increasing ``f`` on ``[lo, hi]`` by vectorised bisection.

    Parameters
    ----------
    f : callable
        Increasing function, vectorised over arrays.
    y : array_like
        Target values; ``lo``, ``hi`` broadcast with it.
    iterations : int
        Halvings of the bracket: 64 bring it to round-off for any float bracket.

    Returns
    -------
    ndarray
        ``x`` with ``f(x) = y`` to round-off, same shape as the broadcast inputs.
    """
    y = np.asarray(y, dtype=float)
    lo, hi = np.broadcast_arrays(np.asarray(lo, dtype=float), np.asarray(hi, dtype=float), y)[:2]
    lo, hi = lo.copy(), hi.copy()
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        below = f(mid) < y
        lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
    return 0.5 * (lo + hi)
