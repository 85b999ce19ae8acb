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
ndof`` pairs repeat the Floquet exponents shifted by ``i k omega``; the truncation
resolves best the copy whose eigenvector lies in the middle of the kept harmonics,
the one with the smallest ``|Im lambda|``, and the copies near the edge of the
truncation are inaccurate. So the exponents are the eigenvalues of the strip
``|Im lambda| <= omega / 2`` (at most ``2 ndof``, by ``|Im|``, copies of one another
at the strip's two edges removed; Lazarus & Thomas 2010). A mode above
``(H + 1/2) omega`` has no copy in the strip: its nearest copies are edge ones,
which can show a spurious positive real part, so it is left out and the verdict
rests on the exponents the kept harmonics resolve. The solution is stable when all
have a negative real part (a point with none is stable, its leading exponent NaN).
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from .hbm import HarmonicBalance, harmonic_operators

#: unknowns up to which Hill's eigenproblem is solved (a dense eigensolution of twice that size per point)
HILL_LIMIT = 300
#: two eigenvalues whose real parts and imaginary parts modulo omega agree to this share of omega are
#: copies of one Floquet exponent (at the two edges of the strip)
COPY_TOLERANCE = 1e-3


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
    return principal_exponents(sla.eigvals(A), omega, 2 * hb.ndof)


def principal_exponents(lam, omega: float, count: int) -> np.ndarray:
    """The Floquet exponents among Hill's eigenvalues ``lam`` (1/s), by decreasing real part.

    At most ``count`` eigenvalues of the strip ``|Im| <= omega / 2`` (with
    :data:`COPY_TOLERANCE` of slack), by increasing ``|Im|``, a copy shifted by
    ``i k omega`` (``k != 0``) of one already kept left out.
    """
    lam = np.asarray(lam, dtype=complex)
    lam = lam[np.isfinite(lam) & (np.abs(lam.imag) <= (0.5 + COPY_TOLERANCE) * omega)]
    lam = lam[np.argsort(np.abs(lam.imag), kind="stable")]
    tol = COPY_TOLERANCE * omega
    keep = np.empty(0, dtype=complex)
    for v in lam:
        if keep.size == count:
            break
        d = (v.imag - keep.imag) / omega
        shift = np.round(d)
        if np.any((np.abs(v.real - keep.real) <= tol) & (np.abs(d - shift) * omega <= tol) & (shift != 0)):
            continue
        keep = np.append(keep, v)
    return keep[np.argsort(-keep.real, kind="stable")]


def stable_points(hb: HarmonicBalance, xs, omegas, *, tolerance: float = 1e-9):
    """``(stable, leading)``: a bool per point and the largest real part of its exponents (1/s).

    A point is stable when that real part is below ``tolerance * omega``.
    """
    leading = np.array([_largest(floquet_exponents(hb, x, w).real) for x, w in zip(xs, omegas)])
    return ~(leading >= tolerance * np.asarray(omegas)), leading


def _largest(values) -> float:
    """The largest value, NaN for none."""
    return float(np.max(values)) if np.size(values) else np.nan


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
