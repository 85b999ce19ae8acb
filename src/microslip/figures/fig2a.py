"""Paper Fig. 2a: the ascending backbone at N_tot, the tuning points and the tuned (discrete) curve."""

from __future__ import annotations

import numpy as np

from .case import element_colors

NAME = "fig2a"
CAPTION = ("Fig. 2a: Cattaneo-Mindlin backbone of the sphere at N_tot = 37.5 N (continuous), "
           "the tuning points and the tuned 4-element array (discrete), with each element's force")


def compute(case) -> dict:
    model, pts = case.model, case.points
    t = np.linspace(0.0, 1.3 * case.gross_slip, 521)
    n_tot = pts.approach
    response = model.simulate(t, n_tot)
    continuous = case.sphere.backbone(t, case.normal_load)
    at_points = model.simulate(np.concatenate([[0.0], pts.t]), n_tot).T[1:]
    return {"t": t, "continuous": continuous, "discrete": response.T, "elements": response.Ti,
            "points_t": pts.t, "points_T": pts.T, "discrete_at_points": at_points,
            "limit": case.sphere.mu * case.normal_load, "normal_load": case.normal_load}


def plot(data):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    um = 1e6
    ax.plot(data["t"] * um, data["continuous"], "k-", lw=2, label="continuous (Cattaneo-Mindlin)")
    ax.plot(data["t"] * um, data["discrete"], "--", color="tab:red", lw=1.8, label="discrete (tuned array)")
    for i, c in enumerate(element_colors(data["elements"].shape[1])):
        ax.plot(data["t"] * um, data["elements"][:, i], color=c, lw=1, label=f"element {i + 1}")
    ax.plot(data["points_t"] * um, data["points_T"], "s", ms=8, mfc="none", mec="tab:green", mew=2,
            label="tuning points")
    ax.set_xlabel("tangential displacement t (µm)")
    ax.set_ylabel("tangential force T (N)")
    ax.set_title(f"Fig. 2a - backbone at N = {data['normal_load']:g} N")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    return fig


def columns(data) -> dict:
    cols = {"t [m]": data["t"], "T continuous [N]": data["continuous"], "T discrete [N]": data["discrete"]}
    for i in range(data["elements"].shape[1]):
        cols[f"T element {i + 1} [N]"] = data["elements"][:, i]
    cols["tuning t [m]"] = data["points_t"]
    cols["tuning T [N]"] = data["points_T"]
    return cols


def error_rows(data) -> list:
    k = int(np.argmax(np.abs(data["discrete"] - data["continuous"])))
    j = int(np.argmax(np.abs(data["discrete_at_points"] - data["points_T"])))
    limit = data["limit"]
    return [
        (f"Fig. 2a: backbone force, largest difference (at t = {data['t'][k] * 1e6:.3g} µm), % of mu N",
         data["discrete"][k], data["continuous"][k],
         100 * abs(data["discrete"][k] - data["continuous"][k]) / limit,
         "chords of a concave curve: a few %"),
        ("Fig. 2a: backbone force at the tuning points, largest difference, % of mu N",
         data["discrete_at_points"][j], data["points_T"][j],
         100 * abs(data["discrete_at_points"][j] - data["points_T"][j]) / limit, "0 (exact)"),
    ]
