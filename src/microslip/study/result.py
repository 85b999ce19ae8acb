"""The results of a design study: one summary row and one curve per case, with the plots a review needs."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..common import _checks
from .spec import Study

#: the summary column each solve's plots read per output DOF, and its label
_MEASURES = {"frf": ("peak {} (m)", "peak amplitude of {} (µm)", 1e6),
             "modes": ("largest damping ratio", "largest modal damping ratio (%)", 100.0)}


@dataclass
class SweepResult:
    """Every case of a study (:func:`~microslip.study.sweep`), in the study's order.

    Attributes
    ----------
    study : Study
        The study solved.
    cases : list of Case
        Its cases (values, key, mistuned disk sample).
    outcomes : list of dict or None
        Each case's outcome as stored: ``row`` (summary values), ``curves``
        (arrays of shape ``(points,)``, amplitudes ``(points, dofs)``, SI
        units), ``error`` (empty when it succeeded), ``time`` (s); None for a
        case not run.
    rows : list of dict
        The summary table (``summary.csv``): per case its key, each varied key
        path's value (SI when it has a unit), the peak amplitude (m) and
        frequency (Hz) of each output DOF, the contacts' dissipation at the
        peak (J) and static state, ``complete``, ``time (s)``, ``error``.
    dof_names : list of str
        The output DOFs (the base configuration's ``[output] plot``).
    out : Path
        The results folder.
    computed : int
        Cases solved by this run (the rest were read back from ``out``).
    elapsed : float
        Wall time of this run (s).
    """

    study: Study
    cases: list
    outcomes: list
    rows: list
    dof_names: list
    out: Path
    computed: int = 0
    elapsed: float = 0.0
    figures: dict = field(default_factory=dict, repr=False)

    def __repr__(self) -> str:
        return (f"SweepResult({len(self.cases)} cases, {self.computed} solved now, {len(self.failed)} failed, "
                f"results in {str(self.out)!r})")

    @property
    def summary(self):
        """The summary table as a :class:`pandas.DataFrame` (one row per case)."""
        from ..common._optional import require

        return require("pandas", "the summary table", "sweep").DataFrame(self.rows)

    @property
    def failed(self) -> list:
        """``(case, error)`` of every case that failed."""
        return [(c, o["error"] if o else "not run") for c, o in zip(self.cases, self.outcomes) if not o or o["error"]]

    def column(self, name: str) -> np.ndarray:
        """A summary column as floats (NaN where a case has no value), shape ``(cases,)``."""
        name = _checks.text("name", name)
        if not any(name in r for r in self.rows):
            known = sorted({k for r in self.rows for k in r})
            raise ValueError(f"name: the summary has no column {name!r} (it has {', '.join(known)})")
        return np.array([_number(r.get(name)) for r in self.rows])

    def measure(self, dof: str | None = None) -> tuple[np.ndarray, str, float]:
        """Each case's main result for ``dof`` (a name of :attr:`dof_names`; default the first): values, label, scale.

        The peak amplitude (m) of a forced response, the largest damping ratio of a mode.
        """
        dof = self.dof_names[0] if dof is None else _checks.one_of("dof", dof, self.dof_names)
        column, label, scale = _MEASURES[self.study.solve]
        return self.column(column.format(dof)), label.format(dof), scale

    def curve(self, index: int) -> dict:
        """The curves of case ``index`` (arrays, SI units; empty if it failed)."""
        k = _checks.positive_int("index", index, minimum=0)
        if k >= len(self.cases):
            raise ValueError(f"index must be below the number of cases {len(self.cases)}, got {k}")
        return dict(self.outcomes[k]["curves"]) if self.outcomes[k] else {}

    def amplification(self, dof: str | None = None) -> np.ndarray:
        """The mistuned disks' amplification factors for ``dof`` (largest blade's peak over the tuned sector's)."""
        dof = self.dof_names[0] if dof is None else _checks.one_of("dof", dof, self.dof_names)
        if self.study.mistuning is None:
            raise ValueError("amplification: the study has no [mistuning] block")
        values = self.column(f"amplification {dof}")
        return values[self.column("mistuned disk") >= 0]

    def plot(self, parameter: str | None = None, dof: str | None = None, ax=None):
        """The main result (peak amplitude, or a mode's largest damping) against a varied parameter.

        One line per combination of the other parameters; a parameter whose
        values are not numbers is shown by its values in order.
        """
        from .report import plot_against

        return plot_against(self, parameter or self.study.parameters[0], dof, ax=ax)

    def to_csv(self, path) -> Path:
        """Write the summary table as CSV (atomically); returns the path."""
        from ..common._io import atomic_write

        return atomic_write(_checks.file_path("path", path), self.summary.to_csv(index=False))


def _number(value) -> float:
    if isinstance(value, bool):
        return float(value)
    if isinstance(value, (int, float)):
        return float(value)
    return float("nan")
