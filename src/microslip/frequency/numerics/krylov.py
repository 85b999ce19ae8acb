"""Linear operators that are cheap to apply and GMRES on them (private; no physics).

The Jacobians of interface-dominated harmonic balance are dense once assembled, but they are sums of
parts that are cheap to apply: harmonic blocks of the linear structure and small blocks per contact.
A Newton step solves them by GMRES, preconditioned by the LU factors of a Jacobian met earlier
(:mod:`~.reuse`), and assembles a dense matrix only when it factorises one. The operators here are what
the continuation composes around such a Jacobian: the bordered systems of pseudo-arclength
continuation (:class:`Bordered`) with scaled columns (:class:`ScaledColumns`).

Every operator has ``shape``, ``matvec(v)`` and ``toarray()`` (the dense matrix); a NumPy array is one too
(:func:`apply`, :func:`dense`).
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla


def apply(A, v: np.ndarray) -> np.ndarray:
    """``A v`` for an operator of this module or an array."""
    return A.matvec(v) if hasattr(A, "matvec") else A @ v


def dense(A) -> np.ndarray:
    """The dense matrix of an operator of this module or an array (a fresh array for an operator)."""
    return A.toarray() if hasattr(A, "toarray") else np.asarray(A)


def submatrix(A, rows: np.ndarray, cols: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
    """The dense block ``A[rows][:, cols]`` of an operator or an array (index arrays), into ``out`` when given."""
    if hasattr(A, "submatrix"):
        return A.submatrix(rows, cols, out)
    block = np.asarray(A)[np.ix_(rows, cols)]
    if out is None:
        return block
    out[...] = block
    return out


def block_index(rows: np.ndarray, cols: np.ndarray) -> tuple:
    """An index of the block ``rows x cols`` of a 2-D array: slices where the indices are runs of consecutive
    integers (a view, not a gather), else :func:`numpy.ix_`."""
    def run(index):
        if index.size and index[-1] - index[0] == index.size - 1 and np.all(np.diff(index) == 1):
            return slice(int(index[0]), int(index[-1]) + 1)
        return None

    r, c = run(rows), run(cols)
    if r is not None and c is not None:
        return r, c
    return np.ix_(rows, cols)


def groups(A) -> list | None:
    """Groups of unknowns an operator lets eliminate first: ``[(interior, coupled), ...]`` or None.

    An operator that has them (a method ``groups()``) promises that its entries in the rows and columns of
    each group's ``interior`` unknowns lie in the group's ``interior`` or ``coupled`` unknowns only, and that
    no two groups share an interior unknown; it then also has ``submatrix(rows, cols)``.
    """
    return A.groups() if hasattr(A, "groups") else None


class ScaledColumns:
    """``A diag(s)``: the operator ``A`` with its columns multiplied by ``s`` (shape ``(n,)``)."""

    def __init__(self, A, s: np.ndarray):
        self.A, self.s = A, np.asarray(s, dtype=float)
        self.shape = A.shape

    def matvec(self, v: np.ndarray) -> np.ndarray:
        return apply(self.A, self.s * v)

    def groups(self) -> list | None:
        return groups(self.A)  # scaling columns moves no entry

    def submatrix(self, rows: np.ndarray, cols: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
        out = submatrix(self.A, rows, cols, out)
        out *= self.s[cols]
        return out

    def toarray(self) -> np.ndarray:
        if not hasattr(self.A, "toarray"):
            return np.asarray(self.A) * self.s
        out = self.A.toarray()  # fresh: scaled in place
        out *= self.s
        return out


class Bordered:
    """``[[A, U], [V, D]]``: an operator ``A`` ``(n, n)`` bordered by ``k`` columns ``U`` ``(n, k)``, rows ``V``
    ``(k, n)`` and a corner ``D`` ``(k, k)``."""

    def __init__(self, A, U: np.ndarray, V: np.ndarray, D: np.ndarray):
        self.A = A
        self.U, self.V, self.D = np.atleast_2d(U.T).T, np.atleast_2d(V), np.atleast_2d(D)
        n, k = A.shape[0], self.D.shape[0]
        self.n = n
        self.shape = (n + k, n + k)

    def matvec(self, v: np.ndarray) -> np.ndarray:
        n = self.n
        head, tail = v[:n], v[n:]
        return np.concatenate([apply(self.A, head) + self.U @ tail, self.V @ head + self.D @ tail])

    def groups(self) -> list | None:
        """The groups of ``A``, each coupled to the border's unknowns as well (its columns and rows are full)."""
        inner = groups(self.A)
        if inner is None:
            return None
        border = np.arange(self.n, self.shape[0])
        return [(interior, np.concatenate([coupled, border])) for interior, coupled in inner]

    def submatrix(self, rows: np.ndarray, cols: np.ndarray, out: np.ndarray | None = None) -> np.ndarray:
        n = self.n
        r_in, c_in = np.flatnonzero(rows < n), np.flatnonzero(cols < n)
        r_out, c_out = np.flatnonzero(rows >= n), np.flatnonzero(cols >= n)
        if out is None:
            out = np.empty((rows.size, cols.size))
        where = block_index(r_in, c_in)
        if isinstance(where[0], slice) and isinstance(where[1], slice):  # a view: filled in place
            submatrix(self.A, rows[r_in], cols[c_in], out[where])
        else:
            out[where] = submatrix(self.A, rows[r_in], cols[c_in])
        out[block_index(r_in, c_out)] = self.U[np.ix_(rows[r_in], cols[c_out] - n)]
        out[block_index(r_out, c_in)] = self.V[np.ix_(rows[r_out] - n, cols[c_in])]
        out[block_index(r_out, c_out)] = self.D[np.ix_(rows[r_out] - n, cols[c_out] - n)]
        return out

    def toarray(self) -> np.ndarray:
        n = self.n
        out = np.empty(self.shape)
        out[:n, :n] = dense(self.A)
        out[:n, n:] = self.U
        out[n:, :n] = self.V
        out[n:, n:] = self.D
        return out


def gmres(A, b: np.ndarray, precondition, *, rtol: float, max_iterations: int):
    """Right-preconditioned GMRES from zero: ``(z, iterations, converged, ritz)``.

    Parameters
    ----------
    A : operator or ndarray, shape (n, n)
    b : ndarray, shape (n,)
    precondition : callable
        ``u -> P^-1 u`` for a matrix ``P`` near ``A``.
    rtol : float
        Converged when ``|b - A z| <= rtol |b|``.
    max_iterations : int
        Krylov vectors at most (no restart).

    Returns
    -------
    z : ndarray, shape (n,)
        The best iterate found.
    iterations : int
    converged : bool
    ritz : ndarray of complex, shape (iterations,)
        Ritz values of ``A P^-1`` on the Krylov space: eigenvalues of ``A P^-1`` far from 1, those the
        preconditioner misses, are among them once GMRES has converged.
    """
    beta = float(np.linalg.norm(b))
    n = b.size
    if beta == 0.0:
        return np.zeros(n), 0, True, np.zeros(0, dtype=complex)
    m = max_iterations
    Q = np.empty((m + 1, n))
    Z = np.empty((m, n))
    Hs = np.zeros((m + 1, m))  # the Arnoldi relation A P^-1 Q_k = Q_(k+1) Hs
    R = np.zeros((m + 1, m))  # Hs rotated to upper triangular (Givens)
    cs, sn = np.zeros(m), np.zeros(m)
    g = np.zeros(m + 1)
    g[0] = beta
    Q[0] = b / beta
    k = 0
    converged = False
    while k < m:
        Z[k] = precondition(Q[k])
        w = apply(A, Z[k])
        for _ in range(2):  # Gram-Schmidt twice: orthogonal to rounding whatever the conditioning
            c = Q[:k + 1] @ w
            w = w - c @ Q[:k + 1]
            Hs[:k + 1, k] += c
        h = float(np.linalg.norm(w))
        Hs[k + 1, k] = h
        col = Hs[:k + 2, k].copy()
        for i in range(k):  # the earlier rotations
            col[i], col[i + 1] = cs[i] * col[i] + sn[i] * col[i + 1], -sn[i] * col[i] + cs[i] * col[i + 1]
        r = float(np.hypot(col[k], col[k + 1]))
        cs[k], sn[k] = (col[k] / r, col[k + 1] / r) if r > 0 else (1.0, 0.0)
        col[k], col[k + 1] = r, 0.0
        R[:k + 2, k] = col
        g[k], g[k + 1] = cs[k] * g[k], -sn[k] * g[k]
        k += 1
        if abs(g[k]) <= rtol * beta or h <= 1e-300 * beta:
            converged = True
            break
        Q[k] = w / h
    if k and np.all(np.diagonal(R[:k, :k]) != 0):
        y = sla.solve_triangular(R[:k, :k], g[:k], check_finite=False)
    else:
        y, converged = np.zeros(k), False
    z = y @ Z[:k]
    ritz = np.linalg.eigvals(Hs[:k, :k]) if k else np.zeros(0, dtype=complex)
    return z, k, converged, ritz
