"""Modal condensation onto retained DOFs: normal modes plus the residual flexibility of the omitted ones.

The receptance of the retained DOFs ``r`` at the frequency ``Omega = h omega`` is

``G(Omega) = Phi_r (Lambda - Omega^2 I + i Omega Phi^T C Phi)^-1 Phi_r^T + R``,

with ``Phi`` the ``modes`` lowest mass-normalised normal modes (sparse
shift-invert eigensolver), ``Lambda`` their squared natural frequencies and
``R = [(K - s M)^-1]_rr - Phi_r (Lambda - s I)^-1 Phi_r^T`` the residual
(static) flexibility of the omitted modes, plus their damping to order
:data:`DAMPING_ORDER` in ``i Omega``: with ``F = (K - s M)^-1``, the terms
``(-i Omega)^k ([F (C F)^k]_rr - Phi_r (Lambda - s I)^-1 (Phi^T C Phi (Lambda - s I)^-1)^k Phi_r^T)``.
Damping that grows with frequency (``C = beta K``: ``zeta = beta omega / 2``)
damps the omitted modes most, and does not fade as modes are added; with these
terms its error is ``(Omega beta)^3`` of their share. The shift ``s < 0`` (tiny against the
omitted modes) keeps ``K - s M`` invertible for structures with rigid-body modes
(a free body held only by its contacts); their modes are among the kept ones. The
condensed dynamic stiffness is ``S = G^-1``; the static term (``h = 0``) is the
exact static condensation of ``K``, so the static contact state is exact.
The omitted modes enter quasi-statically: the error grows like
``(Omega / omega_(modes+1))^2`` (:attr:`ModalCondensation.cutoff`).
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ...common._numeric import eigsh_repeatable
from ..structures.structure import refuse_indefinite
from .condensation import CLASSICAL, ORDERING, Condensation, SingularInteriorError, _Products

#: DOFs up to which the eigenproblem is solved densely
DENSE_EIGEN = 600
#: terms of the omitted modes' damping series in i Omega (for C = beta K its error is (Omega beta)^3 of their share)
DAMPING_ORDER = 2
#: the shift s = -SHIFT * (median of diag K / median of diag M)
SHIFT = 1e-6


class ModalCondensation:
    """Condensed dynamic stiffness of the retained DOFs from ``modes`` normal modes plus residual flexibility.

    Parameters
    ----------
    M, C, K : ndarray or scipy.sparse matrix, shape (ndof, ndof)
        Mass (kg), damping (N s/m) and stiffness (N/m) matrices (symmetric; ``K``
        positive semi-definite: a negative eigenvalue among those computed, the
        lowest ones, is refused by name).
    retained : array_like of int, shape (m,)
        DOFs kept (sorted, unique); external forces act on these only.
    modes : int
        Normal modes kept, ``1 <= modes < ndof``.

    Attributes
    ----------
    frequencies : ndarray, shape (modes,)
        Natural frequencies of the kept modes (rad/s; rigid-body modes 0).
    cutoff : float
        Natural frequency of the first omitted mode (rad/s).
    """

    def __init__(self, M, C, K, retained, modes: int):
        ndof = M.shape[0]
        self.retained = np.asarray(retained, dtype=np.int64)
        self.m = self.retained.size
        self.modes = modes
        diag_k = np.abs(K.diagonal()) if sp.issparse(K) else np.abs(np.diag(K))
        diag_m = np.abs(M.diagonal()) if sp.issparse(M) else np.abs(np.diag(M))
        s = -SHIFT * float(np.median(diag_k[diag_k > 0]) if np.any(diag_k > 0) else 1.0) / float(np.median(diag_m))
        self.shift = s
        shifted = (sp.csc_matrix(K) - s * sp.csc_matrix(M)) if sp.issparse(K) or sp.issparse(M) else \
            np.asarray(K, dtype=float) - s * np.asarray(M, dtype=float)
        k = min(modes + 1, ndof - 1)
        if ndof <= DENSE_EIGEN:
            Kd = shifted.toarray() if sp.issparse(shifted) else shifted
            Md = M.toarray() if sp.issparse(M) else np.asarray(M, dtype=float)
            lam, phi = sla.eigh(Kd, Md, subset_by_index=[0, k - 1])
            lam = lam + s
            refuse_indefinite(lam, K, M, "a modal reduction")  # before Cholesky's factorisation of K - s M fails
            factor = sla.cho_factor(Kd)
            solve = lambda b: sla.cho_solve(factor, b)  # noqa: E731
            flex = solve(np.eye(ndof)[:, self.retained])
        else:
            lu = spla.splu(sp.csc_matrix(shifted), permc_spec=ORDERING)
            op = spla.LinearOperator(shifted.shape, matvec=lu.solve, dtype=float)
            lam, phi = eigsh_repeatable(sp.csr_matrix(K), k=k, M=sp.csr_matrix(M), sigma=s, which="LM", OPinv=op)
            refuse_indefinite(lam, K, M, "a modal reduction")  # the eigenvalues nearest the shift
            order = np.argsort(lam)
            lam, phi = lam[order], phi[:, order]
            E = np.zeros((ndof, self.m))
            E[self.retained, np.arange(self.m)] = 1.0
            flex = lu.solve(E)
            solve = lu.solve
        lam = np.maximum(lam, 0.0)
        self.cutoff = float(np.sqrt(lam[modes])) if lam.size > modes else np.inf
        lam, phi = lam[:modes], phi[:, :modes]
        self.frequencies = np.sqrt(lam)
        self.eigenvalues = lam
        self.phi = phi
        self.phi_r = phi[self.retained]
        Cm = phi.T @ (C @ phi)
        self.modal_damping = 0.5 * (Cm + Cm.T)
        off = np.abs(self.modal_damping - np.diag(np.diag(self.modal_damping)))
        classical = off.size == 0 or off.max() <= CLASSICAL * max(float(np.abs(self.modal_damping).max()), 1e-300)
        # diagonal modal damping (Rayleigh, none): every harmonic from a few products of (m, modes) arrays
        self._damping = np.diag(self.modal_damping).copy() if classical else None
        self._products = _Products(self.phi_r)  # Phi_r diag(w) Phi_r^T
        self.residual = flex[self.retained] - (self.phi_r / (lam - s)) @ self.phi_r.T
        self.flex_full = flex  # (ndof, m): the shifted static flexibility, for recovery
        # the omitted modes' damping, the series sum_k (-i Omega)^k [F (C F)^k - kept modes' share]: under
        # stiffness-proportional damping it grows with their frequency and does not fade as modes are added
        # with a mass-proportional damping -xi M (:meth:`harmonic`'s xi) the series is that of C - xi M: its terms
        # are the words in C and M of each order (computed when first needed), the k M's weighing (-xi)^k
        self._solve, self._matrices = solve, {"C": C, "M": M}
        self._modal = {"C": self.modal_damping, "M": np.eye(modes)}
        self._words = {}  # word -> (F X1 F X2 ... F E, (ndof, m); its kept modes' share, (modes, modes); R, (m, m))
        self.has_damping = bool(C.count_nonzero() if sp.issparse(C) else np.any(C))
        self.damping_terms = [self._word("C" * k) for k in range(1, DAMPING_ORDER + 1)] if self.has_damping else []
        self.static = Condensation(M, C, K, self.retained)  # exact for h = 0
        self._cache = (None, None, None)
        self._static = None

    def _word(self, word: str):
        """``(F X1 F X2 ... F E, (L - s)^-1 X1m (L - s)^-1 ..., R)`` of a word ``X1 X2 ...`` in ``C`` and ``M``."""
        if word not in self._words:
            if word:
                full, kept, _ = self._word(word[1:])
                full = self._solve(np.asarray(self._matrices[word[0]] @ full))
                kept = (self._modal[word[0]] @ kept) / (self.eigenvalues - self.shift)[:, None]
            else:
                full, kept = self.flex_full, np.diag(1.0 / (self.eigenvalues - self.shift))
            self._words[word] = (full, kept, full[self.retained] - self.phi_r @ kept @ self.phi_r.T)
        return self._words[word]

    def _series(self, xi: float, order: int = 0):
        """``[(k, coefficient, word)]``: the omitted modes' damping terms of ``C - xi M`` (or of their
        ``order``-th derivative in ``xi``, 0 or 1), each ``(-i Omega)^k coefficient R_word``."""
        out = [(k, 1.0, "C" * k) for k in range(1, len(self.damping_terms) + 1)] if order == 0 else []
        if not (xi or order):
            return out
        for k in range(1, DAMPING_ORDER + 1):
            for bits in range(1, 2 ** k):  # the words with at least one M
                word = "".join("M" if bits >> j & 1 else "C" for j in range(k))
                masses = word.count("M")
                if "C" in word and not self.has_damping or masses < order:
                    continue
                coef = (-xi) ** masses if order == 0 else -masses * (-xi) ** (masses - 1)
                if coef:
                    out.append((k, coef, word))
        return out

    def _dynamic(self, Omega: float, h: int, omega: float, derivative: bool, xi: float = 0.0):
        """Modal part: ``D`` and, with ``derivative``, ``D'`` (modes x modes, complex), damping ``C - xi M``."""
        damping = self.modal_damping - xi * np.eye(self.modes)
        D = np.diag(self.eigenvalues - Omega * Omega).astype(complex) + (1j * Omega) * damping
        dD = None
        if derivative:
            dD = np.diag(np.full(self.modes, -2.0 * h * h * omega)).astype(complex) + (1j * h) * damping
        return D, dD

    @staticmethod
    def _stiffness(G, where: str):
        """``S = G^-1`` of the receptance(s) ``G``, or the error that names ``where``."""
        try:
            return np.linalg.inv(G)
        except np.linalg.LinAlgError:
            raise SingularInteriorError(f"the modal receptance of the retained DOFs is singular at {where}; "
                                        f"keep more modes") from None

    def _omitted(self, hs, omega: float, derivative: bool, xi: float = 0.0, xi_derivative: bool = False):
        """The omitted modes' damping in the receptance of harmonics ``hs`` and its derivatives.

        ``sum_k (-i h omega)^k R_k``, ``sum_k k (-i h) (-i h omega)^(k-1) R_k`` (in
        ``omega``) and, with ``xi_derivative``, the derivative in ``xi``, each
        ``(len(hs), m, m)`` complex (m/N, m s/N); ``R_k`` those of ``C - xi M``
        (:meth:`_series`); zeros without damping.
        """
        m = self.phi_r.shape[0]
        extra = np.zeros((hs.size, m, m), dtype=complex)
        dextra = np.zeros_like(extra) if derivative else None
        z = -1j * hs * omega
        for k, coef, word in self._series(xi):
            R = coef * self._word(word)[2]
            extra += (z ** k)[:, None, None] * R
            if derivative:
                dextra += (k * (-1j * hs) * z ** (k - 1))[:, None, None] * R
        if not xi_derivative:
            return extra, dextra
        xextra = np.zeros_like(extra)
        for k, coef, word in self._series(xi, 1):
            xextra += (coef * z ** k)[:, None, None] * self._word(word)[2]
        return extra, dextra, xextra

    def _diagonal(self, hs, omega: float, derivative: bool, xi: float = 0.0, xi_derivative: bool = False):
        """``(S, S'[, dS/dxi])``, each ``(len(hs), m, m)``, for harmonics ``hs >= 1`` when the modal damping is
        diagonal (damping ``C - xi M``)."""
        hs = np.asarray(hs, dtype=float)
        W = hs * omega
        damping = self._damping - xi
        d = self.eigenvalues[None] - (W * W)[:, None] + (1j * W)[:, None] * damping[None]
        if np.any(np.abs(d) <= 1e-14 * np.max(np.abs(d), axis=1, keepdims=True)):
            h = int(hs[np.argmin(np.min(np.abs(d), axis=1))])
            raise SingularInteriorError(f"an undamped kept mode resonates exactly at harmonic {h} "
                                        f"({h * omega:.6g} rad/s); add damping")
        u = 1.0 / d
        weights = [u]
        if derivative:  # D'/D^2
            weights.append(((-2.0 * hs * hs * omega)[:, None] + (1j * hs)[:, None] * damping[None]) * u * u)
        if xi_derivative:  # D_xi/D^2
            weights.append(-1j * W[:, None] * u * u)
        Y = self._products(np.stack([w.real for w in weights] + [w.imag for w in weights], axis=1))
        k = len(weights)
        extra = self._omitted(hs, omega, derivative, xi, xi_derivative)
        S = self._stiffness(Y[:, 0] + 1j * Y[:, k] + self.residual + extra[0], f"a harmonic of {omega:.6g} rad/s")
        out = [S, None]
        if derivative:
            out[1] = -S @ (-(Y[:, 1] + 1j * Y[:, k + 1]) + extra[1]) @ S
        if xi_derivative:
            out.append(-S @ (-(Y[:, k - 1] + 1j * Y[:, 2 * k - 1]) + extra[2]) @ S)
        return tuple(out)

    def harmonic(self, h: int, omega: float, *, derivative: bool = True, xi: float = 0.0,
                 xi_derivative: bool = False):
        """``(S, S'[, dS/dxi])`` of harmonic ``h`` (complex, ``(m, m)``; N/m, N s/m), as
        :meth:`Condensation.harmonic`."""
        if h == 0:
            S, _ = self.static.harmonic(0, omega, derivative=False)
            zero = np.zeros_like(S)
            return (S, zero if derivative else None) + ((zero,) if xi_derivative else ())
        if self._damping is not None:
            return tuple(None if r is None else r[0] for r in self._diagonal([h], omega, derivative, xi,
                                                                              xi_derivative))
        Omega = h * omega
        D, dD = self._dynamic(Omega, h, omega, derivative, xi)
        try:
            Y = np.linalg.solve(D, self.phi_r.T.astype(complex))  # D^-1 Phi_r^T, (modes, m)
        except np.linalg.LinAlgError:
            raise SingularInteriorError(f"an undamped kept mode resonates exactly at harmonic {h} "
                                        f"({Omega:.6g} rad/s); add damping") from None
        extra = self._omitted(np.array([float(h)]), omega, derivative, xi, xi_derivative)
        S = self._stiffness(self.phi_r @ Y + self.residual + extra[0][0], f"harmonic {h} ({Omega:.6g} rad/s)")
        out = [S, None]
        # G' = -Phi_r D^-1 D' D^-1 Phi_r^T ;  S' = -S G' S
        Yt = np.linalg.solve(D.T, self.phi_r.T.astype(complex)) if derivative or xi_derivative else None
        if derivative:
            out[1] = -S @ (-(Yt.T @ dD @ Y) + extra[1][0]) @ S
        if xi_derivative:  # D_xi = -i Omega I
            out.append(-S @ ((1j * Omega) * (Yt.T @ Y) + extra[2][0]) @ S)
        return tuple(out)

    operator = Condensation.operator

    def _harmonics(self, omega: float, H: int, xi: float = 0.0, xi_derivative: bool = False):
        """``[(S_h, S'_h[, dS_h/dxi]) for h = 1..H]`` (for :meth:`operator`)."""
        if self._damping is not None:
            return list(zip(*self._diagonal(np.arange(1, H + 1), omega, True, xi, xi_derivative)))
        return [self.harmonic(h, omega, xi=xi, xi_derivative=xi_derivative) for h in range(1, H + 1)]

    def _receptance_row(self, w, h: int, omega: float, xi: float):
        """``c`` with ``w . q = c . f`` for the response ``q`` (every DOF) to forces ``f`` on the retained DOFs at
        harmonic ``h`` (complex, ``(m,)``), and its derivatives in ``omega`` and ``xi``."""
        e = self.phi.T @ w
        D, dD = self._dynamic(h * omega, h, omega, True, xi)
        eD = np.linalg.solve(D.T, e.astype(complex))  # D^-T e
        c = eD @ self.phi_r.T + w @ self.flex_full - (e / (self.eigenvalues - self.shift)) @ self.phi_r.T
        dc = -(eD @ dD @ np.linalg.solve(D, self.phi_r.T.astype(complex)))
        dx = (1j * h * omega) * (eD @ np.linalg.solve(D, self.phi_r.T.astype(complex)))
        z = -1j * h * omega
        for series, order in ((self._series(xi), 0), (self._series(xi, 1), 1)):
            for k, coef, word in series:
                full, kept, _ = self._word(word)
                term = coef * (w @ full - (e @ kept) @ self.phi_r.T)
                if order:
                    dx = dx + z ** k * term
                else:
                    c = c + z ** k * term
                    dc = dc + k * (-1j * h) * z ** (k - 1) * term
        return c, dc, dx

    def projection(self, w, omega: float, xi: float = 0.0):
        """``(g, g_omega, g_xi)``, complex ``(m,)``: ``w . z = g . z_r`` for every DOF's first harmonic recovered
        from the retained DOFs' (:meth:`recover`), as :meth:`Condensation.projection`."""
        w = np.asarray(w, dtype=float)
        S, dS, xS = self.harmonic(1, omega, xi=xi, xi_derivative=True)
        c, dc, xc = self._receptance_row(w, 1, omega, xi)
        return S.T @ c, dS.T @ c + S.T @ dc, xS.T @ c + S.T @ xc

    def recover(self, coefficients, omega: float, H: int, xi: float = 0.0) -> np.ndarray:
        """Every DOF's real coefficients ``(2H+1, ndof)`` (m) from the retained ones ``(2H+1, m)``.

        The force on the retained DOFs is ``S q_r``; the response to it is the
        modal sum plus the residual flexibility (static part: exact condensation);
        damping ``C - xi M``.
        """
        coefficients = np.asarray(coefficients, dtype=float)
        out = np.empty((2 * H + 1, self.phi.shape[0]))
        out[0] = self.static.recover(coefficients[:1], omega, 0)[0]
        for h in range(1, H + 1):
            z = coefficients[2 * h - 1] - 1j * coefficients[2 * h]
            S = self.harmonic(h, omega, derivative=False, xi=xi)[0]
            f = S @ z
            D, _ = self._dynamic(h * omega, h, omega, False, xi)
            eta = np.linalg.solve(D, self.phi_r.T @ f)
            q = self.phi @ eta + self.flex_full @ f - self.phi @ ((self.phi_r.T @ f) / (self.eigenvalues - self.shift))
            for k, coef, word in self._series(xi):
                full, kept, _ = self._word(word)
                q += coef * (-1j * h * omega) ** k * (full @ f - self.phi @ (kept @ (self.phi_r.T @ f)))
            out[2 * h - 1], out[2 * h] = q.real, -q.imag
        return out
