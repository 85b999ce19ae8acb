"""Modal condensation of a cyclic sector: each nodal diameter's modes plus the residual flexibility of the rest.

Harmonic ``h`` of an engine-order response lives in nodal diameter ``h EO mod N``,
where the sector's matrices are the complex Hermitian ``M_phi, C_phi, K_phi`` of
:meth:`~.cyclic.CyclicStructure.matrices`. For each diameter the harmonics use,
the ``modes`` lowest modes ``K_phi psi = lambda M_phi psi`` (``psi^H M_phi psi = 1``)
are found once (sparse shift-invert Arnoldi, cleaned by a Rayleigh--Ritz step so
that they are exactly orthonormal), and the receptance of the retained DOFs is

``G(Omega) = Psi_r (Lambda - Omega^2 I + i Omega Psi^H C_phi Psi)^-1 Psi_r^H + R``,

``R = F_r + (Omega^2 - s) F^H M_phi F - i Omega F^H C_phi F``,

``F = [(K_phi - s M_phi)^-1]_{:r} - Psi (Lambda - s I)^-1 Psi_r^H``

(``F``: the residual flexibility of the omitted modes, ``s < 0`` a shift tiny
against them that keeps a free damper body invertible; the two further terms
carry their inertia and damping to first order, so that the error falls like
``(Omega / omega_omitted)^4`` and the damping of the omitted modes -- large for
stiffness-proportional damping -- is not lost). Damping that is not
proportional couples the kept modes to the omitted ones; that coupling enters
through ``W = Psi^H C_phi F`` and ``X = Psi^H C_phi P C_phi Psi`` (``P`` the
omitted modes' flexibility) as ``G = (Psi_r - i Omega W^H) D^-1 (Psi_r^H - i Omega W) + R``
with ``D = Lambda - Omega^2 + i Omega Psi^H C_phi Psi + Omega^2 X`` (``W`` and
``X`` vanish for proportional damping, where the plain form above is used). The
condensed stiffness is ``S = G^-1``; the static term (diameter 0) is condensed
exactly, so the static contact state is exact. A sector without boundary DOFs
(blades clamped in a rigid disk, joined only through their contacts) has the same
matrices in every diameter: one real eigensolution then serves every harmonic.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .condensation import Condensation, SingularInteriorError
from .modal import DENSE_EIGEN, SHIFT


class DiameterModes:
    """The modes of one nodal diameter and the residual receptance of the omitted ones.

    Parameters
    ----------
    M, C, K : scipy.sparse matrix, shape (n, n)
        The sector's matrices in the diameter (kg, N s/m, N/m), real symmetric
        or complex Hermitian, on its independent DOFs.
    retained : ndarray of int, shape (m,)
        The retained DOFs (independent numbering).
    modes : int
        Modes kept, ``1 <= modes < n``.

    Attributes
    ----------
    eigenvalues : ndarray, shape (modes,)
        Squared natural frequencies ((rad/s)^2) of the kept modes, ascending.
    cutoff : float
        Natural frequency of the first omitted mode (rad/s).
    """

    def __init__(self, M, C, K, retained, modes: int):
        n = M.shape[0]
        self.retained = retained
        k = min(modes + 1, n - 1)
        if n <= DENSE_EIGEN:
            lam, phi = sla.eigh(K.toarray(), M.toarray(), subset_by_index=[0, k - 1])
        else:  # shift-invert about a target below the lowest modes, then Rayleigh-Ritz in the vectors found
            diag_k, diag_m = np.abs(K.diagonal()), np.abs(M.diagonal())
            target = -SHIFT * float(np.median(diag_k[diag_k > 0]) if np.any(diag_k > 0) else 1.0) \
                / float(np.median(diag_m))
            lu = spla.splu(sp.csc_matrix(K - target * M))
            op = spla.LinearOperator(K.shape, matvec=lu.solve, dtype=lu.U.dtype)
            # ARPACK's random start, but seeded: the same modes (to the last digit) on every run
            start = np.random.default_rng(0).standard_normal(n).astype(lu.U.dtype)
            vectors = spla.eigsh(K, k=k, M=M, sigma=target, which="LM", OPinv=op, v0=start)[1]
            lam, phi = self._rayleigh_ritz(M, K, np.linalg.qr(vectors)[0])
        lam = np.maximum(lam, 0.0)
        self.cutoff = float(np.sqrt(lam[modes])) if lam.size > modes else np.inf
        self.eigenvalues, self.phi = lam[:modes], phi[:, :modes]
        self.phi_r = self.phi[retained]
        Cm = self.phi.conj().T @ (C @ self.phi)
        self.modal_damping = 0.5 * (Cm + Cm.conj().T)
        # the flexibility of the omitted modes, from K - s M: s < 0 keeps a free damper body invertible and is
        # tiny against the omitted modes
        self.shift = s = -SHIFT * float(lam[-1] if lam[-1] > 0 else 1.0)
        E = np.zeros((n, retained.size))
        E[retained, np.arange(retained.size)] = 1.0
        shifted = sp.csc_matrix(K - s * M)
        if n <= DENSE_EIGEN:
            factor = sla.lu_factor(shifted.toarray())
            solve = lambda b: sla.lu_solve(factor, b)  # noqa: E731
        else:
            solve = spla.splu(shifted).solve
        # a real factor solves a complex right-hand side in two parts
        self._solve = solve if np.iscomplexobj(shifted.data) else lambda b: solve(b.real) + 1j * solve(b.imag)
        F = solve(E.astype(shifted.dtype)) - (self.phi / (self.eigenvalues - s)) @ self.phi_r.conj().T
        self.M, self.C = M, C
        self.omitted = F  # (n, m): the omitted modes' flexibility at Omega^2 = s, every row
        self.residual = F[retained]
        self.residual_mass = F.conj().T @ (M @ F)
        self.residual_damping = F.conj().T @ (C @ F)
        # damping that couples the kept modes to the omitted ones (zero for proportional damping):
        # W = Psi^H C F, (modes, m), and X = Psi^H C P C Psi, (modes, modes), P the omitted modes' flexibility
        C_phi = C @ self.phi
        self.coupling = C_phi.conj().T @ F
        X = C_phi.conj().T @ self._solve(np.asarray(C_phi, dtype=complex)) \
            - (self.modal_damping / (self.eigenvalues - s)) @ self.modal_damping
        self.coupling_damping = 0.5 * (X + X.conj().T)
        off = self.modal_damping - np.diag(np.diagonal(self.modal_damping))
        scale = np.abs(self.modal_damping).max(initial=0.0)
        top = np.sqrt(lam[-1]) if lam[-1] > 0 else 1.0  # beyond the first omitted mode nothing is modal
        #: whether the damping leaves the modes uncoupled: proportional damping, up to rounding and to coupling
        #: terms that change the receptance by less than 1e-6 up to the cutoff (the eigenvectors' own accuracy
        #: leaves about 1e-7 there, below the truncation error)
        self.diagonal = bool(np.abs(off).max(initial=0.0) <= 1e-12 * scale
                             and top * np.abs(self.coupling).max(initial=0.0) <= 1e-6 * np.abs(self.phi_r).max()
                             and top * np.abs(self.coupling_damping).max(initial=0.0) <= 1e-6 * scale)

    @staticmethod
    def _rayleigh_ritz(M, K, basis):
        """``(lambda, phi)``: the M-orthonormal modes of ``K``, ``M`` in the span of ``basis`` (orthonormal columns)."""
        Kr = basis.conj().T @ (K @ basis)
        Mr = basis.conj().T @ (M @ basis)
        lam, y = sla.eigh(0.5 * (Kr + Kr.conj().T), 0.5 * (Mr + Mr.conj().T))
        return lam, basis @ y

    def _dynamic(self, Omega: float):
        """``D = Lambda - Omega^2 I + i Omega Psi^H C Psi`` (modes x modes, complex)."""
        return np.diag(self.eigenvalues - Omega * Omega).astype(complex) + (1j * Omega) * self.modal_damping

    def harmonic(self, h: int, omega: float, derivative: bool):
        """``(S, S')`` at ``Omega = h omega`` (complex ``(m, m)``; N/m, N s/m; ``S'`` None without ``derivative``)."""
        S, dS = ModalStack([self], [h])(omega, derivative)
        return S[0], (dS[0] if derivative else None)

    def response(self, Omega: float, f) -> np.ndarray:
        """Complex amplitudes of every DOF (m), ``(n,)``, under the force ``f`` (N) on the retained DOFs, ``(m,)``.

        The kept modes' amplitudes, the omitted modes' static response and, to first order, their
        inertia, their damping and their damping coupling to the kept modes (as in :meth:`harmonic`).
        """
        D = self._dynamic(Omega) + (Omega * Omega) * self.coupling_damping
        eta = np.linalg.solve(D, (self.phi_r.conj().T - (1j * Omega) * self.coupling) @ f)
        u = self.omitted @ f
        w = (Omega * Omega - self.shift) * (self.M @ u) - (1j * Omega) * (self.C @ (u + self.phi @ eta))
        v = self._solve(np.asarray(w, dtype=complex)) \
            - self.phi @ ((self.phi.conj().T @ w) / (self.eigenvalues - self.shift))
        return self.phi @ eta + u + v


class ModalStack:
    """The modal data of several harmonics stacked, to condense them all in one batched evaluation.

    ``diameters``: one :class:`DiameterModes` per harmonic of ``harmonics`` (``(B,)`` int).
    """

    def __init__(self, diameters, harmonics):
        self.h = np.asarray(harmonics, dtype=float)
        self.phi_r = np.stack([d.phi_r for d in diameters])  # (B, m, k)
        self.phi_rh = self.phi_r.conj().transpose(0, 2, 1)
        self.lam = np.stack([d.eigenvalues for d in diameters])
        damping = np.stack([d.modal_damping for d in diameters])
        # modal damping diagonal in every diameter (proportional damping): D is diagonal, solved elementwise
        self.diagonal = all(d.diagonal for d in diameters)
        self.damping = np.diagonal(damping, axis1=1, axis2=2).copy() if self.diagonal else damping
        self.residual = np.stack([d.residual for d in diameters])
        self.mass = np.stack([d.residual_mass for d in diameters])
        self.viscous = np.stack([d.residual_damping for d in diameters])
        self.shift = np.array([d.shift for d in diameters])
        self.coupling = np.stack([d.coupling for d in diameters])  # W, (B, k, m)
        self.coupling_h = self.coupling.conj().transpose(0, 2, 1)
        self.coupling_damping = np.stack([d.coupling_damping for d in diameters])  # X, (B, k, k)

    def __call__(self, omega: float, derivative: bool):
        """``(S, S')``, ``(B, m, m)`` complex each (N/m, N s/m; ``S'`` None without ``derivative``).

        ``G = B D^-1 A + G_omitted``, ``A = Psi_r^H - i Omega W``, ``B = Psi_r - i Omega W^H``,
        ``D = Lambda - Omega^2 + i Omega Psi^H C Psi + Omega^2 X`` (:class:`DiameterModes`);
        ``S = G^-1``.
        """
        h = self.h
        Omega = h * omega
        w2, iw = (Omega * Omega)[:, None], (1j * Omega)[:, None]
        eye = np.eye(self.lam.shape[1])
        if self.diagonal:
            D = self.lam - w2 + iw * self.damping
            A, B = self.phi_rh, self.phi_r
            solve = lambda Q: Q / D[:, :, None]  # noqa: E731
        else:
            D = (self.lam - w2)[:, :, None] * eye + iw[:, :, None] * self.damping \
                + w2[:, :, None] * self.coupling_damping
            A = self.phi_rh - iw[:, :, None] * self.coupling
            B = self.phi_r - iw[:, :, None] * self.coupling_h
            solve = lambda Q: np.linalg.solve(D, Q)  # noqa: E731
        try:
            if self.diagonal and not np.all(D):
                raise np.linalg.LinAlgError
            Y = solve(A)  # D^-1 A, (B, k, m)
            G = B @ Y + self.residual + (w2 - self.shift[:, None])[:, :, None] * self.mass \
                - iw[:, :, None] * self.viscous
            S = np.linalg.inv(G)
        except np.linalg.LinAlgError:
            raise SingularInteriorError(
                f"the modal receptance of the retained DOFs is singular at one of harmonics "
                f"{h.astype(int).tolist()} of {omega:.6g} rad/s (an undamped kept mode resonates exactly there, "
                f"or too few modes are kept); add damping or keep more modes") from None
        if not derivative:
            return S, None
        two_h2w, ih = (2.0 * h * h * omega)[:, None], (1j * h)[:, None]
        if self.diagonal:
            dD = -two_h2w + ih * self.damping
            dG = -B @ solve(dD[:, :, None] * Y)
        else:
            dD = -two_h2w[:, :, None] * eye + ih[:, :, None] * self.damping \
                + two_h2w[:, :, None] * self.coupling_damping
            # (B D^-1 A)' = B' D^-1 A + B D^-1 A' - B D^-1 D' D^-1 A, with A' = -i h W, B' = -i h W^H
            dG = -ih[:, :, None] * (self.coupling_h @ Y + B @ solve(self.coupling)) - B @ solve(dD @ Y)
        dG = dG + two_h2w[:, :, None] * self.mass - ih[:, :, None] * self.viscous
        return S, -S @ dG @ S


class CyclicModalCondensation:
    """A sector condensed onto its retained DOFs from the modes of each harmonic's nodal diameter.

    Parameters
    ----------
    exact : Condensation
        The exact condensation of the sector (from
        :func:`~.cyclic_balance.cyclic_linear_part`): the static term and the
        error estimate.
    matrices : callable
        ``h -> (M, C, K)``: the sector's matrices in harmonic ``h``'s diameter.
    diameter : callable
        ``h -> key``: harmonics with the same key share their matrices (the
        phase lag ``phi_h``, or one key for all when the sector has no boundary).
    harmonics : int
        ``H``: the modes of the diameters of harmonics ``1..H`` are computed now.
    modes : int
        Modes kept per diameter, ``1 <= modes < n`` (``n`` independent DOFs).

    Attributes
    ----------
    modes : int
        Modes per diameter.
    cutoff : float
        The lowest natural frequency among the first omitted mode of every
        diameter used (rad/s): the error grows like ``(Omega / cutoff)^2``.
    """

    def __init__(self, exact: Condensation, matrices, diameter, harmonics: int, modes: int):
        self.exact = exact
        self.retained, self.m = exact.retained, exact.m
        self.modes = modes
        self._matrices, self._key = matrices, diameter
        self.diameters: dict[float, DiameterModes] = {}
        for h in range(1, harmonics + 1):
            self._diameter(h)
        self.cutoff = min((d.cutoff for d in self.diameters.values()), default=np.inf)
        self._cache = (None, None, None)
        self._static = self.exact.harmonic(0, 0.0, derivative=False)[0].real
        self.harmonics = harmonics
        self._stack = ModalStack([self._diameter(h) for h in range(1, harmonics + 1)], range(1, harmonics + 1)) \
            if harmonics else None
        self._batch = (None, None, None)

    def _diameter(self, h: int) -> DiameterModes:
        """The modes of harmonic ``h``'s diameter (computed once per distinct phase)."""
        key = self._key(h)
        if key not in self.diameters:
            self.diameters[key] = DiameterModes(*self._matrices(h), self.retained, self.modes)
        return self.diameters[key]

    #: the real block-diagonal operator of the harmonic balance, from :meth:`harmonic`
    operator = Condensation.operator

    def _harmonics(self, omega: float, H: int):
        """``[(S_h, S'_h) for h = 1..H]`` (for :meth:`operator`)."""
        return [self.harmonic(h, omega) for h in range(1, H + 1)]

    def harmonic(self, h: int, omega: float, *, derivative: bool = True):
        """``(S, S')`` of harmonic ``h`` (complex, ``(m, m)``; N/m, N s/m), as :meth:`Condensation.harmonic`.

        With ``derivative`` (the harmonic balance's call, harmonic after harmonic at one frequency) every
        harmonic ``1..H`` is evaluated at once at a new ``omega`` (:class:`ModalStack`) and served from there.
        """
        if h == 0:
            S, _ = self.exact.harmonic(0, omega, derivative=False)
            return S, (np.zeros_like(S) if derivative else None)
        if not (derivative and h <= self.harmonics):
            return self._diameter(h).harmonic(h, omega, derivative)
        if self._batch[0] != omega:
            self._batch = (omega, *self._stack(omega, True))
        return self._batch[1][h - 1], self._batch[2][h - 1]

    def recover(self, coefficients, omega: float, H: int) -> np.ndarray:
        """Real coefficients ``(2H+1, n)`` (m) of every independent DOF from the retained ones ``(2H+1, m)``."""
        coefficients = np.asarray(coefficients, dtype=float)
        out = np.empty((2 * H + 1, self.m + self.exact.interior.size))
        out[0] = self.exact.recover(coefficients[:1], omega, 0)[0]
        for h in range(1, H + 1):
            z = coefficients[2 * h - 1] - 1j * coefficients[2 * h]
            S, _ = self.harmonic(h, omega, derivative=False)
            q = self._diameter(h).response(h * omega, S @ z)
            out[2 * h - 1], out[2 * h] = q.real, -q.imag
        return out

    def error(self, omega: float) -> float:
        """Relative difference (Frobenius) of the modal and the exact first-harmonic stiffness at ``omega``."""
        exact, _ = self.exact.harmonic(1, omega, derivative=False)
        modal, _ = self.harmonic(1, omega, derivative=False)
        return float(np.linalg.norm(modal - exact) / np.linalg.norm(exact))
