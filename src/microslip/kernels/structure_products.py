"""Compiled products of a structure's three matrices with many coefficient vectors at once (private).

The interface harmonic balance applies ``K``, ``M`` and ``C`` (dense, ``(ndof, ndof)``) to every harmonic's
coefficients at each GMRES iteration. A BLAS matrix product with a handful of right-hand sides repacks the
large matrices at every call, and a matrix-vector product per coefficient vector reads each matrix once per
vector; this loop reads each row of the three matrices once and takes all the dot products from it. The sums
may be reassociated (vectorised), so the results equal :func:`structure_products_reference` to rounding;
NaN and infinity propagate as in the plain products.
"""

from __future__ import annotations

import numba as nb
import numpy as np


@nb.njit(cache=True, nogil=True, fastmath={"reassoc", "contract"})
def structure_products(K, M, C, V, KV, MV, CV):  # pragma: no cover - compiled
    """``KV = V K^T``, ``MV = V M^T``, ``CV = V C^T`` (each ``(r, ndof)``) of ``V`` ``(r, ndof)``, C-contiguous
    float64 arrays, written in place."""
    m, n = K.shape
    for i in range(m):
        for r in range(V.shape[0]):
            k = 0.0
            mm = 0.0
            c = 0.0
            for j in range(n):
                v = V[r, j]
                k += K[i, j] * v
                mm += M[i, j] * v
                c += C[i, j] * v
            KV[r, i] = k
            MV[r, i] = mm
            CV[r, i] = c


def structure_products_reference(K, M, C, V) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`structure_products` by NumPy's matrix products (its twin): ``(V K^T, V M^T, V C^T)``."""
    return V @ K.T, V @ M.T, V @ C.T
