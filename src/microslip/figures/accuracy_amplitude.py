"""Beyond the paper: energy error against the tangential amplitude, where a finite array must fail.

Mindlin's loss grows as the cube of the amplitude; a finite array's starts
only when its first element slips, so below some amplitude every finite
array dissipates too little. This section shows, for the paper's J = 4
model and for the optimised array of the smallest J meeting the target, the
worst |energy error| over the family (loads >= 0.2 N_tot) against the
amplitude, and the amplitude below which it exceeds 10 %.
"""

from __future__ import annotations

import numpy as np

from ..tuning.target import TargetProblem
from .accuracy_common import problem, stored_points, sweep

NAME = "accuracy_amplitude"
CAPTION = ("Energy error against tangential amplitude (beyond the paper): worst abs(W/W_ref - 1) over the "
           "variable-load family with N >= 0.2 N_tot, for the paper's J = 4 model and the arrays of the "
           "smallest J meeting the target")


def _models(case):
    pb: TargetProblem = problem(case)
    out = [("J = 4 with force points (paper)", case.model)]
    s = sweep(case)
    known = stored_points(case)
    for spacing in s.energy_error:
        J = s.smallest(spacing)
        note = "" if J else " (none meets the target)"
        J = J or int(s.elements[-1])
        if spacing == "optimal":
            model, _ = pb.tune_fractions(known[J])
        else:
            model = pb.tune_spacing(spacing, J).model
        out.append((f"J = {J} with {spacing} points{note}", model))  # no comma: also a CSV name
    return out


#: the energy error the amplitude threshold of the table refers to (fraction)
LIMIT = 0.10


def parameters(case) -> dict:
    return {"energy error limit of the amplitude table": f"{100 * LIMIT:g} %",
            "models of the amplitude section": "J = 4 (paper) and the smallest J meeting the targets per spacing"}


def compute(case) -> dict:
    pb = problem(case)
    reports = [(label, pb.amplitude_report(model)) for label, model in _models(case)]
    return {"reports": reports}


def plot(data):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for label, rep in data["reports"]:
        rep.plot_amplitude(ax, label=label)
    ax.set_title("worst energy error magnitude over the family (N >= 0.2 N_tot)", fontsize=10)
    fig.tight_layout()
    return fig


def columns(data) -> dict:
    cols = {"t_a / t_gs(N_min) [-]": data["reports"][0][1].worst_by_amplitude()[0]}
    for label, rep in data["reports"]:  # the same family, so the same amplitudes
        cols[f"{label}: worst |energy error| [%]"] = 100 * rep.worst_by_amplitude()[1]
    return cols


def tables(data) -> list:
    rows = []
    for label, rep in data["reports"]:
        a = rep.threshold_amplitude(LIMIT)
        rows.append([label, f"none: above {100 * LIMIT:g} % at every amplitude" if np.isnan(a) else f"{a:g}"])
    return [(f"smallest amplitude (multiple of t_gs(N_min)) from which every path's energy error is within "
             f"{100 * LIMIT:g} %",
             ["model", "t_a / t_gs(N_min)"], rows)]


def error_rows(data) -> list:
    return []
