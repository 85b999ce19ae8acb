"""Paper Fig. 2a: the ascending backbone at N_tot, the tuning points and the tuned (discrete) curve."""

from __future__ import annotations

import numpy as np

from . import _tuned_curve

NAME = "fig2a"
CAPTION = ("Fig. 2a: Cattaneo-Mindlin backbone of the sphere at N_tot = 37.5 N (continuous), "
           "the tuning points and the tuned 4-element array (discrete), with each element's force")


def compute(case) -> dict:
    model, pts = case.model, case.points
    t = np.linspace(0.0, 1.3 * case.gross_slip, 521)
    response = model.simulate(t, pts.approach)
    at_points = model.simulate(np.concatenate([[0.0], pts.t]), pts.approach).T[1:]
    return {"x": t, "continuous": case.sphere.backbone(t, case.normal_load), "discrete": response.T,
            "elements": response.Ti, "points_x": pts.t, "points_y": pts.T, "discrete_at_points": at_points,
            "scale": case.sphere.mu * case.normal_load, "normal_load": case.normal_load}


def plot(data):
    return _tuned_curve.plot(data, reference="Cattaneo-Mindlin", xlabel="tangential displacement t (µm)",
                             ylabel="tangential force T (N)", legend="lower right",
                             title=f"Fig. 2a - backbone at N = {data['normal_load']:g} N")


def columns(data) -> dict:
    return _tuned_curve.columns(data, "t", "T")


def error_rows(data) -> list:
    return _tuned_curve.error_rows(data, "Fig. 2a: backbone force", "t", "mu N",
                                   "chords of a concave curve: a few %")
