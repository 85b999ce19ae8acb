"""Paper Fig. 2b: the normal force--approach curve (Hertz), its tuning points and the array's curve."""

from __future__ import annotations

import numpy as np

from .case import element_colors

NAME = "fig2b"
CAPTION = ("Fig. 2b: normal force against normal approach for the sphere (continuous, Hertz), the points "
           "where each element touches, and the tuned array (discrete) with each element's normal force")


def compute(case) -> dict:
    model, n_tot = case.model, case.points.approach
    n = np.linspace(0.0, 1.15 * n_tot, 461)
    points_n = np.concatenate([model.gaps[1:], [n_tot]])
    return {"n": n, "continuous": case.sphere.normal_force(n), "discrete": model.normal_force(n),
            "elements": model.element_normal_forces(n), "points_n": points_n,
            "points_N": case.sphere.normal_force(points_n), "discrete_at_points": model.normal_force(points_n),
            "normal_load": case.normal_load, "n_tot": n_tot}


def plot(data):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    um = 1e6
    ax.plot(data["n"] * um, data["continuous"], "k-", lw=2, label="continuous (Hertz)")
    ax.plot(data["n"] * um, data["discrete"], "--", color="tab:red", lw=1.8, label="discrete (tuned array)")
    for i, c in enumerate(element_colors(data["elements"].shape[1])):
        ax.plot(data["n"] * um, data["elements"][:, i], color=c, lw=1, label=f"element {i + 1}")
    ax.plot(data["points_n"] * um, data["points_N"], "s", ms=8, mfc="none", mec="tab:green", mew=2,
            label="tuning points")
    ax.axvline(data["n_tot"] * um, color="0.6", lw=0.8, ls=":")
    ax.set_xlabel("normal approach n (µm)")
    ax.set_ylabel("normal force N (N)")
    ax.set_title(f"Fig. 2b - normal curve, tuned at N = {data['normal_load']:g} N")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    return fig


def columns(data) -> dict:
    cols = {"n [m]": data["n"], "N continuous [N]": data["continuous"], "N discrete [N]": data["discrete"]}
    for i in range(data["elements"].shape[1]):
        cols[f"N element {i + 1} [N]"] = data["elements"][:, i]
    cols["tuning n [m]"] = data["points_n"]
    cols["tuning N [N]"] = data["points_N"]
    return cols


def error_rows(data) -> list:
    inside = data["n"] <= data["n_tot"]
    diff = np.abs(data["discrete"] - data["continuous"])[inside]
    k = int(np.argmax(diff))
    j = int(np.argmax(np.abs(data["discrete_at_points"] - data["points_N"])))
    N_tot = data["normal_load"]
    return [
        (f"Fig. 2b: normal force up to n_tot, largest difference (at n = {data['n'][k] * 1e6:.3g} µm), "
         "% of N_tot", data["discrete"][k], data["continuous"][k], 100 * diff[k] / N_tot,
         "chords of a convex curve: a few %"),
        ("Fig. 2b: normal force at the tuning points, largest difference, % of N_tot",
         data["discrete_at_points"][j], data["points_N"][j],
         100 * abs(data["discrete_at_points"][j] - data["points_N"][j]) / N_tot, "0 (exact)"),
    ]
