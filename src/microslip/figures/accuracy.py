"""Beyond the paper: accuracy of its J = 4 model under variable normal loads, against the exact contact.

The paper checks its model where closed forms exist (constant N, one step of
N). Here it runs, with the exact continuous contact (method of
dimensionality reduction, 2000 elements), on the default family of periodic
cycles ``t = t_a sin(tau)``, ``N = N_m + N_a sin(tau + phi)``
(:func:`microslip.paths.default_family`).
"""

from __future__ import annotations

import numpy as np

from ..accuracy import paths
from ..accuracy.compare import accuracy
from ..common.report import ENERGY_UNIT, Energy, plural
from .accuracy_common import LOW_LOAD, MDR_ELEMENTS, MIN_AMPLITUDE, family_run

NAME = "accuracy"
CAPTION = ("Accuracy under variable normal load (beyond the paper): the paper's J = 4 model against the exact "
           "continuous contact (MDR, 2000 elements) on 450 cycles t = t_a sin(tau), N = N_m + N_a sin(tau + phi); "
           "worst error over the load levels for each amplitude, N_a/N_m and phase")
SUMMARY_HEADERS = ["metric", "worst (%)", "median of abs (%)", "where the worst occurs"]


def parameters(case) -> dict:
    join = lambda values: ", ".join(f"{v:g}" for v in values)  # noqa: E731
    return {"exact reference": f"method of dimensionality reduction, {MDR_ELEMENTS} elements",
            "family: load ratios N_a/N_m": join(paths.RATIOS),
            "family: phases phi": join(paths.PHASES_DEG) + " deg",
            "family: peak loads N_m + N_a": join(paths.LEVELS) + " x N_tot",
            "family: tangential amplitudes t_a": join(paths.AMPLITUDES) + " x t_gs(N_min)",
            "family: cycles per path, samples per cycle": "2 (the last measured), 360",
            "restricted family": f"N >= {LOW_LOAD:g} N_tot, t_a >= {MIN_AMPLITUDE:g} t_gs(N_min)"}


def compute(case) -> dict:
    report = accuracy(case.model, family_run(case))
    return {"report": report, "restricted": report.restrict(LOW_LOAD * case.normal_load, MIN_AMPLITUDE),
            "normal_load": case.normal_load}


def plot(data):
    return data["report"].plot()


def columns(data) -> dict:
    return data["report"].columns()


def _rows(report):
    return [[label, f"{100 * w:.3g}", f"{100 * m:.3g}", where] for label, w, m, where in report.summary()]


def tables(data) -> list:
    r, s = data["report"], data["restricted"]
    low = LOW_LOAD * data["normal_load"]
    down = int(r.shakedown.sum())
    return [(f"J = 4, all {plural(len(r), 'path')} ({down} {'shakes' if down == 1 else 'shake'} down in the "
             "reference: no energy error)", SUMMARY_HEADERS, _rows(r)),
            (f"J = 4, the {plural(len(s), 'path')} with N >= {low:g} N and t_a >= {MIN_AMPLITUDE:g} t_gs(N_min)",
             SUMMARY_HEADERS, _rows(s))]


def error_rows(data) -> list:
    s = data["restricted"]
    rows = []
    w, k = s.worst("energy_error")
    rows.append((f"J = 4, variable N (N >= {LOW_LOAD:g} N_tot, t_a >= {MIN_AMPLITUDE:g} t_gs): worst energy per "
                 f"cycle ({ENERGY_UNIT})", Energy(s.energy[k]), Energy(s.energy_reference[k]), 100 * w,
                 "no closed form: exact reference by MDR"))
    w, k = s.worst("force_difference")
    rows.append(("J = 4, same paths: worst force difference (N)", s.peak_reference[k] * w, None, 100 * w,
                 "% of the reference's peak force"))
    e = np.abs(s.energy_error)
    rows.append(("J = 4, same paths: median energy error magnitude", None, None, 100 * float(np.nanmedian(e)), ""))
    return rows
