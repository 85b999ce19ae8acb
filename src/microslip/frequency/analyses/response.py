"""Forced response of a structure with microslip contacts: :func:`frequency_response`.

Harmonic balance (:mod:`~microslip.frequency.equations.hbm`) solved with Newton's
method and the exact Jacobian, followed over a frequency range by
pseudo-arclength continuation (:mod:`~microslip.frequency.numerics.continuation`).
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, field, replace
from typing import Mapping

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ...common._numeric import eigsh_repeatable
from ...common import _checks
from ...common._io import write_csv
from ...common._progress import Progress
from ...common.units import plot_factor
from ...common.errors import CurveInterrupted, IncompleteCurveWarning, PeakOnEdgeWarning
from ..aft import MAX_PERIODS, UnderResolvedWarning, check_harmonics, time_samples
from ..numerics.blas import small_dense
from ..numerics.continuation import StepControl, continuation, newton
from ..equations.hbm import HarmonicBalance, excitation
from ..structures.cyclic import CyclicStructure
from ..equations.build import build_equations
from ..equations.cyclic_balance import check_engine_order, phase_operator
from ..equations.reduced import ReducedHarmonicBalance
from ..reduction.choice import modal_error
from .prestressed import prestressed_structure
from .stability import assess
from ..structures.structure import Structure, direction, dof_label

_CURVE_SAMPLES = 256  # samples per period when reporting the maximum of a time signal


@dataclass(frozen=True, eq=False)
class FrequencyResponse:
    """A forced-response curve (from :func:`frequency_response`).

    ``points`` solutions along the curve, ``nb = 2H + 1`` Fourier coefficients
    ``[c0, a1, b1, ..., aH, bH]`` of ``c0 + sum a_h cos(h omega time) + b_h sin(h omega time)``,
    ``nc`` contacts. How to read one (static state, energies, stability, reductions): the user
    guide's page "Forced responses and stability".

    Attributes
    ----------
    structure : Structure
        The structure solved.
    harmonics, samples : int
        ``H`` and the AFT's time samples per period.
    omega : ndarray, shape (points,)
        Excitation frequency of each point (rad/s), in the order of the curve (not monotonic past a fold).
    coefficients : ndarray, shape (points, nb, len(dofs))
        Fourier coefficients (m) of the DOFs in :attr:`dofs`; :meth:`amplitude`,
        :meth:`time_history` and :meth:`dof_coefficients` recover any other DOF.
    dofs : ndarray of int, shape (m,)
        The DOFs stored: every DOF without reduction, the retained ones with one.
    contact_t, contact_n : ndarray, shape (points, nc, nb)
        Each contact's tangential displacement and normal approach (m).
    contact_T, contact_N : ndarray, shape (points, nc, nb)
        Each contact's tangential and normal force (N); ``contact_N[:, c, 0]`` is the static normal load.
    contact_t2, contact_T2 : ndarray, shape (points, nc, nb)
        The second tangential direction of a contact on its plane (m, N); zero along one direction.
    excitation_work, viscous_dissipation : ndarray, shape (points,)
        Work of the excitation and energy dissipated by ``C`` per cycle (J).
    contact_dissipation : ndarray, shape (points, nc)
        Friction work of each contact over the sampled period (J), never negative.
    contact_harmonic_work : ndarray, shape (points, nc)
        Each contact's energy per cycle from the force harmonics kept (J), which balances the
        excitation's and the viscous work exactly but carries the AFT's sampling error.
    iterations : ndarray of int, shape (points,)
        Newton iterations of each point.
    static_normal_force, static_tangential_force, static_tangential_force2 : ndarray, shape (nc,)
        Each contact's normal load and tangential force components (N) at the static equilibrium.
    static_closed_elements : ndarray of int, shape (nc,)
        Elements of each contact closed at the static equilibrium.
    static_coefficients : ndarray, shape (len(dofs),)
        The static equilibrium's displacement of :attr:`dofs` (m); None where not solved.
    complete : bool
        False when the continuation stopped at ``StepControl.max_points`` or was interrupted
        (the ``partial`` of :class:`CurveInterrupted`).
    elapsed : float
        Wall time of the computation (s).
    labels : dict of str
        Display names for :meth:`plot` (key ``"dof"``); set with ``dataclasses.replace``.
    reduction, modes : str, int or None
        ``"none"``, ``"exact"`` or ``"modal"``, and the normal modes a modal one kept (per nodal diameter).
    reduction_error : float or None
        With ``"modal"``: the relative difference between the modal and the exact condensed
        first-harmonic dynamic stiffness at the peak.
    engine_order : int or None
        For a cyclic sector: the engine order solved (:meth:`sector_coefficients` gives any sector).
    stable : ndarray of bool, shape (points,), or None
        Hill stability of each point (:mod:`~microslip.frequency.analyses.stability`); None when not computed.
    leading_exponent : ndarray of complex, shape (points,), or None
        The Floquet exponent with the largest real part (1/s); NaN where the harmonics resolve none, or where
        the point was not computed because its neighbours lie far inside the stable region (stable; see the
        stability module's rule for skipping points).
    bifurcations : list of Bifurcation
        Folds, branch points, Neimark--Sacker and period-doubling points between the points
        (:class:`~microslip.frequency.analyses.stability.Bifurcation`).
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
    dofs: np.ndarray | None = None
    reduction: str = "none"
    modes: int | None = None
    reduction_error: float | None = None
    engine_order: int | None = None
    contact_harmonic_work: np.ndarray | None = field(default=None, repr=False)
    stable: np.ndarray | None = field(default=None, repr=False)
    bifurcations: list = field(default_factory=list)
    leading_exponent: np.ndarray | None = field(default=None, repr=False)
    recovery: object = field(default=None, repr=False)
    contact_t2: np.ndarray | None = field(default=None, repr=False)
    contact_T2: np.ndarray | None = field(default=None, repr=False)
    static_tangential_force2: np.ndarray | None = field(default=None, repr=False)
    static_coefficients: np.ndarray | None = field(default=None, repr=False)

    def __post_init__(self):
        if self.dofs is None:
            object.__setattr__(self, "dofs", np.arange(self.structure.ndof))

    @property
    def points(self) -> int:
        """Number of points on the curve."""
        return self.omega.size

    def dof_coefficients(self, dof) -> np.ndarray:
        """Fourier coefficients (m), shape ``(points, 2H+1)``, of one DOF or a combination of DOFs.

        ``dof`` as in :meth:`amplitude`. A DOF the reduction did not keep is
        recovered from the contact solution at every point (a solve per point
        and harmonic with ``"exact"``, a modal sum with ``"modal"``).
        """
        b = direction("dof", dof, self.structure.ndof, dof_map=self.structure.dof_map)
        held = b[self.dofs]
        if np.count_nonzero(held) == np.count_nonzero(b):
            return self.coefficients @ held
        if self.recovery is None:
            raise ValueError("dof: this result keeps only its retained DOFs and cannot recover others")
        return np.array([self.recovery(k) @ b for k in range(self.points)])

    _dof_coefficients = dof_coefficients

    def sector_coefficients(self, dof, sector: int) -> np.ndarray:
        """Coefficients (m), ``(points, 2H+1)``, of a DOF of sector ``sector`` of a cyclic structure.

        Sector ``k`` lags this one (sector 0) by ``k`` times the phase of each
        harmonic's nodal diameter, ``z_k = z_0 exp(-i k phi_h)``.
        """
        if self.engine_order is None:
            raise ValueError("sector_coefficients is for the response of a CyclicStructure (engine_order given)")
        k = _checks.positive_int("sector", sector, minimum=0)
        if k >= self.structure.sectors:
            raise ValueError(f"sector must be below the number of sectors {self.structure.sectors}, got {k}")
        P = np.linalg.matrix_power(phase_operator(self.structure, self.harmonics, self.engine_order), k)
        return self.dof_coefficients(dof) @ P.T

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
            q = time_samples(c, max(_CURVE_SAMPLES, 8 * self.harmonics))
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

        Warns
        -----
        PeakOnEdgeWarning
            When the highest point is the curve's first or last point
            (:meth:`peak_on_edge`): the response still rises there, so the
            resonance lies outside the range followed and this is no peak.
        """
        amplitude = self.amplitude(dof, harmonic)
        if on_edge(amplitude):
            warnings.warn(edge_message(self.omega, amplitude, self.complete), PeakOnEdgeWarning, stacklevel=2)
        return curve_peak(self.omega, amplitude)

    def peak_on_edge(self, dof=0, harmonic: int | None = None) -> bool:
        """True when the highest point of the curve is its first or last point.

        The response then still rises at an end of the frequency range followed
        (or at the last point of an incomplete curve): the resonance lies
        outside, and :meth:`peak` gives the end of the range, not a peak.
        ``dof``, ``harmonic`` as in :meth:`amplitude`.
        """
        return on_edge(self.amplitude(dof, harmonic))

    def time_history(self, point: int, dof=0, samples: int = _CURVE_SAMPLES) -> tuple[np.ndarray, np.ndarray]:
        """One period of a DOF's displacement at a point of the curve.

        Returns ``(time, q)``: times (s) and displacement (m), shape ``(samples,)``.
        """
        point = _checks.positive_int("point", point, minimum=0)
        if point >= self.points:
            raise ValueError(f"point must be below the number of points {self.points}, got {point}")
        c = self._dof_coefficients(dof)[point]
        Ns = _checks.size("samples", samples, minimum=2 * self.harmonics + 1)
        return 2 * np.pi / self.omega[point] * np.arange(Ns) / Ns, time_samples(c, Ns)

    def plot(self, dof=0, harmonic: int | None = None, ax=None, *, label: str | None = None, unit: str = "µm",
             frequency_unit: str = "rad/s", **kwargs):
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
        frequency_unit : {"rad/s", "Hz"}, default "rad/s"
            Unit of the excitation frequency on the horizontal axis.
        **kwargs
            Passed to ``Axes.plot``.

        Returns
        -------
        matplotlib.axes.Axes
        """
        import matplotlib.pyplot as plt

        factor = plot_factor(unit)
        if ax is None:
            _, ax = plt.subplots(figsize=(6, 4))
        if frequency_unit not in ("rad/s", "Hz"):
            raise ValueError(f"frequency_unit must be 'rad/s' or 'Hz', got {frequency_unit!r}")
        x = self.omega if frequency_unit == "rad/s" else self.omega / (2 * np.pi)
        y = self.amplitude(dof, harmonic) * factor
        line, = ax.plot(x, y if self.stable is None else np.where(self.stable, y, np.nan), label=label, **kwargs)
        if self.stable is not None and not self.stable.all():  # unstable stretches dashed, same colour
            unstable = ~self.stable
            edge = unstable | np.r_[unstable[1:], False] | np.r_[False, unstable[:-1]]
            ax.plot(x, np.where(edge, y, np.nan), "--", color=line.get_color())
        what = "max |q - q0| over a period" if harmonic is None else f"harmonic {harmonic} amplitude"
        ax.set_xlabel("excitation frequency ω (rad/s)" if frequency_unit == "rad/s" else "excitation frequency f (Hz)")
        ax.set_ylabel(f"{self.labels.get('dof', dof_label(self.structure, dof) or 'response')}: {what} ({unit})")
        ax.grid(True, alpha=0.3)
        if label:
            ax.legend()
        return ax

    def columns(self, dofs=None, names=None) -> dict:
        """The curve as named columns with units (for CSV): frequency, amplitudes, contact loads, energies.

        ``dofs``: the DOFs written (default :attr:`dofs`); ``names``: a name
        for every DOF of the structure (default ``q0``, ``q1``, ... or the DOF
        map's ``node:component``).
        """
        ndof = self.structure.ndof
        dofs = self.dofs if dofs is None else [_checks.positive_int("dofs[i]", d, minimum=0) for d in dofs]
        if names is None:
            dof_map = getattr(self.structure, "dof_map", None)
            names = dof_map.names if dof_map is not None else [f"q{i}" for i in range(ndof)]
        elif len(names) != ndof or not all(isinstance(n, str) and n for n in names):
            raise ValueError(f"names must give a non-empty name to each of the {ndof} DOFs, got {names!r}")
        cols = {"omega [rad/s]": self.omega, "f [Hz]": self.omega / (2 * np.pi)}
        for d in dofs:
            if d >= ndof:
                raise ValueError(f"dofs: DOF {d} is out of range for a structure with {ndof} DOFs")
            c = self.dof_coefficients(int(d))
            q = names[int(d)]
            cols[f"{q} max [m]"] = self.amplitude(int(d))
            cols[f"{q} static [m]"] = c[:, 0]
            for h in range(1, self.harmonics + 1):
                cols[f"{q} a{h} [m]"] = c[:, 2 * h - 1]
                cols[f"{q} b{h} [m]"] = c[:, 2 * h]
        for c, contact in enumerate(self.structure.contacts):
            cols[f"{contact.name} N static [N]"] = self.contact_N[:, c, 0]
            cols[f"{contact.name} T h1 [N]"] = np.hypot(self.contact_T[:, c, 1], self.contact_T[:, c, 2])
            if contact.planar:
                cols[f"{contact.name} T2 h1 [N]"] = np.hypot(self.contact_T2[:, c, 1], self.contact_T2[:, c, 2])
            cols[f"{contact.name} dissipation [J]"] = self.contact_dissipation[:, c]
        if self.stable is not None:
            cols["stable [-]"] = self.stable.astype(int)
            cols["growth rate [1/s]"] = self.leading_exponent.real
        cols["viscous dissipation [J]"] = self.viscous_dissipation
        cols["excitation work [J]"] = self.excitation_work
        return cols

    def to_csv(self, path, dofs=None, names=None):
        """Write :meth:`columns` to ``path`` as CSV (atomically). Returns the path."""
        path = _checks.file_path("path", path)
        return write_csv(path, self.columns(dofs, names))


def _omega_range(omega) -> tuple[float, float]:
    lo, hi = _checks.positive_pair("omega", omega, "(start, end) of frequencies in rad/s")
    if lo == hi:
        raise ValueError(f"omega must span a range, got start = end = {lo!r}")
    return lo, hi


def _static_force(force) -> dict:
    if isinstance(force, Mapping) and 0 in force:
        return {0: force[0]}
    return {}


def on_edge(amplitude) -> bool:
    """True when the largest of ``amplitude`` (one value per point, in the order of the curve) is its first or
    last value: the curve's highest point is an end of it, not a peak (False for a single point: no range)."""
    i = int(np.argmax(amplitude))
    return len(amplitude) > 1 and (i == 0 or i == len(amplitude) - 1)


def edge_message(omega, amplitude, complete: bool = True) -> str:
    """Why the highest point of a curve (``omega`` in rad/s, ``amplitude`` in m) is no peak."""
    i = int(np.argmax(amplitude))
    if i == len(amplitude) - 1 and not complete:
        where = "the last point of the incomplete curve"
    else:
        where = "the start of the frequency range" if i == 0 else "the end of the frequency range"
    return (f"the highest point of the curve is {where} (omega = {float(omega[i]):.6g} rad/s, "
            f"{float(amplitude[i]):.4g} m): the response still rises there, so the resonance lies outside the range "
            f"followed and this is no peak; widen the range past that end")


def curve_peak(omega, amplitude) -> tuple[float, float]:
    """Frequency (rad/s) and amplitude (m) of the highest point of a curve, refined as :meth:`FrequencyResponse.peak`.

    Parameters
    ----------
    omega, amplitude : ndarray, shape (points,)
        The curve's frequencies (rad/s) and amplitudes (m), in the order of the curve.
    """
    omega, amp = np.asarray(omega, float), np.asarray(amplitude, float)
    i = int(np.argmax(amp))
    if i == 0 or i == amp.size - 1:
        return float(omega[i]), float(amp[i])
    w, a = omega[i - 1:i + 2], amp[i - 1:i + 2]
    ws = np.ptp(omega) or 1.0
    s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(w) / ws, np.diff(a) / amp[i]))])
    pa = np.polyfit(s, a, 2)
    if pa[0] >= 0:
        return float(w[1]), float(a[1])
    s_star = -pa[1] / (2 * pa[0])
    return float(np.polyval(np.polyfit(s, w, 2), s_star)), float(np.polyval(pa, s_star))


def static_solution(structure: Structure, force=None, *, tolerance: float = 1e-10, reduction: str = "auto",
                    modes: int | None = None) -> np.ndarray:
    """Static equilibrium ``q0`` (m), shape ``(ndof,)``, under the static force and the preloads.

    Parameters
    ----------
    structure : Structure
        Or a :class:`CyclicStructure` sector: its static state, the same in every sector.
    force : array_like or mapping, optional
        The static force (N): a vector of ``ndof`` values, or the static part
        (key ``0``) of a mapping ``{h: vector}`` as :func:`frequency_response` takes.
    tolerance : float
        Relative residual of Newton's method.
    reduction, modes
        As in :func:`frequency_response` (the static problem is solved on the
        retained DOFs, then every DOF is recovered).
    """
    tolerance = _checks.in_range("tolerance", tolerance, 0.0, 1.0, lo_open=True, hi_open=True)
    if not isinstance(structure, Structure):
        raise TypeError(f"structure must be a microslip Structure, got {type(structure).__name__}")
    if force is None:
        static_force = {}
    elif isinstance(force, Mapping):  # every harmonic checked (keys, vectors), the static one used
        excitation(structure, force, max([0] + [h for h in force if isinstance(h, (int, np.integer))]))
        static_force = _static_force(force)
    else:
        f = structure.force_vector(force, "force")
        if np.iscomplexobj(f):
            raise TypeError(f"force (a static force) must be real, got {_checks._show(force)}")
        static_force = {0: f}
    # a cyclic sector's static state is its zero-diameter one (every sector alike), whatever the excitation
    diameter = 0 if isinstance(structure, CyclicStructure) else None
    static, _, _ = _equations(structure, static_force, 0, None, MAX_PERIODS, reduction, modes, engine_order=diameter)
    x = _static_state(static, tolerance=tolerance)[0]
    return static._full(x, 1.0)[0]


def _equations(structure, force, harmonics, samples, max_periods, reduction, modes, engine_order=None):
    """``(static, dynamic, (reduction, modes))``: the static problem and the harmonic balance equations.

    Both share one condensation of the linear structure when it is reduced.
    """
    if not isinstance(structure, Structure):
        raise TypeError(f"structure must be a microslip Structure, got {type(structure).__name__}")
    H = check_harmonics(harmonics, minimum=0)
    engine_order = check_engine_order(structure, engine_order)
    _check_determined(structure)
    static_force = _static_force(force) if force is not None else {}
    eq = build_equations(structure, force, static_force, H, engine_order=engine_order, samples=samples,
                         max_periods=max_periods, reduction=reduction, modes=modes)
    return eq.static, eq.dynamic, (eq.reduction, eq.modes)


#: DOFs up to which the structure is checked for directions held by friction alone (a dense eigensolution)
DETERMINED_CHECK = 2000


#: sparse structures above this many DOFs are checked with a sparse factorisation first; the dense
#: eigensolution runs only when that finds a direction with (nearly) no stiffness, to name it
SPARSE_CHECK = 200


def _surely_determined(structure: Structure) -> bool:
    """True when a sparse shift-invert eigensolution puts the smallest eigenvalue of ``K`` plus the contacts'
    normal springs above ``1e-11`` of a bound on the largest (the dense check's threshold is ``1e-12``)."""
    if not sp.issparse(structure.K) or structure.ndof <= SPARSE_CHECK:
        return False
    _, Bn, _ = structure.contact_directions()
    kn = np.array([contact.model.kn.sum() for contact in structure.contacts])
    Bs = sp.csr_matrix(Bn)
    K = sp.csr_matrix(structure.K)
    K = (0.5 * (K + K.T) + Bs @ sp.diags(kn) @ Bs.T).tocsc()
    scale = float(abs(K).sum(axis=1).max())  # at least the largest eigenvalue
    if not scale > 0:
        return False
    try:
        lam = eigsh_repeatable(K, k=1, sigma=-1e-10 * scale, which="LM", return_eigenvectors=False)
    except (spla.ArpackError, RuntimeError):  # no convergence or an exactly singular shifted matrix
        return False
    return bool(lam[0] > 1e-11 * scale)


def _check_determined(structure: Structure) -> None:
    """Refuse a structure with a direction that nothing but friction holds: its mean position is undetermined.

    Such a direction has no stiffness in ``K`` and none from the contacts' normal
    springs; a friction contact holds it wherever it stops sliding, so the
    static (mean) term of the response has no unique value and Newton's method
    wanders along it.
    """
    if structure.ndof > DETERMINED_CHECK or isinstance(structure, CyclicStructure):
        return
    if _surely_determined(structure):
        return
    K = structure.K.toarray() if sp.issparse(structure.K) else np.array(structure.K, dtype=float)
    Bt, Bn, _ = structure.contact_directions()
    kn = np.array([contact.model.kn.sum() for contact in structure.contacts])
    K = K + (Bn * kn) @ Bn.T  # each contact's normal springs along its normal
    K = 0.5 * (K + K.T)
    lam, vec = np.linalg.eigh(K)
    scale = max(float(np.max(np.abs(lam))), 1e-300)
    free = vec[:, lam <= 1e-12 * scale]
    if free.shape[1] == 0:
        return
    v = free[:, 0]
    dofs = np.flatnonzero(np.abs(v) > 1e-6 * np.abs(v).max())
    held = "only by the friction of a contact" if np.any(np.abs(Bt.T @ free) > 1e-9) else "by nothing"
    raise ValueError(f"structure: the motion of DOF(s) {dofs[:8].tolist()} has no stiffness from K or from the "
                     f"contacts' normal springs, so it is held {held}: its mean position is undetermined (friction "
                     f"holds it wherever it stops sliding). Ground it with a spring (even one much softer than the "
                     f"contact) or fix the DOF")


def _static_state(hb, *, tolerance: float = 1e-10):
    """``(x0, N0, T0, closed, T0_2)``: the static unknowns of ``hb`` (H = 0), each contact's static forces (N),
    closed elements, the second tangential force (N, zero for a contact along one direction)."""
    structure = hb.structure
    # start from the structure with every contact element closed and stuck
    rhs = hb.f.copy()
    Bt, Bn = hb.static_directions()
    for i, c in enumerate(structure.contacts):
        m = c.model
        rhs += (m.kn @ m.gaps - m.kn.sum() * c.approach) * Bn[:, i]
        # stuck where the sliders were reset (a prestress's), not at t = 0
        rhs += m.kt.sum() * (c.reference * Bt[:, i] + c.reference2 * hb.Bt2[:, i])
    # the residual's scale: the loads, or the contacts' interference forces when nothing else loads it
    r_scale = max(float(np.max(np.abs(rhs))), float(np.max(np.abs(hb.f))), 1e-30)
    K = hb.stuck_stiffness()
    if sp.issparse(K):
        x = spla.lsqr(K.tocsc(), rhs, atol=1e-14, btol=1e-14)[0]
    else:
        x = np.linalg.lstsq(K, rhs, rcond=None)[0]
    x_scale = max(float(np.max(np.abs(x))), 1e-12)
    x, _ = newton(hb, x, 1.0, r_scale=r_scale, x_scale=x_scale, tolerance=tolerance)
    _, n = hb._local(x)
    hb._aft(x)
    closed = np.array([int(np.count_nonzero(n[i, 0] > c.model.gaps)) for i, c in enumerate(structure.contacts)],
                      dtype=np.int64)
    return x, hb.FN[:, 0].copy(), hb.FT[:, 0].copy(), closed, hb.FT2[:, 0].copy()


def frequency_response(structure: Structure, force, omega, *, harmonics: int = 5, samples: int | None = None,
                       control: StepControl | None = None, progress: bool = False,
                       max_periods: int = MAX_PERIODS, reduction: str = "auto",
                       modes: int | None = None, engine_order: int | None = None,
                       stability: bool = True, prestress=None) -> FrequencyResponse:
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
    reduction : {"auto", "exact", "modal", "none"}, default "auto"
        Solve the harmonic balance on the DOFs the contacts, the excitation
        and the preloads use, the rest of the linear structure condensed
        exactly per harmonic (``"exact"``: identical to the full solve to
        solver tolerance) or from normal modes plus the residual flexibility
        of the omitted ones (``"modal"``); ``"none"``: every DOF is an
        unknown. ``"auto"`` chooses by size (``"none"`` for small dense
        problems, unless they have 20 DOFs or more of which the equations
        keep at most a quarter; ``"exact"`` up to 5000 DOFs, ``"modal"``
        above; ``"none"`` too when the equations would keep more than half
        of the DOFs, an interface-dominated structure, solved with its
        Jacobian in parts, see :mod:`~microslip.frequency.equations.interface`)
        and the result says which (:attr:`FrequencyResponse.reduction`). A cyclic
        sector is condensed in each harmonic's nodal diameter, exactly or from
        that diameter's modes (``"auto"``: exact up to 5000 independent DOFs).
    modes : int, optional
        Normal modes of a modal reduction (default 60; per nodal diameter for
        a cyclic sector); implies ``"modal"`` with ``reduction="auto"``.
    stability : bool, default True
        Mark each point stable or unstable (Hill's method on the harmonic
        balance Jacobian: the whole structure's with ``"exact"``, or a 60-mode
        modal model of it above ``stability.WHOLE_LIMIT`` (4000) unknowns, the
        modal model's with ``"modal"``; :mod:`~microslip.frequency.analyses.stability`) and
        locate the folds and other bifurcations between points, while the Hill
        problem has at most ``stability.HILL_LIMIT`` (20000) unknowns (else, and
        for a cyclic sector, :attr:`FrequencyResponse.stable` is None).
    prestress : Prestress, optional
        Start from the static state of :func:`~microslip.frequency.prestress`
        on this structure (the static loads and friction state there, the
        sliders reset at it with the friction released): its
        :attr:`~microslip.frequency.Prestress.prestressed` structure is solved
        (and is the result's ``structure``); ``force`` then holds harmonics
        ``>= 1`` only.
    engine_order : int, optional
        For a :class:`~microslip.frequency.CyclicStructure` (required there):
        the engine order ``EO`` of the travelling-wave excitation; ``force``
        then acts on every sector, sector ``s + 1`` a fraction ``EO / N`` of a
        period after sector ``s``, and the result is this sector's response.

    Returns
    -------
    FrequencyResponse
        With ``complete`` False when the continuation stopped at
        ``control.max_points`` before the end of the range.

    Raises
    ------
    ConvergenceError
        When Newton's method fails at the start or the continuation stalls.
    CurveInterrupted
        On Ctrl-C along the curve (a ``KeyboardInterrupt``): its ``partial``
        is the curve up to the last point reached (``complete`` False).

    Warns
    -----
    IncompleteCurveWarning
        When the curve stops at ``control.max_points`` points (the message
        names the limit and the frequency reached), or where it runs onto a
        line of solutions at one frequency that does not end (only a body's
        mean position changes along it: a damper held by no closed contact;
        see :func:`~microslip.frequency.numerics.continuation.continuation`).
    """
    start = time.perf_counter()
    lo, hi = _omega_range(omega)
    if control is not None and not isinstance(control, StepControl):
        raise TypeError(f"control must be a StepControl, got {type(control).__name__}")
    progress = _checks.flag("progress", progress)
    stability = _checks.flag("stability", stability)
    if not isinstance(structure, Structure):
        raise TypeError(f"structure must be a microslip Structure, got {type(structure).__name__}")
    structure = prestressed_structure(structure, prestress, force)
    with small_dense(structure, check_harmonics(harmonics, minimum=0)):  # small systems solved many times
        hb, x, x_scale, r_scale, static = _first_point(structure, force, harmonics, samples, max_periods, lo, hi,
                                                       reduction, modes, engine_order)
        report = Progress(10, enabled=progress)
        describe = lambda w, count: f"omega = {w:.6g} rad/s ({w / (2 * np.pi):.6g} Hz), {count} points"  # noqa: E731
        lines = []
        xs, omegas, iters, complete, stopped = follow(hb, x, lo, hi, x_scale=x_scale, r_scale=r_scale,
                                                      control=control, report=report, describe=describe, lines=lines)
        result = _collect(hb, xs, omegas, iters, static, complete)
        if stopped:
            raise CurveInterrupted(f"interrupted at omega = {omegas[-1]:.6g} rad/s after {omegas.size} points, "
                                   f"before the end of the range ({hi:.6g} rad/s)",
                                   replace(result, elapsed=time.perf_counter() - start)) from None
        if stability:
            try:
                result = _with_stability(result, hb, xs, omegas)
            except KeyboardInterrupt:
                raise CurveInterrupted("interrupted while assessing the stability of the curve's points (the curve "
                                       "itself is complete; its stability is not known)",
                                       replace(result, elapsed=time.perf_counter() - start)) from None
    report.done(f"frequency response: {omegas.size} points")
    if lines:
        warnings.warn(f"the curve ran onto a line of solutions at omega = {lines[0]:.6g} rad/s that does not end: "
                      f"along it only the mean (harmonic 0) position of some body changes -- typically a damper whose "
                      f"contacts all slide or stay open over the period, so that nothing holds its mean position; "
                      f"the curve ends there, before the end of the range ({hi:.6g} rad/s)", IncompleteCurveWarning,
                      stacklevel=2)
    elif not complete:
        warnings.warn(incomplete_message(result, hi, control or StepControl()), IncompleteCurveWarning,
                      stacklevel=2)
    return replace(result, elapsed=time.perf_counter() - start)


#: seconds of work after which progress says where a continuation has got to, when no tenth of its range was
#: reached meanwhile
PROGRESS_EVERY = 15.0


class _Accepted:
    """A continuation's problem that keeps each point the continuation accepts.

    The continuation announces an accepted point to its callback right after the
    corrector evaluated the problem there (or Newton's method, at the range's
    edge); the point is kept when the parameter announced is the one of that
    last evaluation. Every evaluation also calls ``heartbeat`` (progress in the
    middle of slow steps).
    """

    def __init__(self, problem, callback=None, heartbeat=None):
        self._problem = problem
        self._callback = callback
        self._heartbeat = heartbeat
        self._last = None
        self.xs: list = []
        self.params: list = []

    def __getattr__(self, name):
        return getattr(self._problem, name)

    def _evaluate(self, x, param, *, jacobian: bool = True):
        self._last = (x, param)
        if self._heartbeat is not None:
            self._heartbeat()
        return self._problem._evaluate(x, param, jacobian=jacobian)

    def _evaluate_operator(self, x, param):
        self._last = (x, param)
        if self._heartbeat is not None:
            self._heartbeat()
        return self._problem._evaluate_operator(x, param)

    def accepted(self, param, count) -> None:
        if self._last is not None and self._last[1] == param:
            self.xs.append(np.array(self._last[0], dtype=float))
            self.params.append(float(param))
        if self._callback is not None:
            self._callback(param, count)


def follow(problem, x0, start: float, end: float, *, x_scale: float, r_scale: float, control=None,
           report: Progress | None = None, describe=None, branch_points: list | None = None,
           lines: list | None = None, folds: list | None = None):
    """:func:`~microslip.frequency.numerics.continuation.continuation`, keeping what it has when interrupted.

    ``(xs, params, iterations, complete, interrupted)``: on Ctrl-C the points
    accepted so far (iterations 0, ``complete`` False) and ``interrupted`` True.
    ``report`` announces each tenth of the range reached and, after
    :data:`PROGRESS_EVERY` seconds without one, where the curve has got to, in
    the words of ``describe(param, points)``. Trial points at which the problem
    is not finite (a corrector diverging, refused and halved by the
    continuation) raise no NumPy floating-point warnings.
    """
    where = [start, 1]

    def tick(param, count):
        where[:] = [param, count]
        step(param, count)

    step = tenths(report, start, end, describe) if report is not None else (lambda param, count: None)
    heartbeat = None
    if report is not None and report.enabled:
        def heartbeat():
            report.note(f"{describe(*where)} so far", every=PROGRESS_EVERY)
    followed = _Accepted(problem, tick, heartbeat)
    try:
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            xs, params, iters, complete = continuation(followed, x0, start, end, x_scale=x_scale, r_scale=r_scale,
                                                       control=control, callback=followed.accepted,
                                                       branch_points=branch_points, lines=lines, folds=folds)
    except KeyboardInterrupt:
        xs = np.array([np.asarray(x0, dtype=float)] + followed.xs)
        params = np.array([start] + followed.params)
        return xs, params, np.zeros(params.size, dtype=int), False, True
    return xs, params, iters, complete, False


def tenths(report: Progress, lo: float, hi: float, describe):
    """A continuation callback that announces on ``report`` each tenth of the parameter's range ``lo..hi``
    reached, in the words of ``describe(value, points)``."""
    reached = [0]

    def tick(value, count):
        done = int(10 * (value - lo) / (hi - lo))
        while reached[0] < min(done, 10):
            reached[0] += 1
            report.step(describe(value, count))

    return tick


def incomplete_message(result: FrequencyResponse, omega_end: float, control: StepControl) -> str:
    """Why a curve is incomplete: the point limit and the frequency reached."""
    return (f"the continuation stopped at max_points = {control.max_points} points at omega = "
            f"{result.omega[-1]:.6g} rad/s, before the end of the range ({omega_end:.6g} rad/s); "
            f"raise StepControl.max_points (or ds_max) to follow the whole curve")


def _first_point(structure, force, harmonics, samples, max_periods, lo, hi, reduction="auto", modes=None,
                 engine_order=None):
    """The equations, the solution at ``lo`` (from the static state) and the scales of x and R."""
    H = check_harmonics(harmonics)
    static_hb, hb, _ = _equations(structure, force, H, samples, max_periods, reduction, modes, engine_order)
    if not np.any(hb.f_ext[1:]):
        raise ValueError("force must have a non-zero dynamic part (harmonic >= 1)")
    r_scale = float(np.max(np.abs(hb.f)))
    x = np.zeros(hb.n)
    x[:hb.ndof], *static = _static_state(static_hb)
    static.append(x[:hb.ndof].copy())  # the static displacement, for the result
    x_scale = _response_scale(hb, x, lo, hi, grid=1 if lo == hi else 24)
    x, _ = newton(hb, x, lo, r_scale=r_scale, x_scale=x_scale)
    return hb, x, max(x_scale, float(np.max(np.abs(x[hb.ndof:])))), r_scale, static


def frequency_point(structure: Structure, force, omega: float, *, harmonics: int = 5, samples: int | None = None,
                    max_periods: int = MAX_PERIODS, reduction: str = "auto",
                    modes: int | None = None, engine_order: int | None = None,
                    stability: bool = True, prestress=None) -> FrequencyResponse:
    """The harmonic balance solution at one frequency, reached from the static state by Newton's method.

    Where the response has several solutions at ``omega`` (past a fold) this is
    the one Newton's method finds from the response of the stuck structure; use
    :func:`frequency_response` to follow a branch.

    Parameters
    ----------
    structure, force, harmonics, samples, max_periods, reduction, modes, engine_order, stability, prestress
        As in :func:`frequency_response`.
    omega : float
        Excitation frequency (rad/s).

    Returns
    -------
    FrequencyResponse
        With one point.
    """
    start = time.perf_counter()
    omega = HarmonicBalance._omega(omega)
    stability = _checks.flag("stability", stability)
    if not isinstance(structure, Structure):
        raise TypeError(f"structure must be a microslip Structure, got {type(structure).__name__}")
    structure = prestressed_structure(structure, prestress, force)
    hb, x, _, _, static = _first_point(structure, force, harmonics, samples, max_periods, omega, omega, reduction,
                                       modes, engine_order)
    result = _collect(hb, x[None, :], np.array([omega]), np.array([0]), static, True)
    if stability:
        result = _with_stability(result, hb, x[None, :], np.array([omega]))
    return replace(result, elapsed=time.perf_counter() - start)


def _with_stability(result: FrequencyResponse, hb, xs, omegas) -> FrequencyResponse:
    """``result`` with the stability of its points and the bifurcations between them (not for a cyclic sector)."""
    if isinstance(result.structure, CyclicStructure):
        return result
    stable, leading, found = assess(hb, xs, omegas)
    return replace(result, stable=stable, leading_exponent=leading, bifurcations=found)


def _response_scale(hb: HarmonicBalance, x_static, lo, hi, grid: int = 24) -> float:
    """Largest dynamic response of the structure with its contacts stuck, over the range (m)."""
    if hasattr(hb, "response_scale"):  # equations that hold their Jacobian in parts compute it harmonic by harmonic
        return hb.response_scale(x_static, np.linspace(lo, hi, grid))
    # x_static has no harmonics, so the residual R does not depend on omega: evaluated once
    R, Jx, _ = hb._evaluate(x_static, lo)
    Jc = Jx - hb.dynamic_stiffness(lo)
    best = 0.0
    for w in np.linspace(lo, hi, grid):
        dx = hb.solve(hb.dynamic_stiffness(w) + Jc, -R)
        if np.all(np.isfinite(dx)):
            best = max(best, float(np.max(np.abs(dx[hb.ndof:]))))
    return best if best > 0 else max(float(np.max(np.abs(x_static))), 1e-12)


#: the sampling error of a contact's energy (harmonic estimate against the friction work) that is
#: reported, as a fraction of the excitation's work per cycle
RESOLUTION = 1e-3


def _check_resolution(q: dict, samples: int, contacts, omegas) -> None:
    """Warn when a contact opens and closes during the cycle faster than the AFT's samples resolve it.

    The energy it dissipates then differs, from the force harmonics and from the
    friction work of the same samples, by more than :data:`RESOLUTION` of the
    excitation's work; the difference falls like ``1/samples^2``. The warning
    names the worst contact and the frequency where it is worst, and points at
    the caller of :func:`frequency_response` or :func:`frequency_point`.
    """
    if not q["opens"].any():
        return
    scale = np.maximum(np.abs(q["excitation"]), 1e-300)[:, None]
    error = np.where(q["opens"], np.abs(q["contacts_harmonic"] - q["contacts"]) / scale, 0.0)
    k, c = np.unravel_index(int(np.argmax(error)), error.shape)
    worst = float(error[k, c])
    if worst > RESOLUTION:
        need = samples * int(2 ** np.ceil(np.log2(np.sqrt(worst / RESOLUTION))))
        warnings.warn(f"contact {contacts[c].name!r} opens and closes during the cycle faster than {samples} samples "
                      f"per period resolve (worst at omega = {float(omegas[k]):.6g} rad/s): its energy per cycle is "
                      f"uncertain by {worst:.2g} of the excitation's work; samples={need} resolves it to "
                      f"{RESOLUTION:g} (the error falls like 1/samples^2)", UnderResolvedWarning, stacklevel=4)


def _collect(hb: HarmonicBalance, xs, omegas, iters, static, complete: bool) -> FrequencyResponse:
    """The result object from the solutions ``xs`` and the static state ``(N0, T0, closed, T0_2)``."""
    q = hb.curve_quantities(xs, omegas)
    _check_resolution(q, hb.samples, hb.structure.contacts, omegas)
    reduced = isinstance(hb, ReducedHarmonicBalance)
    extra = {"contact_harmonic_work": q["contacts_harmonic"], "contact_t2": q["t2"], "contact_T2": q["T2"],
             "static_tangential_force2": static[3], "static_coefficients": static[4]}
    if reduced:
        linear = hb.linear
        extra.update(dofs=hb.retained, reduction="modal" if hasattr(linear, "modes") else "exact",
                     engine_order=getattr(hb, "engine_order", None),
                     modes=getattr(linear, "modes", None),
                     recovery=lambda k: hb._full(xs[k], float(omegas[k])))
        if extra["reduction"] == "modal":
            peak = int(np.argmax(np.abs(xs[:, hb.ndof:]).max(axis=1)))
            estimate = getattr(linear, "error", None)  # a cyclic sector's, in its diameters
            extra["reduction_error"] = (estimate(float(omegas[peak])) if estimate
                                        else modal_error(linear, float(omegas[peak])))
    return FrequencyResponse(hb.structure, hb.H, hb.samples, omegas, xs.reshape(omegas.size, hb.nb, hb.ndof),
                             q["t"], q["n"], q["T"], q["N"], q["excitation"], q["viscous"], q["contacts"], iters,
                             *static[:3], complete=complete, **extra)
