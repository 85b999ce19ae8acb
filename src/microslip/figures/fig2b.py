"""Paper Fig. 2b: the normal force--approach curve (Hertz), its tuning points and the array's curve."""

from __future__ import annotations

import numpy as np

from . import _tuned_curve

NAME = "fig2b"
CAPTION = ("Fig. 2b: normal force against normal approach for the sphere (continuous, Hertz), the points "
           "where each element touches, and the tuned array (discrete) with each element's normal force")


def compute(case) -> dict:
    model, n_tot = case.model, case.points.approach
    n = np.linspace(0.0, 1.15 * n_tot, 461)
    points_n = np.concatenate([model.gaps[1:], [n_tot]])
    return {"x": n, "continuous": case.sphere.normal_force(n), "discrete": model.normal_force(n),
            "elements": model.element_normal_forces(n), "points_x": points_n,
            "points_y": case.sphere.normal_force(points_n), "discrete_at_points": model.normal_force(points_n),
            "scale": case.normal_load, "normal_load": case.normal_load, "n_tot": n_tot}


def plot(data):
    return _tuned_curve.plot(data, reference="Hertz", xlabel="normal approach n (µm)",
                             ylabel="normal force N (N)", legend="upper left", x_mark=data["n_tot"],
                             title=f"Fig. 2b - normal curve, tuned at N = {data['normal_load']:g} N")


def columns(data) -> dict:
    return _tuned_curve.columns(data, "n", "N")


def error_rows(data) -> list:
    return _tuned_curve.error_rows(data, "Fig. 2b: normal force up to n_tot", "n", "N_tot",
                                   "chords of a convex curve: a few %", upto=data["n_tot"])
