"""Stability of harmonic balance solutions: Hill's method, folds and other bifurcations.

A periodic solution ``q*(time)`` is perturbed by ``y = exp(lambda time) p(time)``
with ``p`` periodic (period ``2 pi / omega``), expanded on the same harmonics as
``q*`` (harmonic-major coefficients ``[c0, a1, b1, ..., aH, bH]``, see
:mod:`~microslip.frequency.equations.hbm`). With ``d/dtime = omega D`` on the coefficients
(``D``: the harmonic derivative of :func:`~microslip.frequency.equations.hbm.harmonic_operators`),
``y' = exp(lambda time) (lambda + omega D) p`` and ``y'' = exp(lambda time)
(lambda + omega D)^2 p``, so ``M y'' + C y' + K y + (dF/dq) y = 0`` becomes the
quadratic eigenproblem of Hill's method

``(Jx + lambda Delta1 + lambda^2 Delta2) p = 0``,
``Delta1 = I (x) C + 2 omega D (x) M``, ``Delta2 = I (x) M``,

where ``Jx = Kx + omega Cx - omega^2 Mx + Jc`` is the harmonic balance Jacobian at the
solution (``(omega D)^2 = -omega^2 W``). The contact part ``Jc`` does not depend on
``lambda``: the friction law is rate independent, and its linearisation is the
periodic one of the alternating frequency--time Jacobian, as is usual with Hill's
method for friction (exact at ``lambda = 0``, where folds are decided).

The ``2 (2H+1) m`` eigenvalues of the truncated problem (``m`` unknowns per
harmonic) approximate the Floquet exponents, each of which appears ``2H+1`` times,
shifted by ``i k omega``: ``lambda + i k omega`` is an eigenvalue too, with the
eigenvector's harmonics shifted by ``k``. The truncation resolves best the copy
whose eigenvector lies in the middle of the kept harmonics, which is the copy with
the smallest ``|Im lambda|``; the copies near the edge of the truncation are
inaccurate. So the eigenvalues with the smallest ``|Im|`` are kept as the Floquet
exponents (Lazarus & Thomas 2010), at most ``2 m`` of them, copies of one another
removed, and only those of the strip ``|Im| <= omega / 2`` where every exponent has
its representative: a mode above ``(H + 1/2) omega`` has no copy there (its
nearest copy is an inaccurate edge one, which can even show a spurious positive
real part), so the verdict rests on the exponents the kept harmonics resolve (a
point with none is stable, its leading exponent NaN). The multipliers are
``exp(lambda 2 pi / omega)``. A point is stable when every kept exponent has a
real part below ``TOLERANCE * omega`` (a growth of less than ``2 pi TOLERANCE``
per period).

Forms of the equations:

* every DOF an unknown (:class:`~microslip.frequency.equations.hbm.HarmonicBalance`): the
  problem above;
* ``reduction="exact"``: the condensation is exact, so the Hill problem is that of
  the whole structure with the contact Jacobian of the retained DOFs (``Jc`` of the
  reduced equations placed at the retained DOFs; no recovery of the interior), while
  it has at most :data:`WHOLE_LIMIT` unknowns. Above, one sparse factorisation of
  that problem per point would cost far more than the curve (a 1024-DOF blade,
  H = 5: 0.4-0.8 s per point against 5 ms), and the exponents are those of a modal
  model of the structure (:data:`~microslip.frequency.reduction.choice.DEFAULT_MODES` modes
  plus the residual flexibility, the next form) with the same contact Jacobian;
  on a 384-DOF scikit-fem blade its leading exponents equal the whole structure's
  to 1.1e-5 of ``omega`` (the real part to 0.11 %: the modal model leaves out the
  damping of the omitted modes; ``tests/frequency/test_stability.py``);
* ``reduction="modal"``: the reduced equations are the exact harmonic balance of the
  modal model (kept modes ``eta`` plus the quasi-static residual flexibility ``R``
  of the omitted ones: ``q_r = Phi_r eta + R f_r``); the massless residual part is
  eliminated exactly, giving the quadratic problem in the modal coordinates

  ``(Lambda + omega Cm D - omega^2 W + lambda (Cm + 2 omega D) + lambda^2
  + Phi_r^T Jc (I + R Jc)^-1 Phi_r) p_eta = 0`` (each term ``(x)`` over the harmonics).

  Its static term is the modal model's, which differs from the exact static
  condensation the reduced equations use by the modal shift (a relative 1e-6).

Stability is computed while the Hill problem has at most :data:`HILL_LIMIT`
unknowns (``(2H+1)`` times the DOFs, or the modes of a modal reduction), and not
for a cyclic sector. Up to :data:`DENSE_LIMIT` unknowns the companion linearisation
is solved densely (:func:`numpy.linalg.eigvals`: every eigenvalue); above, the
eigenvalues nearest to 0 are found by shift-invert Arnoldi
(:func:`scipy.sparse.linalg.eigs` on a factorisation of ``Jx``), starting from
:data:`NEAREST_START` and doubling until they cover the disc ``|lambda| <= omega``
(hence every exponent of the strip ``|Im| <= omega / 2`` whose real part is below
``0.87 omega`` in size). Dense LAPACK runs with one BLAS thread here: on a loaded
machine OpenBLAS's threads make calls of this size a hundred times slower.

The modal problem (``reduction="modal"``, or an exact reduction above
:data:`WHOLE_LIMIT`) is not formed above :data:`DENSE_LIMIT` unknowns (``method=
"structured"`` of :func:`assess`, the default): its linear part is block-diagonal over
the harmonics (diagonal over the modes under classical damping) and its contact part
has the rank of the retained unknowns, so the shift-invert products cost a solve of
the linear part per harmonic and one of a capacitance system of the retained
unknowns, whose receptance is built harmonic by harmonic (:class:`_ModalHill`),
and the Arnoldi iteration starts from the previous point's eigenvectors. It covers
the smaller disc ``|lambda| < DISC omega`` (:data:`DISC`): every exponent of the
strip whose real part is below ``sqrt(DISC^2 - 1/4) omega`` in size. Where no
exponent of the strip found has a real part above ``-sqrt(DISC^2 - 1/4) omega``
(the leading exponent could lie beyond), and at the two points of each
bifurcation (the exponents its position is interpolated from), the disc is
``|lambda| < omega`` as for the formed problem. The eigenvalues are those of the
formed problem, to the Arnoldi tolerance (``method="full"`` forms and factorises
it at every point, the reference the tests compare with).

Along a curve the structured solver skips points far inside the stable region
(:func:`assess`, ``every_point=False``): a point is skipped when the last point
computed has its leading exponent below ``-FAR omega`` (:data:`FAR`: a decay of
more than ``2 pi FAR`` per period, four orders of magnitude inside
:data:`TOLERANCE`), the straight line through the leading real parts of the last
two points computed stays below that at it, at most :data:`SKIP_RUN` points in a
row are skipped, and the curve does not turn back in frequency within
:data:`TURN_WINDOW` points (where folds are). A run of skipped points whose two
computed neighbours are not both far inside is computed after all. So every
change of verdict lies between two computed points: the bifurcations are found
and located from the same exponents as with every point computed, and a skipped
point is stable (its leading exponent NaN). What this does not see: an
instability that starts and ends within the (at most :data:`SKIP_RUN`) points
skipped between two computed points far inside the stable region, away from a
turn of the curve (a Neimark--Sacker or period-doubling bubble, or a pair of
branch points, narrower than ``SKIP_RUN + 1`` steps); ``every_point=True``
computes every point.

Limit: where a contact element just reaches its slip limit somewhere on the orbit
(the onset of microslip, a contact dissipating almost nothing), the friction force
has a kink on the orbit and its linearisation depends on which side of it the AFT
samples fall. The verdict there can change with the samples and ``H``: on a blade
with platform contacts near the onset of slip, the leading exponent moved between
+45 and -55 1/s with 128, 512 and 2048 samples and H = 5 or 9, while time
integration from the solution showed no growth over 400 periods. Check such
stretches by time integration (:class:`~microslip.frequency.analyses.transient.PeriodMap`).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..numerics.blas import one_blas_thread
from ..equations.hbm import HarmonicBalance, harmonic_operators
from ..reduction.modal import ModalCondensation
from ..reduction.choice import DEFAULT_MODES
from ..reduction.condensation import CLASSICAL

#: unknowns of the quadratic eigenproblem up to which it is solved densely (every eigenvalue); above, the
#: iterative solver is faster (already on a 40-mode blade model with H = 3, 280 unknowns, by far)
DENSE_LIMIT = 64
#: unknowns of the Hill problem up to which stability is computed
HILL_LIMIT = 20000
#: unknowns of the whole structure's Hill problem up to which an exact reduction's stability is computed on it
#: (above: on a modal model of the structure)
WHOLE_LIMIT = 4000
#: eigenvalues the iterative solver asks for first (doubled until the disc |lambda| <= omega is covered)
NEAREST_START = 8
#: eigenvalues the iterative solver asks for at most
NEAREST_LIMIT = 400
#: the structured solver's Arnoldi iteration (a modal model's Hill problem): its smallest basis, and the
#: eigenvalues it asks for beyond those the previous point's disc |lambda| <= omega held
ARNOLDI_BASIS = 20
ARNOLDI_EXTRA = 2
#: two eigenvalues whose real parts and imaginary parts modulo omega agree to this share of omega are
#: copies of one Floquet exponent (at the two edges of the strip)
COPY_TOLERANCE = 1e-3
#: the Arnoldi iteration's tolerance: a Ritz pair is converged when its residual is below this share of its value
ARNOLDI_TOLERANCE = 1e-10
#: the structured solver's disc ``|lambda| < DISC omega`` (a share of omega; 1 for the formed problem's rule), and
#: eigenvectors beyond it passed on to the next point (an eigenvalue entering the disc is then already in the start)
DISC = 0.75
BLOCK_GUARD = 2
#: a Floquet exponent is unstable when its real part exceeds ``TOLERANCE * omega``
TOLERANCE = 1e-7
#: how :func:`assess` solves the Hill problem of a modal model: without forming it (the linear part inverted
#: per harmonic, the contacts through a capacitance system of the retained unknowns) or formed and factorised
METHODS = {"structured": "the linear part per harmonic and the contacts' low rank",
           "full": "the formed problem, factorised at every point"}
#: an exponent with ``|Im| >= (1 - PD_BAND) omega / 2`` gives negative multipliers (period doubling)
PD_BAND = 1e-6
#: the structured solver's skipping (:func:`assess`): a point is far inside the stable region when its leading
#: exponent's real part is below ``-FAR omega`` (a decay of more than ``2 pi FAR`` per period); at most ``SKIP_RUN``
#: points in a row are skipped between two computed ones, and none within ``TURN_WINDOW`` points of a point where
#: the curve turns back in frequency (where folds are)
FAR = 1e-3
SKIP_RUN = 3
TURN_WINDOW = 2


@dataclass(frozen=True)
class Bifurcation:
    """A bifurcation located between two points of a curve.

    Attributes
    ----------
    kind : str
        ``"fold"`` (a real Floquet multiplier crosses +1 where the curve turns back
        in frequency), ``"branch point"`` (the same crossing where it does not turn),
        ``"Neimark-Sacker"`` (a complex pair crosses the unit circle) or
        ``"period doubling"`` (a multiplier crosses -1).
    omega : float
        Excitation frequency (rad/s), by linear interpolation between the points.
    point : float
        Position along the curve as a fractional point index (``3.25``: a quarter
        of the way from point 3 to point 4).
    """

    kind: str
    omega: float
    point: float

    def interpolate(self, values) -> float:
        """A per-point quantity ``values`` (shape ``(points,)``) at :attr:`point` (linear)."""
        values = np.asarray(values, dtype=float)
        return float(np.interp(self.point, np.arange(values.size), values))


class HillProblem:
    """``(J0, Delta1, Delta2)`` of Hill's method for one solution, and its Floquet exponents.

    Parameters
    ----------
    J0, D1, D2 : ndarray or scipy.sparse matrix, shape (n, n)
        The matrices of ``(J0 + lambda D1 + lambda^2 D2) p = 0`` (``D2`` positive definite).
    per_harmonic : int
        Unknowns per harmonic ``m`` (``n = (2H+1) m``): ``2 m`` exponents are kept.
    omega : float
        Excitation frequency (rad/s).
    solve_D2 : callable, optional
        ``solve_D2(B)``: ``D2^-1 B`` for a dense ``B`` (default: a Cholesky factorisation of ``D2``).
    start : int, optional
        Eigenvalues the iterative solver asks for first (default :data:`NEAREST_START`).

    Attributes
    ----------
    needed : int
        After :meth:`eigenvalues` by the iterative solver: how many eigenvalues
        the disc ``|lambda| <= omega`` held (a start for the next point of a curve).
    """

    def __init__(self, J0, D1, D2, per_harmonic: int, omega: float, solve_D2=None, start: int | None = None):
        self.J0, self.D1, self.D2 = J0, D1, D2
        self.m = per_harmonic
        self.n = J0.shape[0]
        self.omega = float(omega)
        self._solve_D2 = solve_D2
        self.start = NEAREST_START if start is None else start
        self.needed = 0

    def eigenvalues(self) -> np.ndarray:
        """Eigenvalues of the quadratic problem (1/s): all of them (dense) or those nearest 0 (iterative)."""
        if self.n > DENSE_LIMIT:
            return self._nearest()
        J0, D1 = (A.toarray() if sp.issparse(A) else np.asarray(A) for A in (self.J0, self.D1))
        solve = self._solve_D2
        if solve is None:
            cho = sla.cho_factor(self.D2.toarray() if sp.issparse(self.D2) else self.D2)
            solve = lambda B: sla.cho_solve(cho, B, check_finite=False)  # noqa: E731
        n = self.n
        A = np.zeros((2 * n, 2 * n))
        A[:n, n:] = np.eye(n)
        A[n:, :n] = -solve(J0)
        A[n:, n:] = -solve(D1)
        return np.linalg.eigvals(A)

    def _nearest(self) -> np.ndarray:
        """Shift-invert Arnoldi on ``[[0, I], [-J0, -D1]] z = lambda [[I, 0], [0, D2]] z``, at 0.

        At a point exactly on a fold ``J0`` is singular: the shift is then moved
        off 0 by ``1e-6 omega``, which changes nothing else.
        """
        n = self.n
        D1, D2 = (sp.csr_matrix(A) for A in (self.D1, self.D2))  # block-sparse: cheap products
        for sigma in (0.0, 1e-6 * self.omega):
            solve = _factor(self.J0 + sigma * D1 + sigma ** 2 * D2 if sigma else self.J0)
            if solve is not None:
                break
        else:
            raise np.linalg.LinAlgError("Hill's problem is singular at and near 0")
        shifted = D1 + sigma * D2

        def op(z):  # (A - sigma B)^-1 B z
            a, b = z[:n], D2 @ z[n:]
            y = -solve(b + shifted @ a)
            return np.concatenate([y, a + sigma * y])

        linear = spla.LinearOperator((2 * n, 2 * n), matvec=op, dtype=float)
        most = min(2 * n - 2, NEAREST_LIMIT)
        k = min(max(self.start, 1), most)
        while True:
            mu = spla.eigs(linear, k=k, which="LM", return_eigenvectors=False, tol=ARNOLDI_TOLERANCE)
            lam = sigma + 1.0 / mu
            if np.max(np.abs(lam - sigma)) >= self.omega or k >= most:
                self.needed = int(np.count_nonzero(np.abs(lam - sigma) < self.omega))
                return lam
            k = min(2 * k, most)

    def exponents(self) -> np.ndarray:
        """The Floquet exponents (1/s), by decreasing real part (see :func:`principal_exponents`)."""
        return principal_exponents(self.eigenvalues(), self.omega, 2 * self.m)


class _ModalHill(HillProblem):
    """Hill's problem of a modal model, solved without forming ``J0``.

    Its linear part is block-diagonal over the harmonics (diagonal over the modes
    under classical damping) and its contact part has the rank of the retained
    unknowns, so each shifted solve is one of the linear part plus a capacitance
    system of the retained unknowns (Sherman--Morrison--Woodbury). With
    ``Q(sigma) = A(sigma) + Phi^T Jc (I + R Jc)^-1 Phi`` (the module docstring's
    modal problem, ``A`` its linear part) and ``G(sigma) = R + Phi A(sigma)^-1 Phi^T``
    (the modal model's receptance of the retained unknowns, harmonic-major, one
    block per harmonic):

    ``Q^-1 = A^-1 - A^-1 Phi^T Jc (I + G Jc)^-1 Phi A^-1``.

    The eigenvalues nearest the shift come from ARPACK's Arnoldi iteration started
    from the previous point's eigenvectors (``basis``, ``(2n, q)``, or None), until
    they cover the disc ``|lambda| < DISC omega`` and hold the leading exponent
    (:meth:`_arnoldi`); ``disc`` overrides :data:`DISC`.
    """

    def __init__(self, model, Jc, omega: float, start: int, basis=None, disc: float | None = None):
        self.J0 = self.D1 = self.D2 = None  # never formed
        self.disc = DISC if disc is None else float(disc)
        self.m, self.n, self.omega = model.modes, model.nb * model.modes, float(omega)
        self.start, self.needed = start, 0
        self.model, self.Jc, self.basis = model, Jc, basis
        self.vectors = None  # after eigenvalues(): an orthonormal basis of the disc's eigenvectors (the next start)

    def eigenvalues(self) -> np.ndarray:
        for sigma in (0.0, 1e-6 * self.omega):
            solve = self._shifted_solver(sigma)
            if solve is not None:
                break
        else:
            raise np.linalg.LinAlgError("Hill's problem is singular at and near 0")
        return self._arnoldi(self._companion(solve, sigma), sigma)

    def _companion(self, solve, sigma: float):
        """``(A - sigma B)^-1 B`` of the companion form applied to ``z`` ``(2n,)`` or ``(2n, p)`` (``D2 = I``), its
        second half scaled by ``1 / omega`` (the same eigenvalues; both halves of an eigenvector ``(p, lambda p /
        omega)`` of one size near the disc, which the iteration's accuracy needs)."""
        n, omega, model = self.n, self.omega, self.model

        def op(z):
            a = z[:n]
            y = -solve(omega * z[n:] + model.apply_D1(a, omega) + sigma * a)
            return np.concatenate([y, (a + sigma * y) / omega])

        return op

    def _keep(self, lam, sigma: float, X, radius: float) -> None:
        """:attr:`needed` and :attr:`vectors` from the eigenvalues ``lam`` and eigenvectors ``X`` ``(2n, k)`` found:
        the disc's eigenvectors and :data:`BLOCK_GUARD` beyond it (the nearest), one of each conjugate pair, real
        and imaginary parts, orthonormalised."""
        distance = np.abs(lam - sigma)
        inside = distance < radius
        self.needed = int(np.count_nonzero(inside))
        order = np.argsort(distance, kind="stable")
        chosen = order[:self.needed + BLOCK_GUARD]
        chosen = chosen[lam[chosen].imag >= 0]  # a conjugate pair's span is that of one member's two parts
        parts = [X[:, chosen].real, X[:, chosen[lam[chosen].imag > 0]].imag]
        V = np.hstack(parts)
        self.vectors = np.linalg.qr(V)[0] if V.shape[1] else None

    def _arnoldi(self, op, sigma: float) -> np.ndarray:
        """The eigenvalues nearest ``sigma`` by ARPACK, the iteration started from the previous point's eigenvectors,
        until they cover the disc ``|lambda - sigma| < DISC omega`` (the rule of :meth:`HillProblem._nearest` on a
        smaller disc) and hold the leading exponent: a strip exponent found with a real part above ``-sqrt(DISC^2 -
        1/4) omega``, which no exponent of the strip outside the disc can exceed unless unstable (else the disc
        ``|lambda - sigma| < omega``)."""
        size = 2 * self.n
        linear = spla.LinearOperator((size, size), matvec=op, dtype=float)
        v0 = None
        if self.basis is not None and self.basis.shape[0] == size:  # and a little of every direction
            v0 = self.basis.sum(axis=1) + 1e-3 * np.random.default_rng(0).standard_normal(size) / np.sqrt(size)
        most = min(size - 2, NEAREST_LIMIT)
        k = min(max(self.start, 1), most)
        radius = self.disc * self.omega
        while True:
            ncv = min(max(2 * k + 1, ARNOLDI_BASIS), size)
            mu, X = spla.eigs(linear, k=k, which="LM", tol=ARNOLDI_TOLERANCE, v0=v0, ncv=ncv)
            lam = sigma + 1.0 / mu
            covered = np.max(np.abs(lam - sigma)) >= radius
            if covered and radius < self.omega:
                strip = lam[np.abs(lam.imag) <= 0.5 * self.omega]
                floor = -np.sqrt(max(self.disc ** 2 - 0.25, 0.0)) * self.omega
                if not strip.size or strip.real.max() <= floor:  # the leading exponent may lie beyond the disc
                    radius = self.omega
                    covered = np.max(np.abs(lam - sigma)) >= radius
            if covered or k >= most:
                self._keep(lam, sigma, X, radius)
                return lam
            k = min(2 * k, most)

    def _shifted_solver(self, sigma: float):
        model = self.model
        inverse = model.inverse_linear(self.omega, sigma)
        if inverse is None:
            return None
        G = model.receptance(inverse)  # R + Phi A^-1 Phi^T, (r, r)
        r = G.shape[0]
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", sla.LinAlgWarning)  # a zero pivot: refused just below
            lu, piv = sla.lu_factor(np.eye(r) + G @ self.Jc, check_finite=False)
        if not np.all(np.diag(lu)):
            return None
        Jc, getrs = self.Jc, sla.lapack.dgetrs

        def solve(b):
            y = model.apply_inverse(inverse, b)
            z = getrs(lu, piv, model.project(y))[0]  # (I + G Jc)^-1 Phi y
            return y - model.apply_inverse(inverse, model.lift(Jc @ z))

        return solve


class _ModalParts:
    """The parts of a modal model's Hill problem that do not change along a curve (for :class:`_ModalHill`).

    Harmonic ``h >= 1`` of the linear part ``A(sigma)`` acts on the cosine and sine
    coefficients ``(a, b)`` of the modes as ``[[K, E], [-E, K]]`` with
    ``K = Lambda - h^2 omega^2 + sigma Cm + sigma^2``, ``E = h omega (Cm + 2 sigma)``:
    on ``a - i b`` it is the complex matrix ``K + i E``, whose inverse ``P + i Q``
    acts as ``[[P, Q], [-Q, P]]``; ``h = 0`` is ``K`` with ``h = 0``. Under classical
    damping (off-diagonal modal damping below
    :data:`~microslip.frequency.reduction.condensation.CLASSICAL` of its largest
    entry) ``P`` and ``Q`` are diagonal and every product is elementwise, with each
    coefficient's partner (cosine <-> sine of its harmonic) gathered by :attr:`partner`.
    Vectors are flat, harmonic-major ``(n,)`` or ``(n, p)``, ``n = (2H+1) modes``.
    """

    def __init__(self, linear, H: int, D):
        self.H, self.nb, self.D = H, 2 * H + 1, D
        m = self.modes = linear.modes
        self.Lam = np.asarray(linear.eigenvalues, dtype=float)
        self.Cm = np.asarray(linear.modal_damping, dtype=float)
        off = np.abs(self.Cm - np.diag(np.diag(self.Cm)))
        classical = off.size == 0 or off.max() <= CLASSICAL * max(float(np.abs(self.Cm).max()), 1e-300)
        self.damping = np.diag(self.Cm).copy() if classical else None
        self.phi_r = np.asarray(linear.phi_r, dtype=float)
        self.retained = self.phi_r.shape[0]
        self.R = np.kron(np.eye(self.nb), np.asarray(linear.residual, dtype=float))
        p = np.arange(self.nb)
        self.harmonic = (p + 1) // 2  # of each row of coefficients
        self.sign = np.where(p == 0, 0.0, np.where(p % 2 == 1, 1.0, -1.0))  # +1 cosine, -1 sine
        partner = np.where(p == 0, 0, np.where(p % 2 == 1, p + 1, p - 1))
        self.partner = (partner[:, None] * m + np.arange(m)[None, :]).ravel()
        if self.damping is not None:
            self.c_flat = np.tile(self.damping, self.nb)
            self.d_flat = np.repeat(self.sign * self.harmonic, m)  # D a = d_flat * a[partner]

    def inverse_linear(self, omega: float, sigma: float):
        """``A(sigma)^-1``: ``(P, Q)`` flat ``(n,)`` each (classical damping; ``Q`` signed per row) or
        ``(H+1, modes, modes)`` each; None when ``A(sigma)`` is singular."""
        h = np.arange(self.H + 1, dtype=float)
        if self.damping is not None:
            Z = (self.Lam[None, :] - (h * omega)[:, None] ** 2 + sigma * self.damping[None, :] + sigma ** 2
                 + 1j * (h * omega)[:, None] * (self.damping[None, :] + 2.0 * sigma))
            if not np.all(Z):
                return None
            Zi = 1.0 / Z
            return Zi.real[self.harmonic].ravel(), (self.sign[:, None] * Zi.imag[self.harmonic]).ravel()
        eye = np.eye(self.modes)
        Z = (np.diag(self.Lam)[None] - (h * omega)[:, None, None] ** 2 * eye + sigma * self.Cm
             + sigma ** 2 * eye + 1j * (h * omega)[:, None, None] * (self.Cm + 2.0 * sigma * eye))
        try:
            Zi = np.linalg.inv(Z)
        except np.linalg.LinAlgError:
            return None
        return Zi.real.copy(), Zi.imag.copy()

    def apply_inverse(self, inverse, x) -> np.ndarray:
        """``A^-1 x`` for ``x`` ``(n,)`` or ``(n, p)``."""
        P, Q = inverse
        if P.ndim == 1:
            if x.ndim == 2:
                P, Q = P[:, None], Q[:, None]
            return P * x + Q * x[self.partner]
        Y = x.reshape(self.nb, self.modes, -1)
        out = np.empty_like(Y)
        out[0] = P[0] @ Y[0]
        out[1::2] = P[1:] @ Y[1::2] + Q[1:] @ Y[2::2]
        out[2::2] = P[1:] @ Y[2::2] - Q[1:] @ Y[1::2]
        return out.reshape(x.shape)

    def project(self, y) -> np.ndarray:
        """``Phi y``: the retained unknowns ``(nb mr,)`` or ``(nb mr, p)`` of modal coefficients ``y``."""
        Y = y.reshape(self.nb, self.modes, -1)
        return (self.phi_r @ Y).reshape((self.nb * self.retained,) + y.shape[1:])

    def apply_D1(self, a, omega: float) -> np.ndarray:
        """``(I (x) Cm + 2 omega D (x) I) a`` for ``a`` ``(n,)`` or ``(n, p)``."""
        if self.damping is not None:
            c, d = (self.c_flat, self.d_flat) if a.ndim == 1 else (self.c_flat[:, None], self.d_flat[:, None])
            return c * a + (2.0 * omega) * d * a[self.partner]
        A = a.reshape(self.nb, self.modes, -1)
        out = np.einsum("ij,hjp->hip", self.Cm.T, A) + (2.0 * omega) * np.einsum("hk,kjp->hjp", self.D, A)
        return out.reshape(a.shape)

    def lift(self, w) -> np.ndarray:
        """``Phi^T w``: modal coefficients ``(n,)`` or ``(n, p)`` of forces ``w`` on the retained unknowns
        ``(nb mr,)`` or ``(nb mr, p)``."""
        W = w.reshape(self.nb, self.retained, -1)
        return (self.phi_r.T @ W).reshape((self.nb * self.modes,) + w.shape[1:])

    def receptance(self, inverse) -> np.ndarray:
        """``G = R + Phi A^-1 Phi^T`` ``(nb mr, nb mr)`` from :meth:`inverse_linear`'s ``A^-1``: on harmonic ``h``'s
        cosine and sine rows ``[[Phi P Phi^T, Phi Q Phi^T], [-Phi Q Phi^T, Phi P Phi^T]]`` (``h = 0``: its ``P``)."""
        P, Q = inverse
        phi, nb, mr = self.phi_r, self.nb, self.retained
        if P.ndim == 1:  # classical damping: the diagonals of each harmonic (Q signed per row: + on cosine rows)
            rows = np.r_[0, 1:nb:2]  # the static row and each harmonic's cosine rows
            P, Q = P.reshape(nb, self.modes)[rows], Q.reshape(nb, self.modes)[rows]
            GP = (phi[None] * P[:, None, :]) @ phi.T
            GQ = (phi[None] * Q[:, None, :]) @ phi.T
        else:
            GP = phi @ P @ phi.T
            GQ = phi @ Q @ phi.T
        G = self.R.copy()
        G[:mr, :mr] += GP[0]
        for h in range(1, self.H + 1):
            c, s = slice((2 * h - 1) * mr, 2 * h * mr), slice(2 * h * mr, (2 * h + 1) * mr)
            G[c, c] += GP[h]
            G[s, s] += GP[h]
            G[c, s] += GQ[h]
            G[s, c] -= GQ[h]
        return G

def _factor(A):
    """``solve(b)`` with a factorisation of ``A`` (sparse or dense), None when ``A`` is exactly singular."""
    if sp.issparse(A):
        # the pattern of J0 is symmetric but for the contacts' normal-on-tangential blocks: a minimum degree
        # ordering of A^T + A fills half as much as SuperLU's default (COLAMD) on finite-element structures
        try:
            return spla.splu(sp.csc_matrix(A), permc_spec="MMD_AT_PLUS_A").solve
        except RuntimeError:  # exactly singular
            return None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", sla.LinAlgWarning)  # a zero pivot: refused just below
        lu, piv = sla.lu_factor(np.asarray(A), check_finite=False)
    if not np.all(np.diag(lu)):
        return None
    return lambda b: sla.lu_solve((lu, piv), b, check_finite=False)


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
    return keep[np.lexsort((-keep.imag, -keep.real))]  # by decreasing real part, a pair's +Im first


def _kron(a, b, sparse: bool):
    if sparse:
        return sp.kron(sp.csr_matrix(a), sp.csr_matrix(b), format="csr")
    return np.kron(a, b)


def _dense(A) -> np.ndarray:
    return A.toarray() if sp.issparse(A) else np.asarray(A, dtype=float)


class _Builder:
    """The parts of the Hill problems of one set of equations that do not change along a curve.

    ``hb`` is a :class:`~microslip.frequency.equations.hbm.HarmonicBalance` or a
    :class:`~microslip.frequency.equations.reduced.ReducedHarmonicBalance` (exact or modal).
    :attr:`assessed` is False when the Hill problem has more than :data:`HILL_LIMIT` unknowns.
    """

    def __init__(self, hb: HarmonicBalance, method: str = "structured"):
        self.hb = hb
        self.method = method
        self.start = NEAREST_START  # the iterative solver's first request, from the point before
        self.basis = None  # the structured solver's start: the point before's eigenvectors
        nb = hb.nb
        self.D, self.W = harmonic_operators(hb.H)
        linear = getattr(hb, "linear", None)
        self.kind = "none" if linear is None else ("modal" if hasattr(linear, "modes") else "exact")
        s = hb.structure
        if self.kind == "exact" and nb * s.ndof > WHOLE_LIMIT:  # the whole problem is too costly per point
            linear = ModalCondensation(s.M, s.C, s.K, hb.retained, min(DEFAULT_MODES, s.ndof - 1))
            self.kind = "modal"
        if self.kind == "modal":
            M, C, m = np.eye(linear.modes), linear.modal_damping, linear.modes
        else:
            M, C, m = s.M, s.C, s.ndof
        self.m = m
        self.n = n = nb * m
        self.assessed = n <= HILL_LIMIT
        if not self.assessed:
            return
        sparse = self.sparse = n > DENSE_LIMIT
        if self.kind == "modal" and sparse and method == "structured":  # never formed: no Kronecker products
            self.parts = _ModalParts(linear, hb.H, self.D)
            return
        if not sparse:
            M, C = _dense(M), _dense(C)
        I = np.eye(nb)
        self.C1, self.M1, self.D2 = (_kron(I, C, sparse), _kron(self.D, M, sparse), _kron(I, M, sparse))
        self.solve_D2 = None
        if not sparse:
            Minv = np.linalg.inv(_dense(M))  # D2^-1 = I (x) M^-1, applied block by block
            self.solve_D2 = lambda B: np.einsum("ij,hjk->hik", Minv, B.reshape(nb, m, -1)).reshape(B.shape)
        if self.kind == "modal":
            self.Phi = np.kron(I, linear.phi_r)  # (nb m_r, nb modes)
            self.R = np.kron(I, linear.residual)
            self.Lam = np.kron(I, np.diag(linear.eigenvalues))
            self.DC = np.kron(self.D, linear.modal_damping)
            self.WI = np.kron(self.W, np.eye(m))
        elif self.kind == "exact":
            K = s.K if sparse else _dense(s.K)
            self.Kx, self.Cx, self.Mx = (_kron(I, K, sparse), _kron(self.D, C, sparse), _kron(self.W, M, sparse))
            self.rows = (np.arange(nb)[:, None] * m + hb.retained[None, :]).ravel()  # the retained unknowns

    def problem(self, x, omega: float, disc: float | None = None) -> HillProblem:
        """The Hill problem at the solution ``x`` (m) of ``hb`` at ``omega`` (rad/s) (``disc``: the structured solver's
        disc as a share of ``omega``, default :data:`DISC`)."""
        hb = self.hb
        if self.kind == "none":
            _, J0, _ = hb._evaluate(x, omega)
            J0 = J0.tocsc() if sp.issparse(J0) else J0
        else:
            hb._aft(x)
            Jc = _dense(hb._contact_jacobian()) if hb.nc else np.zeros((hb.n, hb.n))  # on the retained DOFs
            if hasattr(self, "parts"):
                return _ModalHill(self.parts, Jc, omega, self.start, self.basis, disc)
            if self.kind == "modal":
                X = np.linalg.solve(np.eye(Jc.shape[0]) + self.R @ Jc, self.Phi)
                J0 = self.Lam + omega * self.DC - omega ** 2 * self.WI + self.Phi.T @ (Jc @ X)
            else:
                J0 = self._whole(Jc, omega)
        return HillProblem(J0, self.C1 + (2.0 * omega) * self.M1, self.D2, self.m, omega, self.solve_D2, self.start)

    def exponents(self, x, omega: float, disc: float | None = None) -> np.ndarray:
        """The Floquet exponents at the solution ``x`` (m) at ``omega`` (rad/s); the next point's solver starts from
        a few more eigenvalues than this one's disc ``|lambda| <= omega`` held (the curve changes little)."""
        problem = self.problem(x, omega, disc)
        lam = problem.exponents()
        self.start = max(NEAREST_START, problem.needed + problem.needed // 4 + 2)
        if isinstance(problem, _ModalHill):
            self.start = problem.needed + ARNOLDI_EXTRA
        self.basis = getattr(problem, "vectors", None)
        return lam

    def _whole(self, Jc, omega: float):
        """The whole structure's ``J0`` with the contact Jacobian ``Jc`` of the retained DOFs (exact reduction)."""
        linear = self.Kx + omega * self.Cx - omega ** 2 * self.Mx
        if self.sparse:
            Jc = sp.coo_matrix(Jc)
            contact = sp.csr_matrix((Jc.data, (self.rows[Jc.row], self.rows[Jc.col])), shape=linear.shape)
            return (linear + contact).tocsc()
        linear[np.ix_(self.rows, self.rows)] += Jc
        return linear


def hill_problem(hb: HarmonicBalance, x, omega: float) -> HillProblem | None:
    """The Hill problem of a harmonic balance solution ``x`` (m) at ``omega`` (rad/s).

    ``hb`` is a :class:`~microslip.frequency.equations.hbm.HarmonicBalance` or a
    :class:`~microslip.frequency.equations.reduced.ReducedHarmonicBalance`. None when
    stability is not computed: more than :data:`HILL_LIMIT` unknowns.
    """
    x, omega = hb._point(x, omega)
    builder = _Builder(hb, "full")  # formed: its matrices J0, D1, D2 are the caller's to inspect
    return builder.problem(x, omega) if builder.assessed else None


def floquet_exponents(hb: HarmonicBalance, x, omega: float) -> np.ndarray | None:
    """The Floquet exponents (1/s) of the solution ``x`` at ``omega``, by decreasing real part.

    Parameters
    ----------
    hb : HarmonicBalance or ReducedHarmonicBalance
        The equations ``x`` solves.
    x : array_like, shape (n,)
        A solution (m), harmonic-major.
    omega : float
        Excitation frequency (rad/s).

    Returns
    -------
    ndarray of complex, shape (k,) with k <= 2 m, or None
        ``m`` the unknowns per harmonic (DOFs; modes with a modal reduction;
        every DOF with an exact one); fewer than ``2 m`` when modes lie above the
        kept harmonics (see the module docstring). None when not computed (see
        :func:`hill_problem`).
    """
    problem = hill_problem(hb, x, omega)
    if problem is None:
        return None
    with one_blas_thread():
        return problem.exponents()


def _kinds(lam: np.ndarray, omega: float) -> dict:
    """Masks of the exponents on the real axis, in complex pairs, and at ``|Im| = omega / 2`` (period doubling)."""
    im = np.abs(lam.imag)
    real = im <= 1e-9 * omega
    doubling = im >= (1 - PD_BAND) * omega / 2
    return {"real": real, "complex": ~real & ~doubling, "doubling": doubling}


def _leading(lam: np.ndarray, mask: np.ndarray, nearest_zero: bool = False) -> float:
    """Largest real part (1/s) of the exponents in ``mask`` (or the one nearest 0); 0 when there is none."""
    vals = lam.real[mask]
    if not vals.size:
        return 0.0
    return float(vals[np.argmin(np.abs(vals))] if nearest_zero else np.max(vals))


def _crossing(a: float, b: float) -> float:
    """Fraction in [0, 1] where a quantity going linearly from ``a`` to ``b`` crosses 0 (0.5 if it does not)."""
    return float(np.clip(a / (a - b), 0.0, 1.0)) if a != b and a * b <= 0 else 0.5


def _unstable(exponents, omegas) -> tuple[list, list]:
    """Per point: the unstable exponents of each kind (counts) and :func:`_kinds`' masks."""
    kinds = [_kinds(lam, w) for lam, w in zip(exponents, omegas)]
    unstable = [{k: int(np.count_nonzero(m & (lam.real > TOLERANCE * w))) for k, m in kind.items()}
                for lam, w, kind in zip(exponents, omegas, kinds)]
    return unstable, kinds


def _far(lam: np.ndarray, omega: float) -> bool:
    """True when the exponents ``lam`` (by decreasing real part) of a point put it far inside the stable region
    (:data:`FAR`); a point with no exponent resolved is not (nothing is known of it)."""
    return bool(lam.size) and lam[0].real < -FAR * omega


def _turning(omegas: np.ndarray) -> np.ndarray:
    """Per point: True within :data:`TURN_WINDOW` points of a point where the curve turns back in frequency."""
    steps = np.diff(omegas)
    turns = np.flatnonzero(steps[:-1] * steps[1:] < 0) + 1
    near = np.zeros(omegas.size, dtype=bool)
    for k in turns:
        near[max(k - TURN_WINDOW, 0):k + TURN_WINDOW + 1] = True
    return near


def _skipping(builder: _Builder, xs: np.ndarray, omegas: np.ndarray) -> list:
    """The exponents of each point (None where skipped) by the structured solver, which skips the points far inside
    the stable region.

    A point is skipped when the last point computed is far inside (:func:`_far`), the straight line through the
    leading real parts (over ``omega``) of the last two points computed stays below ``-FAR`` at it, at most
    :data:`SKIP_RUN` points before it were skipped, it is not the first or last point, and the curve does not turn
    back in frequency near it (:func:`_turning`). Then every run of skipped points whose two computed neighbours are
    not both far inside is computed after all: a change of verdict (a bifurcation) always lies between two
    computed points, so the bifurcations are located from the same exponents as when every point is computed.
    """
    count = len(omegas)
    exponents = [None] * count
    turning = _turning(omegas)
    computed, run = [], 0

    def far_ahead(k: int) -> bool:  # the last point computed far inside, and the trend of the last two stays so at k
        if not computed or not _far(exponents[computed[-1]], omegas[computed[-1]]):
            return False
        if len(computed) == 1:
            return True
        a, b = computed[-2], computed[-1]
        if not exponents[a].size:  # nothing known of the trend
            return False
        ra, rb = exponents[a][0].real / omegas[a], exponents[b][0].real / omegas[b]
        return rb + (rb - ra) / (b - a) * (k - b) < -FAR

    for k in range(count):
        if 0 < k < count - 1 and run < SKIP_RUN and not turning[k] and far_ahead(k):
            run += 1
            continue
        exponents[k] = builder.exponents(xs[k], float(omegas[k]))
        computed.append(k)
        run = 0
    for a, b in zip(computed[:-1], computed[1:]):
        if b - a > 1 and not (_far(exponents[a], omegas[a]) and _far(exponents[b], omegas[b])):
            for k in range(a + 1, b):
                exponents[k] = builder.exponents(xs[k], float(omegas[k]))
    return exponents


def assess(hb: HarmonicBalance, xs, omegas, method: str = "structured", every_point: bool = False
           ) -> tuple[np.ndarray | None, np.ndarray | None, list[Bifurcation]]:
    """Stability of every point of a curve and the bifurcations between them.

    Parameters
    ----------
    hb : HarmonicBalance or ReducedHarmonicBalance
        The equations.
    xs : ndarray, shape (points, n)
        Solutions (m) along the curve, in its order.
    omegas : ndarray, shape (points,)
        Their frequencies (rad/s).
    method : {"structured", "full"}, default "structured"
        How the Hill problem of a modal model is solved: ``"structured"`` never
        forms it (:data:`METHODS`); ``"full"`` forms and factorises it at every
        point. Both find the same eigenvalues by the same iteration.
    every_point : bool, default False
        Compute the structured solver's exponents at every point. By default it
        skips points far inside the stable region (:func:`_skipping`: a leading
        exponent below ``-FAR omega`` at the computed points around, at most
        :data:`SKIP_RUN` in a row, none near a turn of the curve); a skipped
        point is stable and its leading exponent NaN. The formed problem
        (``method="full"``) and the other forms of the equations compute every
        point.

    Returns
    -------
    stable : ndarray of bool, shape (points,), or None
        None when stability is not computed for these equations (see :func:`hill_problem`).
    leading : ndarray of complex, shape (points,), or None
        The Floquet exponent with the largest real part at each point (1/s;
        NaN where no exponent is resolved or the point was skipped).
    bifurcations : list of Bifurcation
        Where the number of unstable exponents changes: a real one (fold or
        branch point), a complex pair (Neimark--Sacker) or a pair at
        ``|Im| = omega / 2`` (period doubling).
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {sorted(METHODS)}, got {method!r}")
    if not isinstance(every_point, (bool, np.bool_)):
        raise TypeError(f"every_point must be True or False, got {every_point!r}")
    xs = np.asarray(xs, dtype=float)
    omegas = np.asarray(omegas, dtype=float)
    builder = _Builder(hb, method)
    if not builder.assessed:
        return None, None, []
    with one_blas_thread():
        if hasattr(builder, "parts") and not every_point:
            exponents = _skipping(builder, xs, omegas)
        else:
            exponents = [builder.exponents(x, float(w)) for x, w in zip(xs, omegas)]
        exponents = [np.empty(0, dtype=complex) if lam is None else lam for lam in exponents]  # skipped: stable
        unstable, kinds = _unstable(exponents, omegas)
        if hasattr(builder, "parts"):  # the structured solver's smaller disc: each side of a bifurcation on the
            # formed problem's disc, so that the exponents it is interpolated from are those the formed rule finds
            changed = [k for k in range(len(omegas) - 1) if unstable[k] != unstable[k + 1]]
            for k in sorted({k for c in changed for k in (c, c + 1)}):
                exponents[k] = builder.exponents(xs[k], float(omegas[k]), disc=1.0)
            unstable, kinds = _unstable(exponents, omegas)
    stable = np.array([not np.any(lam.real > TOLERANCE * w) for lam, w in zip(exponents, omegas)])
    leading = np.array([lam[0] if lam.size else complex(np.nan, np.nan) for lam in exponents])
    found = []
    for k in range(len(omegas) - 1):
        a, b = exponents[k], exponents[k + 1]
        if (unstable[k]["real"] - unstable[k + 1]["real"]) % 2:  # a real multiplier crosses +1
            f = _crossing(_leading(a, kinds[k]["real"], True), _leading(b, kinds[k + 1]["real"], True))
            # a fold where the curve turns back in frequency within two points of the crossing
            steps = np.diff(omegas[max(k - 2, 0):k + 4])
            found.append(("fold" if np.any(steps > 0) and np.any(steps < 0) else "branch point", k, f))
        for kind, name in (("complex", "Neimark-Sacker"), ("doubling", "period doubling")):
            if unstable[k][kind] != unstable[k + 1][kind]:
                f = _crossing(_leading(a, kinds[k][kind]), _leading(b, kinds[k + 1][kind]))
                found.append((name, k, f))
    bifurcations = [Bifurcation(kind, float(omegas[k] + f * (omegas[k + 1] - omegas[k])), k + f)
                    for kind, k, f in found]
    return stable, leading, bifurcations
