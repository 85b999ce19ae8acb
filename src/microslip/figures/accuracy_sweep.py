"""Beyond the paper: worst errors against the number of elements for three choices of the tuning points.

(a) points evenly spaced in force (the paper's), (b) evenly spaced in
displacement, (c) optimised (:mod:`microslip.tuning_target`). Errors are the
worst over the default family restricted to ``N >= 0.2 N_tot`` and
``t_a >= 0.5 t_gs(N_min)``, against the exact contact. The optimised points
were found once by ``microslip target --sweep 2-16,20,24,28,32 --save-points``
(minutes) and are stored with the package; here every model is tuned and
measured afresh.
"""

from __future__ import annotations

from .accuracy_common import sweep

NAME = "accuracy_sweep"
CAPTION = ("Accuracy against J (beyond the paper): worst energy error and worst force difference over "
           "the variable-load family (N >= 0.2 N_tot, t_a >= 0.5 t_gs(N_min)) for points evenly spaced in force, "
           "evenly spaced in displacement, and optimised")


def compute(case) -> dict:
    return {"sweep": sweep(case)}


def plot(data):
    return data["sweep"].plot()


def columns(data) -> dict:
    return data["sweep"].columns()


def tables(data) -> list:
    s = data["sweep"]
    headers = ["J"] + [f"{name} points: energy / force (%)" for name in s.energy_error]
    return [("worst energy error magnitude / worst force difference (% of the reference's peak)", headers,
             s.rows())]


def error_rows(data) -> list:
    s = data["sweep"]
    rows = []
    expected = {"force": "", "displacement": "issue: about 16 on its measurement (coarser amplitude samples: README)",
                "optimal": "issue target: at most 10 (not reached, see README)"}
    for name in s.energy_error:
        J = s.smallest(name)
        rows.append((f"smallest J with both worst errors <= 2 %, {name} points", J, None, None,
                     f"none up to {int(s.elements[-1])}; " + expected[name] if J is None else expected[name]))
    return rows
