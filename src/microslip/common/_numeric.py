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


def eigsh_repeatable(A, k: int, **options):
    """:func:`scipy.sparse.linalg.eigsh` that gives the same answer in every run.

    ARPACK starts from a random vector of its own unless given one, so the same matrices gave eigenvalues
    differing in their last digits and eigenvectors of either sign from one run to the next (and so reduced
    models, linear modes and every curve built on them). Here the start vector is fixed (a generic one: a
    seeded normal draw, which no eigenvector is orthogonal to in practice) and each eigenvector is signed so
    that its entry of largest magnitude is positive. ``options`` are eigsh's (``M``, ``sigma``, ``which``,
    ``OPinv``, ``return_eigenvectors``, ...); the return value is eigsh's.
    """
    import scipy.sparse.linalg as spla

    options.setdefault("v0", np.random.default_rng(0).standard_normal(A.shape[0]))
    out = spla.eigsh(A, k=k, **options)
    if not options.get("return_eigenvectors", True):
        return out
    lam, vec = out
    big = vec[np.argmax(np.abs(vec), axis=0), np.arange(vec.shape[1])]
    return lam, vec * np.where(big < 0, -1.0, 1.0)
