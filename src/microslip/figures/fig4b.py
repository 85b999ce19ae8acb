"""Paper Fig. 4b: each element's tangential force along the raised-load path and the virgin path."""

from __future__ import annotations

from ..common._style import element_colors
from .fig4a import compute  # noqa: F401  (the same computation as Fig. 4a)

NAME = "fig4b"
CAPTION = ("Fig. 4b: tangential force of each element of the tuned array along O-A-B-C (solid: N raised "
           "at A) and along O-B-C (dashed: constant N + dN); colours as in Fig. 2a")


def plot(data):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    um = 1e6
    J = data["Ti_discrete"].shape[1]
    for i, c in enumerate(element_colors(J)):
        ax.plot(data["t"] * um, data["Ti_discrete"][:, i], "-", color=c, lw=1.8,
                label=f"element {i + 1}, O-A-B-C")
        ax.plot(data["t_virgin"] * um, data["Ti_virgin"][:, i], "--", color=c, lw=1.2,
                label=f"element {i + 1}, O-B-C")
    t_A = data["points"]["A"][0]
    ax.axvline(t_A * um, color="0.5", lw=0.8, ls=":")
    ax.annotate("A: N raised", (t_A * um, ax.get_ylim()[1]), textcoords="offset points", xytext=(4, -14),
                fontsize=9)
    ax.set_xlabel("tangential displacement t (µm)")
    ax.set_ylabel("element tangential force T_i (N)")
    ax.set_title("Fig. 4b - element forces, N raised at A vs constant N + dN")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    fig.set_size_inches(8.6, 4.6)
    fig.tight_layout()
    return fig


def columns(data) -> dict:
    cols = {"t O-A-B-C [m]": data["t"]}
    J = data["Ti_discrete"].shape[1]
    for i in range(J):
        cols[f"T element {i + 1} O-A-B-C [N]"] = data["Ti_discrete"][:, i]
    cols["t O-B-C [m]"] = data["t_virgin"]
    for i in range(J):
        cols[f"T element {i + 1} O-B-C [N]"] = data["Ti_virgin"][:, i]
    return cols


def error_rows(data) -> list:
    return []
