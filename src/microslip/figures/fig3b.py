"""Paper Fig. 3b: loops at lower normal loads with the array tuned at 37.5 N."""

from __future__ import annotations

import numpy as np

from ..common.report import ENERGY_UNIT, Energy, plural
from ._loops import array_loop, loop_energy

NAME = "fig3b"
CAPTION = ("Fig. 3b: hysteresis loops at lower normal loads (same displacement amplitude, the gross-slip "
           "displacement at 37.5 N), continuous and discrete, with the array tuned at 37.5 N; the "
           "discrete model is given the Hertz approach of each load")


def compute(case) -> dict:
    sphere, model = case.sphere, case.model
    amp = case.gross_slip
    rows = []
    for N in case.lower_loads:
        n = float(sphere.approach(N))
        t, T_c = sphere.loop(amp, N, points=801)
        _, T_d, energy = array_loop(model, amp, n, points=801)
        rows.append({"N": N, "t": t, "continuous": T_c, "discrete": T_d,
                     "slip_continuous": sphere.mu * N, "slip_discrete": float(model.slip_force(n)),
                     "energy_continuous": loop_energy(t, T_c), "energy_discrete": energy,
                     "active": int(np.count_nonzero(model.gaps < n))})
    return {"loops": rows, "amplitude": amp}


def plot(data):
    import matplotlib
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8.6, 4.8))
    um = 1e6
    colors = matplotlib.colormaps["plasma"](np.linspace(0.0, 0.8, len(data["loops"])))
    for lp, c in zip(data["loops"], colors):
        ax.plot(lp["t"] * um, lp["continuous"], "-", color=c, lw=2, label=f"N = {lp['N']:g} N continuous")
        ax.plot(lp["t"] * um, lp["discrete"], "--", color=c, lw=1.3,
                label=f"N = {lp['N']:g} N discrete ({lp['active']} el.)")
    ax.set_xlabel("tangential displacement t (µm)")
    ax.set_ylabel("tangential force T (N)")
    ax.set_title("Fig. 3b - loops at several normal loads (tuned at 37.5 N)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    fig.tight_layout()
    return fig


def columns(data) -> dict:
    cols = {"t [m]": data["loops"][0]["t"]}
    for lp in data["loops"]:
        cols[f"T continuous N={lp['N']:g} [N]"] = lp["continuous"]
        cols[f"T discrete N={lp['N']:g} [N]"] = lp["discrete"]
    return cols


def parameters(case) -> dict:
    return {"Fig. 3b loads": ", ".join(f"{N:g}" for N in case.lower_loads) + " N",
            "Fig. 3b amplitude": f"the gross-slip displacement at {case.normal_load:g} N"}


def error_rows(data) -> list:
    rows = []
    for lp in data["loops"]:
        sd, sc = lp["slip_discrete"], lp["slip_continuous"]
        rows.append((f"Fig. 3b: slip load at N = {lp['N']:g} N ({plural(lp['active'], 'element')} in contact) (N)",
                     sd, sc, 100 * (sd - sc) / sc, "paper: below 8 %"))
    for lp in data["loops"]:
        ed, ec = lp["energy_discrete"], lp["energy_continuous"]
        rows.append((f"Fig. 3b: energy per cycle at N = {lp['N']:g} N ({ENERGY_UNIT})", Energy(ed), Energy(ec),
                     100 * (ed - ec) / ec, ""))
    return rows
