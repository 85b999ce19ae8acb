"""The problem a tuning to an accuracy target is measured on: family, exact reference, targets.

See :mod:`microslip.tuning.target` for the method.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ...common import _checks
from ...accuracy.compare import AccuracyReport, accuracy, reference_run, restriction_mask
from ...accuracy.paths import default_family
from ...reference.mdr import mdr
from ..paper import TuningPoints, model_from_points, tuning_points

SPACINGS = ("force", "displacement", "optimal")

#: MDR elements of the exact reference used by the optimisation (errors below 1e-4 of the metrics)
REFERENCE_ELEMENTS = 2000


@dataclass(frozen=True, eq=False)
class TargetTuning:
    """A model tuned for accuracy, with its measured worst errors.

    Attributes
    ----------
    model : MicroslipModel
        The tuned array (``J`` elements).
    points : TuningPoints
        Its tuning points on the backbone at ``N_hi`` (m, N).
    spacing : str
        ``'force'`` (even in force, the paper's), ``'displacement'`` (even in
        displacement) or ``'optimal'``.
    energy_error : float
        Worst ``|W/W_ref - 1|`` over the problem's family (fraction).
    force_difference : float
        Worst ``max|T - T_ref| / max|T_ref|`` over the family (fraction).
    meets : bool
        Both within the problem's targets.
    evaluations : int
        Models evaluated to find it.
    """

    model: object
    points: TuningPoints
    spacing: str
    energy_error: float
    force_difference: float
    meets: bool
    evaluations: int = 1

    @property
    def elements(self) -> int:
        """Number of elements ``J`` of the tuned array (int)."""
        return self.model.elements

    def plot(self, reference, ax=None):
        """The reference backbone at the tuning load, the model's, and the tuning points.

        Parameters
        ----------
        reference : Sphere or similar
            The reference it was tuned on.
        ax : matplotlib Axes, optional

        Returns
        -------
        matplotlib.axes.Axes
        """
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(6, 4))
        N = self.points.normal_load
        t = np.linspace(0.0, 1.2 * self.points.t[-1], 400)
        ax.plot(t * 1e6, reference.backbone(t, N), "k-", lw=2, label="reference backbone")
        ax.plot(t * 1e6, self.model.backbone(t, self.points.approach), "--", color="tab:red",
                label=f"tuned array, J = {self.elements}")
        ax.plot(self.points.t * 1e6, self.points.T, "s", mfc="none", color="tab:green",
                label=f"{self.spacing} points")
        ax.set_xlabel("tangential displacement t (µm)")
        ax.set_ylabel("tangential force T (N)")
        ax.set_title(f"N = {N:g} N: worst energy error {100 * self.energy_error:.3g} %, "
                     f"force {100 * self.force_difference:.3g} %", fontsize=9)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        return ax

    def __repr__(self) -> str:
        return (f"TargetTuning(J={self.elements}, spacing={self.spacing!r}, "
                f"energy_error={100 * self.energy_error:.3g} %, "
                f"force_difference={100 * self.force_difference:.3g} %, meets={self.meets})")


class TargetProblem:
    """The family, the exact reference and the targets a tuning is measured on.

    Parameters
    ----------
    reference : Sphere or similar
        The contact (``mu``, backbone, normal law; ``E_star``, ``G_star``,
        ``radius`` for its MDR reference).
    load_range : (float, float)
        ``(N_lo, N_hi)`` (N), ``0 < N_lo < N_hi``: the model is tuned at
        ``N_hi``; the family keeps the paths whose lowest load is at least
        ``N_lo``.
    energy_target, force_target : float, default 0.02
        Worst allowed ``|energy error|`` and force difference, fractions in
        ``(0, 1]`` (0.02 means 2 %; above 1 is refused); ``math.inf`` leaves
        that error out of the objective.
    min_amplitude : float, default 0.5
        Smallest tangential amplitude kept, as a multiple of the gross-slip
        displacement at the path's lowest load.
    steps_per_cycle : int, default 180
        Samples per cycle of the family (the errors change by < 1e-4 from 180
        to 1440, measured in the tests).
    reference_elements : int, default 2000
        Elements of the MDR reference.
    family_options : dict, optional
        Passed to :func:`~microslip.paths.default_family` (``ratios``,
        ``phases_deg``, ``amplitudes``, ``levels``).
    dense : bool, default False
        Sample the amplitudes (40, geometric from ``min_amplitude`` to 3) and
        the peak-load levels (10, from 0.1 to 1) densely instead of the
        default family's 9 amplitudes and 5 levels (:func:`dense_options`;
        ``family_options`` still override). The 2 % targets are met on
        the default family's samples; points optimised on those samples place
        element thresholds between them, so the worst error over the
        continuous ranges is larger (README, "Accuracy"): the dense sampling
        measures that.

    Notes
    -----
    The family is the default one, read as follows: loads never
    above the tuning load ``N_hi`` (beyond it the paper's array extrapolates
    linearly: 31.7 % energy error whatever J, ``scripts/target_readings.py``),
    and ``N >= N_lo`` read as the path's lowest load ``N_m - N_a >= N_lo``.
    """

    def __init__(self, reference, load_range, *, energy_target=0.02, force_target=0.02, min_amplitude=0.5,
                 steps_per_cycle: int = 180, reference_elements: int = REFERENCE_ELEMENTS, family_options=None,
                 dense: bool = False):
        lo, hi = _load_range(load_range)
        reference_elements = _checks.size("reference_elements", reference_elements)
        family_options = _checks.mapping("family_options", {} if family_options is None else family_options)
        self.reference = reference
        self.load_range = (lo, hi)
        self.energy_target = target_fraction("energy_target", energy_target)
        self.force_target = target_fraction("force_target", force_target)
        self.min_amplitude = _checks.positive_scalar("min_amplitude", min_amplitude, allow_zero=True)
        if not isinstance(dense, (bool, np.bool_)):
            raise TypeError(f"dense must be True or False, got {dense!r}")
        self.dense = bool(dense)
        options = {**(dense_options(self.min_amplitude) if dense else {}), **family_options}
        family = default_family(reference, hi, steps_per_cycle=steps_per_cycle, **options)
        self.full_family = family
        keep = [p for p, k in zip(family, restriction_mask(family, lo, self.min_amplitude)) if k]
        if not keep:
            raise ValueError(f"load_range {self.load_range} and min_amplitude {self.min_amplitude:g} leave no path "
                             "of the family; lower N_lo or min_amplitude")
        self.family = keep
        self.reference_model = mdr(reference, max_load=hi, elements=reference_elements)
        self._run = reference_run(self.reference_model, keep)
        self._full_run = None
        self.evaluations = 0

    @property
    def normal_load(self) -> float:
        """Tuning load ``N_hi`` (N)."""
        return self.load_range[1]

    def report(self, model) -> AccuracyReport:
        """Accuracy of ``model`` on the problem's (restricted) family."""
        self.evaluations += 1
        return accuracy(model, self._run)

    def amplitude_report(self, model) -> AccuracyReport:
        """Accuracy of ``model`` on the whole family (all amplitudes, loads >= N_lo), for error vs amplitude."""
        if self._full_run is None:
            mask = restriction_mask(self.full_family, self.load_range[0])
            paths = [p for p, k in zip(self.full_family, mask) if k]
            self._full_run = reference_run(self.reference_model, paths)
        return accuracy(model, self._full_run)

    def worst(self, model) -> tuple[float, float]:
        """``(worst |energy error|, worst force difference)`` of ``model`` on the family (fractions)."""
        r = self.report(model)
        return abs(r.worst("energy_error")[0]), abs(r.worst("force_difference")[0])

    def score(self, model) -> float:
        """``max(|energy error| / energy_target, force difference / force_target)``; <= 1 meets the target."""
        return self.normalised(*self.worst(model))

    def normalised(self, energy_error: float, force_difference: float) -> float:
        """The larger of ``energy_error / energy_target`` and ``force_difference / force_target`` (-)."""
        energy_error = _checks.positive_scalar("energy_error", energy_error, allow_zero=True)
        force_difference = _checks.positive_scalar("force_difference", force_difference, allow_zero=True)
        return max(energy_error / self.energy_target, force_difference / self.force_target)

    def result(self, model, points, spacing, evaluations=1) -> TargetTuning:
        """``model`` measured on the problem's family, with its points.

        Parameters
        ----------
        model : MicroslipModel
            The tuned array (``J`` elements).
        points : TuningPoints
            Its tuning points at ``N_hi`` (m, N), shape (J,) each.
        spacing : str
            ``'force'``, ``'displacement'`` or ``'optimal'``.
        evaluations : int, default 1
            Models evaluated to find it.

        Returns
        -------
        TargetTuning
            With the worst ``|energy error|`` and force difference over the
            family (fractions) and whether both meet the targets.
        """
        if not isinstance(points, TuningPoints):
            raise TypeError(f"points must be TuningPoints (from tuning_points), got {type(points).__name__}")
        spacing = _checks.one_of("spacing", spacing, SPACINGS)
        evaluations = _checks.positive_int("evaluations", evaluations)
        e, f = self.worst(model)
        return TargetTuning(model=model, points=points, spacing=spacing, energy_error=e, force_difference=f,
                            meets=bool(e <= self.energy_target and f <= self.force_target),
                            evaluations=evaluations)

    # -- models -------------------------------------------------------------
    def tune_fractions(self, fractions):
        """Tune at ``N_hi`` on the points ``t_j = fractions[j] * t_gs(N_hi)``; returns ``(model, points)``.

        ``fractions`` (-): strictly increasing in ``(0, 1]``, the last 1 (gross slip).
        """
        fractions = _checks.positive_array("fractions", fractions, ndim=1, min_size=1)
        if np.any(np.diff(fractions) <= 0) or abs(fractions[-1] - 1.0) > 1e-6:
            raise ValueError("fractions must increase strictly up to 1 (gross slip), got "
                             f"{np.array2string(fractions, precision=6, threshold=8)}")
        t = fractions * float(self.reference.gross_slip_displacement(self.normal_load))
        pts = tuning_points(self.reference, self.normal_load, displacements=t)
        return self.tune_points(pts), pts

    def tune_points(self, points):
        """The paper's model on ``points`` (TuningPoints at ``N_hi``), its provenance naming this problem."""
        return ranged(model_from_points(self.reference, points), self.load_range, energy_target=self.energy_target,
                      force_target=self.force_target, min_amplitude=self.min_amplitude, dense_family=self.dense)

    def tune_spacing(self, spacing: str, elements: int) -> TargetTuning:
        """The model with ``elements`` points spaced evenly in ``'force'`` or ``'displacement'``."""
        J = _checks.size("elements", elements, minimum=1)
        if spacing == "force":
            pts = tuning_points(self.reference, self.normal_load, elements=J)
            model = self.tune_points(pts)
        elif spacing == "displacement":
            model, pts = self.tune_fractions(np.arange(1, J + 1) / J)
        else:
            raise ValueError(f"spacing must be 'force' or 'displacement' here, got {spacing!r}")
        return self.result(model, pts, spacing)


def dense_options(min_amplitude: float = 0.5, *, amplitudes: int = 40, levels: int = 10) -> dict:
    """``family_options`` sampling the amplitudes and the load levels of the default family densely.

    Parameters
    ----------
    min_amplitude : float, default 0.5
        Smallest amplitude factor (multiple of the gross-slip displacement at
        a path's lowest load); positive.
    amplitudes : int, default 40
        Amplitude factors, geometric from ``min_amplitude`` to 3 (or just
        ``min_amplitude`` when it is 3 or more).
    levels : int, default 10
        Peak-load levels, linear from 0.1 to 1 of the tuning load.

    Returns
    -------
    dict
        ``{"amplitudes": tuple, "levels": tuple}`` for :func:`~microslip.paths.default_family`.
    """
    a = _checks.positive_scalar("min_amplitude", min_amplitude)
    na = _checks.positive_int("amplitudes", amplitudes, minimum=2)
    nl = _checks.positive_int("levels", levels, minimum=2)
    amps = np.geomspace(a, 3.0, na) if a < 3.0 else np.array([a])
    return {"amplitudes": tuple(float(x) for x in amps), "levels": tuple(float(x) for x in np.linspace(0.1, 1.0, nl))}


def target_fraction(name: str, value) -> float:
    """An accuracy target: a fraction in ``(0, 1]`` (0.02 means 2 %), or ``math.inf`` for no limit."""
    if isinstance(value, (float, np.floating)) and value == np.inf:
        return float(value)
    x = _checks.positive_scalar(name, value)
    if x > 1.0:
        raise ValueError(f"{name} must be a fraction in (0, 1] (fractions: 0.02 means 2 %), got {x:g}; "
                         f"for {x:g} % pass {x / 100:g}, and math.inf for no limit")
    return x


def ranged(model, load_range, **problem):
    """``model`` whose provenance adds the load range (N) and the problem (targets as fractions) its points were chosen for."""
    notes = {k: "no limit" if isinstance(v, float) and v == np.inf else v for k, v in problem.items()}
    return model.with_provenance(replace(model.provenance, load_range=tuple(load_range), notes=notes))


def _load_range(load_range):
    lo, hi = _checks.positive_pair("load_range", load_range, "(N_lo, N_hi) in N")
    if not lo < hi:
        raise ValueError(f"load_range must satisfy N_lo < N_hi, got ({lo:g}, {hi:g}) N")
    return lo, hi
