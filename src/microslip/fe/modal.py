"""Natural frequencies of a finite-element model ``M q'' + K q = 0``."""

from __future__ import annotations

import numpy as np
import scipy.linalg
import scipy.sparse as sp

from ..common._numeric import eigsh_repeatable
from ..common import _checks
from .files import check_matrix


def natural_frequencies(M, K, count: int = 6) -> np.ndarray:
    """The ``count`` lowest natural frequencies (Hz) of ``M q'' + K q = 0``.

    Parameters
    ----------
    M, K : ndarray or scipy.sparse matrix, shape (ndof, ndof)
        Mass (kg) and stiffness (N/m), symmetric; ``M`` positive definite,
        ``K`` positive semi-definite (rigid-body modes give 0 Hz).
    count : int
        How many, ``1 <= count < ndof``.

    Returns
    -------
    ndarray, shape (count,)
        Frequencies ``sqrt(lambda) / (2 pi)`` in Hz, ascending.

    Raises
    ------
    ValueError
        ``M`` or ``K`` is not a square, finite, real, symmetric matrix
        (:func:`~microslip.fe.files.check_matrix`), they differ in size, or
        ``M`` is not positive definite (the eigenvalue problem has no
        solution, e.g. ``M`` singular).
    TypeError
        ``count`` is not an integer.

    Notes
    -----
    Sparse matrices are solved by shift-invert Lanczos (``scipy.sparse.linalg.eigsh``) about
    ``-1 (rad/s)^2``: ``K + M`` is positive definite even when ``K`` is singular (a free body).
    """
    M, K = check_matrix(M, "M"), check_matrix(K, "K")
    if M.shape != K.shape:
        raise ValueError(f"M and K must be square matrices of one size, got shapes {M.shape} and {K.shape}")
    n = M.shape[0]
    count = _checks.positive_int("count", count)
    if count >= n:
        raise ValueError(f"count must be below the number of DOFs ({n}), got {count}")
    if sp.issparse(M) or sp.issparse(K):
        try:
            lam = eigsh_repeatable(sp.csc_matrix(K), k=count, M=sp.csc_matrix(M), sigma=-1.0, which="LM",
                             return_eigenvectors=False)
        except RuntimeError as err:  # K + M singular (splu) or no convergence (ARPACK)
            raise ValueError(f"the natural frequencies of M and K could not be computed ({err}): M must be "
                             f"positive definite and K positive semi-definite") from None
    else:
        try:
            lam = scipy.linalg.eigh(K, M, eigvals_only=True, subset_by_index=[0, count - 1])
        except np.linalg.LinAlgError as err:
            if "of B is not positive definite" in str(err):
                raise ValueError(f"M must be positive definite ({err})") from None
            raise ValueError(f"the eigenvalue problem of M and K did not converge ({err})") from None
    return np.sqrt(np.clip(np.sort(lam), 0.0, None)) / (2 * np.pi)
