"""Beyond the paper: worst errors against the number of elements for three choices of the tuning points.

(a) points evenly spaced in force (the paper's), (b) evenly spaced in
displacement, (c) optimised (:mod:`microslip.tuning.target`). Errors are the
worst over the default family restricted to ``N >= 0.2 N_tot`` and
``t_a >= 0.5 t_gs(N_min)``, against the exact contact. The optimised points
were found once by ``microslip target --sweep 2-16,20,24,28,32 --save-points``
(minutes) and are stored with the package; here every model is tuned and
measured afresh.
"""

from __future__ import annotations

from .accuracy_common import SWEEP, sweep

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


def parameters(case) -> dict:
    return {"J swept": ", ".join(str(J) for J in SWEEP),
            "targets": "worst energy error and worst force difference both <= 2 % over the restricted family",
            "optimised points": "stored with the package (microslip target --save-points), re-measured here"}


def tables(data) -> list:
    s = data["sweep"]
    headers = ["J"] + [f"{name} points: {what} (%)" for name in s.energy_error for what in ("energy", "force")]
    rows = [[int(J)] + [f"{100 * error[name][k]:.3g}" for name in s.energy_error
                        for error in (s.energy_error, s.force_difference)] for k, J in enumerate(s.elements)]
    return [("worst energy error magnitude and worst force difference (% of the reference's peak)", headers, rows)]


def error_rows(data) -> list:
    s = data["sweep"]
    largest = int(s.elements[-1])
    return [(f"smallest J with both worst errors <= 2 %, {name} points", s.smallest(name), None, None,
             "" if s.smallest(name) else f"none up to {largest}") for name in s.energy_error]
