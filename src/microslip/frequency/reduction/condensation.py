"""Exact dynamic condensation of a linear structure onto a set of retained DOFs, harmonic by harmonic.

For harmonic ``h`` at the excitation frequency ``omega`` the structure's complex
dynamic stiffness is ``Z = K - (h omega)^2 M + i h omega C``. Partitioned into
retained DOFs ``r`` and the others ``i`` (no external force on ``i``), the
interior is eliminated exactly:

``S = Z_rr - Z_ri Z_ii^-1 Z_ir``  (the Schur complement),
``q_i = -Z_ii^-1 Z_ir q_r``      (recovery of the interior).

Its derivative with respect to ``omega`` (for continuation) is exact too:
``S' = Z'_rr - Z'_ri W - V^T Z'_ir + V^T Z'_ii W`` with ``W = Z_ii^-1 Z_ir``,
``V^T = Z_ri Z_ii^-1`` and ``Z' = -2 h^2 omega M + i h C``; when ``M``, ``C`` and
``K`` are symmetric (finite-element matrices), ``Z`` is complex symmetric and
``V = W``, so one solve gives both.

Cost at finite-element sizes: the interior block is assembled from arrays
aligned once on its sparsity pattern and factorised with a minimum-degree
ordering of ``Z + Z^T`` (less fill than SuperLU's default column ordering on
these symmetric patterns: 3-5 times faster at 10^5 DOFs); a static or undamped
harmonic is solved in real arithmetic.

Along a curve, from the second frequency on (a dense interior: the fourth), a
symmetric structure whose damping the held structure's normal modes diagonalise
(none, Rayleigh damping, modal damping) is condensed through those modes
instead of a factorisation per frequency and harmonic. With ``K_ii Phi = M_ii
Phi Lambda``, ``Phi^T M_ii Phi = I``, ``Phi^T C_ii Phi = diag(c)`` and the static
constraint modes ``Psi = -K_ii^-1 K_ir`` the condensed stiffness is

``S = S0(W) - G D^-1 G^T``,  ``D = Lambda - W^2 I + i W diag(c)``,

``S0`` the static condensation's ``K - W^2 M + i W C``, ``G = -W^2 M^_r,eta +
i W C^_r,eta`` (Craig-Bampton coordinates with every mode: exact, not a modal
truncation). A sparse interior with Rayleigh damping ``c = a + b lambda``
keeps its :data:`SERIES_MODES` lowest modes (more on demand) and sums all the
others exactly as a power series in ``(W^2 - i W a) / ((1 + i W b) lambda)``
whose coefficients come from a few solves with ``K_ii``
(:class:`_Tail`); otherwise an interior of up to :data:`SPECTRAL_INTERIOR`
DOFs takes every mode from a dense eigensolution.

A complex amplitude ``z = a - i b`` of ``a cos + b sin`` acted on by ``S = S_r + i S_i``
gives the real harmonic-balance block ``[[S_r, S_i], [-S_i, S_r]]`` on ``(a, b)``.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ...common._numeric import eigsh_repeatable
from ...common.errors import MicroslipError, SingularInteriorError

#: interior DOFs up to which the interior block is factorised densely
DENSE_INTERIOR = 400
#: interior DOFs up to which a classically damped interior is condensed through all its normal modes
#: (a sparse interior with Rayleigh damping, of any size, through a few of them and the series of the others)
SPECTRAL_INTERIOR = 2000
#: normal modes of the held structure the series form starts with, and at most (also at most a quarter)
SERIES_MODES = 16
SERIES_MODES_MAX = 256
#: largest ratio of the series' successive terms; above it more modes are computed
SERIES_RATIO = 0.25
#: terms of the series at most (SERIES_RATIO^60 is far below rounding)
SERIES_TERMS = 60
#: frequencies of a harmonic factorised before the normal modes of its interior are computed (a dense
#: interior: all of them; a sparse one: the lowest few, :data:`SERIES_MODES`, which cost far less)
SPECTRAL_AFTER = 3
SERIES_AFTER = 1
#: off-diagonal modal damping, relative to its largest entry, below which damping counts as classical
CLASSICAL = 1e-12
#: largest ``modes x (coupling rows)^2 / 2`` kept for the spectral interior (160 MB)
PAIRS_LIMIT = 20_000_000
#: fill-reducing ordering of the sparse factorisations (minimum degree on the pattern of A + A^T)
ORDERING = "MMD_AT_PLUS_A"


def _split(A, r, i):
    """Blocks ``(A_rr, A_ri, A_ir, A_ii)``: the first three dense, ``A_ii`` sparse CSC or dense."""
    if sp.issparse(A):  # each entry sent to its block in one vectorised pass (fancy indexing copies twice)
        A = sp.coo_matrix(A)
        n = A.shape[0]
        side = np.zeros(n, dtype=bool)
        side[i] = True  # True: interior
        at = np.empty(n, dtype=np.int64)
        at[r], at[i] = np.arange(r.size), np.arange(i.size)
        row_i, col_i = side[A.row], side[A.col]
        rows, cols = at[A.row], at[A.col]
        out = []
        for a, b, shape in ((False, False, (r.size, r.size)), (False, True, (r.size, i.size)),
                            (True, False, (i.size, r.size)), (True, True, (i.size, i.size))):
            keep = (row_i == a) & (col_i == b)
            out.append(sp.coo_matrix((A.data[keep], (rows[keep], cols[keep])), shape=shape))
        Aii = out[3].tocsc()
        return (out[0].toarray(), out[1].toarray(), out[2].toarray(),
                Aii if i.size > DENSE_INTERIOR else Aii.toarray())
    A = np.asarray(A)
    return A[np.ix_(r, r)], A[np.ix_(r, i)], A[np.ix_(i, r)], A[np.ix_(i, i)]


def _symmetric(A) -> bool:
    """True when ``A`` (dense or sparse) equals its transpose exactly."""
    if sp.issparse(A):
        A = sp.csr_matrix(A)
        return (A != A.T).nnz == 0
    A = np.asarray(A)
    return bool(np.array_equal(A, A.T))


def _canonical(A) -> sp.csc_matrix:
    """``A`` as CSC without duplicates, its row indices sorted in each column."""
    A = sp.csc_matrix(A)
    A.sum_duplicates()
    A.sort_indices()
    return A


def _keys(A) -> np.ndarray:
    """Column-major position ``col * rows + row`` of every stored entry of canonical CSC ``A`` (sorted)."""
    cols = np.repeat(np.arange(A.shape[1], dtype=np.int64), np.diff(A.indptr))
    return cols * A.shape[0] + A.indices


class _AlignedInterior:
    """``Z_ii = K_ii - W^2 M_ii + i W C_ii`` assembled from data arrays on one CSC pattern (no sparse sums).

    Finite-element matrices usually share one pattern (then their data arrays are
    used as they are); otherwise each is laid out on the union of the patterns.
    """

    def __init__(self, bM, bC, bK):
        mats = [_canonical(A) for A in (bK, bM, bC)]  # one may be dense (a dense C with sparse M, K)
        stored = [A for A in mats if A.nnz]
        first = stored[0] if stored else mats[0]
        if all(np.array_equal(A.indptr, first.indptr) and np.array_equal(A.indices, first.indices) for A in stored):
            self.indptr, self.indices = first.indptr, first.indices
            data = [A.data if A.nnz else np.zeros(first.nnz) for A in mats]
        else:  # the union of the stored entries (explicit zeros included), from ones that cannot cancel
            pattern = sum(sp.csc_matrix((np.ones(A.nnz), A.indices, A.indptr), shape=A.shape) for A in stored)
            pattern = _canonical(pattern)
            self.indptr, self.indices = pattern.indptr, pattern.indices
            keys = _keys(pattern)
            data = []
            for A in mats:
                d = np.zeros(pattern.nnz, dtype=A.dtype)
                d[np.searchsorted(keys, _keys(A))] = A.data
                data.append(d)
        self.shape = first.shape
        self.k, self.m, self.c = data
        self.damped = bool(np.any(self.c))

    def __call__(self, key):
        w2, w = key
        data = self.k - w2 * self.m
        if w and self.damped:
            data = data + (1j * w) * self.c
        return sp.csc_matrix((data, self.indices, self.indptr), shape=self.shape)


def _dense(A) -> np.ndarray:
    return A.toarray() if sp.issparse(A) else np.asarray(A)


def _rayleigh(M, C, K):
    """``(a, b)`` with ``C = a M + b K`` to :data:`CLASSICAL` of ``|C|`` (entrywise, least squares), or None."""
    if sp.issparse(M) or sp.issparse(C) or sp.issparse(K):
        aligned = _AlignedInterior(M, C, K)
        m, c, k = aligned.m, aligned.c, aligned.k
    else:
        m, c, k = (np.ravel(A) for A in (M, C, K))
    A = np.stack([m, k], axis=1)
    scale = np.maximum(np.abs(A).max(axis=0), 1e-300)
    ab = np.linalg.lstsq(A / scale, c, rcond=None)[0] / scale
    if np.max(np.abs(c - A @ ab), initial=0.0) > CLASSICAL * max(float(np.max(np.abs(c), initial=0.0)), 1e-300):
        return None
    return float(ab[0]), float(ab[1])


class _Products:
    """``X diag(w) X^T`` for many real weight vectors ``w`` at once: one product with the pairs ``X[a] X[b]``."""

    def __init__(self, X):
        self.p = X.shape[0]
        self.upper = np.triu_indices(self.p)
        self.pairs = np.ascontiguousarray((X[self.upper[0]] * X[self.upper[1]]).T)  # (modes, pairs)

    def __call__(self, wts) -> np.ndarray:
        """``(..., p, p)`` from weights ``(..., modes)``."""
        flat = wts @ self.pairs
        out = np.empty(wts.shape[:-1] + (self.p, self.p))
        out[..., self.upper[0], self.upper[1]] = flat
        out[..., self.upper[1], self.upper[0]] = flat
        return out


class _TooFewModes(MicroslipError):
    """The series of the omitted modes would converge too slowly at a frequency: more modes are needed."""

    def __init__(self, needed: float):
        super().__init__(needed)
        self.needed = needed  # the eigenvalue (rad^2/s^2) the omitted modes must start above


class _Tail:
    """The omitted modes' share of ``X diag(1/d) X^T``, exactly, as a power series (Rayleigh damping).

    With ``c = a + b lambda``, ``d_k = p lambda_k - q`` (``p = 1 + i W b``,
    ``q = W^2 - i W a``) and for every omitted mode ``lambda_k >= lambda_c``::

        sum_k x_k x_k^T / d_k = sum_j z^j / p R_j,   z = q / (p lambda_c),
        R_j = lambda_c^j sum_k x_k x_k^T / lambda_k^(j+1) = B^T V_j,

    ``V_0 = P K_ii^-1 B``, ``V_j = lambda_c P K_ii^-1 M_ii V_(j-1)``, ``P`` the
    projection that removes the kept modes. Terms are added until they fall
    below rounding; ``|z| <= SERIES_RATIO`` (else :class:`_TooFewModes`).
    """

    def __init__(self, solve, M, phi, lam_c: float, Bs, a: float, b: float):
        self.solve, self.M, self.phi, self.lam_c, self.Bs, self.a, self.b = solve, M, phi, lam_c, Bs, a, b
        self.V = self._project(solve(Bs))
        self.R = []

    def _project(self, V):
        return V - self.phi @ (self.phi.T @ np.asarray(self.M @ V))

    def _terms(self, J: int) -> np.ndarray:
        while len(self.R) < J:
            self.R.append(self.Bs.T @ self.V)
            self.V = self.lam_c * self._project(self.solve(np.asarray(self.M @ self.V)))
        return np.stack(self.R[:J])

    def add(self, W, derivative: bool, xi: float = 0.0, xi_derivative: bool = False):
        """``[sum_k x x^T / d_k, its W-derivative, its xi-derivative]`` over the omitted modes, each
        ``(len(W), p, p)`` (the derivatives only when asked for); ``xi`` lowers the mass-proportional
        damping ``a`` (the extended periodic motion concept's ``-xi M``)."""
        a = self.a - xi
        q = W * W - 1j * W * a
        p = 1.0 + 1j * W * self.b
        z = q / (p * self.lam_c)
        rho = float(np.max(np.abs(z)))
        if rho > SERIES_RATIO:
            raise _TooFewModes(float(np.max(np.abs(q / p))) / (0.5 * SERIES_RATIO))
        J = 1 if rho == 0 else int(min(SERIES_TERMS, max(1, np.ceil(np.log(1e-17) / np.log(rho)))))
        R = self._terms(J)
        zj = z[:, None] ** np.arange(J)[None]  # (H, J)
        out = [np.einsum("hj,jab->hab", zj / p[:, None], R)]
        zjm1 = np.concatenate([np.zeros((W.size, 1), dtype=complex), zj[:, :-1]], axis=1)  # z^(j-1)
        if derivative:
            dz = ((2 * W - 1j * a) * p - q * (1j * self.b)) / (self.lam_c * p * p)
            dcoef = np.arange(J)[None] * zjm1 * (dz / p)[:, None] - zj * (1j * self.b / (p * p))[:, None]
            out.append(np.einsum("hj,jab->hab", dcoef, R))
        if xi_derivative:  # dz/dxi = i W / (p lambda_c)
            dcoef = np.arange(J)[None] * zjm1 * (1j * W / (self.lam_c * p * p))[:, None]
            out.append(np.einsum("hj,jab->hab", dcoef, R))
        return out


def _static_part(blocks, psi):
    """``(rr, Bs, gamma)``: the condensed ``(K^_rr, M^_rr, C^_rr)``, the coupling columns and their damping.

    ``Bs`` holds ``B = M_ir + M_ii Psi`` (the mass coupling of the constraint modes),
    then ``C_ir + C_ii Psi`` unless that is ``gamma B`` (Rayleigh damping; ``gamma`` None otherwise).
    """
    (Mrr, Mri, Mir, Mii), (Crr, Cri, Cir, Cii), (Krr, Kri, Kir, Kii) = blocks
    Mir, Cir = np.asarray(Mir), np.asarray(Cir)
    Mi_psi, Ci_psi = np.asarray(Mii @ psi), np.asarray(Cii @ psi)
    rr = (np.asarray(Krr) + np.asarray(Kri) @ psi,
          np.asarray(Mrr) + np.asarray(Mri) @ psi + psi.T @ Mir + psi.T @ Mi_psi,
          np.asarray(Crr) + np.asarray(Cri) @ psi + psi.T @ Cir + psi.T @ Ci_psi)
    B, BC = Mir + Mi_psi, Cir + Ci_psi
    gamma = float(np.sum(BC * B) / max(np.sum(B * B), 1e-300))
    # C_ir + C_ii Psi cancels (to rounding) for C = beta K: compare with the size of its two terms
    if np.linalg.norm(BC - gamma * B) <= CLASSICAL * (np.linalg.norm(Cir) + np.linalg.norm(Ci_psi)):
        return rr, B, gamma
    return rr, np.hstack([B, BC]), None


class _SpectralInterior:
    """The interior condensed through the normal modes of the held structure (see the module docstring).

    In the coordinates ``q_i = Psi q_r + Phi eta`` (``Psi = -K_ii^-1 K_ir``, the
    static constraint modes; ``Phi`` the fixed-interface modes) the stiffness
    couples nothing and ``S = S0(W) - G D^-1 G^T`` with
    ``S0 = K^_rr - W^2 M^_rr + i W C^_rr``, ``G = -W^2 M^_r,eta + i W C^_r,eta``.
    ``G D^-1 G^T`` and its derivative are sums of ``X diag(w) X^T`` over the
    rows ``X`` of ``M^_r,eta`` (and ``C^_r,eta`` unless it is a multiple of it, as
    with Rayleigh damping) with weights ``w`` from ``1/d``: real products, all
    harmonics in one.

    :meth:`full`: every mode from a dense eigensolution; :meth:`series`: a few
    modes from a sparse one, the others summed exactly by :class:`_Tail`. Both
    return None where they do not apply: ``M_ii`` not positive definite,
    ``K_ii`` singular, damping the modes do not diagonalise (off-diagonal modal
    damping above :data:`CLASSICAL` of its largest entry; the series needs
    Rayleigh damping of the interior).
    """

    def __init__(self, lam, c, phi, psi, rr, X, gamma, tail=None):
        self.lam, self.c, self.phi, self.psi = lam, c, phi, psi
        self.rr = rr  # K^_rr, M^_rr, C^_rr, (m, m)
        self.X = X  # (p, modes): M^_r,eta, then C^_r,eta unless gamma is not None (C^_r,eta = gamma M^_r,eta)
        self.products = _Products(X)
        self.gamma = gamma
        self.tail = tail
        self.m = rr[0].shape[0]
        self.damped = bool(np.any(c)) or bool(np.any(rr[2])) or gamma != 0.0

    @classmethod
    def full(cls, blocks):
        (_, _, Mir, Mii), (_, _, _, Cii), (_, _, Kir, Kii) = blocks
        try:
            lam, phi = sla.eigh(_dense(Kii), _dense(Mii), driver="gvd", check_finite=False)
        except (np.linalg.LinAlgError, ValueError):  # M_ii not positive definite
            return None
        if lam[0] <= 1e-12 * max(abs(lam[-1]), 1e-300):  # the held structure can move freely: K_ii singular
            return None
        rayleigh = _rayleigh(Mii, Cii, Kii)
        if rayleigh is not None:  # C_ii = a M_ii + b K_ii: c = a + b lambda, without an n^3 product
            c = rayleigh[0] + rayleigh[1] * lam
        else:
            Cm = phi.T @ np.asarray(Cii @ phi)
            off = np.abs(Cm - np.diag(np.diag(Cm)))
            if off.size and off.max() > CLASSICAL * max(float(np.abs(Cm).max()), 1e-300):
                return None
            c = np.real(np.diag(Cm)).copy()
        psi = -phi @ ((phi.T @ np.asarray(Kir)) / lam[:, None])  # -K_ii^-1 K_ir through the modes
        rr, Bs, gamma = _static_part(blocks, psi)
        X = Bs.T @ phi
        if X.shape[0] * (X.shape[0] + 1) // 2 * X.shape[1] > PAIRS_LIMIT:
            return None
        return cls(lam, c, phi, psi, rr, X, gamma)

    @classmethod
    def series(cls, blocks, needed: float = 0.0):
        """The lowest :data:`SERIES_MODES` modes (more until the omitted ones start above ``needed``) and the tail."""
        (_, _, Mir, Mii), (_, _, _, Cii), (_, _, Kir, Kii) = blocks
        rayleigh = _rayleigh(Mii, Cii, Kii)
        if rayleigh is None:
            return None
        K, M = sp.csc_matrix(Kii), sp.csr_matrix(Mii)
        n = K.shape[0]
        try:
            lu = spla.splu(K, permc_spec=ORDERING)
        except RuntimeError:  # K_ii exactly singular
            return None
        psi = -lu.solve(np.asarray(Kir, dtype=float))
        op = spla.LinearOperator(K.shape, matvec=lu.solve, dtype=float)
        most = min(SERIES_MODES_MAX, n // 4)  # beyond: a dense spectrum, better computed whole
        k = min(SERIES_MODES, most)
        while True:
            try:
                lam, phi = eigsh_repeatable(K, k=k, M=M, sigma=0.0, which="LM", OPinv=op)
            except (spla.ArpackError, ValueError):
                return None
            # Rayleigh-Ritz on the converged subspace: exactly mass-orthonormal modes
            lam, v = sla.eigh(phi.T @ (K @ phi), phi.T @ (M @ phi))
            phi = phi @ v
            if lam[-1] >= needed or k >= most:
                break
            k = min(2 * k, most)
        if lam[0] <= 1e-12 * max(abs(lam[-1]), 1e-300) or lam[-1] < needed:
            return None
        rr, Bs, gamma = _static_part(blocks, psi)
        c = rayleigh[0] + rayleigh[1] * lam
        tail = _Tail(lu.solve, M, phi, float(lam[-1]), Bs, *rayleigh)
        return cls(lam, c, phi, psi, rr, Bs.T @ phi, gamma, tail)

    def _factors(self, W, xi: float = 0.0):
        """``(f, f', f_xi)``, each ``(len(W), blocks)``: the coupling ``G = sum_j f_j X_j``, ``dG/dW`` and
        ``dG/dxi`` with the damping ``C - xi M``."""
        if self.gamma is not None:
            g = self.gamma - xi
            return (-W * W + 1j * g * W)[:, None], (-2 * W + 1j * g)[:, None], (-1j * W)[:, None]
        return (np.stack([-W * W - 1j * xi * W, 1j * W], axis=1), np.stack([-2 * W - 1j * xi, np.full(W.shape, 1j)],
                                                                            axis=1),
                np.stack([-1j * W, np.zeros(W.shape)], axis=1))

    def _d(self, W, xi: float = 0.0):
        """The diagonal of ``D`` for each frequency, ``(len(W), modes)``, with the damping ``C - xi M``;
        None when one is singular."""
        damped = self.damped or xi != 0.0
        d = self.lam[None] - (W * W)[:, None] + ((1j * W)[:, None] * (self.c - xi)[None] if damped else 0.0)
        if np.any(np.abs(d) <= 1e-14 * np.max(np.abs(d), axis=1, keepdims=True)):
            return None
        return d

    def evaluate(self, hs, omega: float, derivative: bool, xi: float = 0.0, xi_derivative: bool = False):
        """``(S, S', S_xi)``, each ``(len(hs), m, m)`` complex, for harmonics ``hs`` at ``omega`` with the damping
        ``C - xi M`` (``S'``, ``S_xi = dS/dxi`` None unless asked for); None when ``D`` is singular.

        Raises :class:`_TooFewModes` when the tail's series would converge too slowly.
        """
        hs = np.asarray(hs, dtype=float)
        W = hs * omega
        d = self._d(W, xi)
        if d is None:
            return None
        damped = self.damped or xi != 0.0
        u = 1.0 / d
        weights = [u]
        if derivative:
            weights.append((2 * W[:, None] - 1j * (self.c - xi)[None]) * u * u)  # d(1/d)/dW
        if xi_derivative:
            weights.append(1j * W[:, None] * u * u)  # d(1/d)/dxi
        parts = [w.real for w in weights] + ([w.imag for w in weights] if damped else [])
        Y = self.products(np.stack(parts, axis=1))  # (H, q, p, p) for the weights (H, q, modes)
        H, k = W.size, len(weights)
        Yc = Y[:, :k] + (1j * Y[:, k:] if damped else 0.0)  # (H, k, p, p): X diag(w) X^T, complex w
        if self.tail is not None:
            Yc = Yc + np.stack(self.tail.add(W, derivative, xi, xi_derivative), axis=1)
        f, fp, fx = self._factors(W, xi)
        nb, m = f.shape[1], self.m
        Kr, Mr, Cr = self.rr
        Cr = Cr - xi * Mr
        S = np.empty((H, m, m), dtype=complex)
        S[:] = Kr[None] - (W * W)[:, None, None] * Mr[None] + (1j * W)[:, None, None] * Cr[None]
        dS = dSx = None
        if derivative:
            dS = np.empty((H, m, m), dtype=complex)
            dS[:] = -2 * W[:, None, None] * Mr[None] + 1j * Cr[None]
        if xi_derivative:
            dSx = -(1j * W)[:, None, None] * Mr[None]
        for j in range(nb):
            for l in range(nb):
                Bu = Yc[:, 0, j * m:(j + 1) * m, l * m:(l + 1) * m]
                ff = (f[:, j] * f[:, l])[:, None, None]
                S -= ff * Bu
                if derivative:
                    Bd = Yc[:, 1, j * m:(j + 1) * m, l * m:(l + 1) * m]
                    dS -= (fp[:, j] * f[:, l] + f[:, j] * fp[:, l])[:, None, None] * Bu + ff * Bd
                if xi_derivative:
                    Bx = Yc[:, k - 1, j * m:(j + 1) * m, l * m:(l + 1) * m]
                    dSx -= (fx[:, j] * f[:, l] + f[:, j] * fx[:, l])[:, None, None] * Bu + ff * Bx
        if derivative:
            dS *= hs[:, None, None]  # d/domega = h d/dW
        return S, dS, dSx

    def interior(self, W: float, q_r, xi: float = 0.0):
        """Interior amplitudes ``Psi q_r - Phi D^-1 G^T q_r`` at the frequency ``W`` with the damping ``C - xi M``;
        None when ``D`` is singular or only some modes are kept (the interior is then solved by factorisation)."""
        Wa = np.array([float(W)])
        d = self._d(Wa, xi)
        if d is None or self.tail is not None:
            return None
        f = self._factors(Wa, xi)[0]
        m = self.m
        Gq = sum(f[0, j] * (self.X[j * m:(j + 1) * m].T @ q_r) for j in range(f.shape[1]))
        eta = Gq / (d[0] if np.ndim(Gq) == 1 else d[0][:, None])
        return self.psi @ q_r - self.phi @ eta

    def projection(self, W: float, w_i, xi: float = 0.0):
        """``(g, dg/dW, dg/dxi)``, complex ``(m,)``: ``w_i . q_i = g . q_r`` for the interior amplitudes of
        :meth:`interior` (damping ``C - xi M``); None when ``D`` is singular.

        ``w_i . q_i = (Psi^T w_i) . q_r - sum_k (G^T q_r)_k (phi_k . w_i) / d_k`` over every mode; with only some
        modes kept the others' share ``sum_k x_k (phi_k . w_i) / d_k`` is the series of :class:`_Tail` with
        ``w_i`` as one more column (raises :class:`_TooFewModes` where it would converge too slowly).
        """
        Wa = np.array([float(W)])
        d = self._d(Wa, xi)
        if d is None:
            return None
        u = 1.0 / d[0]
        e = self.phi.T @ w_i  # the kept modes' share of w_i
        f, fp, fx = (a[0] for a in self._factors(Wa, xi))
        c = self.c - xi if (self.damped or xi) else 0.0
        # X diag(e/d) and its W and xi derivatives: one column per block of G (rows of X)
        cols = [self.X @ (e * u), self.X @ (e * (2 * W - 1j * c) * u * u), self.X @ (e * (1j * W) * u * u)]
        if self.tail is not None:
            p = self.X.shape[0]
            parts = self._tail_for(w_i).add(Wa, True, xi, True)  # (1, p + 1, p + 1) each: the last column
            cols = [col + part[0, :p, p] for col, part in zip(cols, parts)]
        m = self.m
        block = [[col[j * m:(j + 1) * m] for j in range(f.size)] for col in cols]
        g = self.psi.T @ w_i - sum(f[j] * block[0][j] for j in range(f.size))
        gW = -sum(fp[j] * block[0][j] + f[j] * block[1][j] for j in range(f.size))
        gx = -sum(fx[j] * block[0][j] + f[j] * block[2][j] for j in range(f.size))
        return g, gW, gx

    def _tail_for(self, w_i) -> _Tail:
        """The series of the omitted modes with ``w_i`` as one more coupling column (kept for the last ``w_i``)."""
        key = w_i.tobytes()
        if getattr(self, "_weighted", (None,))[0] != key:
            t = self.tail
            self._weighted = (key, _Tail(t.solve, t.M, t.phi, t.lam_c, np.column_stack([t.Bs, w_i]), t.a, t.b))
        return self._weighted[1]


def _key(W: float, xi: float = 0.0):
    """``(W^2 + i W xi, W)``: the factor of ``M`` and of ``i C`` in ``Z = K - W^2 M + i W (C - xi M)``."""
    return (W * W + 1j * W * xi if xi else W * W), W


def _schur_derivative(blocks, a, b, W, V):
    """The derivative of the Schur complement ``S`` along ``Z' = a M + b C`` (complex, ``(m, m)``).

    ``S' = Z'_rr - Z'_ri W - V^T Z'_ir + V^T Z'_ii W`` with ``W = Z_ii^-1 Z_ir`` and
    ``V^T = Z_ri Z_ii^-1`` (None when there is no interior).
    """
    bM, bC, _ = blocks
    dS = np.array(a * bM[0] + b * bC[0], dtype=complex)
    if W is not None:
        dZii_W = a * (bM[3] @ W) + (b * (bC[3] @ W) if b else 0.0)
        dS = dS - (a * bM[1] + b * bC[1]) @ W - V.T @ (a * bM[2] + b * bC[2]) + V.T @ dZii_W
    return dS


class Condensation:
    """The dynamic stiffness of a linear structure condensed onto retained DOFs.

    Parameters
    ----------
    M, C, K : ndarray or scipy.sparse matrix, shape (ndof, ndof)
        Mass (kg), damping (N s/m) and stiffness (N/m) matrices.
    retained : array_like of int, shape (m,)
        The DOFs kept (sorted, unique); external forces act on these only.
    harmonic_matrices : callable, optional
        ``h -> (M_h, C_h, K_h)``: matrices that differ from harmonic to
        harmonic (complex Hermitian, e.g. a cyclic sector's matrices in the
        nodal diameter of harmonic ``h``); then ``M, C, K`` give only the size.

    Notes
    -----
    One evaluation at a new ``omega`` factorises the interior block once per
    harmonic (sparse LU above :data:`DENSE_INTERIOR` interior DOFs) and solves
    for the ``m`` retained columns; the last frequency's blocks are cached.
    """

    def __init__(self, M, C, K, retained, *, harmonic_matrices=None):
        ndof = M.shape[0]
        r = np.asarray(retained, dtype=np.int64)
        mask = np.ones(ndof, dtype=bool)
        mask[r] = False
        self.retained, self.interior = r, np.flatnonzero(mask)
        self.m = r.size
        self._matrices = harmonic_matrices or (lambda h: (M, C, K))
        self._per_harmonic = harmonic_matrices is not None
        self._split_blocks = {}
        self._aligned = {}
        self._spectral = {}  # matrices key -> _SpectralInterior, or None where it does not apply
        self._factorisations = {}  # matrices key -> frequencies factorised so far
        self.sparse = sp.issparse(self._blocks(0)[2][3])
        # V = W when Z is complex symmetric (each harmonic's matrices are then checked once, below)
        self._symmetric = harmonic_matrices is None and all(_symmetric(A) for A in (M, C, K))
        self._damped = harmonic_matrices is not None or (np.any(C.data) if sp.issparse(C) else np.any(C))
        self._cache = (None, None, None)
        self._static = None
        self._static_factor = None  # the static interior's factorisation, for recovery

    def _blocks(self, h: int):
        """``(M, C, K)`` of harmonic ``h``, each split into ``(rr, ri, ir, ii)`` blocks (computed once)."""
        key = h if self._per_harmonic else 0
        if key not in self._split_blocks:
            self._split_blocks[key] = tuple(_split(A, self.retained, self.interior) for A in self._matrices(h))
        return self._split_blocks[key]

    # -- one harmonic --------------------------------------------------------------
    def _z(self, blocks, key, k):
        """Block ``k`` (0: rr, 1: ri, 2: ir) of ``Z`` for ``key = (Omega^2, Omega)``; real when undamped or static."""
        (w2, w), (bM, bC, bK) = key, blocks
        Z = bK[k] - w2 * bM[k]
        return Z + (1j * w) * bC[k] if w and self._damped else Z

    def _zii(self, h: int, blocks, key):
        """The interior block of ``Z`` (sparse CSC or dense) for ``key = (Omega^2, Omega)``."""
        if not self.sparse:
            return self._z(blocks, key, 3)
        if key == (0.0, 0.0):  # the static harmonic, factorised once: K_ii as it is
            return blocks[2][3]
        k = h if self._per_harmonic else 0
        if k not in self._aligned:
            self._aligned[k] = _AlignedInterior(*(b[3] for b in blocks))
        return self._aligned[k](key)

    def _spectral_for(self, h: int, omega: float):
        """The spectral interior of harmonic ``h``'s matrices, once they were factorised at
        :data:`SPECTRAL_AFTER` (dense) or :data:`SERIES_AFTER` (sparse) excitation frequencies: a single
        point never pays for an eigensolution."""
        k = h if self._per_harmonic else 0
        if k in self._spectral:
            return self._spectral[k]
        seen = self._factorisations.setdefault(k, set())
        if not self._symmetric or len(seen | {omega}) <= (SERIES_AFTER if self.sparse else SPECTRAL_AFTER):
            if h:  # the static harmonic is factorised once: it does not count
                seen.add(omega)
            return None
        self._spectral[k] = self._build_spectral(h)
        return self._spectral[k]

    def _build_spectral(self, h: int, needed: float = 0.0):
        """The series form for a sparse interior, else (or where it does not apply) every mode up to
        :data:`SPECTRAL_INTERIOR` interior DOFs; None where neither applies."""
        blocks = self._blocks(h)
        spectral = _SpectralInterior.series(blocks, needed) if self.sparse else None
        if spectral is None and self.interior.size <= SPECTRAL_INTERIOR:
            spectral = _SpectralInterior.full(blocks)
        return spectral

    def _spectral_evaluate(self, spectral, h: int, hs, omega: float, derivative: bool, xi: float = 0.0,
                           xi_derivative: bool = False):
        """``spectral.evaluate``, computing more modes when the series would converge too slowly (None: factorise)."""
        try:
            return spectral.evaluate(hs, omega, derivative, xi, xi_derivative)
        except _TooFewModes as more:
            k = h if self._per_harmonic else 0
            self._spectral[k] = spectral = self._build_spectral(h, more.needed)
            if spectral is None:
                return None
            try:
                return spectral.evaluate(hs, omega, derivative, xi, xi_derivative)
            except _TooFewModes:
                return None

    def _factor(self, Zii):
        """``solve(b, trans)`` with a factorisation of ``Zii`` (real or complex ``b``), None when singular."""
        if self.sparse:
            try:
                lu = spla.splu(sp.csc_matrix(Zii), permc_spec=ORDERING)
            except RuntimeError:  # exactly singular
                return None
            one = lu.solve
        else:
            try:
                lu = sla.lu_factor(Zii, check_finite=False)
            except (np.linalg.LinAlgError, ValueError):
                return None
            if np.any(np.abs(np.diag(lu[0])) <= 1e-14 * max(np.max(np.abs(np.diag(lu[0]))), 1e-300)):
                return None

            def one(b, trans="N"):
                return sla.lu_solve(lu, b, trans=1 if trans == "T" else 0, check_finite=False)
        if np.iscomplexobj(Zii):
            return one

        def real_factor(b, trans="N"):  # a real factorisation: real and imaginary parts apart
            b = np.asarray(b)
            if not np.iscomplexobj(b):
                return one(b, trans)
            return one(np.ascontiguousarray(b.real), trans) + 1j * one(np.ascontiguousarray(b.imag), trans)

        return real_factor

    def harmonic(self, h: int, omega: float, *, derivative: bool = True, xi: float = 0.0,
                 xi_derivative: bool = False):
        """``(S, S')``: the condensed complex dynamic stiffness of harmonic ``h`` and its ``omega``-derivative.

        Parameters
        ----------
        h : int
            Harmonic (0: static).
        omega : float
            Excitation frequency (rad/s).
        derivative : bool
            Also compute ``dS/domega``.
        xi : float, default 0
            A mass-proportional damping ``-xi M`` (1/s) added to ``C``: the
            structure condensed is ``M, C - xi M, K`` (the extended periodic
            motion concept's negative damping).
        xi_derivative : bool, default False
            Also return ``dS/dxi``.

        Returns
        -------
        S, dS : ndarray, shape (m, m), complex
            N/m and N s/m (``dS`` is None without ``derivative``).
        dS_xi : ndarray, shape (m, m), complex
            ``dS/dxi`` (N s/m); a third value, only with ``xi_derivative``.

        Raises
        ------
        SingularInteriorError
            When the structure with the retained DOFs held is singular (a
            natural frequency of the held structure equals ``h omega`` with no
            damping, or a part moves freely when they are held).
        """
        W_omega = h * omega
        key = _key(W_omega, xi)
        blocks = self._blocks(h)
        Zrr, Zri, Zir = (self._z(blocks, key, k) for k in range(3))
        spectral = self._spectral_for(h, omega) if self.interior.size else None
        result = self._spectral_evaluate(spectral, h, [h], omega, derivative, xi, xi_derivative) \
            if spectral is not None else None
        if result is not None:
            out = tuple(None if r is None else r[0] for r in result)
            return out if xi_derivative else out[:2]
        if self.interior.size == 0:
            S = np.array(Zrr, dtype=complex)
            W = V = None
        else:
            solve = self._factor(self._zii(h, blocks, key))
            if solve is None:
                raise SingularInteriorError(
                    f"the structure with its contact and excitation DOFs held fixed is singular at harmonic {h} "
                    f"(frequency {W_omega:.6g} rad/s): a part of it moves freely, or an undamped natural "
                    f"frequency of the held structure equals the harmonic's frequency; add damping or keep "
                    f"more DOFs")
            W = solve(np.asarray(Zir))  # real when the harmonic is static or undamped
            V = W if self._symmetric else solve(np.asarray(Zri).T.copy(), "T")
            S = np.array(Zrr - Zri @ W, dtype=complex)
        # Z' = a M + b C: dZ/domega with a = -2 h^2 omega - i h xi, b = i h; dZ/dxi with a = -i h omega, b = 0
        dS = _schur_derivative(blocks, -2.0 * h * h * omega - 1j * h * xi, 1j * h, W, V) if derivative else None
        if not xi_derivative:
            return S, dS
        return S, dS, _schur_derivative(blocks, -1j * W_omega, 0.0, W, V)

    def interior_response(self, h: int, omega: float, q_r, xi: float = 0.0) -> np.ndarray:
        """Complex amplitudes of the interior DOFs ``(ni, k)`` from those of the retained ones ``(m, k)`` (m),
        with the damping ``C - xi M``."""
        if self.interior.size == 0:
            return np.zeros((0,) + np.shape(q_r)[1:], dtype=complex)
        W_omega = h * omega
        key = _key(W_omega, xi)
        blocks = self._blocks(h)
        spectral = self._spectral.get(h if self._per_harmonic else 0)
        q_i = spectral.interior(W_omega, np.asarray(q_r), xi) if spectral is not None else None
        if q_i is not None:
            return np.asarray(q_i, dtype=complex)
        if W_omega == 0.0:  # the static interior does not change: factorised once
            if self._static_factor is None:
                self._static_factor = self._factor(self._zii(h, blocks, key))
            solve = self._static_factor
        else:
            solve = self._factor(self._zii(h, blocks, key))
        if solve is None:
            raise SingularInteriorError(f"the held structure is singular at harmonic {h} ({W_omega:.6g} rad/s)")
        return -np.asarray(solve(np.asarray(self._z(blocks, key, 2) @ q_r)), dtype=complex)

    def projection(self, w, omega: float, xi: float = 0.0):
        """A linear functional of every DOF's first harmonic as one of the retained DOFs'.

        Parameters
        ----------
        w : array_like, shape (ndof,)
            Weights of every DOF (e.g. ``M phi``, a mode's modal coordinate), real or complex.
        omega : float
            Frequency of the first harmonic (rad/s).
        xi : float, default 0
            Mass-proportional damping removed from ``C`` (1/s), as in :meth:`harmonic`.

        Returns
        -------
        g, g_omega, g_xi : ndarray, shape (m,), complex
            ``w . z = g . z_r`` for the complex amplitudes ``z`` of every DOF
            recovered from those of the retained DOFs ``z_r`` at ``(omega, xi)``
            (:meth:`interior_response`), and the derivatives of ``g`` in
            ``omega`` and ``xi``.
        """
        w = np.asarray(w)  # complex for a cyclic sector: conj(M phi) in a nodal diameter
        w_r, w_i = w[self.retained].astype(complex), w[self.interior]
        zero = np.zeros(self.m, dtype=complex)
        if not np.any(w_i):
            return w_r, zero, zero.copy()
        spectral = self._spectral.get(1 if self._per_harmonic else 0)
        try:
            result = spectral.projection(omega, w_i, xi) if spectral is not None else None
        except _TooFewModes:  # the omitted modes' series would converge too slowly here: factorised
            result = None
        if result is not None:
            return w_r + result[0], result[1], result[2]
        # w_i . q_i = -u^T Z_ir q_r with u = Z_ii^-T w_i; d/dtheta: -u^T Z_ir' + v^T Z_ir, v = Z_ii^-T Z_ii'^T u
        blocks = self._blocks(1)
        key = _key(omega, xi)
        solve = self._factor(self._zii(1, blocks, key))
        if solve is None:
            raise SingularInteriorError(f"the held structure is singular at harmonic 1 ({omega:.6g} rad/s)")
        Zir = self._z(blocks, key, 2)
        u = solve(w_i.astype(complex), "T")
        bM, bC, _ = blocks
        out = [w_r - Zir.T @ u]
        for a, b in ((-2.0 * omega - 1j * xi, 1j), (-1j * omega, 0.0)):  # Z' = a M + b C: d/domega, d/dxi
            dZii_u = a * (bM[3].T @ u) + (b * (bC[3].T @ u) if b else 0.0)
            v = solve(np.asarray(dZii_u, dtype=complex), "T")
            out.append(-(a * bM[2] + b * bC[2]).T @ u + Zir.T @ v)
        return tuple(out)

    def _harmonics(self, omega: float, H: int, xi: float = 0.0, xi_derivative: bool = False):
        """``[(S_h, S'_h[, dS_h/dxi]) for h = 1..H]``: all at once through the spectral interior once it applies."""
        spectral = self._spectral_for(1, omega) if self.interior.size and not self._per_harmonic else None
        result = self._spectral_evaluate(spectral, 1, np.arange(1, H + 1), omega, True, xi, xi_derivative) \
            if spectral is not None else None
        if result is not None:
            return list(zip(*(result if xi_derivative else result[:2])))
        return [self.harmonic(h, omega, xi=xi, xi_derivative=xi_derivative) for h in range(1, H + 1)]

    # -- the real harmonic-balance operator --------------------------------------------
    def operator(self, omega: float, H: int, xi: float | None = None):
        """Real block-diagonal ``Z(omega)`` and ``dZ/domega``, shape ``((2H+1) m, (2H+1) m)`` (N/m, N s/m).

        Harmonic-major layout ``[c0 (m), a1 (m), b1 (m), ..., bH (m)]``, the
        layout of :class:`~microslip.frequency.equations.hbm.HarmonicBalance`. Both are
        computed together and cached for the last ``(omega, H)`` (a Newton
        step asks for the one, then the other); the static block, which does
        not depend on ``omega``, is computed once. With ``xi`` (1/s) the
        damping is ``C - xi M`` and a third operator, ``dZ/dxi`` (N s/m), is
        returned too.
        """
        key = (omega, H, xi)
        if self._cache[0] == key:
            return self._cache[1:] if xi is not None else self._cache[1:3]
        m = self.m
        n = (2 * H + 1) * m
        blocks = [np.zeros((n, n)) for _ in range(2 if xi is None else 3)]
        if self._static is None:
            self._static = self.harmonic(0, 0.0, derivative=False)[0].real
        blocks[0][:m, :m] = self._static
        parts = self._harmonics(omega, H) if xi is None else self._harmonics(omega, H, xi, True)
        for h, matrices in enumerate(parts, start=1):
            a = slice((2 * h - 1) * m, 2 * h * m)
            b = slice(2 * h * m, (2 * h + 1) * m)
            for target, M in zip(blocks, matrices):
                target[a, a] = target[b, b] = M.real
                target[a, b] = M.imag
                target[b, a] = -M.imag
        self._cache = (key, *blocks)
        return tuple(blocks)

    def recover(self, coefficients, omega: float, H: int, xi: float = 0.0) -> np.ndarray:
        """Every DOF's real coefficients ``(2H+1, ndof)`` (m) from the retained ones ``(2H+1, m)`` (damping
        ``C - xi M``)."""
        coefficients = np.asarray(coefficients, dtype=float)
        ndof = self.m + self.interior.size
        out = np.zeros((2 * H + 1, ndof))
        out[:, self.retained] = coefficients
        if self.interior.size == 0:
            return out
        out[0, self.interior] = self.interior_response(0, omega, coefficients[0]).real
        for h in range(1, H + 1):
            z = coefficients[2 * h - 1] - 1j * coefficients[2 * h]
            zi = self.interior_response(h, omega, z, xi)
            out[2 * h - 1, self.interior] = zi.real
            out[2 * h, self.interior] = -zi.imag
        return out
