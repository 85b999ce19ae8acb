"""Paper Fig. 6: the cylinder on a plane, tuned on measured loops (here the SYNTHETIC data set).

The paper's measured loops are not public; this section reads the synthetic
data set shipped in ``microslip/data`` (see :mod:`microslip.loops.synthetic`:
a physically grounded stand-in, clearly labelled synthetic) through the
same code a user runs (``microslip tune LOOPS... --normal-law TABLE``):
:func:`microslip.loops.read`, :func:`microslip.loops.analyse`,
:class:`microslip.Cylinder` with the specimen's normal curve, and
:func:`microslip.tune_on_loops` with 6 elements at the highest load.

Panels: (a) the per-element loops at the tuning load, 36.6 N; (b) the same,
predicted, at the lowest load, 16.4 N; (c) the normal force--approach curve,
the array's and each element's spring, with the Palmgren and
Lundberg--Sjövall laws for comparison; (d) the load raised at constant T
(the paper's Fig. 4a, for the cylinder).
"""

from __future__ import annotations

import numpy as np

from ..common.report import ENERGY_UNIT, Energy

NAME = "fig6"
CAPTION = ("Fig. 6: cylinder l = d = 10 mm on a plane tuned at 36.6 N with 6 elements on the SYNTHETIC loops "
           "shipped in microslip/data: (a) per-element loops at 36.6 N, (b) predicted at 16.4 N, (c) normal "
           "curve and element springs, (d) load raised 16.4 -> 36.6 N at constant T (Fig. 4a for the cylinder)")

ELEMENTS = 6
GEOMETRY = dict(length=10e-3, radius=5e-3, E=200e9, nu=0.3)


def compute(case=None) -> dict:
    """Read the shipped data set, tune, validate. ``case`` (the sphere benchmark) is not used."""
    from ..measured import loops
    from ..measured.loop_tuning import tune_on_loops
    from ..measured.loops.synthetic import dataset_files, normal_curve_file
    from ..reference import Cylinder

    records = [loops.analyse(loops.read(path)) for path in dataset_files()]
    cylinder = Cylinder.from_file(normal_curve_file(), **GEOMETRY)
    result = tune_on_loops(records, cylinder, elements=ELEMENTS)
    others = [("Palmgren (Harris)", Cylinder(**GEOMETRY, law="palmgren")),
              ("Lundberg-Sjövall", Cylinder(**GEOMETRY, law="lundberg"))]
    return {"result": result, "others": others, "transition": result.transition()}


def plot(data):
    import matplotlib.pyplot as plt

    result = data["result"]
    fig, axes = plt.subplots(2, 2, figsize=(12, 9))
    result.plot_elements(ax=axes[0, 0])
    result.plot_elements(result.validation.loads[-1].normal_load, ax=axes[0, 1])
    result.plot_normal(ax=axes[1, 0], others=data["others"])
    result.plot_transition(ax=axes[1, 1])
    for ax, letter in zip(axes.flat, "abcd"):
        ax.set_title(f"({letter}) {ax.get_title()}", fontsize=10)
    fig.suptitle("Fig. 6 - cylinder on a plane, tuned on SYNTHETIC measured loops", fontsize=11)
    fig.tight_layout()
    return fig


def columns(data) -> dict:
    result = data["result"]
    cols = {}
    for v in result.validation.loads:
        L, P = v.measured, v.predicted
        a, b = L.cycle_bounds(L.steady_to - 1)
        t_c, T_c = L.centre
        tag = f"{v.normal_load:.4g} N"
        cols[f"t {tag} [m]"] = L.record.t[a:b + 1] - t_c
        cols[f"T measured {tag} [N]"] = L.record.T[a:b + 1] - T_c
        cols[f"T model {tag} [N]"] = P.record.T[a:b + 1]
    n = np.linspace(0.0, 1.05 * result.points.approach, 200)
    cols["n [m]"] = n
    cols["N normal law [N]"] = result.reference.normal_force(n)
    cols["N array [N]"] = result.model.normal_force(n)
    tr = data["transition"]
    cols["transition t model [m]"] = tr["t_model"]
    cols["transition T model [N]"] = tr["T_model"]
    cols["transition t reference [m]"] = tr["t_reference"]
    cols["transition T reference [N]"] = tr["T_reference"]
    return cols


#: largest expected |model - measured| per quantity (%), with why; checked by tests/test_measured_tuning.py
BOUNDS = {
    "energy": (2.0, "the synthetic specimen obeys the lower-load rule the reference assumes and its normal curve "
                    "is given: only the 6 elements and the noise differ"),
    "slip_force": (2.0, "mu is fitted from the slip forces of all five records, each with 0.04 N of force noise"),
    "stiffness": (10.0, "the array is straight until its first element slips while the data curve over the 10 % "
                        "stick window; 2 nm of displacement noise"),
}
TABLE_HEADERS = ["N (N)", "role", "quantity", "measured", "model", "difference (%)", "bound (%)",
                 "reason for the bound"]


def parameters(case=None) -> dict:
    """The cylinder's run (``case``, the sphere benchmark, is not used)."""
    g = GEOMETRY
    return {"Fig. 6 data set": "the SYNTHETIC cylinder loops shipped in microslip/data (5 loads)",
            "Fig. 6 cylinder": f"length {g['length'] * 1e3:g} mm, radius {g['radius'] * 1e3:g} mm, "
                               f"E = {g['E'] / 1e9:g} GPa, nu = {g['nu']:g}",
            "Fig. 6 elements": f"{ELEMENTS}, tuned at the highest load; mu fitted from the slip forces"}


def error_rows(data) -> list:
    """Empty: the cylinder is compared with its measured loops in its own table (:func:`tables`)."""
    return []


def tables(data) -> list:
    """The measured against the model's loops at every load: ``[(caption, headers, rows)]``."""
    result = data["result"]
    tuned = result.reference.normal_load
    rows = []
    for v in result.validation.loads:
        m, p = v.measured.summary(), v.predicted.summary()
        role = ("tuning load (fitted, not a prediction)" if abs(v.normal_load - tuned) <= 1e-9 * tuned
                else f"predicted (tuned at {tuned:.4g} N)")
        for key, label, cell, error in (("energy", f"energy per cycle ({ENERGY_UNIT})", Energy, v.energy_error),
                                        ("slip_force", "slip force (N)", float, v.slip_force_error),
                                        ("stick_stiffness", "stick stiffness (N/µm)", lambda k: k * 1e-6,
                                         v.stiffness_error)):
            bound, why = BOUNDS["stiffness" if key == "stick_stiffness" else key]
            rows.append([f"{v.normal_load:.4g}", role, label, cell(m[key]), cell(p[key]), 100 * error, bound, why])
    caption = (f"Fig. 6, cylinder on the SYNTHETIC data set: measured loops against the {result.model.elements}-"
               f"element model tuned at {tuned:.4g} N; the tuning-load rows check the fit, the others are "
               f"predictions")
    return [(caption, TABLE_HEADERS, rows)]
