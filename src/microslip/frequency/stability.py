"""Stability of harmonic balance solutions: Hill's method.

A perturbation ``y(time) = exp(lambda time) p(tau)`` of a periodic solution, ``p``
periodic and expanded in the same harmonics, obeys ``Delta(lambda) p = 0`` with

``Delta(lambda) = J + lambda Delta1 + lambda^2 Delta2``,
``Delta1 = I (x) C + 2 omega D (x) M``, ``Delta2 = I (x) M``,

``J`` the harmonic balance Jacobian at the solution (contacts included: friction
is rate independent, so the contact forces depend on the displacements only) and
``D`` the harmonic derivative ``d/dtau`` (:func:`~.hbm.harmonic_operators`); this is
``(lambda + omega d/dtau)`` substituted for ``d/dtime`` in ``M q'' + C q' + K q``.
The quadratic eigenproblem is solved through its companion form. Its ``(2H+1)
ndof`` pairs repeat the Floquet exponents shifted by ``i k omega``; the ``2 ndof``
with the smallest ``|Im lambda|`` are taken as the exponents (the principal
strip ``|Im lambda| <= omega / 2``, the usual sorting), and the solution is stable
when all have a negative real part.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from .hbm import HarmonicBalance, harmonic_operators

#: unknowns up to which Hill's eigenproblem is solved (a dense eigensolution of twice that size per point)
HILL_LIMIT = 300


def floquet_exponents(hb: HarmonicBalance, x, omega: float) -> np.ndarray:
    """The ``2 ndof`` Floquet exponents (1/s) of the solution ``x`` at ``omega``, complex, by real part, largest first.

    Parameters
    ----------
    hb : HarmonicBalance
        The equations (every DOF an unknown).
    x : ndarray, shape (n,)
        A solution (m).
    omega : float
        Its excitation frequency (rad/s).
    """
    x = hb._unknowns(x)
    omega = hb._omega(omega)
    _, J, _ = hb._evaluate(x, omega)
    J = J.toarray() if sp.issparse(J) else np.asarray(J)
    s = hb.structure
    M, C = (A.toarray() if sp.issparse(A) else np.asarray(A, dtype=float) for A in (s.M, s.C))
    D, _ = harmonic_operators(hb.H)
    eye = np.eye(hb.nb)
    D1 = np.kron(eye, C) + 2.0 * omega * np.kron(D, M)
    D2 = np.kron(eye, M)
    n = hb.n
    # companion form: [[0, I], [-D2^-1 J, -D2^-1 D1]] [p; lambda p] = lambda [p; lambda p]
    lu = sla.lu_factor(D2)
    A = np.zeros((2 * n, 2 * n))
    A[:n, n:] = np.eye(n)
    A[n:, :n] = -sla.lu_solve(lu, J)
    A[n:, n:] = -sla.lu_solve(lu, D1)
    lam = sla.eigvals(A)
    principal = lam[np.argsort(np.abs(lam.imag), kind="stable")[:2 * hb.ndof]]
    return principal[np.argsort(-principal.real)]


def stable_points(hb: HarmonicBalance, xs, omegas, *, tolerance: float = 1e-9):
    """``(stable, leading)``: a bool per point and the largest real part of its exponents (1/s).

    A point is stable when that real part is below ``tolerance * omega``.
    """
    leading = np.array([floquet_exponents(hb, x, w)[0].real for x, w in zip(xs, omegas)])
    return leading < tolerance * np.asarray(omegas), leading


def bifurcations(omegas, amplitude, leading, stable) -> list:
    """Where stability changes along a curve: ``[(kind, omega, amplitude), ...]``.

    ``kind`` is ``"fold"`` where the frequency turns back (``d omega`` changes sign)
    and ``"neimark-sacker"`` where stability is lost or regained without a turn;
    the place is interpolated linearly on the leading exponent's real part.
    """
    out = []
    omegas, amplitude = np.asarray(omegas), np.asarray(amplitude)
    turn = np.sign(np.diff(omegas))
    for k in np.flatnonzero(stable[:-1] != stable[1:]):
        a, b = leading[k], leading[k + 1]
        f = a / (a - b) if a != b else 0.5
        w = omegas[k] + f * (omegas[k + 1] - omegas[k])
        amp = amplitude[k] + f * (amplitude[k + 1] - amplitude[k])
        near = turn[max(k - 1, 0):k + 2]
        kind = "fold" if near.size and (np.any(near != near[0])) else "neimark-sacker"
        out.append((kind, float(w), float(amp)))
    return out
