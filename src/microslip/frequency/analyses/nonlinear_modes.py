"""Damped nonlinear modes of structures with microslip contacts: :func:`nonlinear_modes`, :class:`NonlinearModes`.

The extended periodic motion concept (:mod:`~microslip.frequency.equations.epmc`): the
mode's natural frequency and damping ratio as functions of its amplitude,
followed by pseudo-arclength continuation in the logarithm of the modal
amplitude from the linear mode (contacts stuck) to gross slip. The result
carries the periodic motion at every amplitude, as a
:class:`~microslip.frequency.FrequencyResponse` does along a frequency sweep
(``omega`` is then the mode's natural frequency), and synthesises forced
responses near the mode (:meth:`NonlinearModes.forced_response`).
"""

from __future__ import annotations

import time
import warnings
from contextlib import nullcontext
from dataclasses import dataclass, field, replace

import numpy as np

from ...common import _checks
from ...common._progress import Progress
from ..aft import MAX_PERIODS, check_harmonics
from ..numerics.blas import small_dense, solver_threads
from ..numerics.continuation import BranchPointWarning, StepControl, newton
from ..structures.cyclic import CyclicStructure
from ..equations.build import build_equations
from ..equations.epmc import DENSE_EIGEN, SPARSE_EIGEN, EpmcEquations, stuck_mode
from ..equations.hbm import HarmonicBalance
from ..equations.reduced import ReducedHarmonicBalance
from ..reduction.choice import interface_dominated, modal_error, retained_dofs
from .response import (CurveInterrupted, FrequencyResponse, IncompleteCurveWarning, _check_determined,
                       _check_resolution, _static_state, follow)
from ..structures.structure import Structure
from .prestressed import prestressed_structure


@dataclass(frozen=True, eq=False, repr=False)
class NonlinearModes(FrequencyResponse):
    """A damped nonlinear mode along its amplitude (from :func:`nonlinear_modes`).

    Every attribute and method of :class:`~microslip.frequency.FrequencyResponse`
    applies to the periodic motion at each of the ``points`` amplitudes
    (:attr:`omega` is the mode's natural frequency there; the excitation's work is
    zero); these are added:

    Attributes
    ----------
    mode : int
        The linear mode the nonlinear one starts from (1: the lowest).
    modal_amplitude : ndarray, shape (points,)
        ``a = phi^T M z_1`` (kg^1/2 m): the first harmonic of the coordinate of the
        linear mode ``phi`` (contacts stuck, mass-normalised) -- at small
        amplitude ``q = a phi cos(omega time)``. :meth:`amplitude` gives any DOF's.
    xi : ndarray, shape (points,)
        The mass-proportional damping (1/s) that makes up for the dissipation:
        ``-xi M q'`` was added to the unforced structure.
    damping_ratio : ndarray, shape (points,)
        ``xi / (2 omega)``: the mode's damping ratio.
    viscous_damping_ratio, contact_damping_ratio : ndarray, shape (points,)
        Its shares dissipated by ``C`` and by the contacts (energy per cycle
        over ``2 pi omega^2 sum_h h^2 z_h^H M z_h``); they add up to
        :attr:`damping_ratio` (the energy balance of the harmonics kept).
    linear_frequency : float
        Natural frequency of the linear mode, contacts stuck (rad/s).
    linear_mode : ndarray, shape (ndof,)
        That mode, mass-normalised (kg^-1/2); for a cyclic sector, in the mode's
        nodal diameter, on the sector's DOFs (complex amplitudes, the right
        boundary from the left one).
    modal_mass, modal_damping : ndarray, shape (points,)
        ``z_1^H M z_1 / a^2`` (dimensionless, 1 for the linear mode) and
        ``z_1^H C z_1 / a^2`` (1/s) of the first harmonic: the single-mode
        model of :meth:`forced_response`.
    """

    mode: int = 1
    modal_amplitude: np.ndarray | None = field(default=None, repr=False)
    xi: np.ndarray | None = field(default=None, repr=False)
    damping_ratio: np.ndarray | None = field(default=None, repr=False)
    viscous_damping_ratio: np.ndarray | None = field(default=None, repr=False)
    contact_damping_ratio: np.ndarray | None = field(default=None, repr=False)
    linear_frequency: float = float("nan")
    linear_mode: np.ndarray | None = field(default=None, repr=False)
    modal_mass: np.ndarray | None = field(default=None, repr=False)
    modal_damping: np.ndarray | None = field(default=None, repr=False)

    def __repr__(self) -> str:
        return (f"NonlinearModes(mode={self.mode}, points={self.points}, modal amplitude "
                f"{self.modal_amplitude[0]:.3g} to {self.modal_amplitude[-1]:.3g} kg^1/2 m, frequency "
                f"{self.omega[0]:.6g} to {self.omega[-1]:.6g} rad/s, damping ratio {self.damping_ratio.min():.3g} to "
                f"{self.damping_ratio.max():.3g}, harmonics={self.harmonics}, reduction={self.reduction!r})")

    def frequency(self, unit: str = "rad/s") -> np.ndarray:
        """The mode's natural frequency at every point, ``(points,)``: rad/s, or Hz with ``unit="Hz"``."""
        unit = _checks.one_of("unit", unit, ("rad/s", "Hz"))
        return self.omega.copy() if unit == "rad/s" else self.omega / (2 * np.pi)

    def amplitude(self, dof=None, harmonic: int | None = None) -> np.ndarray:
        """The modal amplitude (``dof`` None, kg^1/2 m), or a DOF's amplitude as
        :meth:`FrequencyResponse.amplitude <microslip.frequency.FrequencyResponse.amplitude>` (m), ``(points,)``."""
        if dof is None:
            if harmonic is not None:
                raise ValueError("harmonic is for a DOF's amplitude; the modal amplitude is the first harmonic's")
            return self.modal_amplitude.copy()
        return super().amplitude(dof, harmonic)

    def shape(self, point: int) -> np.ndarray:
        """Every DOF's Fourier coefficients ``(2H+1, ndof)`` (m) at a point: the periodic motion, recovered."""
        point = _checks.positive_int("point", point, minimum=0)
        if point >= self.points:
            raise ValueError(f"point must be below the number of points {self.points}, got {point}")
        if self.recovery is None:
            return self.coefficients[point].copy()
        return self.recovery(point)

    def plot(self, dof=None, harmonic: int | None = 1, axes=None, *, frequency_unit: str = "Hz", unit: str = "µm",
             label: str | None = None, **kwargs):
        """Natural frequency and damping ratio against amplitude (log axis), on two axes.

        Parameters
        ----------
        dof : optional
            Amplitude on the horizontal axis: None, the modal amplitude
            (kg^1/2 m); else a DOF as in :meth:`amplitude`, in ``unit``.
        harmonic : int, optional
            The DOF's harmonic (None: max ``|q - q0|`` over a period).
        axes : pair of matplotlib Axes, optional
            Where to draw (a new figure if omitted).
        frequency_unit : {"Hz", "rad/s"}
        unit : str
            Length unit of a DOF's amplitude (:mod:`microslip.common.units`).
        label : str, optional
            Legend label of the curves.
        **kwargs
            Passed to ``Axes.plot``.

        Returns
        -------
        tuple of two matplotlib Axes
        """
        import matplotlib.pyplot as plt

        from ...common.units import plot_factor

        frequency_unit = _checks.one_of("frequency_unit", frequency_unit, ("Hz", "rad/s"))
        if axes is None:
            _, axes = plt.subplots(2, 1, figsize=(6.5, 6), sharex=True)
        top, bottom = axes
        if dof is None:
            x, xlabel = self.modal_amplitude, "modal amplitude a (kg^1/2 m)"
        else:
            x = self.amplitude(dof, harmonic) * plot_factor(unit)
            what = "max |q - q0|" if harmonic is None else f"harmonic {harmonic} amplitude"
            xlabel = f"{self.labels.get('dof', 'DOF')}: {what} ({unit})"
        top.plot(x, self.frequency(frequency_unit), label=label, **kwargs)
        top.set_ylabel(f"natural frequency ({frequency_unit})")
        line, = bottom.plot(x, 100 * self.damping_ratio, label="total" if label is None else label, **kwargs)
        if np.any(self.viscous_damping_ratio):
            bottom.plot(x, 100 * self.contact_damping_ratio, "--", color=line.get_color(),
                        label="contacts" if label is None else f"{label}: contacts")
        bottom.set_ylabel("damping ratio (%)")
        bottom.set_xlabel(xlabel)
        for ax in axes:
            ax.set_xscale("log")
            ax.grid(True, which="both", alpha=0.3)
        if label is not None or np.any(self.viscous_damping_ratio):
            bottom.legend()
        return top, bottom

    def columns(self, dofs=None, names=None) -> dict:
        """The mode as named columns with units (for CSV): amplitude, frequency, damping, then as
        :meth:`FrequencyResponse.columns <microslip.frequency.FrequencyResponse.columns>`."""
        cols = {"modal amplitude [kg^0.5 m]": self.modal_amplitude, "omega [rad/s]": self.omega,
                "f [Hz]": self.omega / (2 * np.pi), "damping ratio [-]": self.damping_ratio,
                "viscous damping ratio [-]": self.viscous_damping_ratio,
                "contact damping ratio [-]": self.contact_damping_ratio, "xi [1/s]": self.xi}
        rest = super().columns(dofs, names)
        for key in ("omega [rad/s]", "f [Hz]", "excitation work [J]"):
            rest.pop(key)
        cols.update(rest)
        return cols

    def forced_response(self, force, omega=None, *, points: int = 400):
        """The forced response near this mode from the mode alone (single nonlinear mode synthesis).

        See :func:`~microslip.frequency.analyses.synthesis.forced_response`: ``force`` (N) the excitation's
        amplitudes on the DOFs, ``omega`` (rad/s) an optional range to keep, ``points`` about how many
        points; returns a :class:`~microslip.frequency.SynthesizedResponse`.
        """
        from .synthesis import forced_response

        return forced_response(self, force, omega, points=points)

    def synthesize(self, force, omega=None, *, points: int = 400):
        """Deprecated name of :meth:`forced_response` (the same method; warns)."""
        from ...common.errors import deprecated

        deprecated("NonlinearModes.synthesize", "NonlinearModes.forced_response")
        return self.forced_response(force, omega, points=points)


#: the smallest modal amplitude (kg^1/2 m) a mode is followed from: the mode is mass-normalised, so its energies are
#: ``a^2`` times its modal mass (1 at small amplitude) and its stiffness (``omega^2``) whatever the structure; below
#: ``sqrt(tiny / eps)`` (1.0e-146) they lose digits to underflow, below ``sqrt(tiny)`` (1.5e-154) they are zero and
#: the modal mass and damping ratios NaN
MIN_AMPLITUDE = float(np.sqrt(np.finfo(float).tiny / np.finfo(float).eps))


def _amplitude_range(amplitude) -> tuple[float, float]:
    lo, hi = _checks.positive_pair("amplitude", amplitude, "(start, end) of modal amplitudes in kg^1/2 m")
    if not lo < hi:
        raise ValueError(f"amplitude must rise from start to end, got start = {lo!r} >= end = {hi!r}")
    if lo < MIN_AMPLITUDE:
        raise ValueError(f"amplitude must start at {MIN_AMPLITUDE:.3g} kg^1/2 m or above, got start = {lo!r}: the "
                         f"mode is mass-normalised, so its energies are a^2 times its modal mass (1 for the linear "
                         f"mode), which underflows double precision below that (a rigid mass m moves by a / sqrt(m))")
    return lo, hi


def _check_mode(structure: Structure, mode) -> int:
    mode = _checks.positive_int("mode", mode)
    n = structure.independent.size if isinstance(structure, CyclicStructure) else structure.ndof
    limit = n if n <= (SPARSE_EIGEN if structure.sparse else DENSE_EIGEN) else n - 1  # a sparse eigensolver
    if mode > limit:                                                                  # finds fewer than all
        raise ValueError(f"mode must be at most {limit} (the structure has {n} DOFs"
                         f"{' besides its right boundary' if n < structure.ndof else ''}), got {mode}")
    return mode


def _check_diameter(structure: Structure, nodal_diameter):
    """``nodal_diameter`` checked: required for a :class:`CyclicStructure` (0 to N - 1), refused otherwise."""
    if not isinstance(structure, CyclicStructure):
        if nodal_diameter is not None:
            raise ValueError(f"nodal_diameter is only for a CyclicStructure; this structure is not cyclic, got "
                             f"nodal_diameter = {nodal_diameter!r}")
        return None
    if nodal_diameter is None:
        raise ValueError("nodal_diameter must be given for a CyclicStructure (the mode's number of nodal diameters, "
                         f"0 to {structure.sectors // 2})")
    nd = _checks.positive_int("nodal_diameter", nodal_diameter, minimum=0)
    if nd >= structure.sectors:
        raise ValueError(f"nodal_diameter must be below the number of sectors {structure.sectors}, got {nd}")
    return nd


#: what :func:`nonlinear_modes` does where the mode turns back in amplitude
FOLDS = ("stop", "follow")

#: points per decade of amplitude at least with the turn rule (``default_control(lo, hi, chord_error=None)``)
POINTS_PER_DECADE = 20

#: the default chord error of :func:`default_control`: the largest difference between the backbone and the
#: straight lines joining its points that the steps aim at, in frequency and ``xi`` over the stuck frequency (about
#: 1.5e-5 of the stuck frequency, 7.5e-6 in damping ratio) against the log amplitude over its range; chosen with
#: benchmarks/bench_step_control.py, where it gives a smaller interpolation error than the turn rule at 1/20 decade
#: on a blade and two lap joints, with fewer points in all (more on the blade, whose curve bends most)
CHORD_ERROR = 1.5e-5

#: the longest step (decades of modal amplitude) and largest turn (rad) of ``default_control`` with the chord rule:
#: the chord error sets the steps, these only bound them
LONGEST_STEP = 1.0
CHORD_MAX_ANGLE = 0.3


def default_control(lo: float, hi: float, chord_error: float | None = CHORD_ERROR) -> StepControl:
    """The step control of a mode from ``lo`` to ``hi`` (kg^1/2 m, ``0 < lo < hi``).

    With a ``chord_error`` (the default, :data:`CHORD_ERROR`; see :class:`~microslip.frequency.StepControl`):
    steps sized so that the frequency and ``xi`` stray about that far (over the stuck frequency) from the
    straight lines between two points against the log amplitude, of at most :data:`LONGEST_STEP` decades of
    amplitude and :data:`CHORD_MAX_ANGLE` of turn, the first 1/20 decade. ``chord_error=None``: the turn rule,
    steps of at most 1/20 decade of amplitude (:data:`POINTS_PER_DECADE`) and turns of at most
    ``StepControl.max_angle`` (0.1 rad).
    """
    decade = np.log(10.0) / np.log(hi / lo)  # a decade of amplitude in the scaled arclength (the range is 1)
    step = decade / POINTS_PER_DECADE
    if chord_error is None:
        return StepControl(ds_initial=step, ds_max=step)
    return StepControl(ds_initial=step, ds_max=LONGEST_STEP * decade, max_angle=CHORD_MAX_ANGLE,
                       chord_error=chord_error)


def nonlinear_modes(structure: Structure, mode: int = 1, amplitude=(1e-8, 1e-4), *, harmonics: int = 3,
                    samples: int | None = None, reduction: str = "auto", modes: int | None = None,
                    control: StepControl | None = None, progress: bool = False,
                    max_periods: int = MAX_PERIODS, nodal_diameter: int | None = None,
                    prestress=None, folds: str = "stop") -> NonlinearModes:
    """A damped nonlinear mode over a range of amplitudes (extended periodic motion concept).

    The unforced structure with the extra damping ``-xi M q'`` is solved for its
    periodic motion (harmonic balance with ``harmonics`` harmonics plus the static
    term, the contacts by alternating frequency--time with exact Jacobians), its
    frequency ``omega`` and ``xi`` unknowns, normalised by the modal amplitude
    ``a = phi^T M z_1`` of the linear mode ``phi`` (structure with its contacts
    stuck at the static state, mass-normalised) and the phase condition
    ``Im(phi^T M z_1) = 0``, and followed in ``ln a`` by pseudo-arclength
    continuation (:mod:`~microslip.frequency.equations.epmc`). Krack, "Nonlinear modal
    analysis of nonconservative systems: extension of the periodic motion
    concept", Computers & Structures 154 (2015).

    Parameters
    ----------
    structure : Structure
        Structure and contacts (SI units).
    mode : int, default 1
        Which linear mode of the stuck structure to start from (1: the lowest).
    amplitude : (float, float), default (1e-8, 1e-4)
        Start and end of the modal amplitude ``a`` (kg^1/2 m, ``start < end``,
        ``start >=`` :data:`MIN_AMPLITUDE` = 1.0e-146, below which the energies,
        ``a^2`` times the unit modal mass, underflow);
        a DOF where the mass-normalised mode has the value ``phi_i`` moves by
        ``a phi_i`` (m) at small amplitude, so for a structure of mass ``m``
        moving as a whole ``a = sqrt(m) x``.
    harmonics : int, default 3
        Harmonics kept, ``H >= 1``.
    samples : int, optional
        AFT time samples per period (default
        :func:`~microslip.frequency.aft.default_samples`).
    reduction : {"auto", "exact", "modal", "none"}, default "auto"
        As in :func:`~microslip.frequency.frequency_response`: the equations on
        the contact DOFs, the rest of the structure condensed exactly or from
        ``modes`` normal modes, each with the damping ``C - xi M``.
    modes : int, optional
        Normal modes of a modal reduction (default 60).
    control : StepControl, optional
        Continuation settings (arclength in scaled units; the whole amplitude
        range has length 1). Default (:func:`default_control`): steps sized so
        that the frequency and damping between two points stray from the
        straight line joining them by about :data:`CHORD_ERROR` of the stuck
        frequency (``StepControl.chord_error``): long where the backbone is
        straight, short where it bends; ``default_control(lo, hi,
        chord_error=None)``: steps of at most 1/20 of a decade of amplitude,
        shorter where the curve turns.
    progress : bool, default False
        Report progress on standard error.
    max_periods : int
        Periods allowed for each contact's state to become periodic.
    nodal_diameter : int, optional
        For a :class:`~microslip.frequency.CyclicStructure` (required there):
        the mode's nodal diameter ``k`` (0 to ``N - 1``); the sector's mode is a
        travelling wave, sector ``s + 1`` a fraction ``k / N`` of a period after
        sector ``s``, harmonic ``h`` in diameter ``h k mod N`` (as the response
        to engine order ``k``), condensed exactly in each diameter;
        ``mode`` counts the modes of that diameter. The result reports this
        sector (:attr:`NonlinearModes.engine_order` is ``k``).
    prestress : Prestress, optional
        Vibrate about the static state of :func:`~microslip.frequency.prestress`
        on this structure: its :attr:`~microslip.frequency.Prestress.prestressed`
        structure is solved (the result's ``structure``), and the linear mode
        the nonlinear one starts from is :meth:`Prestress.modes
        <microslip.frequency.Prestress.modes>`'s.
    folds : {"stop", "follow"}, default "stop"
        What the mode does where it turns back in amplitude (a fold: beyond it
        there is no longer one periodic motion per amplitude). ``"stop"``: it
        ends at its last point before the turn, with an
        :class:`~microslip.common.errors.IncompleteCurveWarning` that says
        where. ``"follow"``: the curve is followed on, through an internal
        resonance's loop or, on a damper whose contacts slide or open over
        most of the period, along the periodic motions that differ by the
        damper's mean position (such a curve may wander at nearly constant
        amplitude for thousands of points).

    Returns
    -------
    NonlinearModes

    Raises
    ------
    TypeError, ValueError
        A parameter of the wrong type or out of range (the message names it);
        a mode without stiffness.
    ConvergenceError
        When Newton's method fails at the first amplitude or the continuation stalls.
    CurveInterrupted
        On Ctrl-C along the mode (a ``KeyboardInterrupt``): its ``partial`` is
        the mode up to the last amplitude reached (``complete`` False).

    Warns
    -----
    IncompleteCurveWarning
        When the continuation stops at ``control.max_points`` before ``amplitude[1]``,
        where the mode turns back in amplitude (``folds="stop"``), or where the mode runs onto a line of periodic motions at one amplitude
        that does not end (only the mean position of a body changes along it:
        an under-platform damper whose contacts all slide or stay open over the
        period); the mode then ends where the line starts.
    BranchPointWarning
        When the mode passes a branch point (another branch of periodic motions
        crosses it; the curve goes on along its own).
    """
    start = time.perf_counter()
    if not isinstance(structure, Structure):
        raise TypeError(f"structure must be a microslip Structure, got {type(structure).__name__}")
    structure = prestressed_structure(structure, prestress)
    diameter = _check_diameter(structure, nodal_diameter)
    mode = _check_mode(structure, mode)
    lo, hi = _amplitude_range(amplitude)
    H = check_harmonics(harmonics)
    if control is not None and not isinstance(control, StepControl):
        raise TypeError(f"control must be a StepControl, got {type(control).__name__}")
    ctl = control or default_control(lo, hi)
    progress = _checks.flag("progress", progress)
    folds = _checks.one_of("folds", folds, FOLDS)
    preload = structure.preload_force()[None]
    every_dof = (not isinstance(structure, CyclicStructure) and reduction in ("auto", "none") and modes is None
                 and interface_dominated(structure, H, retained_dofs(structure, preload).size))
    # small dense systems solved many times, or an interface-dominated structure's small products: one BLAS thread
    with small_dense(structure, H), (solver_threads() if every_dof else nullcontext()):
        _check_determined(structure)
        static_hb, hb, reduction, modes = build_equations(structure, {}, {}, H, engine_order=diameter,
                                                          samples=samples, max_periods=max_periods,
                                                          reduction=reduction, modes=modes, damped=True)
        x0, *static = _static_state(static_hb)
        lam, phi, M, C = stuck_mode(structure, static_hb._full(x0, 1.0)[0], mode, diameter)
        phi_u = phi[hb.linear.retained] if hasattr(hb, "linear") else phi  # on the unknowns' DOFs
        rho = float(np.max(np.abs(hb.stuck_stiffness() @ phi_u)))
        # a = phi^H M z_1 = w . z_1 over the DOFs the matrices act on
        eq = EpmcEquations(hb, x0, np.conj(M @ phi), float(np.max(np.abs(phi))), float(np.sqrt(lam)), rho)

        s0, s1 = np.log(lo), np.log(hi)
        x = np.zeros(hb.n)
        x[:hb.ndof] = x0
        x[hb.ndof:2 * hb.ndof] = lo * phi_u.real  # z_1 = a_1 - i b_1 = lo phi
        x[2 * hb.ndof:3 * hb.ndof] = -lo * phi_u.imag
        y = eq.pack(x, np.sqrt(lam), float(np.real(np.conj(phi) @ (C @ phi))), s0)
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):  # a diverging iterate fails by name
            y, _ = newton(eq, y, s0, r_scale=1.0, x_scale=1.0, tolerance=ctl.tolerance)
        report = Progress(10, enabled=progress)
        branches, lines, turns = [], [], ([] if folds == "stop" else None)
        ys, ss, iters, complete, stopped = follow(
            eq, y, s0, s1, x_scale=1.0, r_scale=1.0, control=ctl, report=report, branch_points=branches, lines=lines,
            folds=turns,
            describe=lambda s, count: f"modal amplitude {np.exp(s):.3g} kg^1/2 m, {count} points")
        if diameter is not None:  # the mode on every DOF of the sector, the right boundary from the left one
            phi = np.asarray(structure.constraint(structure.phase(1, diameter)) @ phi)
        result = _collect(eq, ys, ss, iters, static, complete, mode, lam, phi, reduction, modes, diameter)
    if stopped:
        raise CurveInterrupted(f"interrupted at modal amplitude {result.modal_amplitude[-1]:.6g} kg^1/2 m after "
                               f"{result.points} points, before the end of the range ({hi:.6g} kg^1/2 m)",
                               replace(result, elapsed=time.perf_counter() - start)) from None
    report.done(f"nonlinear mode: {result.points} points")
    if lines:
        warnings.warn(f"the mode ran onto a line of periodic motions at modal amplitude {np.exp(lines[0]):.6g} "
                      f"kg^1/2 m ({result.omega[-1]:.6g} rad/s) that does not end: along it only the mean (harmonic 0) "
                      f"position of some body changes -- typically an under-platform damper whose contacts all slide "
                      f"or stay open over the period, so that nothing holds its mean position; the curve ends there, "
                      f"below the range's end ({hi:.6g}). A retention (UnderPlatformDamper(retention=...), N/m) "
                      f"holds the damper's mean position", IncompleteCurveWarning, stacklevel=2)
    elif turns:
        warnings.warn(f"the mode turns back in amplitude at modal amplitude {result.modal_amplitude[-1]:.6g} kg^1/2 m "
                      f"({result.omega[-1]:.6g} rad/s), below the range's end ({hi:.6g}): beyond that fold there is no "
                      f"longer one periodic motion per amplitude -- usually an internal resonance (a harmonic of the "
                      f"mode meets another mode), or a body held only by contacts that slide or open over most of the "
                      f"period (an under-platform damper), whose mean position then changes along the curve. The mode "
                      f"ends at the fold; folds='follow' follows the curve beyond it", IncompleteCurveWarning,
                      stacklevel=2)
    elif not complete:
        warnings.warn(f"the continuation stopped at max_points = {ctl.max_points} points at modal amplitude "
                      f"{result.modal_amplitude[-1]:.6g} kg^1/2 m, before the end of the range ({hi:.6g}); raise "
                      f"StepControl.max_points (or ds_max) to follow the whole mode", IncompleteCurveWarning,
                      stacklevel=2)
    elif ss[-1] < s1 - 1e-9:  # left the range at its start
        turn = int(np.argmax(result.modal_amplitude))
        warnings.warn(f"the mode turned back at modal amplitude {result.modal_amplitude[turn]:.6g} kg^1/2 m "
                      f"({result.omega[turn]:.6g} rad/s) and left the range at its start: a fold in amplitude, "
                      f"usually an internal resonance (a harmonic of the mode meets another mode); the curve ends "
                      f"there, below the range's end ({hi:.6g})", IncompleteCurveWarning, stacklevel=2)
    for s in branches:
        warnings.warn(f"the mode passes a branch point at modal amplitude {np.exp(s):.6g} kg^1/2 m: another branch "
                      f"of periodic motions meets it there (usually an internal resonance, a harmonic of the mode "
                      f"meeting another mode, or a symmetry of the structure); the curve goes on along the same "
                      f"branch", BranchPointWarning, stacklevel=2)
    return replace(result, elapsed=time.perf_counter() - start)


def _energies(structure: Structure, X: np.ndarray) -> tuple[float, float, float, float]:
    """``(sum h^2 z^H M z, sum h^2 z^H C z, z_1^H M z_1, z_1^H C z_1)`` of every DOF's coefficients ``X`` (2H+1, ndof)."""
    H = (X.shape[0] - 1) // 2
    Z = X[1::2] - 1j * X[2::2]  # (H, ndof)
    mass = np.real(np.einsum("hi,hi->h", Z.conj(), np.asarray((structure.M @ Z.T).T)))
    damp = np.real(np.einsum("hi,hi->h", Z.conj(), np.asarray((structure.C @ Z.T).T)))
    h2 = np.arange(1, H + 1) ** 2
    return float(h2 @ mass), float(h2 @ damp), float(mass[0]), float(damp[0])


def _collect(eq: EpmcEquations, ys, ss, iters, static, complete, mode, lam, phi, reduction, modes,
             diameter=None) -> NonlinearModes:
    """The result from the continuation's scaled points."""
    hb = eq.hb
    structure = hb.structure
    P = ss.size
    xs = np.empty((P, hb.n))
    omegas, xis = np.empty(P), np.empty(P)
    a = np.empty(P)
    for k in range(P):
        xs[k], omegas[k], xis[k] = eq.unpack(ys[k], ss[k])
        a[k] = eq.modal_amplitude(xs[k], omegas[k], xis[k]).real  # exp(s) to the tolerance of the normalisation
    q = HarmonicBalance.curve_quantities(hb, xs, omegas, viscous=False)
    energy = np.empty((P, 4))

    def recovery(k):
        hb.xi = xis[k]
        return hb._full(xs[k], float(omegas[k]))

    for k in range(P):
        energy[k] = _energies(structure, recovery(k))
    mass_sum, damp_sum = energy[:, 0], energy[:, 1]
    # what drives the mode: the work of -xi M q' per cycle, the scale of the contacts' sampling error
    _check_resolution(dict(q, excitation=np.pi * omegas * xis * mass_sum), hb.samples, structure.contacts, omegas)
    damping = xis / (2 * omegas)
    viscous = damp_sum / (2 * omegas * mass_sum)
    contact = q["contacts_harmonic"].sum(axis=-1) / (2 * np.pi * omegas ** 2 * mass_sum)
    reduced = isinstance(hb, ReducedHarmonicBalance)
    extra = {}
    if reduced:
        extra.update(dofs=hb.retained, recovery=recovery, modes=modes, engine_order=diameter,
                     reduction_error=modal_error(hb.linear, float(omegas[-1])) if reduction == "modal" else None)
    return NonlinearModes(structure, hb.H, hb.samples, omegas, xs.reshape(P, hb.nb, hb.ndof), q["t"], q["n"], q["T"],
                          q["N"], np.zeros(P), np.pi * omegas * damp_sum, q["contacts"], iters, *static[:3],
                          complete=complete, reduction=reduction, contact_harmonic_work=q["contacts_harmonic"],
                          contact_t2=q["t2"], contact_T2=q["T2"], static_tangential_force2=static[3],
                          mode=mode, modal_amplitude=a, xi=xis, damping_ratio=damping, viscous_damping_ratio=viscous,
                          contact_damping_ratio=contact, linear_frequency=float(np.sqrt(lam)), linear_mode=phi,
                          modal_mass=energy[:, 2] / a ** 2, modal_damping=energy[:, 3] / a ** 2, **extra)
