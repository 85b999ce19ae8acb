"""One LU factorisation reused over many Newton iterations and continuation steps (private; no physics).

A dense factorisation of the whole Jacobian costs ``n^3``; applying the Jacobian as an operator
(:mod:`~.krylov`) and solving with factors already held cost ``n^2``. :class:`ReusedFactorisation`
solves each system by GMRES preconditioned with the factors of a Jacobian met earlier -- along a
curve, a nearby one, so GMRES needs a few iterations -- and factorises the current system again when
that stops working: GMRES did not converge in :data:`MAX_KRYLOV` iterations, or needed more than
:data:`SLOW_KRYLOV` once the iterations since the last factorisation have cost about one
(``n /`` :data:`FACTOR_EQUIVALENT` of them): the factors have drifted from the curve and are renewed at
the next system.
Each solve is to :data:`RTOL` of the right-hand side unless the caller asks less: a Newton step needs
its linearised residual only below the corrector's tolerance (:func:`newton_rtol`, an inexact Newton
method), and the corrector converges to the same tolerance.

An operator whose unknowns include groups coupled to a few others only (the DOFs no contact touches, see
:func:`~.krylov.groups`) is factorised by eliminating those groups first (:class:`_Eliminated`): the
dense factorisation is of the Schur complement of the rest.

The sign of a determinant (the orientation of the continuation's bordered systems) comes from the
factors held when the preconditioned operator ``A P^-1`` has all its Ritz values on a GMRES solve with a
generic right-hand side (to :data:`PROBE_RTOL`) within :data:`RITZ_DISC` of 1 (no real eigenvalue of
``A P^-1`` crossed zero between ``P`` and ``A``, so their determinants have one sign); otherwise ``A``
itself is factorised.
"""

from __future__ import annotations

import warnings

import numpy as np
import scipy.linalg as sla

from .blas import factor_threads
from .krylov import block_index, dense, gmres, groups, submatrix

#: GMRES iterations before the system is factorised instead
MAX_KRYLOV = 40
#: GMRES iterations of one solve above which the factors are renewed at the next system, once the iterations
#: since they were computed have cost about one factorisation
SLOW_KRYLOV = 8
#: unknowns per GMRES iteration that cost about as much as one factorisation: a dense LU costs ``n^3`` against
#: ``n^2`` for an iteration (a product with the operator and a solve with the factors), and the solves are bound by
#: memory while the factorisation is not
FACTOR_EQUIVALENT = 40
#: relative residual of each solve unless the caller asks less (:func:`newton_rtol`)
RTOL = 1e-12
#: relative residual of the probe whose Ritz values decide :meth:`ReusedFactorisation.sign`: GMRES's polynomial is
#: 1 at zero, so it damps the component of an eigenvalue at or beyond zero this far only with a Ritz value near
#: that eigenvalue (unless the generic probe holds less than about 1e-4 of that component)
PROBE_RTOL = 1e-8
#: the loosest relative residual of a Newton step's solve (:func:`newton_rtol`)
LOOSEST_NEWTON = 1e-3
#: Ritz values of the preconditioned operator within this distance of 1: the determinants have one sign
RITZ_DISC = 0.9
#: factorisations and GMRES iterations of every ReusedFactorisation of the process (read by the benchmarks)
COUNTS = {"factorisations": 0, "krylov_iterations": 0}


#: reciprocal condition number (1-norm estimate) below which a group of interior unknowns is not eliminated alone
#: (the whole matrix is factorised with pivoting over every unknown instead)
ELIMINATION_RCOND = 1e-8


def lu_sign(lu: np.ndarray, piv: np.ndarray) -> float:
    """Sign of the determinant of the matrix whose LU factors (LAPACK's ``getrf``: unit lower ``L``) are ``lu``,
    ``piv``: the signs of ``U``'s diagonal times the parity of the row interchanges."""
    swaps = int(np.count_nonzero(piv != np.arange(piv.size)))
    return float(np.prod(np.sign(np.diagonal(lu)))) * (-1.0 if swaps % 2 else 1.0)


def factors(A, dtype):
    """LU factors of the operator or array ``A`` (:class:`_Eliminated` when it has groups of interior unknowns that
    can be eliminated first, else :class:`_Factors` of its dense matrix)."""
    parts = groups(A)
    if parts:
        eliminated = _Eliminated(A, parts, dtype)
        if eliminated.stable:
            return eliminated
    return _Factors(dense(A), dtype)


class _Factors:
    """LU factors of a dense matrix in ``dtype``, the sign of its determinant, and solves in float64."""

    def __init__(self, A: np.ndarray, dtype):
        self.shape = A.shape
        self.singular = not np.all(np.isfinite(A))
        self.sign = 0.0
        if self.singular:
            return
        with warnings.catch_warnings(), factor_threads(A.shape[0]):
            warnings.simplefilter("ignore", sla.LinAlgWarning)
            self.lu, self.piv = sla.lu_factor(np.asarray(A, dtype=dtype), overwrite_a=True, check_finite=False)
        self.sign = lu_sign(self.lu, self.piv)
        self.singular = self.sign == 0 or not np.all(np.isfinite(np.diagonal(self.lu)))

    def solve(self, b: np.ndarray) -> np.ndarray:
        if self.singular:
            return np.full(np.shape(b), np.nan)
        out = sla.lu_solve((self.lu, self.piv), b.astype(self.lu.dtype), check_finite=False)
        return out.astype(float)


class _Eliminated:
    """LU factors of a matrix whose groups of interior unknowns are eliminated first (block Gaussian elimination).

    With ``A`` ordered as ``[[E, F], [G, K]]`` (``E`` the interior unknowns, block diagonal by group; each group
    coupled to some of the other unknowns only), ``det A = det E det S`` and ``A^-1`` follows from ``E^-1`` and
    the Schur complement ``S = K - G E^-1 F``: the dense factorisation is of ``S`` alone, the groups' blocks are
    small. ``E``'s groups are inverted in double precision (and kept in ``dtype``); ``S`` is factorised in
    ``dtype``; solves run in ``dtype``, as a preconditioner's may. :attr:`stable` is False when a group's block
    is too ill-conditioned to be eliminated alone (:data:`ELIMINATION_RCOND`).
    """

    def __init__(self, A, parts: list, dtype):
        n = A.shape[0]
        self.shape = A.shape
        self.dtype = dtype
        interior = np.concatenate([e for e, _ in parts])
        self.keep = np.setdiff1d(np.arange(n), interior)
        position = np.full(n, -1)
        position[self.keep] = np.arange(self.keep.size)
        # the Schur complement is assembled in the precision and the column order of its factorisation: no copy
        S = submatrix(A, self.keep, self.keep, np.empty((self.keep.size,) * 2, dtype=dtype, order="F"))
        sign, self.parts, self.stable = 1.0, [], True
        for e, coupled in parts:
            E = submatrix(A, e, e)
            if not np.all(np.isfinite(E)):
                self.stable = False
                return
            lu, piv = sla.lu_factor(E, check_finite=False)
            rcond, _ = sla.lapack.dgecon(lu, np.linalg.norm(E, 1), norm="1")
            if not rcond >= ELIMINATION_RCOND:
                self.stable = False
                return
            inverse = sla.lu_solve((lu, piv), np.eye(e.size), check_finite=False)
            X = inverse @ submatrix(A, e, coupled)  # E^-1 F
            G = submatrix(A, coupled, e)
            at = position[coupled]
            S[block_index(at, at)] -= G @ X
            sign *= lu_sign(lu, piv)
            self.parts.append((e, at, inverse.astype(dtype), X.astype(dtype), G.astype(dtype)))
        self.rest = _Factors(S, dtype)
        self.singular = self.rest.singular
        self.sign = sign * self.rest.sign  # a symmetric permutation of A's unknowns keeps its determinant

    def solve(self, b: np.ndarray) -> np.ndarray:
        if self.singular:
            return np.full(np.shape(b), np.nan)
        b = b.astype(self.dtype)
        rhs = b[self.keep]
        interior = []
        for e, at, inverse, _, G in self.parts:
            y = inverse @ b[e]
            rhs[at] -= G @ y
            interior.append(y)
        kept = sla.lu_solve((self.rest.lu, self.rest.piv), rhs, overwrite_b=True, check_finite=False)
        x = np.empty(b.shape, dtype=self.dtype)
        x[self.keep] = kept
        for (e, at, _, X, _), y in zip(self.parts, interior):
            x[e] = y - X @ kept[at]
        return x.astype(float)


def newton_rtol(residual: float, tolerance: float) -> float:
    """Relative residual enough for the linear solve of a Newton step (an inexact Newton method).

    From a point whose residual is ``residual`` (relative to the residual's scale) towards ``tolerance``:
    the step's linearised residual at a quarter of the tolerance, so the next iterate is within it as far
    as the linearisation holds -- as an exact solve would leave it -- at :data:`RTOL` to
    :data:`LOOSEST_NEWTON` of the right-hand side.
    """
    if not residual > 0:
        return RTOL
    return float(np.clip(0.25 * tolerance / residual, RTOL, LOOSEST_NEWTON))


class ReusedFactorisation:
    """Solves ``A z = b`` for a sequence of nearby operators ``A`` with as few factorisations as possible.

    Parameters
    ----------
    single : bool, default True
        Factorise in single precision (half the memory, about 1.5 times faster); GMRES in double
        precision refines every solve to :data:`RTOL` all the same (a few more iterations).

    Attributes
    ----------
    factorisations, krylov_iterations : int
        Counts, for reports and benchmarks.
    """

    def __init__(self, single: bool = True):
        self.dtype = np.float32 if single else np.float64
        self.factors: _Factors | None = None
        self.renew = False
        self.since = 0
        self.factorisations = 0
        self.krylov_iterations = 0
        self.probe = None

    def factorise(self, A, dtype=None) -> _Factors:
        """Factorise ``A`` (an operator of :mod:`~.krylov` or an array) in ``dtype`` (default: this solver's) and
        keep its factors."""
        self.factors = factors(A, dtype or self.dtype)
        self.since = 0  # GMRES iterations with these factors
        self.factorisations += 1
        COUNTS["factorisations"] += 1
        self.renew = False
        return self.factors

    def solve(self, A, b: np.ndarray, rtol: float = RTOL) -> np.ndarray:
        """``A^-1 b`` to ``rtol`` relative residual (at least :data:`RTOL`); all NaN when ``A`` is singular."""
        rtol = max(rtol, RTOL)
        held = not (self.factors is None or self.renew or self.factors.singular or self.factors.shape != A.shape)
        if held:
            z = self._krylov(A, b, rtol)
            if z is not None:
                return z
        # new factors of A; in double precision too when single precision cannot precondition a matrix this
        # ill-conditioned
        for dtype in dict.fromkeys([self.dtype, np.float64]):
            if not self.factorise(A, dtype).singular:
                z = self._krylov(A, b, rtol)
                if z is not None:
                    return z
        return np.full(np.shape(b), np.nan)

    def _krylov(self, A, b, rtol):
        """GMRES with the factors held: the solution, or None when it did not converge in :data:`MAX_KRYLOV`."""
        z, k, converged, _ = gmres(A, b, self.factors.solve, rtol=rtol, max_iterations=MAX_KRYLOV)
        self.krylov_iterations += k
        COUNTS["krylov_iterations"] += k
        self.since += k
        if not (converged and np.all(np.isfinite(z))):
            return None
        self.renew = k > SLOW_KRYLOV and self.since > A.shape[0] / FACTOR_EQUIVALENT
        return z

    def sign(self, A) -> float:
        """Sign of ``det A``: from the factors held when GMRES finds ``A P^-1`` near the identity, else from new
        factors of ``A``."""
        if self.factors is not None and not self.factors.singular and self.factors.shape == A.shape:
            if self.probe is None or self.probe.size != A.shape[0]:
                self.probe = np.random.default_rng(0).standard_normal(A.shape[0])  # generic, fixed
            _, k, converged, ritz = gmres(A, self.probe, self.factors.solve, rtol=PROBE_RTOL,
                                          max_iterations=MAX_KRYLOV)
            self.krylov_iterations += k
            COUNTS["krylov_iterations"] += k
            if converged and np.all(np.abs(ritz - 1.0) < RITZ_DISC):
                return self.factors.sign
        return self.factorise(A).sign
