"""Validation of a model tuned on measured loops: its loops predicted at every measured load.

:func:`validate` drives a model with each measured displacement record at
the approach the normal law gives for its load and compares the analysed
loops (energy, slip force, stick stiffness): the paper's claim is that a
model tuned at the highest load reproduces the lower ones.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..common import _checks
from ._loop_checks import loops_list, normal_law
from .loops import Loops, Record, analyse
from ..model import MicroslipModel

_UM = 1e6


@dataclass(frozen=True, eq=False)
class LoadValidation:
    """Measured and predicted loops at one normal load.

    Attributes
    ----------
    normal_load : float
        The load (N).
    measured, predicted : Loops
        Analysis of the measured record and of the model driven by its
        displacement (offset removed) at the approach of the normal law.
    """

    normal_load: float
    measured: Loops
    predicted: Loops

    def _rel(self, key):
        m, p = self.measured.summary()[key], self.predicted.summary()[key]
        return (p - m) / m

    @property
    def energy_error(self) -> float:
        """Relative difference of the energy per steady cycle, predicted vs measured."""
        return self._rel("energy")

    @property
    def slip_force_error(self) -> float:
        """Relative difference of the slip force ``(F+ - F-)/2``."""
        return self._rel("slip_force")

    @property
    def stiffness_error(self) -> float:
        """Relative difference of the stick stiffness after reversals."""
        return self._rel("stick_stiffness")


@dataclass(frozen=True, eq=False)
class Validation:
    """Predicted against measured loops at every measured load (highest first)."""

    loads: tuple

    HEADERS = ("N (N)", "energy meas. (µJ)", "energy pred. (µJ)", "diff (%)", "slip force meas. (N)",
               "slip force pred. (N)", "diff (%)", "stick stiffness meas. (N/µm)", "pred. (N/µm)", "diff (%)")

    def rows(self) -> list:
        """Table rows matching :attr:`HEADERS` (energies in µJ, stiffness in N/µm, differences in %)."""
        out = []
        for v in self.loads:
            m, p = v.measured.summary(), v.predicted.summary()
            out.append([f"{v.normal_load:.4g}", m["energy"] * 1e6, p["energy"] * 1e6, 100 * v.energy_error,
                        m["slip_force"], p["slip_force"], 100 * v.slip_force_error,
                        m["stick_stiffness"] / 1e6, p["stick_stiffness"] / 1e6, 100 * v.stiffness_error])
        return out

    def worst(self) -> dict:
        """Largest absolute relative differences over the loads: energy, slip_force, stiffness."""
        return {k: max(abs(getattr(v, f"{k}_error")) for v in self.loads)
                for k in ("energy", "slip_force", "stiffness")}

    def plot(self, ax=None):
        """Measured steady cycles (grey) and the predicted ones (coloured) at every load; returns the Axes."""
        import matplotlib.pyplot as plt

        if ax is None:
            _, ax = plt.subplots(figsize=(6.4, 4.6))
        colors = plt.get_cmap("plasma")(np.linspace(0.0, 0.8, len(self.loads)))
        for v, color in zip(self.loads, colors):
            t_c, T_c = v.measured.centre
            for loops, style, label, shift in ((v.measured, dict(color="0.6", lw=2.2), None, (t_c, T_c)),
                                               (v.predicted, dict(color=color, lw=1.1, ls="--"),
                                                f"N = {v.normal_load:.3g} N", (0.0, 0.0))):
                a, b = loops.cycle_bounds(loops.steady_to - 1)
                ax.plot((loops.record.t[a:b + 1] - shift[0]) * _UM, loops.record.T[a:b + 1] - shift[1],
                        label=label, **style)
        ax.plot([], [], color="0.6", lw=2.2, label="measured")
        ax.set_xlabel("tangential displacement t (µm)")
        ax.set_ylabel("tangential force T (N)")
        ax.set_title("measured (grey, offsets removed) and predicted (dashed) steady loops", fontsize=9)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
        return ax


def validate(model: MicroslipModel, normal, loops) -> Validation:
    """Drive ``model`` with each measured displacement record and compare the loops.

    Parameters
    ----------
    model : MicroslipModel
        The tuned array.
    normal : object
        Normal law with ``approach(N)`` (m of N): the approach at each load,
        finite and positive.
    loops : Loops or sequence of Loops
        Analysed records with their normal loads.

    Returns
    -------
    Validation
        Highest load first. Each record's displacement is shifted by its
        loop centre (the sensor offset); the model's loops are analysed with
        the same options as the measured ones, without the correction for
        displacement noise (the model's force follows the noisy
        displacement exactly).

    Raises
    ------
    TypeError
        ``model`` is not a :class:`MicroslipModel`, ``normal`` has no
        ``approach``, ``loops`` holds something else than analysed records.
    ValueError
        A record without a normal load, or an approach that is not finite
        and positive.
    """
    if not isinstance(model, MicroslipModel):
        raise TypeError(f"model must be a MicroslipModel, got {type(model).__name__}")
    normal_law(normal, needs=("approach",))
    items = sorted(loops_list(loops), key=lambda L: -L.normal_load)
    out = []
    for L in items:
        n = _checks.positive_scalar(f"normal.approach({L.normal_load:.4g} N)", normal.approach(L.normal_load))
        t = L.record.t - L.centre[0]
        r = model.simulate(t, n, per_element=False)
        rec = Record(t=t, T=r.T, time=L.record.time, normal_load=L.normal_load,
                     source=f"model at {L.normal_load:.4g} N")
        options = dict(L.options, noise_correction=False)  # the model's T is exact for the t it is given
        out.append(LoadValidation(L.normal_load, L, analyse(rec, **options)))
    return Validation(tuple(out))
