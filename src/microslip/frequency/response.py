"""Forced response of a structure with microslip contacts: :func:`frequency_response`.

Harmonic balance (:mod:`~microslip.frequency.hbm`) solved with Newton's
method and the exact Jacobian, followed over a frequency range by
pseudo-arclength continuation (:mod:`~microslip.frequency.continuation`).
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, field, replace
from typing import Mapping

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..common import _checks
from ..common._io import write_csv
from ..common._progress import Progress
from ..common.units import unit_factor
from .aft import MAX_PERIODS, synthesise
from .continuation import StepControl, continuation, newton
from .hbm import HarmonicBalance
from .structure import Structure, direction

_CURVE_SAMPLES = 256  # samples per period when reporting the maximum of a time signal


@dataclass(frozen=True, eq=False)
class FrequencyResponse:
    """A forced-response curve (from :func:`frequency_response`).

    ``points`` solutions along the curve, ``nb = 2H + 1`` Fourier
    coefficients ``[c0, a1, b1, ..., aH, bH]`` of ``c0 + sum a_h cos(h omega time)
    + b_h sin(h omega time)``, ``nc`` contacts.

    Attributes
    ----------
    structure : Structure
        The structure solved.
    harmonics : int
        ``H``.
    samples : int
        AFT time samples per period.
    omega : ndarray, shape (points,)
        Excitation frequency of each point (rad/s), in the order of the
        curve (not monotonic past a fold).
    coefficients : ndarray, shape (points, nb, ndof)
        Fourier coefficients of every DOF (m).
    contact_t, contact_n : ndarray, shape (points, nc, nb)
        Coefficients of each contact's tangential displacement and normal approach (m).
    contact_T, contact_N : ndarray, shape (points, nc, nb)
        Coefficients of each contact's tangential and normal force (N);
        ``contact_N[:, c, 0]`` is the static normal load.
    excitation_work, viscous_dissipation : ndarray, shape (points,)
        Work of the excitation and energy dissipated by ``C`` per cycle (J).
    contact_dissipation : ndarray, shape (points, nc)
        Energy dissipated per cycle by each contact (J).
    iterations : ndarray of int, shape (points,)
        Newton iterations of each point.
    static_normal_force, static_tangential_force : ndarray, shape (nc,)
        Each contact's normal load and tangential force (N) at the static
        equilibrium under the preloads and the static force, before any
        vibration. A ``preload`` is a force on the structure, shared between
        the contact and the structure's own stiffness, so the static normal
        force can be well below it; ``|T0| = mu N0`` means the contact is
        already in gross slip statically.
    static_closed_elements : ndarray of int, shape (nc,)
        Elements of each contact closed at the static equilibrium.
    complete : bool
        True when the curve reaches the end of the range (or leaves the range
        past a fold); False when the continuation stopped at
        ``StepControl.max_points`` first (:func:`frequency_response` warns).
    elapsed : float
        Wall time of the computation (s).
    labels : dict of str
        Display names used by :meth:`plot`: key ``"dof"``, the quantity on
        the vertical axis (default ``"response"``). Empty by default; set with
        ``dataclasses.replace(result, labels={"dof": "blade tip"})``.
    """

    structure: Structure
    harmonics: int
    samples: int
    omega: np.ndarray
    coefficients: np.ndarray
    contact_t: np.ndarray
    contact_n: np.ndarray
    contact_T: np.ndarray
    contact_N: np.ndarray
    excitation_work: np.ndarray
    viscous_dissipation: np.ndarray
    contact_dissipation: np.ndarray
    iterations: np.ndarray
    static_normal_force: np.ndarray
    static_tangential_force: np.ndarray
    static_closed_elements: np.ndarray
    complete: bool = True
    elapsed: float = 0.0
    labels: dict = field(default_factory=dict)

    @property
    def points(self) -> int:
        """Number of points on the curve."""
        return self.omega.size

    def _dof_coefficients(self, dof) -> np.ndarray:
        """Coefficients ``(points, nb)`` of one DOF or of a linear combination of DOFs."""
        b = direction("dof", dof, self.structure.ndof)
        return self.coefficients @ b

    def amplitude(self, dof=0, harmonic: int | None = None) -> np.ndarray:
        """Vibration amplitude of a DOF (or a combination of DOFs) at every point (m).

        Parameters
        ----------
        dof : int, mapping or array_like
            A DOF index, ``{dof: coefficient}`` or ``ndof`` coefficients
            (e.g. a relative displacement).
        harmonic : int, optional
            ``h >= 1``: amplitude ``sqrt(a_h^2 + b_h^2)`` of that harmonic;
            ``0``: the static value; ``None`` (default): the largest
            deviation from the static value over a period.

        Returns
        -------
        ndarray, shape (points,)
        """
        c = self._dof_coefficients(dof)
        if harmonic is None:
            q = synthesise(c, max(_CURVE_SAMPLES, 8 * self.harmonics))
            return np.max(np.abs(q - c[:, :1]), axis=1)
        h = _checks.positive_int("harmonic", harmonic, minimum=0)
        if h > self.harmonics:
            raise ValueError(f"harmonic must be at most harmonics = {self.harmonics}, got {h}")
        if h == 0:
            return c[:, 0].copy()
        return np.hypot(c[:, 2 * h - 1], c[:, 2 * h])

    def peak(self, dof=0, harmonic: int | None = None) -> tuple[float, float]:
        """Frequency (rad/s) and amplitude (m) of the highest point of the curve.

        The discrete maximum is refined by a parabola through it and its two
        neighbours, in the arclength of the curve (so it works at folds too).
        """
        amp = self.amplitude(dof, harmonic)
        i = int(np.argmax(amp))
        if i == 0 or i == amp.size - 1:
            return float(self.omega[i]), float(amp[i])
        w, a = self.omega[i - 1:i + 2], amp[i - 1:i + 2]
        ws = np.ptp(self.omega) or 1.0
        s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(w) / ws, np.diff(a) / amp[i]))])
        pa = np.polyfit(s, a, 2)
        if pa[0] >= 0:
            return float(w[1]), float(a[1])
        s_star = -pa[1] / (2 * pa[0])
        return float(np.polyval(np.polyfit(s, w, 2), s_star)), float(np.polyval(pa, s_star))

    def time_history(self, point: int, dof=0, samples: int = _CURVE_SAMPLES) -> tuple[np.ndarray, np.ndarray]:
        """One period of a DOF's displacement at a point of the curve.

        Returns ``(time, q)``: times (s) and displacement (m), shape ``(samples,)``.
        """
        point = _checks.positive_int("point", point, minimum=0)
        if point >= self.points:
            raise ValueError(f"point must be below the number of points {self.points}, got {point}")
        c = self._dof_coefficients(dof)[point]
        Ns = _checks.positive_int("samples", samples, minimum=2 * self.harmonics + 1)
        return 2 * np.pi / self.omega[point] * np.arange(Ns) / Ns, synthesise(c, Ns)

    def plot(self, dof=0, harmonic: int | None = None, ax=None, *, label: str | None = None, unit: str = "µm",
             **kwargs):
        """Plot the amplitude of a DOF against the excitation frequency.

        Parameters
        ----------
        dof, harmonic
            As in :meth:`amplitude`.
        ax : matplotlib Axes, optional
            Where to draw (a new figure if omitted).
        label : str, optional
            Legend label.
        unit : str, default "µm"
            Displacement unit of the plot: a length unit of :mod:`microslip.common.units`
            ("µm", "mm", "m", "nm", "in", ...).
        **kwargs
            Passed to ``Axes.plot``.

        Returns
        -------
        matplotlib.axes.Axes
        """
        import matplotlib.pyplot as plt

        try:
            factor = 1.0 / unit_factor(unit, "length")
        except ValueError as exc:
            raise ValueError(f"unit must be one of the length units, got {unit!r} ({exc})") from None
        if ax is None:
            _, ax = plt.subplots(figsize=(6, 4))
        ax.plot(self.omega, self.amplitude(dof, harmonic) * factor, label=label, **kwargs)
        what = "max |q - q0| over a period" if harmonic is None else f"harmonic {harmonic} amplitude"
        ax.set_xlabel("excitation frequency ω (rad/s)")
        ax.set_ylabel(f"{self.labels.get('dof', 'response')}: {what} ({unit})")
        ax.grid(True, alpha=0.3)
        if label:
            ax.legend()
        return ax

    def columns(self, dofs=None) -> dict:
        """The curve as named columns with units (for CSV): frequency, amplitudes, contact loads, energies."""
        ndof = self.structure.ndof
        dofs = range(ndof) if dofs is None else [_checks.positive_int("dofs[i]", d, minimum=0) for d in dofs]
        cols = {"omega [rad/s]": self.omega}
        for d in dofs:
            if d >= ndof:
                raise ValueError(f"dofs: DOF {d} is out of range for a structure with {ndof} DOFs")
            cols[f"q{d} max [m]"] = self.amplitude(d)
            cols[f"q{d} static [m]"] = self.amplitude(d, 0)
            for h in range(1, self.harmonics + 1):
                cols[f"q{d} a{h} [m]"] = self.coefficients[:, 2 * h - 1, d]
                cols[f"q{d} b{h} [m]"] = self.coefficients[:, 2 * h, d]
        for c, contact in enumerate(self.structure.contacts):
            cols[f"{contact.name} N static [N]"] = self.contact_N[:, c, 0]
            cols[f"{contact.name} T h1 [N]"] = np.hypot(self.contact_T[:, c, 1], self.contact_T[:, c, 2])
            cols[f"{contact.name} dissipation [J]"] = self.contact_dissipation[:, c]
        cols["viscous dissipation [J]"] = self.viscous_dissipation
        cols["excitation work [J]"] = self.excitation_work
        return cols

    def to_csv(self, path, dofs=None):
        """Write :meth:`columns` to ``path`` as CSV (atomically). Returns the path."""
        return write_csv(path, self.columns(dofs))


def _omega_range(omega) -> tuple[float, float]:
    lo, hi = _checks.positive_pair("omega", omega, "(start, end) of frequencies in rad/s")
    if lo == hi:
        raise ValueError(f"omega must span a range, got start = end = {lo!r}")
    return lo, hi


def _static_force(force) -> dict:
    if isinstance(force, Mapping) and 0 in force:
        return {0: force[0]}
    return {}


def static_solution(structure: Structure, force=None, *, tolerance: float = 1e-10) -> np.ndarray:
    """Static equilibrium ``q0`` (m), shape ``(ndof,)``, under the static force and the preloads.

    Parameters
    ----------
    structure : Structure
    force : array_like or mapping, optional
        Only its static part (key ``0`` of a mapping) is used.
    tolerance : float
        Relative residual of Newton's method.
    """
    return _static_state(structure, force, tolerance=tolerance)[0]


def _static_state(structure: Structure, force=None, *, tolerance: float = 1e-10):
    """``(q0, N0, T0, closed)``: :func:`static_solution` and each contact's static forces (N), closed elements."""
    hb = HarmonicBalance(structure, _static_force(force) if force is not None else {}, 0)
    r_scale = max(float(np.max(np.abs(hb.f))), 1e-30)
    # start from the structure with every contact element closed and stuck
    rhs = hb.f.copy()
    for c in structure.contacts:
        m = c.model
        rhs += (m.kn @ m.gaps - m.kn.sum() * c.approach) * c.normal
    K = structure.stuck_stiffness()
    if sp.issparse(K):
        x = spla.lsqr(K.tocsc(), rhs, atol=1e-14, btol=1e-14)[0]
    else:
        x = np.linalg.lstsq(K, rhs, rcond=None)[0]
    x_scale = max(float(np.max(np.abs(x))), 1e-12)
    x, _ = newton(hb, x, 1.0, r_scale=r_scale, x_scale=x_scale, tolerance=tolerance)
    _, n = hb.local(x)
    hb._aft(x)
    closed = np.array([int(np.count_nonzero(n[i, 0] > c.model.gaps)) for i, c in enumerate(structure.contacts)],
                      dtype=np.int64)
    return x, hb.FN[:, 0].copy(), hb.FT[:, 0].copy(), closed


def frequency_response(structure: Structure, force, omega, *, harmonics: int = 5, samples: int | None = None,
                       control: StepControl | None = None, progress: bool = False,
                       max_periods: int = MAX_PERIODS) -> FrequencyResponse:
    """Forced response of a structure with microslip contacts over a frequency range.

    Harmonic balance with ``harmonics`` harmonics plus the static term (the
    static normal approach of every contact is an unknown), contact forces by
    alternating frequency--time with exact Jacobians, Newton's method and
    pseudo-arclength continuation with step control (folds pass).

    Parameters
    ----------
    structure : Structure
        Structure and contacts (SI units).
    force : array_like or mapping
        Excitation (N): one vector of ``ndof`` amplitudes (real, or complex
        for a phase) at the excitation frequency, or ``{h: vector}`` with
        ``0 <= h <= harmonics`` (``h = 0``: a static force). Amplitude ``F``
        means ``Re(F exp(i h omega time))``.
    omega : (float, float)
        Start and end of the sweep (rad/s); a descending pair sweeps down.
    harmonics : int, default 5
        Harmonics kept, ``H >= 1``.
    samples : int, optional
        AFT time samples per period (default
        :func:`~microslip.frequency.aft.default_samples`: 128 for ``H = 7``).
    control : StepControl, optional
        Continuation settings.
    progress : bool, default False
        Report progress along the curve on standard error.
    max_periods : int
        Periods allowed for each contact's state to become periodic.

    Returns
    -------
    FrequencyResponse
        With ``complete`` False when the continuation stopped at
        ``control.max_points`` before the end of the range.

    Raises
    ------
    ConvergenceError
        When Newton's method fails at the start or the continuation stalls.

    Warns
    -----
    IncompleteCurveWarning
        When the curve stops at ``control.max_points`` points (the message
        names the limit and the frequency reached).
    """
    start = time.perf_counter()
    lo, hi = _omega_range(omega)
    if control is not None and not isinstance(control, StepControl):
        raise TypeError(f"control must be a StepControl, got {type(control).__name__}")
    hb, x, x_scale, r_scale, static = _first_point(structure, force, harmonics, samples, max_periods, lo, hi)
    report = Progress(10, enabled=progress)
    reached = [0]

    def tick(w, count):
        done = int(10 * (w - lo) / (hi - lo))
        while reached[0] < min(done, 10):
            reached[0] += 1
            report.step(f"omega = {w:.6g} rad/s, {count} points")

    xs, omegas, iters, complete = continuation(hb, x, lo, hi, x_scale=x_scale, r_scale=r_scale,
                                               control=control, callback=tick)
    result = _collect(hb, xs, omegas, iters, static, complete)
    report.done(f"frequency response: {omegas.size} points")
    if not complete:
        warnings.warn(incomplete_message(result, hi, control or StepControl()), IncompleteCurveWarning,
                      stacklevel=2)
    return replace(result, elapsed=time.perf_counter() - start)


class IncompleteCurveWarning(RuntimeWarning):
    """The continuation stopped at ``StepControl.max_points`` before the end of the frequency range."""


def incomplete_message(result: FrequencyResponse, omega_end: float, control: StepControl) -> str:
    """Why a curve is incomplete: the point limit and the frequency reached."""
    return (f"the continuation stopped at max_points = {control.max_points} points at omega = "
            f"{result.omega[-1]:.6g} rad/s, before the end of the range ({omega_end:.6g} rad/s); "
            f"raise StepControl.max_points (or ds_max) to follow the whole curve")


def _first_point(structure, force, harmonics, samples, max_periods, lo, hi):
    """The equations, the solution at ``lo`` (from the static state) and the scales of x and R."""
    H = _checks.positive_int("harmonics", harmonics, minimum=1)
    hb = HarmonicBalance(structure, force, H, samples=samples, max_periods=max_periods)
    if not np.any(hb.f_ext[1:]):
        raise ValueError("force must have a non-zero dynamic part (harmonic >= 1)")
    r_scale = float(np.max(np.abs(hb.f)))
    x = np.zeros(hb.n)
    x[:hb.ndof], *static = _static_state(structure, force)
    x_scale = _response_scale(hb, x, lo, hi, grid=1 if lo == hi else 24)
    x, _ = newton(hb, x, lo, r_scale=r_scale, x_scale=x_scale)
    return hb, x, max(x_scale, float(np.max(np.abs(x[hb.ndof:])))), r_scale, static


def frequency_point(structure: Structure, force, omega: float, *, harmonics: int = 5, samples: int | None = None,
                    max_periods: int = MAX_PERIODS) -> FrequencyResponse:
    """The harmonic balance solution at one frequency, reached from the static state by Newton's method.

    Where the response has several solutions at ``omega`` (past a fold) this is
    the one Newton's method finds from the response of the stuck structure; use
    :func:`frequency_response` to follow a branch.

    Parameters
    ----------
    structure, force, harmonics, samples, max_periods
        As in :func:`frequency_response`.
    omega : float
        Excitation frequency (rad/s).

    Returns
    -------
    FrequencyResponse
        With one point.
    """
    start = time.perf_counter()
    omega = _checks.positive_scalar("omega", omega)
    hb, x, _, _, static = _first_point(structure, force, harmonics, samples, max_periods, omega, omega)
    result = _collect(hb, x[None, :], np.array([omega]), np.array([0]), static, True)
    return replace(result, elapsed=time.perf_counter() - start)


def _response_scale(hb: HarmonicBalance, x_static, lo, hi, grid: int = 24) -> float:
    """Largest dynamic response of the structure with its contacts stuck, over the range (m)."""
    # x_static has no harmonics, so the residual R does not depend on omega: evaluated once
    R, Jx, _ = hb._evaluate(x_static, lo)
    Jc = Jx - hb.dynamic_stiffness(lo)
    best = 0.0
    for w in np.linspace(lo, hi, grid):
        dx = hb.solve(hb.dynamic_stiffness(w) + Jc, -R)
        if np.all(np.isfinite(dx)):
            best = max(best, float(np.max(np.abs(dx[hb.ndof:]))))
    return best if best > 0 else max(float(np.max(np.abs(x_static))), 1e-12)


def _collect(hb: HarmonicBalance, xs, omegas, iters, static, complete: bool) -> FrequencyResponse:
    """The result object from the solutions ``xs`` and the static state ``(N0, T0, closed)``."""
    q = hb.curve_quantities(xs, omegas)
    return FrequencyResponse(hb.structure, hb.H, hb.samples, omegas, xs.reshape(omegas.size, hb.nb, hb.ndof),
                             q["t"], q["n"], q["T"], q["N"], q["excitation"], q["viscous"], q["contacts"], iters,
                             *static, complete=complete)
