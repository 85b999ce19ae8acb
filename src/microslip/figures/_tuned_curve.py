"""Plot, CSV columns and errors of a tuned curve (Figs. 2a and 2b): reference, array, elements, points (private).

The data dict holds ``x`` (m), ``continuous``, ``discrete`` (N, shape (m,)),
``elements`` (N, shape (m, J)), ``points_x``, ``points_y`` and
``discrete_at_points`` (shape (p,)), and ``scale`` (N) for relative errors.
"""

from __future__ import annotations

import numpy as np

from ..common._style import element_colors


def plot(data, *, reference: str, xlabel: str, ylabel: str, title: str, legend: str, x_mark=None):
    """Continuous and discrete curves, each element's curve and the tuning points."""
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    x = data["x"] * 1e6
    ax.plot(x, data["continuous"], "k-", lw=2, label=f"continuous ({reference})")
    ax.plot(x, data["discrete"], "--", color="tab:red", lw=1.8, label="discrete (tuned array)")
    for i, c in enumerate(element_colors(data["elements"].shape[1])):
        ax.plot(x, data["elements"][:, i], color=c, lw=1, label=f"element {i + 1}")
    ax.plot(data["points_x"] * 1e6, data["points_y"], "s", ms=8, mfc="none", mec="tab:green", mew=2,
            label="tuning points")
    if x_mark is not None:
        ax.axvline(x_mark * 1e6, color="0.6", lw=0.8, ls=":")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc=legend)
    fig.tight_layout()
    return fig


def columns(data, x_name: str, y_name: str) -> dict:
    """CSV columns: ``x``, both curves, each element, the points (SI units in the names)."""
    cols = {f"{x_name} [m]": data["x"], f"{y_name} continuous [N]": data["continuous"],
            f"{y_name} discrete [N]": data["discrete"]}
    for i in range(data["elements"].shape[1]):
        cols[f"{y_name} element {i + 1} [N]"] = data["elements"][:, i]
    cols[f"tuning {x_name} [m]"] = data["points_x"]
    cols[f"tuning {y_name} [N]"] = data["points_y"]
    return cols


def error_rows(data, what: str, x_name: str, scale_name: str, between: str, upto=None) -> list:
    """Largest difference between the curves (up to ``upto``) and at the tuning points, in % of ``scale``."""
    inside = np.ones(data["x"].size, bool) if upto is None else data["x"] <= upto
    diff = np.where(inside, np.abs(data["discrete"] - data["continuous"]), -1.0)
    k = int(np.argmax(diff))
    j = int(np.argmax(np.abs(data["discrete_at_points"] - data["points_y"])))
    scale = data["scale"]
    return [
        (f"{what}, largest difference (at {x_name} = {data['x'][k] * 1e6:.3g} µm), % of {scale_name}",
         data["discrete"][k], data["continuous"][k], 100 * diff[k] / scale, between),
        (f"{what} at the tuning points, largest difference, % of {scale_name}",
         data["discrete_at_points"][j], data["points_y"][j],
         100 * abs(data["discrete_at_points"][j] - data["points_y"][j]) / scale, "0 (exact)"),
    ]
