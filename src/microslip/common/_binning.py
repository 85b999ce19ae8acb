"""Means of scattered points in bins of their abscissa (private)."""

from __future__ import annotations

import numpy as np


def binned_means(x, edges, *values):
    """Count and mean of each of ``values`` in the bins ``edges`` of ``x``.

    Bin ``k`` holds ``edges[k] <= x < edges[k + 1]``; the last bin also holds
    ``x == edges[-1]``; points outside ``[edges[0], edges[-1]]`` are left out.

    Parameters
    ----------
    x : ndarray, shape (P,)
        Abscissa of the points (any unit).
    edges : ndarray, shape (B + 1,)
        Increasing bin edges (unit of ``x``).
    *values : ndarray, shape (P,)
        Quantities to average per bin (e.g. ``x`` itself and ``y``).

    Returns
    -------
    count : ndarray of int, shape (B,)
        Points in each bin.
    means : list of ndarray, shape (B,)
        Mean of each of ``values`` per bin, NaN in an empty bin.
    """
    B = edges.size - 1
    which = np.minimum(np.digitize(x, edges) - 1, B - 1)
    keep = (which >= 0) & (x <= edges[-1])
    which = which[keep]
    count = np.bincount(which, minlength=B)
    with np.errstate(invalid="ignore", divide="ignore"):
        means = [np.bincount(which, weights=np.asarray(v)[keep], minlength=B) / count for v in values]
    return count, means
