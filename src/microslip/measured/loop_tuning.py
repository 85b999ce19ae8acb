"""Tuning on measured loops, end to end, and validation at the other measured loads.

:func:`tune_on_loops` takes analysed loops at several normal loads and a
normal law, builds the :class:`~microslip.MeasuredContact` reference
on the steady loops at the highest load, tunes the paper's array on it (the
steps of :func:`microslip.tune`, unchanged) and predicts the loops at every
measured load (:func:`~microslip.measured.loop_validation.validate`): the paper's
claim is that a model tuned at the highest load reproduces the lower ones.
The result, :class:`LoopTuning`, draws itself (:mod:`microslip.measured.loop_plots`)
and writes all of it as HTML and Markdown (:mod:`microslip.measured.loop_report`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from ..common import _checks
from . import loop_plots
from ..accuracy import paths
from ._loop_checks import loops_list
from .loops import Loops
from .loop_validation import LoadValidation, Validation, validate
from .contact import MeasuredContact
from ..model import MicroslipModel
from ..reference.mindlin import raised_load_path
from ..tuning import TuningPoints, model_from_points, tuning_points

__all__ = ["LoadValidation", "LoopTuning", "Validation", "raised_load_path", "tune_on_loops", "validate"]


@dataclass(frozen=True, eq=False)
class LoopTuning:
    """A model tuned on measured loops, with its reference, points and validation.

    Attributes
    ----------
    reference : MeasuredContact
        The fitted reference (backbone, normal law, mu).
    model : MicroslipModel
        The tuned array.
    points : TuningPoints
        The points on the fitted backbone (m, N).
    loops : tuple of Loops
        The analysed records, highest load first.
    validation : Validation
        Predicted against measured loops at every load.
    """

    reference: MeasuredContact
    model: MicroslipModel
    points: TuningPoints
    loops: tuple
    validation: Validation

    @property
    def tuned_loops(self) -> Loops:
        """The record the model was tuned on (highest load)."""
        return self.loops[0]

    # -- figures (drawn by microslip.measured.loop_plots) -------------------------------------
    def plot_branch(self, ax=None):
        """The measured steady branches (as ``2 x backbone``), the fitted curve and the tuning points; the Axes."""
        return loop_plots.plot_branch(self, ax)

    def plot_elements(self, normal_load=None, ax=None):
        """Paper Fig. 6a-b: the measured loop, the model's loop and each element's loop at a load (N); the Axes."""
        return loop_plots.plot_elements(self, normal_load, ax)

    def plot_normal(self, ax=None, *, others=()):
        """Paper Fig. 6c: the normal law, the array's normal curve and each element's spring; the Axes.

        Parameters
        ----------
        others : sequence of (label, normal law)
            Further laws to draw for comparison (e.g. Palmgren, Lundberg--Sjövall).
        """
        return loop_plots.plot_normal(self, ax, others=others)

    def plot_transition(self, ax=None, **kwargs):
        """Plot :meth:`transition` (paper Fig. 4a, for this contact); returns the Axes."""
        return loop_plots.plot_transition(self, ax, **kwargs)

    def transition(self, N=None, dN=None, at: float = 0.5, points: int = 400) -> dict:
        """The Fig. 4-like path on the tuned model and on the reference: load raised from N to N + dN.

        Defaults: ``N`` the lowest measured load, ``N + dN`` the highest;
        the load is raised when ``T = at * mu * N``.

        Returns
        -------
        dict
            ``t_model``, ``T_model`` (m, N) along the model's path;
            ``t_reference``, ``T_reference`` the reference's; ``N``, ``dN``, ``T_A``.
        """
        loads = [L.normal_load for L in self.loops]
        N = min(loads) if N is None else _checks.positive_scalar("N", N)
        dN = max(loads) - N if dN is None else _checks.positive_scalar("dN", dN)
        if N + dN > self.reference.normal_load * (1 + 1e-12):
            raise ValueError(f"dN: N + dN = {N + dN:g} N must not exceed the tuning load "
                             f"{self.reference.normal_load:g} N (no measured data above it)")
        ref, mu = self.reference, self.reference.mu
        T_A = _checks.in_range("at", at, 0.0, 1.0) * mu * N
        points = _checks.size("points", points, minimum=3)
        path = paths.paper_fig4(ref, N, dN, at, beyond=1.2, steps=max(points // 3, 2))
        r = path.simulate(self.model)
        T_ref = np.linspace(0.0, mu * (N + dN), points)
        return {"t_model": path.t, "T_model": r.T, "t_reference": raised_load_path(ref, T_ref, N, dN, T_A),
                "T_reference": T_ref, "N": N, "dN": dN, "T_A": T_A}

    def validation_at(self, normal_load=None) -> LoadValidation:
        """The validation at the measured load ``normal_load`` (N, to 0.1 %); default the tuning load."""
        if normal_load is None:
            return self.validation.loads[0]
        N = _checks.positive_scalar("normal_load", normal_load)
        for v in self.validation.loads:
            if abs(v.normal_load - N) <= 1e-3 * N:
                return v
        raise ValueError(f"normal_load: no record at {N:g} N; the loads are "
                         f"{[round(v.normal_load, 4) for v in self.validation.loads]} N")

    # -- report -------------------------------------------------------------------
    def report(self, out_dir, *, stem: str = "report", title: str | None = None) -> tuple[Path, Path]:
        """Write ``stem.html`` and ``stem.md`` (and the PNG figures, prefixed with ``stem``) into ``out_dir``."""
        from .loop_report import write_report

        out_dir, stem = _checks.file_path("out_dir", out_dir), _checks.text("stem", stem)
        title = None if title is None else _checks.text("title", title, allow_empty=True)
        return write_report(self, out_dir, stem=stem, title=title)


def tune_on_loops(loops, normal, *, elements=None, forces=None, displacements=None, mu=None,
                  normal_load=None, masing_tolerance: float = 0.1) -> LoopTuning:
    """Tune the paper's array on measured loops and validate it at every measured load.

    Parameters
    ----------
    loops : Loops or sequence of Loops
        Analysed records (:func:`microslip.loops.analyse`), each with its normal load.
    normal : object
        Normal law with ``approach(N)`` and ``normal_force(n)`` (e.g. :class:`microslip.Cylinder`).
    elements, forces, displacements
        The tuning points, as in :func:`microslip.tune` (default ``elements=4``).
    mu : float, optional
        Friction coefficient; default ``normal.mu``, else fitted from the slip forces.
    normal_load : float, optional
        Tuning load (N); default the highest record's.
    masing_tolerance : float, default 0.1
        See :meth:`MeasuredContact.from_loops` (positive).

    Returns
    -------
    LoopTuning

    Examples
    --------
    >>> from microslip import Cylinder, loops, tune_on_loops
    >>> from microslip.loops.synthetic import dataset_files, normal_curve_file
    >>> records = [loops.analyse(loops.read(p)) for p in dataset_files()]
    >>> result = tune_on_loops(records, Cylinder(10e-3, 5e-3, 200e9, 0.3, law="palmgren"), elements=6)
    >>> result.model.elements, round(result.reference.mu, 2)
    (6, 0.4)
    """
    items = sorted(loops_list(loops), key=lambda L: -L.normal_load)
    reference = MeasuredContact.from_loops(items, normal, mu=mu, normal_load=normal_load,
                                           masing_tolerance=masing_tolerance)
    if elements is None and forces is None and displacements is None:
        elements = 4
    N_tot = reference.normal_load
    points = tuning_points(reference, N_tot, forces=forces, displacements=displacements, elements=elements)
    model = model_from_points(reference, points)
    model = model.with_provenance(replace(model.provenance, loops=tuple(L.record.source for L in items)))
    usable = [L for L in items if L.normal_load <= N_tot * (1 + 1e-9)]
    return LoopTuning(reference, model, points, tuple(items), validate(model, normal, usable))
