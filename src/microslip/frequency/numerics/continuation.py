"""Newton's method and pseudo-arclength continuation with step control.

Works on any problem ``R(x, omega) = 0`` that provides
``_evaluate(x, omega, jacobian=True) -> (R, dR/dx, dR/domega)`` (``R`` alone
without the Jacobian; unchecked: the solvers build ``x`` themselves),
``solve(A, b)`` and ``augmented(Jx, R_omega, row)`` (see
:class:`~microslip.frequency.equations.hbm.HarmonicBalance`); optionally
``watched``, the indices into ``x`` of the quantities whose interpolation
error against the parameter sets the chord rule's steps (see
``StepControl.chord_error``; a nonlinear mode's frequency and damping).
All arclength geometry is done in scaled variables ``(x / x_scale, omega / omega_scale)``
so that displacements (µm) and frequencies (rad/s) weigh alike.

Predictor: along the secant through the last two points (the tangent at the
first point). The contact forces are only piecewise smooth (each element
that starts to slip or to open at one more time sample puts a kink in the
curve), so the local tangent jumps from facet to facet while the secant
follows the curve's shape at the scale of the step. Corrector: Newton on
``R = 0`` plus the hyperplane orthogonal to the predictor through the
predicted point, so turning points (folds in ``omega``) pass. Step control:
the step grows when the corrector needs few iterations, shrinks when it
needs many, and a step is refused (and halved) when the corrector fails or
the secant turns by more than ``max_angle`` (which keeps points dense where
the curve bends, at peaks and folds) -- unless halving does not reduce the
turn, which marks a kink. With ``StepControl.chord_error`` the steps are also
sized and refused by the distance between the curve and each step's chord.
Where the steps creep towards a wall (Newton's method failing from every
predictor just across a point where the forces are not smooth, converging
further on) until they fall below ``ds_min``, longer steps are tried from
there (:func:`_leap`) before the continuation gives up, and an
:class:`~microslip.common.errors.IncompleteCurveWarning` says which stretch
the curve stepped over.

Corners. Where the Jacobian jumps and its determinant, bordered by the
direction of travel, changes sign, the curve turns back by more than a right
angle at the kink (a fold without a smooth turning point: a lightly loaded
damper whose contacts open or stick there). No hyperplane ahead meets the
curve; when the corrector fails twice at one point, the branch beyond the
corner is taken along the Jacobian's null direction on the far side, oriented
so that ``det [[Jx, R_omega], [tangent]]`` keeps the sign it had at the start
(the orientation of the whole curve, as on a piecewise-linear curve). A step
whose new point has that sign reversed along the secant has jumped past a
corner onto the branch that comes back from it, and is refused (one
determinant per point: for dense problems of 64 unknowns or more, from the
LU factors of the corrector's last iteration, its last row changed to the
secant by the matrix determinant lemma, so no factorisation is added). A
sign change that persists across a straight step :data:`BRANCH_STEP` times
``ds_max`` is no corner but a branch point of a smooth curve (the
determinant crosses zero there): the step is taken, the orientation flips,
and the curve goes on along its own branch (``branch_points`` tells where).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ...common import _checks
from ...common.errors import BranchPointWarning, ConvergenceError, IncompleteCurveWarning
from .blas import solver_threads
from .krylov import Bordered, ScaledColumns
from .reuse import ReusedFactorisation, lu_sign, newton_rtol


@dataclass
class StepControl:
    """Settings of the continuation (scaled arclength units; see the module docstring).

    Attributes
    ----------
    ds_initial, ds_min, ds_max : float
        First, smallest and largest step (positive; ``ds_initial`` is
        clipped into ``[ds_min, ds_max]``).
    max_angle : float
        Largest turn of the tangent per step (rad), in ``(0, pi)``.
    target_iterations : int
        Corrector iterations the step size aims at (>= 1).
    max_iterations : int
        Corrector iterations before a step is refused (>= 1).
    max_points : int
        Points after which the continuation stops (>= 2); the curve is then
        incomplete (see :func:`continuation`).
    tolerance : float
        Convergence: scaled Newton step and relative residual below this, in ``(0, 1)``.
    chord_error : float or None
        Interpolation error the steps aim at (scaled arclength units, positive, or None): the
        largest distance between the curve and the straight line joining two consecutive points.
        For a problem that names ``watched`` quantities (a nonlinear mode: its frequency and
        ``xi``), it is their largest difference from the straight line at the same parameter value
        instead (what a plot of each against the parameter shows between points), except on
        steps whose parameter's share of their unit direction (scaled) is at most
        :data:`WATCHED_SLOPE` (near a fold), measured as a whole. Each step's
        error is estimated from the cubic through its ends with the curve's tangents there
        (:func:`_chord_error`; one more solve per point, with the corrector's last factors where
        it kept them); the next step is the one whose estimate would be this (it grows as the
        square of the step), within ``[ds / 4, 2 ds]`` and ``ds_max``, and a step whose estimate
        exceeds :data:`CHORD_REFUSE` times this is refused and halved, across a kink too (a
        shorter step cuts less of its corner). A corner the continuation had to search for (see
        the module docstring) becomes a point of the curve. Steps then lengthen where the curve
        is straight and shorten where it bends. None (the default here; nonlinear modes take
        the chord rule by default, see their ``default_control``): steps are set by
        ``max_angle``, the corrector's iterations and ``ds_max`` alone, which puts the largest
        error where the curve is nearly straight (a step's turn is held below ``max_angle``, so
        its error ``ds * turn / 8`` is largest at ``ds_max``).
        ``max_angle`` refusals, branch points and lines behave alike with either.

    Raises
    ------
    TypeError, ValueError
        A setting of the wrong type or out of range (the message names it).
    """

    ds_initial: float = 0.02
    ds_min: float = 1e-7
    ds_max: float = 0.05
    max_angle: float = 0.1
    target_iterations: int = 3
    max_iterations: int = 12
    max_points: int = 5000
    tolerance: float = 1e-9
    chord_error: float | None = None

    def __post_init__(self):
        for name in ("ds_initial", "ds_min", "ds_max", "max_angle", "tolerance"):
            setattr(self, name, _checks.positive_scalar(name, getattr(self, name)))
        for name in ("target_iterations", "max_iterations"):
            setattr(self, name, _checks.positive_int(name, getattr(self, name)))
        self.max_points = _checks.positive_int("max_points", self.max_points, minimum=2)
        if self.ds_min > self.ds_max:
            raise ValueError(f"ds_min must not exceed ds_max, got ds_min = {self.ds_min!r} > "
                             f"ds_max = {self.ds_max!r}")
        if self.max_angle >= np.pi:
            raise ValueError(f"max_angle must be below pi (rad), got {self.max_angle!r}")
        if self.tolerance >= 1:
            raise ValueError(f"tolerance must be below 1 (a relative residual), got {self.tolerance!r}")
        if self.chord_error is not None:
            self.chord_error = _checks.positive_scalar("chord_error", self.chord_error)


def _solver_for(problem):
    """A :class:`~.reuse.ReusedFactorisation` for a problem whose Jacobian is an operator, else None."""
    return ReusedFactorisation() if getattr(problem, "operator_jacobian", False) else None


def _evaluate(problem, x, omega: float, solver):
    """``(R, dR/dx, dR/domega)``; ``dR/dx`` an operator (:mod:`~.krylov`) when the problem is solved by ``solver``."""
    if solver is not None:
        return problem._evaluate_operator(x, omega)
    return problem._evaluate(x, omega)


def _solve(problem, A, b, solver):
    """``A^-1 b`` by ``solver`` (an operator) or the problem's own solve."""
    return solver.solve(A, b) if solver is not None else problem.solve(A, b)


def newton(problem, x, omega: float, *, r_scale: float, x_scale: float, tolerance: float = 1e-9,
           max_iterations: int = 50, solver=None) -> tuple[np.ndarray, int]:
    """Solve ``R(x, omega) = 0`` at fixed ``omega`` with a backtracking Newton method.

    Returns ``(x, iterations)``; raises :class:`ConvergenceError` on failure. A problem whose Jacobian is an
    operator (``operator_jacobian``) is solved by ``solver`` (a new :class:`~.reuse.ReusedFactorisation` if
    None).
    """
    solver = solver if solver is not None else _solver_for(problem)
    if solver is None:
        return _newton(problem, x, omega, r_scale, x_scale, tolerance, max_iterations, solver)
    with solver_threads():  # small products; the rare factorisations take the threads they need
        return _newton(problem, x, omega, r_scale, x_scale, tolerance, max_iterations, solver)


def _newton(problem, x, omega, r_scale, x_scale, tolerance, max_iterations, solver):
    x = np.array(x, dtype=float)
    R, Jx, _ = _evaluate(problem, x, omega, solver)
    norm = np.linalg.norm(R) / r_scale
    for it in range(1, max_iterations + 1):
        dx = _solve(problem, Jx, -R, solver)
        if not np.all(np.isfinite(dx)):
            raise ConvergenceError(f"Newton's method met a singular Jacobian at omega = {omega:g} rad/s")
        lam = 1.0
        x_new = x + dx  # the full step with its Jacobian, kept when accepted
        R_new, J_new, _ = _evaluate(problem, x_new, omega, solver)
        norm_new = np.linalg.norm(R_new) / r_scale
        while not (norm_new < norm or lam < 1e-4):  # backtrack on the residual alone
            lam *= 0.5
            x_new = x + lam * dx
            R_new, J_new = problem._evaluate(x_new, omega, jacobian=False), None
            norm_new = np.linalg.norm(R_new) / r_scale
        x = x_new
        step = lam * float(np.max(np.abs(dx) / x_scale))
        if J_new is None:
            R_new, J_new, _ = _evaluate(problem, x, omega, solver)
            norm_new = np.linalg.norm(R_new) / r_scale
        R, Jx, norm = R_new, J_new, norm_new
        if norm < tolerance and step < max(tolerance, 1e-3) or norm < 1e-3 * tolerance:
            return x, it
    raise ConvergenceError(f"Newton's method did not converge at omega = {omega:g} rad/s "
                           f"(relative residual {norm:.3g} after {max_iterations} iterations)")


def _scaled_system(problem, Jx, R_omega, row, scale):
    """``[[Jx, R_omega], [row]]`` with the columns multiplied by ``scale`` (an operator when ``Jx`` is one)."""
    if hasattr(Jx, "matvec"):
        return Bordered(ScaledColumns(Jx, scale[:-1]), (R_omega * scale[-1])[:, None], row[None, :-1], row[None, -1:])
    Js = Jx.multiply(scale[None, :-1]).tocsc() if hasattr(Jx, "multiply") else Jx * scale[:-1]
    return problem.augmented(Js, R_omega * scale[-1], row)


def _tangent(problem, Jx, R_omega, row, scale, solver=None) -> np.ndarray:
    """Unit tangent (scaled) of ``R = 0``: ``[Jx, R_omega] z = 0`` with ``row . z = 1``."""
    A = _scaled_system(problem, Jx, R_omega, row, scale)
    rhs = np.zeros(scale.size)
    rhs[-1] = 1.0
    z = _solve(problem, A, rhs, solver)
    return z / np.linalg.norm(z)


def _correct(problem, y_pred, tau, scale, r_scale, ctl, last=None, solver=None):
    """Newton on ``R = 0`` and ``tau . (y - y_pred) = 0`` (scaled); ``(y, iterations)`` or ``(None, k)``.

    ``last``, a list, receives ``[Jx, R_omega, factors]`` at the converged point:
    its Jacobian and, for a dense problem of at least :data:`FACTORED_MIN`
    unknowns, the :class:`_Factored` system of the last iteration (see
    :func:`_sign`), for a problem solved by ``solver`` (its Jacobian an
    operator) the solver, else None.
    """
    yc = y_pred.copy()
    step = np.inf
    factors = solver
    for it in range(ctl.max_iterations + 1):
        R, Jx, Rw = _evaluate(problem, yc[:-1], yc[-1], solver)
        res = np.linalg.norm(R) / r_scale
        if it and res < ctl.tolerance and step < np.sqrt(ctl.tolerance):
            if last is not None:
                last[:] = [Jx, Rw, factors]
            return yc, it
        if it == ctl.max_iterations or not np.isfinite(res):
            break
        g = np.append(R, tau @ ((yc - y_pred) / scale))
        A = _scaled_system(problem, Jx, Rw, tau, scale)
        if solver is not None:  # an inexact Newton step: the solve as accurate as the tolerance needs
            dz = solver.solve(A, -g, newton_rtol(res, ctl.tolerance))
        elif sp.issparse(A) or A.shape[0] < FACTORED_MIN:
            dz = problem.solve(A, -g)
        else:
            factors = _Factored(A, tau)
            dz = factors.solve(-g)
        if not np.all(np.isfinite(dz)):
            break
        yc = yc + dz * scale
        step = float(np.max(np.abs(dz)))
    return None, it


#: a change of orientation that persists over a straight step this much shorter than ``ds_max`` is a branch point
#: of a smooth curve, passed on the same branch (a step past a corner onto the branch coming back from it loses
#: the change when halved well before that)
BRANCH_STEP = 1e-3

#: a step along which the parameter moves less than this fraction of the step's length, and which turns by less than
#: :data:`LINE_ANGLE` times ``max_angle`` from the last, lies on a line of solutions at one parameter value
LINE_PARAMETER = 1e-9
LINE_ANGLE = 1e-3

#: such a line is crossed in steps that double from one point to the next (its points differ only along the line);
#: still straight at a step this many times ``ds_max``, it does not end and the continuation stops there
LINE_REACH = 1e6

#: a step whose estimated chord error exceeds this many times ``StepControl.chord_error`` is refused (halved, which
#: quarters the error of a smooth stretch): the steps aim at the target, so only a bend sharper than the last step
#: foretold is redone, and no chord strays much beyond the target
CHORD_REFUSE = 2.0

#: smallest dense bordered system whose LU factors are kept for the point's orientation: below it, a solve
#: and a determinant of their own cost less than the factors' calls (the crossover was measured on small
#: bordered systems; the figures belong to a benchmark, not here)
FACTORED_MIN = 64


class _Factored:
    """The LU factors of a dense bordered system ``A = [[Jx, R_omega], [row]]``: solves and determinant signs."""

    def __init__(self, A: np.ndarray, row: np.ndarray):
        self.row = row
        self.singular = not np.all(np.isfinite(A))
        if self.singular:
            return
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", sla.LinAlgWarning)  # exactly singular: solves give NaN
            self.lu, self.piv = sla.lu_factor(A, check_finite=False)
        self.sign = lu_sign(self.lu, self.piv)
        self.singular = self.sign == 0

    def solve(self, b: np.ndarray) -> np.ndarray:
        """``A^-1 b``; all NaN when ``A`` is singular (the callers then shorten the step)."""
        if self.singular:
            return np.full(np.shape(b), np.nan)
        return sla.lu_solve((self.lu, self.piv), b, check_finite=False)

    def sign_with_row(self, row: np.ndarray) -> float:
        """Sign of the determinant with the last row replaced by ``row``, from these factors.

        ``det(A + e (row - self.row)^T) = det(A) (1 + (row - self.row) . A^-1 e)``
        (the matrix determinant lemma, ``e`` the last unit vector).
        """
        if self.singular:
            return 0.0
        e = np.zeros(self.row.size)
        e[-1] = 1.0
        return self.sign * float(np.sign(1.0 + (row - self.row) @ self.solve(e)))


def _sign(problem, last, row, scale) -> float:
    """Sign of ``det [[Jx, R_omega], [row]]`` at the corrector's converged point (``last``, see :func:`_correct`).

    Dense problems of at least :data:`FACTORED_MIN` unknowns take it from the
    factors of the corrector's last iteration (its Jacobian one Newton step
    before the point, within the convergence tolerance of it, bordered by
    ``row`` instead of the predictor): no new factorisation. Others factor the
    system at the point.
    """
    Jx, Rw, factors = last
    if isinstance(factors, ReusedFactorisation):  # the Jacobian an operator: see ReusedFactorisation.sign
        return factors.sign(_scaled_system(problem, Jx, Rw, row, scale))
    if factors is not None:
        return factors.sign_with_row(row)
    return _orientation(problem, Jx, Rw, row, scale)


def _orientation(problem, Jx, R_omega, row, scale, solver=None) -> float:
    """Sign of ``det [[Jx, R_omega], [row]]`` (scaled columns): the side of the curve ``row`` points to."""
    A = _scaled_system(problem, Jx, R_omega, row, scale)
    if solver is not None:
        return solver.sign(A)
    if not sp.issparse(A):
        return float(np.linalg.slogdet(A)[0])
    try:
        lu = spla.splu(A.tocsc())
    except RuntimeError:  # exactly singular
        return 0.0
    sign = np.prod(np.sign(lu.U.diagonal()))  # L has a unit diagonal
    for perm in (lu.perm_r, lu.perm_c):  # each permutation's parity: (-1)^(size - cycles)
        seen = np.zeros(perm.size, dtype=bool)
        cycles = 0
        for i in range(perm.size):
            if not seen[i]:
                cycles += 1
                while not seen[i]:
                    seen[i] = True
                    i = perm[i]
        sign *= -1.0 if (perm.size - cycles) % 2 else 1.0
    return float(sign)


#: relative residual of the tangent solved for a chord error by a problem whose Jacobian is an operator: the
#: estimate takes differences of unit tangents about a step's turn apart, so their error must be a small part of it
TANGENT_RTOL = 1e-6

def _leap(problem, y, tau, step, scale, r_scale, ctl, last, solver, here):
    """A point beyond a wall the steps creep towards: ``(y, iterations, step)`` or None.

    Where the contact forces are not smooth (an element's state changes within the period), Newton's
    method may fail from a predictor just across the change while it converges from one further on:
    halved steps then converge short of the change and approach it without passing. This corrects
    from ``step`` (the one that failed first), twice and four times as far, and takes the first point
    ahead of ``y`` on the same side of the curve (orientation ``here``).
    """
    for factor in (1.0, 2.0, 4.0):
        ds = factor * step
        yc, it = _correct(problem, y + ds * tau * scale, tau, scale, r_scale, ctl, last, solver)
        if yc is None:
            continue
        secant = (yc - y) / scale
        if secant @ tau > 0 and _sign(problem, last, secant / np.linalg.norm(secant), scale) == here:
            return yc, it, ds
    return None


def _corner(problem, y, tau, ds, scale, r_scale, ctl, here, solver=None, here_corner=None):
    """A point about ``ds`` past a corner just ahead of ``y``: ``(y, iterations, direction)`` or ``(None, k, None)``.

    The corner itself (on the curve to the tolerance) is left in ``here_corner[0]`` when a list is given.

    Where an element starts to slip or to open, the Jacobian jumps. When the jump
    reverses the orientation of the curve (the sign of ``det [[Jx, R_omega], [tau]]``)
    the branch beyond turns back by more than a right angle -- a fold at a kink, where
    a floating body's contacts change state -- so the hyperplane ahead of ``y`` meets no
    solution and halving the step only creeps towards the corner. The corner is found
    on the straight line the curve follows from ``y`` (where the residual leaves zero);
    the branch beyond leaves it along the null direction of the Jacobian on the far
    side, oriented so that the determinant keeps its sign ``here`` (as on a
    piecewise-linear curve).
    """
    _, Jx, Rw = _evaluate(problem, y[:-1], y[-1], solver)
    along = _tangent(problem, Jx, Rw, tau, scale, solver)  # the curve's direction at y

    def off(s):  # y + s along has left the curve
        p = y + s * along * scale
        return np.linalg.norm(problem._evaluate(p[:-1], p[-1], jacobian=False)) > ctl.tolerance * r_scale

    if not np.all(np.isfinite(along)) or not off(ds):
        return None, 0, None
    a, b = 0.0, ds
    while b - a > 1e-6 * ds:
        m = 0.5 * (a + b)
        a, b = (a, m) if off(m) else (m, b)
    corner, probe = y + a * along * scale, y + b * along * scale
    _, Jx, Rw = _evaluate(problem, probe[:-1], probe[-1], solver)
    far = _tangent(problem, Jx, Rw, along, scale, solver)  # far . along > 0
    there = _orientation(problem, Jx, Rw, along, scale, solver)
    if not np.all(np.isfinite(far)) or here * there == 0 or (here == there and far @ along > np.cos(ctl.max_angle)):
        return None, 0, None  # nothing turns there: not a corner
    if here != there:
        far = -far
    yc, it = _correct(problem, corner + ds * far * scale, far, scale, r_scale, ctl, solver=solver)
    if yc is None:
        return None, it, None
    secant = (yc - y) / scale
    length = np.linalg.norm(secant)
    if length > 2 * ds + a:
        return None, it, None  # converged elsewhere than near the corner
    # the curve's direction there, oriented as the whole curve (the determinant's sign)
    _, Jx, Rw = _evaluate(problem, yc[:-1], yc[-1], solver)
    ahead = _tangent(problem, Jx, Rw, far, scale, solver)
    if _orientation(problem, Jx, Rw, ahead, scale, solver) != here:
        ahead = -ahead
    behind = np.cos(0.1 * ctl.max_angle)
    if not np.all(np.isfinite(ahead)) or (ahead @ tau > behind and secant @ tau < -behind * length):
        return None, it, None  # back on the branch already followed, behind y
    if here_corner is not None:
        here_corner[:] = [corner]
    return yc, it, ahead


#: a chord steeper than this (its parameter's share of its unit direction below it) is measured as a whole: near a
#: fold the watched quantities are no function of the parameter
WATCHED_SLOPE = 0.05

#: the fractions of a step at which :func:`_chord_error` looks for the largest distance (its cubic's
#: distance from the chord is smooth and vanishes at both ends: a few fractions find its largest value to
#: a small fraction of it)
_CHORD_FRACTIONS = np.linspace(0.0, 1.0, 33)[1:-1]


def _chord_error(start: np.ndarray, end: np.ndarray, secant: np.ndarray, length: float, watched=None) -> float:
    """Largest distance between a step's chord and the curve between its ends (scaled units).

    ``start`` and ``end`` are the curve's unit tangents at the step's ends, ``secant`` the chord's unit
    direction and ``length`` its length. The curve is taken as the cubic with those end points and
    tangents (Hermite), whose distance from the chord at the fraction ``t`` of the step is
    ``length t (1 - t) |(1 - t) (start - secant) - t (end - secant)|``: exact to third order in
    ``length`` on a smooth curve (``kappa length^2 / 8`` on a circle of curvature ``kappa``), and on a
    corner within the step the corner's own distance to first order. With ``watched`` (indices into
    the vectors; the parameter is their last entry): the largest difference of those entries from the
    chord at the same parameter value, from the same cubic.
    """
    u, v = start - secant, end - secant
    t = _CHORD_FRACTIONS
    if watched is not None and abs(secant[-1]) > WATCHED_SLOPE:
        # the cubic's offset from the chord at t, less what the parameter's own offset moves along the chord:
        # the quantity's difference from the straight line at the same parameter value
        slope = secant[watched] / secant[-1]
        du, dv = u[watched] - slope * u[-1], v[watched] - slope * v[-1]
        off = (t * (1 - t))[:, None] * ((1 - t)[:, None] * du - t[:, None] * dv)
        return length * float(np.max(np.abs(off)))
    uu, uv, vv = float(u @ u), float(u @ v), float(v @ v)
    squared = (t * (1 - t)) ** 2 * ((1 - t) ** 2 * uu - 2 * t * (1 - t) * uv + t ** 2 * vv)
    return length * float(np.sqrt(max(squared.max(), 0.0)))


def _tangent_at(problem, last, row, scale, solver) -> np.ndarray:
    """Unit tangent (scaled) at the corrector's converged point (``last``, see :func:`_correct`), ``row . t > 0``.

    From the factors of the corrector's last iteration when it kept them (a dense problem of at least
    :data:`FACTORED_MIN` unknowns: its Jacobian one Newton step before the point, bordered by the
    predictor's direction); by the problem's solver to :data:`TANGENT_RTOL` when its Jacobian is an
    operator; else from a solve of its own.
    """
    Jx, Rw, factors = last
    e = np.zeros(scale.size)
    e[-1] = 1.0
    z = np.full(scale.size, np.nan)
    if isinstance(factors, _Factored):
        z = factors.solve(e)
    elif isinstance(factors, ReusedFactorisation):
        z = factors.solve(_scaled_system(problem, Jx, Rw, row, scale), e, TANGENT_RTOL)
    t = z / np.linalg.norm(z)
    if not np.all(np.isfinite(t)):
        t = _tangent(problem, Jx, Rw, row, scale, solver)
    return -t if t @ row < 0 else t


def continuation(problem, x0, omega_start: float, omega_end: float, *, x_scale: float, r_scale: float,
                 control: StepControl | None = None, callback=None, branch_points: list | None = None,
                 lines: list | None = None, folds: list | None = None):
    """Follow the solution curve of ``R(x, omega) = 0`` from ``omega_start`` to ``omega_end``.

    Parameters
    ----------
    problem
        See the module docstring.
    x0 : ndarray, shape (n,)
        A solution at ``omega_start`` (converged).
    omega_start, omega_end : float
        Frequency range (rad/s); the curve is followed while it stays inside.
    x_scale : float or ndarray, shape (n,)
        Scale of ``x`` (m), one for all unknowns or one each (the arclength weighs
        ``x / x_scale``).
    r_scale : float
        Scale of the residual (N).
    control : StepControl, optional
        Step-size settings.
    callback : callable, optional
        ``callback(omega, count)`` after each accepted point.
    branch_points : list, optional
        Receives the ``omega`` (rad/s) of each branch point the curve passed:
        where the orientation ``det [[Jx, R_omega], [tangent]]`` changes sign on a
        smooth stretch (the secant straight, the corrector converging), which
        halving the step does not remove: another branch of solutions crosses the
        curve there. The curve goes on along the same branch.
    lines : list, optional
        Receives the ``omega`` (rad/s) where the curve ran onto a straight line
        of solutions at that one value and followed it, in steps doubling from
        point to point, to :data:`LINE_REACH` times ``control.ds_max`` without
        reaching its end: the continuation stops there (``complete`` False), and
        the points on the line are dropped (the curve ends where it starts).
        Such a line is a free motion of the solution at one parameter value
        (a body whose contacts all slide or stay open over the period, its mean
        position then free); a line that ends (at a kink, where a contact changes
        state) is crossed in those doubling steps and the curve goes on.

    Returns
    -------
    xs : ndarray, shape (points, n)
    omegas : ndarray, shape (points,)
    iterations : ndarray of int, shape (points,)
        Corrector iterations of each point.
    complete : bool
        True when the curve was followed until it left the range; False when
        it stopped at ``control.max_points`` points first (then the last point
        is where it stopped).
    """
    ctl = control or StepControl()
    solver = _solver_for(problem)  # one factorisation reused over many steps when the Jacobian is an operator
    if solver is None:
        return _continuation(problem, x0, omega_start, omega_end, x_scale, r_scale, ctl, callback, branch_points,
                             solver, lines, folds)
    with solver_threads():  # small products; the rare factorisations take the threads they need
        return _continuation(problem, x0, omega_start, omega_end, x_scale, r_scale, ctl, callback, branch_points,
                             solver, lines, folds)


def _continuation(problem, x0, omega_start, omega_end, x_scale, r_scale, ctl, callback, branch_points, solver,
                  lines=None, folds=None):
    n = x0.size
    scale = np.empty(n + 1)
    scale[:-1] = x_scale
    w_scale = abs(omega_end - omega_start)
    scale[-1] = w_scale
    direction = 1.0 if omega_end > omega_start else -1.0
    lo, hi = sorted((omega_start, omega_end))

    y = np.append(x0, omega_start)
    R, Jx, Rw = _evaluate(problem, x0, omega_start, solver)
    e_w = np.zeros(n + 1)
    e_w[-1] = 1.0
    tau = _tangent(problem, Jx, Rw, e_w, scale, solver)
    if tau[-1] * direction < 0:
        tau = -tau
    orientation = _orientation(problem, Jx, Rw, tau, scale, solver)  # the same all along the curve
    last = []  # the Jacobian at the corrector's last point
    xs, omegas, iters = [x0.copy()], [omega_start], [0]
    ds = min(max(ctl.ds_initial, ctl.ds_min), ctl.ds_max)
    complete = False
    line_start = None  # index of the point where a line at one parameter value starts
    here = tau  # the curve's unit tangent at y (scaled), for the chord error of the step from y
    watched = getattr(problem, "watched", None)
    if watched is not None and ctl.chord_error is not None:
        watched = np.atleast_1d(np.arange(n)[np.asarray(watched, dtype=int)])  # indices >= 0 into x (and y)
        watched = watched if watched.size else None  # none named: the whole vector
    else:
        watched = None
    walled = 0  # points in a row reached by a shorter step after the corrector failed at a longer one
    wall_step = ds  # the step that failed at the first of them
    while len(omegas) < ctl.max_points:
        refused_angle = np.inf  # turn at the last step refused for turning too much
        failed = walled > 0  # the corrector failed at this point already, or just ahead of the last one
        leap = None
        corner = []  # the corner the step passes, if _corner finds one
        while leap is None:
            if ds < ctl.ds_min:  # crept towards a wall: step over it from the step that first failed, or give up
                leap = _leap(problem, y, tau, wall_step, scale, r_scale, ctl, last, solver, orientation)
                if leap is None:
                    raise ConvergenceError(
                        f"the continuation stalled at omega = {y[-1]:g} rad/s: the step fell below "
                        f"ds_min = {ctl.ds_min:g}")
                warnings.warn(
                    f"the continuation stepped over the stretch from {y[-1]:.6g} to {leap[0][-1]:.6g} (its parameter: "
                    f"omega in rad/s, or the log of a nonlinear mode's amplitude), where Newton's method failed from "
                    f"every shorter step (a point where the contact forces are not smooth): the curve is a straight "
                    f"line there and may miss a detail of it; a smaller StepControl.ds_min or more samples may "
                    f"resolve it", IncompleteCurveWarning, stacklevel=3)
                break
            yc, it = _correct(problem, y + ds * tau * scale, tau, scale, r_scale, ctl, last, solver)
            if yc is None and failed:  # failing again, nearer: look for a corner within the step
                yc, it, ahead = _corner(problem, y, tau, ds, scale, r_scale, ctl, orientation, solver, corner)
                if yc is not None:  # its turn is the corner's: no reason to shrink the next step
                    secant, angle, kink, there = ahead, 0.0, True, ahead  # ahead: the tangent at yc
                    break
            if yc is None:
                if not failed and walled == 0:
                    wall_step = ds
                failed = True
                ds *= 0.5
                continue
            secant = (yc - y) / scale
            length = float(np.linalg.norm(secant))
            secant /= length
            angle = float(np.arccos(np.clip(secant @ tau, -1.0, 1.0)))
            if _sign(problem, last, secant, scale) == -orientation and ds > 2 * ctl.ds_min:
                if ds > BRANCH_STEP * ctl.ds_max or angle > 0.1 * ctl.max_angle:
                    failed = True  # past a corner, on the branch that comes back from it: shorter
                    ds *= 0.5
                    continue
                # the sign still changes across a tiny straight step: the determinant crosses zero on a
                # smooth curve (a branch point), not at a corner; pass it on the same branch
                orientation = -orientation
                if branch_points is not None:
                    branch_points.append(float(0.5 * (y[-1] + yc[-1])))
            # On a smooth curve the turn shrinks with the step; where it does not, the
            # step crosses a kink (an element starts to slip or to open: the contact
            # force is only piecewise smooth) and a smaller step would not help.
            kink = angle > 0.75 * refused_angle
            if angle > ctl.max_angle and ds > 2 * ctl.ds_min and not kink:
                refused_angle = angle
                ds *= 0.5
                continue
            if ctl.chord_error is not None:  # across a kink too: a shorter step cuts less of its corner
                there = _tangent_at(problem, last, secant, scale, solver)
                chord = _chord_error(here, there, secant, length, watched)
                if chord > CHORD_REFUSE * ctl.chord_error and ds > 2 * ctl.ds_min:
                    ds *= 0.5
                    continue
            break
        if leap is not None:  # over the wall: the turn is the wall's, no reason to shrink the next step
            yc, it, ds = leap
            secant = (yc - y) / scale
            length = float(np.linalg.norm(secant))
            secant /= length
            angle, kink = 0.0, True
            there = _tangent_at(problem, last, secant, scale, solver) if ctl.chord_error is not None else None
        walled = walled + 1 if failed and not kink else 0
        # a straight step that leaves the parameter where it was (to rounding): the solutions form a line at one
        # parameter value (a body held by contacts that all slide or stay open, its mean position free)
        still = LINE_PARAMETER * np.linalg.norm((yc - y) / scale) * scale[-1]  # the parameter's rounding on this step
        on_line = not kink and angle <= LINE_ANGLE * ctl.max_angle and abs(yc[-1] - y[-1]) <= still
        if folds is not None and (yc[-1] - y[-1]) * direction < -still:
            folds.append(float(y[-1]))  # the curve turns back: it ends at its point before the turn
            break
        y, tau = yc, secant
        if corner and ctl.chord_error is not None and lo <= corner[0][-1] <= hi:
            xs.append(corner[0][:-1].copy())  # a point of the curve (to the tolerance): the chords then cut nothing
            omegas.append(float(corner[0][-1]))
            iters.append(0)
        if not lo <= y[-1] <= hi:
            # left the range: end exactly on its edge (or stop if it turned back out)
            edge = hi if y[-1] > hi else lo
            if edge == (hi if direction > 0 else lo):
                x_prev, w_prev = xs[-1], omegas[-1]
                frac = (edge - w_prev) / (y[-1] - w_prev)
                x_edge, k = newton(problem, x_prev + frac * (y[:-1] - x_prev), edge,
                                   r_scale=r_scale, x_scale=x_scale, tolerance=ctl.tolerance, solver=solver)
                xs.append(x_edge)
                omegas.append(edge)
                iters.append(k)
                if callback is not None:
                    callback(edge, len(omegas))
            complete = True
            break
        xs.append(y[:-1].copy())
        omegas.append(float(y[-1]))
        iters.append(it)
        if callback is not None:
            callback(float(y[-1]), len(omegas))
        # grow when the corrector was quick and the curve straight, shrink otherwise
        turn = 0.0 if kink else angle
        factor = min(ctl.target_iterations / max(it, 1), 2.0, 0.9 * ctl.max_angle / max(turn, 1e-12))
        longest = np.inf  # the step whose chord error is the one asked for (it grows as the step's square)
        if ctl.chord_error is not None and not kink:
            longest = max(ds * np.sqrt(ctl.chord_error / max(chord, 1e-300)), 0.25 * ds)
        here = there if ctl.chord_error is not None else None
        if on_line:  # every point of a straight line at one parameter value is as good: cross it in doubling steps
            line_start = len(omegas) - 2 if line_start is None else line_start
            if ds >= LINE_REACH * ctl.ds_max:  # still straight after that: the line does not end
                if lines is not None:
                    lines.append(float(y[-1]))
                del xs[line_start + 1:], omegas[line_start + 1:], iters[line_start + 1:]  # the curve ends where
                break                                                                     # the line starts
            ds *= 2.0
            continue
        line_start = None
        ds = float(np.clip(min(ds * max(factor, 0.5), longest), ctl.ds_min, ctl.ds_max))
    return np.array(xs), np.array(omegas), np.array(iters), complete
