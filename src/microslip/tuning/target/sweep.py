"""Worst errors against the number of elements for the three spacings of the tuning points."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...common import _checks
from ...common._progress import Progress
from .problem import SPACINGS, TargetProblem
from .search import _resample, optimal_points


@dataclass(frozen=True, eq=False)
class ElementSweep:
    """Worst errors against the number of elements for each spacing of the points.

    Attributes
    ----------
    elements : ndarray of int, shape (K,)
    energy_error, force_difference : dict of str -> ndarray, shape (K,)
        Per spacing (``'force'``, ``'displacement'``, ``'optimal'``), worst
        fractions over the problem's family.
    fractions : dict of int -> ndarray
        The optimised points of each ``J`` (fractions of ``t_gs(N_hi)``).
    energy_target, force_target : float
    """

    elements: np.ndarray
    energy_error: dict
    force_difference: dict
    fractions: dict
    energy_target: float
    force_target: float

    def smallest(self, spacing: str) -> int | None:
        """Smallest ``J`` of the sweep meeting both targets with ``spacing``, or None."""
        _checks.one_of("spacing", spacing, tuple(self.energy_error))
        ok = (self.energy_error[spacing] <= self.energy_target) & (self.force_difference[spacing] <= self.force_target)
        return int(self.elements[np.argmax(ok)]) if ok.any() else None

    def columns(self) -> dict:
        """``{'name [unit]': column}`` for CSV."""
        cols = {"J [-]": self.elements}
        for s in self.energy_error:
            cols[f"energy error {s} [%]"] = 100 * self.energy_error[s]
            cols[f"force difference {s} [%]"] = 100 * self.force_difference[s]
        return cols

    def rows(self) -> list:
        """Table rows ``[J, energy and force (%) per spacing...]``."""
        return [[int(J)] + [f"{100 * self.energy_error[s][k]:.3g} / {100 * self.force_difference[s][k]:.3g}"
                            for s in self.energy_error] for k, J in enumerate(self.elements)]

    def plot(self):
        """Worst energy and force errors (%) against ``J``, one line per spacing; returns the Figure."""
        import matplotlib.pyplot as plt

        fig, axes = plt.subplots(1, 2, figsize=(10, 4), constrained_layout=True)
        for ax, what, target, title in ((axes[0], self.energy_error, self.energy_target, "worst |energy error|"),
                                        (axes[1], self.force_difference, self.force_target,
                                         "worst max|T - T_ref| / max|T_ref|")):
            for s, v in what.items():
                ax.semilogy(self.elements, 100 * v, "o-", ms=3, label=f"{s} points")
            ax.axhline(100 * target, color="0.4", ls="--", lw=1, label=f"target {100 * target:g} %")
            ax.set_xlabel("number of elements J (-)")
            ax.set_ylabel(f"{title} (%)")
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=8)
        return fig


def element_sweep(problem: TargetProblem, elements=range(2, 33), *, spacings=SPACINGS, fractions=None,
                  starts=None, progress: bool = False, **options) -> ElementSweep:
    """Worst errors of the three spacings against ``J``.

    Parameters
    ----------
    problem : TargetProblem
    elements : iterable of int
        The ``J`` to try.
    spacings : sequence of str
        Among ``'force'``, ``'displacement'``, ``'optimal'``.
    fractions : dict of int -> array, optional
        Optimised points already known (e.g. :func:`load_optimal_points`):
        they are only re-measured, not searched again.
    starts : dict of int -> array, optional
        Points to start the search of each ``J`` from, besides the spacing
        laws and the previous ``J``'s result resampled (the search never
        returns worse than its best start).
    progress : bool
    **options
        Passed to :func:`optimal_points`.
    """
    if not isinstance(problem, TargetProblem):
        raise TypeError(f"problem must be a TargetProblem, got {type(problem).__name__}")
    if isinstance(elements, (str, bytes)) or not hasattr(elements, "__iter__"):
        raise TypeError(f"elements must be a sequence of integers (numbers of elements), got {elements!r}")
    Js = np.array([_checks.size("elements[i]", J) for J in elements], dtype=int)
    if isinstance(spacings, (str, bytes)) or not hasattr(spacings, "__iter__"):
        raise TypeError(f"spacings must be a sequence of spacing names, got {spacings!r}")
    for s in spacings:
        if s not in SPACINGS:
            raise ValueError(f"spacings must be among {', '.join(SPACINGS)}, got {s!r}")
    known = {int(k): np.asarray(v, dtype=float) for k, v in (fractions or {}).items()}
    seeds = {int(k): np.asarray(v, dtype=float) for k, v in (starts or {}).items()}
    bar = Progress(len(Js), enabled=progress)
    energy = {s: np.empty(len(Js)) for s in spacings}
    force = {s: np.empty(len(Js)) for s in spacings}
    found = {}
    for k, J in enumerate(Js):
        bar.step(f"J = {J}")
        for s in spacings:
            if s != "optimal":
                res = problem.tune_spacing(s, J)
            elif J in known:
                model, pts = problem.tune_fractions(known[J])
                res = problem.result(model, pts, "optimal")
            else:
                given = [_resample(u, J) for u in found.values()][-1:] + ([seeds[J]] if J in seeds else [])
                res = optimal_points(problem, J, start=given or None, **options)
            energy[s][k], force[s][k] = res.energy_error, res.force_difference
            if s == "optimal":
                found[int(J)] = res.points.t / res.points.t[-1]
    bar.done("sweep")
    return ElementSweep(Js, energy, force, found, problem.energy_target, problem.force_target)


def points_record(problem: TargetProblem, sweep: ElementSweep) -> dict:
    """Plain-JSON record of a sweep's optimised points and the problem they solve."""
    r = problem.reference
    return {"problem": {"reference": type(r).__name__, "radius": getattr(r, "radius", None),
                        "E": getattr(r, "E", None), "nu": getattr(r, "nu", None), "mu": r.mu,
                        "load_range": list(problem.load_range), "min_amplitude": problem.min_amplitude,
                        "energy_target": problem.energy_target, "force_target": problem.force_target},
            "fractions": {str(J): [float(x) for x in u] for J, u in sorted(sweep.fractions.items())}}
