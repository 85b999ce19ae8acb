"""Direct time integration to the periodic steady state: :func:`steady_state`.

An independent check of harmonic balance: the same structure and contacts,
integrated in time with explicit central differences (compiled, see
:mod:`microslip.kernels.transient`) period after period, until the
response repeats.

Where it starts matters. A contact element that sticks through the whole
steady cycle keeps the force it took before: friction makes the steady state
depend on the history. By default the integration starts at rest at the
static equilibrium (the contacts closed at ``t = 0`` with no tangential force,
then loaded statically) and the excitation is switched on: off a resonance
the start-up transient beats, its first peaks larger than the steady ones,
and may make an element slip that then sticks for good. Harmonic balance
instead loads every contact once to the mean of its periodic motion
(:mod:`microslip.frequency.aft`), so where an element sticks throughout the
two steady states can differ by more than the harmonic truncation (up to
1.2 % off the resonance of the blade of ``examples/fe_blade.py``, nothing
at its peak). With ``start=`` a
harmonic-balance solution, the integration starts on that motion with the
contacts in the state harmonic balance assumes for it; it then settles on the
exact periodic solution next to it, and the difference measures the
truncation of the harmonics and the time step only.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Mapping

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from ...common import _checks
from ...kernels.element import NO_CONDITIONS, NO_ELEMENTS, NO_WORK, march
from ...common._progress import Progress
from ...kernels import (aft as _aft, plane_march as _plane_march, transient as _transient,
                        transient_plane as _transient_plane)
from ..aft import MAX_HARMONICS, MAX_PERIODS, MAX_TABLE, check_periodic, check_table
from ..equations.hbm import excitation
from .prestressed import prestressed_structure
from .response import FrequencyResponse, static_solution
from ..structures.structure import Structure, direction


@dataclass(frozen=True, eq=False)
class SteadyState:
    """The last period of a time integration (from :func:`steady_state`).

    Attributes
    ----------
    omega : float
        Excitation frequency (rad/s).
    time : ndarray, shape (steps,)
        Times within the period (s), from 0.
    q : ndarray, shape (steps, ndof)
        Displacements (m) at those times.
    coefficients : ndarray, shape (2H+1, ndof)
        Fourier coefficients of ``q`` over the period (m), ``[c0, a1, b1, ...]``.
    periods : int
        Periods integrated.
    change : float
        Relative change of the first harmonic over the last period.
    converged : bool
        ``change`` fell below the tolerance.
    """

    structure: Structure
    omega: float
    time: np.ndarray
    q: np.ndarray
    coefficients: np.ndarray
    periods: int
    change: float
    converged: bool

    def amplitude(self, dof=0, harmonic: int | None = None) -> float:
        """Amplitude of a DOF or a combination (m): harmonic ``h``, or the largest deviation (``None``)."""
        b = direction("dof", dof, self.structure.ndof)
        if harmonic is None:
            x = self.q @ b
            return float(np.max(np.abs(x - np.mean(x))))
        h = _checks.positive_int("harmonic", harmonic, minimum=1)
        if h > (self.coefficients.shape[0] - 1) // 2:
            raise ValueError(f"harmonic must be at most {(self.coefficients.shape[0] - 1) // 2} (the harmonics "
                             f"computed), got {h}")
        c = self.coefficients @ b
        return float(np.hypot(c[2 * h - 1], c[2 * h]))


def _fourier(q: np.ndarray, H: int) -> np.ndarray:
    """Coefficients ``(2H+1, ndof)`` of samples ``q`` ``(steps, ndof)`` at ``tau_k = 2 pi (k+1) / steps``."""
    # the cached projection takes samples at tau_k = 2 pi k / steps: the last sample (tau = 2 pi) comes first
    return _aft.tables(H, q.shape[0])[1] @ np.roll(q, 1, axis=0)


def _start_coefficients(structure: Structure, start) -> np.ndarray:
    """The Fourier coefficients ``(2H+1, ndof)`` (m) of every DOF of a one-point harmonic balance result, checked."""
    if not isinstance(start, FrequencyResponse):
        raise TypeError(f"start must be None or a FrequencyResponse (from frequency_point), got "
                        f"{type(start).__name__}")
    if start.points != 1:
        raise ValueError(f"start must be a solution at one frequency (frequency_point), got a curve of "
                         f"{start.points} points")
    if start.engine_order is not None or start.structure.ndof != structure.ndof:
        raise ValueError(f"start must be a solution of a structure with the same {structure.ndof} DOFs, got one "
                         f"with {start.structure.ndof}" + (" (a cyclic sector)" if start.engine_order else ""))
    if start.dofs.size == structure.ndof:
        return start.coefficients[0][:, np.argsort(start.dofs)]
    return start.recovery(0)


def _periodic_start(structure: Structure, coefficients, steps: int):
    """``(q_prev, q, sliders)``: on the motion ``coefficients`` at ``tau = 0``, contacts as harmonic balance has them.

    ``coefficients`` ``(2H+1, ndof)`` (m) of every DOF; ``q`` at ``tau = 0`` and
    ``q_prev`` one step of ``2 pi / steps`` before (m, ``(ndof,)`` each). Every
    contact is loaded once from the virgin state to the mean of its motion,
    then marched along the motion sampled at the ``steps`` time steps, period
    after period, until its state repeats (at most ``aft.MAX_PERIODS``): the
    convention of :mod:`microslip.frequency.aft`. ``sliders`` (m) is that
    state at the end of a period (with contacts on their planes, both
    components: see :class:`PeriodMap`).
    """
    H = (coefficients.shape[0] - 1) // 2
    q = _aft.tables(H, steps)[0] @ coefficients  # tau_k = 2 pi k / steps
    Bt, Bn, n0 = structure.contact_directions()
    Bt2 = structure.second_tangential_directions()
    ref, ref2 = structure.tangential_references()
    t, t2, n = q @ Bt - ref, q @ Bt2 - ref2, q @ Bn + n0  # t from where the sliders were reset
    kt, kn, gaps, offsets, mu = structure.packed_models()
    planar = _planar(structure)
    sliders = np.zeros((2, kt.size))
    T, N = np.empty(steps), np.empty(steps)
    for i in range(len(structure.contacts)):
        lo, hi = offsets[i], offsets[i + 1]
        law = (kt[lo:hi], kn[lo:hi], gaps[lo:hi], mu[i])
        mean = (coefficients[0] @ Bt[:, i] - ref[i], coefficients[0] @ Bt2[:, i] - ref2[i],
                coefficients[0] @ Bn[:, i] + n0[i])
        roll = [np.roll(x[:, i], -1) for x in (t, t2, n)]  # tau_1, ..., tau_(steps-1), 2 pi: the period ends at 0
        if planar[i]:  # the AFT's own periodic state, on these samples
            periods = _plane_march.periodic_state_of_samples(*law, *mean, *roll, MAX_PERIODS, sliders[:, lo:hi])
            check_periodic(int(periods), MAX_PERIODS)
            continue
        s = sliders[0, lo:hi]
        march(*law, np.array([mean[0]]), np.array([mean[2]]), s, T[:1], N[:1], NO_WORK, NO_ELEMENTS, NO_CONDITIONS)
        for _ in range(MAX_PERIODS):
            before = s.copy()
            march(*law, roll[0], roll[2], s, T, N, NO_WORK, NO_ELEMENTS, NO_CONDITIONS)
            if np.array_equal(before, s):
                break
    sliders += np.repeat(np.stack([ref, ref2]), np.diff(offsets), axis=1)  # back to where t is measured from
    return q[-1].copy(), q[0].copy(), sliders.ravel() if planar.any() else sliders[0].copy()


def _planar(structure: Structure) -> np.ndarray:
    """Which contacts move on their planes, ``(nc,)`` bool."""
    return np.array([c.planar for c in structure.contacts], dtype=bool)


class PeriodMap:
    """The explicit central-difference scheme of :func:`steady_state`, one period at a time.

    Its state is ``(q_prev, q, sliders)``: the displacements (m) one step before
    and at the start of a period, ``(ndof,)`` each, and the sliders of every contact
    element (m), ``(elements,)``; when some contact moves on its plane, both
    components of every slider, ``(2 elements,)`` (the first components, then
    the second; the second unused on a contact along one direction).
    :meth:`period` maps a state to the state one period later (the Poincare map
    of shooting and Floquet analyses).

    Parameters
    ----------
    structure, force, omega
        As in :func:`steady_state` (checked there).
    steps : int
        Time steps per period, raised when the scheme would be unstable.
    harmonics : int, optional
        ``H`` of the steady state's Fourier analysis, which bounds ``steps``.

    Attributes
    ----------
    steps : int
        Time steps per period.
    dt : float
        Time step (s).
    """

    def __init__(self, structure: Structure, force, omega: float, steps: int, harmonics: int | None = None):
        M, C, K = (A.toarray() if sp.issparse(A) else np.asarray(A) for A in (structure.M, structure.C, structure.K))
        self.structure = structure
        self.force = force
        self.K = K
        self.Bt, self.Bn, self.n0 = structure.contact_directions()
        self.Bt2, self.planar = structure.second_tangential_directions(), _planar(structure)
        # stability: dt < 2 / omega_max with every contact element closed and stuck
        K_max = structure.stuck_stiffness()
        K_max = K_max.toarray() if sp.issparse(K_max) else K_max
        w_max = float(np.sqrt(np.max(np.abs(sla.eigvals(K_max, M)))))
        period = 2 * np.pi / omega
        steps = max(steps, int(np.ceil(period * w_max / 1.8)))
        # the steady state's Fourier table holds steps x (2H+1) values
        limit = _checks.MAX_SIZE if harmonics is None else MAX_TABLE // (2 * harmonics + 1)
        if steps > limit:
            raise ValueError(f"omega = {omega:g} rad/s is too low: a stable step needs {steps:.3g} steps per period "
                             f"(at most {limit}" + ("" if harmonics is None else f" with harmonics = {harmonics}") + ")")
        self.steps = steps
        self.dt = dt = period / steps
        self.A_inv = np.linalg.inv(M / dt**2 + C / (2 * dt))
        self.B1 = 2 * M / dt**2
        self.B0 = M / dt**2 - C / (2 * dt)
        keys = [h for h in force if isinstance(h, (int, np.integer))] if isinstance(force, Mapping) else []
        coef = excitation(structure, force, max(keys, default=1))
        coef[0] += structure.preload_force()
        # forcing (steps, ndof) at tau_k = 2 pi k / steps: aft.time_samples's cached table, without its
        # samples >= 2H+1 check (steps_per_period is raised for stability only, never refused here)
        self.f = _aft.tables((coef.shape[0] - 1) // 2, steps)[0] @ coef
        self.packed = structure.packed_models()

    def start(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(q_prev, q, sliders)`` at rest at the static equilibrium, the contacts loaded statically.

        The static force is the excitation's static part (key 0 of a mapping; an array is a first
        harmonic and has none) plus the contacts' preloads.
        """
        q = static_solution(self.structure, self.force if isinstance(self.force, Mapping) else None)
        kt, kn, gaps, offsets, mu = self.packed
        sliders = np.zeros(kt.size)
        if self.planar.any():
            both = np.zeros((2, kt.size))
            sliders = both[0]
        ref, ref2 = self.structure.tangential_references()  # the sliders' reset positions: t is measured from there
        for i in range(len(self.structure.contacts)):
            lo, hi = offsets[i], offsets[i + 1]
            if self.planar[i]:
                both[:, lo:hi] = _plane_march.static_sliders(self.structure.contacts[i].model,
                                                             self.Bt[:, i] @ q - ref[i], self.Bt2[:, i] @ q - ref2[i],
                                                             self.Bn[:, i] @ q + self.n0[i])
                both[0, lo:hi] += ref[i]
                both[1, lo:hi] += ref2[i]
                continue
            march(kt[lo:hi], kn[lo:hi], gaps[lo:hi], mu[i], np.array([self.Bt[:, i] @ q - ref[i]]),
                  np.array([self.Bn[:, i] @ q + self.n0[i]]), sliders[lo:hi], np.empty(1), np.empty(1), NO_WORK,
                  NO_ELEMENTS, NO_CONDITIONS)
            sliders[lo:hi] += ref[i]
        return q.copy(), q, both.ravel() if self.planar.any() else sliders

    def integrate(self, q_prev, q, sliders, out) -> None:
        """March ``out.shape[0]`` steps from the start of a period, updating ``q_prev, q, sliders`` in place.

        ``out`` (shape ``(steps, ndof)``) receives the displacements (m) at times ``dt, 2 dt, ...``.
        """
        if self.planar.any():
            _transient_plane.integrate_plane(self.A_inv, self.K, self.B1, self.B0, self.f, self.Bt, self.Bt2, self.Bn,
                                             self.n0, self.planar, *self.packed, sliders.reshape(2, -1), q_prev, q,
                                             out.shape[0], out)
            return
        _transient.integrate(self.A_inv, self.K, self.B1, self.B0, self.f, self.Bt, self.Bn, self.n0,
                             *self.packed, sliders, q_prev, q, out.shape[0], out)

    def period(self, state) -> np.ndarray:
        """The state ``[q_prev, q, sliders]`` (shape ``(2 ndof + elements,)``, or ``(2 ndof + 2 elements,)`` with
        contacts on their planes) one period later."""
        ndof = self.structure.ndof
        state = np.array(state, dtype=float)
        q_prev, q, sliders = state[:ndof], state[ndof:2 * ndof], state[2 * ndof:]
        self.integrate(q_prev, q, sliders, np.empty((self.steps, ndof)))
        return state


def steady_state(structure: Structure, force, omega: float, *, steps_per_period: int = 4096,
                 harmonics: int = 7, tolerance: float = 1e-7, max_periods: int = 5000,
                 progress: bool = False, start: FrequencyResponse | None = None, prestress=None) -> SteadyState:
    """Integrate in time until the periodic steady state.

    Parameters
    ----------
    structure : Structure
        Dense structure (a sparse one is converted; meant for small models).
    force : array_like or mapping
        Excitation (N), as in :func:`~microslip.frequency.frequency_response`.
    omega : float
        Excitation frequency (rad/s).
    steps_per_period : int, default 4096
        Time steps per period; raised automatically if the explicit scheme
        would be unstable.
    harmonics : int, default 7
        Harmonics of the returned Fourier coefficients.
    tolerance : float, default 1e-7
        Steady when the first harmonic of every DOF changes by less than
        this (relative to its size) from one period to the next.
    max_periods : int, default 5000
        Periods integrated at most.
    progress : bool
        Report progress on standard error.
    start : FrequencyResponse, optional
        Where to start: by default at rest at the static equilibrium, the
        excitation switched on at ``t = 0``; a harmonic balance solution at
        one frequency (:func:`~microslip.frequency.frequency_point`, of this
        structure, any reduction) starts on its motion at ``t = 0`` with the
        contacts in the state harmonic balance assumes for it (see the
        module: the steady state of a contact with elements that stick
        throughout depends on where it starts).
    prestress : Prestress, optional
        Start from the static state of :func:`~microslip.frequency.prestress`
        on this structure (at rest there by default, the sliders where the
        prestress left them): its :attr:`~microslip.frequency.Prestress.prestressed`
        structure is integrated; ``force`` then holds harmonics ``>= 1`` only.
        A ``start`` is then a solution with the same prestress.

    Returns
    -------
    SteadyState
    """
    if not isinstance(structure, Structure):
        raise TypeError(f"structure must be a microslip Structure, got {type(structure).__name__}")
    structure = prestressed_structure(structure, prestress, force)
    omega = _checks.positive_scalar("omega", omega)
    _checks.finite_result("omega", omega, omega * omega)  # the step's M / dt^2
    steps = _checks.size("steps_per_period", steps_per_period, minimum=8)
    H = _checks.size("harmonics", harmonics, minimum=1, maximum=min(MAX_HARMONICS, steps // 2 - 1))
    check_table("steps_per_period", steps, H)
    progress = _checks.flag("progress", progress)
    tolerance = _checks.positive_scalar("tolerance", tolerance)
    max_periods = _checks.positive_int("max_periods", max_periods)
    coefficients = None if start is None else _start_coefficients(structure, start)
    scheme = PeriodMap(structure, force, omega, steps, harmonics=H)
    steps, ndof = scheme.steps, structure.ndof
    if coefficients is not None:  # on a harmonic balance solution
        q_prev, q, sliders = _periodic_start(structure, coefficients, steps)
    else:  # at rest at the static equilibrium, contacts loaded statically from the virgin state
        q_prev, q, sliders = scheme.start()
    out = np.empty((steps, ndof))
    report = Progress(max_periods, enabled=progress)
    previous = None
    change = np.inf
    done = 0
    while done < max_periods:
        scheme.integrate(q_prev, q, sliders, out)
        done += 1
        first = _fourier(out, 1)[1:3]
        if previous is not None:
            size = np.max(np.hypot(first[0], first[1]))
            change = float(np.max(np.abs(first - previous)) / max(size, 1e-300))
            if done % 50 == 0:
                report.step(f"period {done}: relative change {change:.2e}")
            if change < tolerance:
                break
        previous = first
    # the recorded samples are at times dt, 2 dt, ..., period
    return SteadyState(structure, omega, scheme.dt * (np.arange(steps) + 1), out.copy(), _fourier(out, H), done,
                       change, change < tolerance)
