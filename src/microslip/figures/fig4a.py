"""Paper Fig. 4a: normal load raised by dN while T rises (Mindlin--Deresiewicz), continuous and discrete.

Path O-A-B-C: from O the tangential force rises at constant load N to A;
there the load is raised to N + dN at constant T; then T rises again. The
continuous curve joins the virgin curve at N + dN at B, once the tangential
increment reaches ``mu dN``, and follows it to gross slip at C. The discrete
model is driven by the displacements of the continuous path: ``t`` as
computed, ``n`` from Hertz at N and at N + dN.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

NAME = "fig4a"
CAPTION = ("Fig. 4a: normal load raised from N = 25 N to N + dN = 37.5 N at A while T keeps rising "
           "(path O-A-B-C), against the virgin curve at 37.5 N (O-B-C): continuous (Mindlin-Deresiewicz) "
           "and discrete (tuned array)")


def parameters(case) -> dict:
    return {"Fig. 4 load before the step N": f"{case.raised_from:g} N", "Fig. 4 load step dN": f"{case.raised_by:g} N",
            "Fig. 4 load raised at T": f"{case.raised_at:g} mu N"}


@lru_cache(maxsize=2)  # Fig. 4b plots the same computation
def compute(case) -> dict:
    sphere, model = case.sphere, case.model
    N1, dN = case.raised_from, case.raised_by
    N2 = N1 + dN
    mu = sphere.mu
    T_A = case.raised_at * mu * N1
    n1, n2 = float(sphere.approach(N1)), float(sphere.approach(N2))
    t_B, T_B = sphere.join_point(N1, dN, T_A)
    t_A = float(sphere.backbone_displacement(T_A, N1))
    t_C = float(sphere.gross_slip_displacement(N2))
    # continuous path O-A-B-C, parametrised by the force, then a stretch of gross slip
    T_path = np.concatenate([np.linspace(0.0, T_A, 200), np.linspace(T_A, mu * N2, 601)[1:]])
    t_path = sphere.raised_load_path(T_path, N1, dN, T_A)
    t_end = 1.15 * t_C
    t_path = np.concatenate([t_path, np.linspace(t_C, t_end, 40)[1:]])
    T_path = np.concatenate([T_path, np.full(39, mu * N2)])
    # the normal approach steps from n1 to n2 at A, at constant t
    n_path = np.where(np.arange(t_path.size) < 200, n1, n2)
    t_drive = np.insert(t_path, 200, t_A)
    n_drive = np.insert(n_path, 200, n1)
    n_drive[200] = n2
    discrete = model.simulate(t_drive, n_drive)
    # virgin curve at N + dN (O-B-C)
    t_virgin = np.linspace(0.0, t_end, 601)
    virgin_c = sphere.backbone(t_virgin, N2)
    virgin_d = model.simulate(t_virgin, n2)
    T_B_discrete = float(np.interp(t_B, t_drive[201:], discrete.T[201:]))
    return {"t": t_drive, "n": n_drive, "T_continuous": np.insert(T_path, 200, T_A),
            "T_discrete": discrete.T, "Ti_discrete": discrete.Ti,
            "t_virgin": t_virgin, "virgin_continuous": virgin_c, "virgin_discrete": virgin_d.T,
            "Ti_virgin": virgin_d.Ti,
            "points": {"O": (0.0, 0.0), "A": (t_A, T_A), "B": (t_B, T_B), "C": (t_C, mu * N2)},
            "T_B_discrete": T_B_discrete, "N1": N1, "N2": N2, "mu": mu}


def plot(data):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    um = 1e6
    ax.plot(data["t_virgin"] * um, data["virgin_continuous"], "-", color="0.55", lw=2,
            label=f"O-B-C continuous (N = {data['N2']:g} N)")
    ax.plot(data["t_virgin"] * um, data["virgin_discrete"], "--", color="0.35", lw=1.3,
            label=f"O-B-C discrete (N = {data['N2']:g} N)")
    ax.plot(data["t"] * um, data["T_continuous"], "k-", lw=2, label="O-A-B-C continuous (N raised at A)")
    ax.plot(data["t"] * um, data["T_discrete"], "--", color="tab:red", lw=1.8, label="O-A-B-C discrete")
    for name, (t, T) in data["points"].items():
        ax.plot(t * um, T, "o", color="tab:blue", ms=6)
        ax.annotate(name, (t * um, T), textcoords="offset points", xytext=(-12, 6), fontsize=11,
                    fontweight="bold")
    ax.set_xlabel("tangential displacement t (µm)")
    ax.set_ylabel("tangential force T (N)")
    ax.set_title(f"Fig. 4a - N raised from {data['N1']:g} N to {data['N2']:g} N at A")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    return fig


def columns(data) -> dict:
    return {"t [m]": data["t"], "n [m]": data["n"], "T continuous O-A-B-C [N]": data["T_continuous"],
            "T discrete O-A-B-C [N]": data["T_discrete"], "t virgin [m]": data["t_virgin"],
            "T continuous O-B-C [N]": data["virgin_continuous"], "T discrete O-B-C [N]": data["virgin_discrete"]}


def error_rows(data) -> list:
    t_B, T_B = data["points"]["B"]
    limit = data["mu"] * data["N2"]
    diff = np.abs(data["T_discrete"] - data["T_continuous"])
    k = int(np.argmax(diff))
    return [
        ("Fig. 4a: tangential force at the join point B (N)", data["T_B_discrete"], T_B,
         100 * (data["T_B_discrete"] - T_B) / T_B, "coarse array: a few %"),
        (f"Fig. 4a: path O-A-B-C, largest force difference (at t = {data['t'][k] * 1e6:.3g} µm), % of mu(N+dN)",
         data["T_discrete"][k], data["T_continuous"][k], 100 * diff[k] / limit, "coarse array: a few %"),
    ]
