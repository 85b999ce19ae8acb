"""Paper Fig. 3a: the complete hysteresis loop at the tuning load, continuous and discrete."""

from __future__ import annotations

import numpy as np

from ..common.report import ENERGY_UNIT, Energy
from ._loops import array_loop

NAME = "fig3a"
CAPTION = ("Fig. 3a: complete hysteresis loop at N = 37.5 N, mu = 0.4, amplitude at gross slip: continuous "
           "(Cattaneo-Mindlin + Masing) and discrete (tuned array); the boxes mark the tuning points, "
           "mapped onto the branches by Masing's rule")

AMPLITUDES = (1.0, 0.5)  # loop amplitudes as fractions of the gross-slip displacement (the first is plotted)


def compute(case) -> dict:
    sphere, model, pts = case.sphere, case.model, case.points
    N = case.normal_load
    n = pts.approach
    loops = []
    for fraction in AMPLITUDES:
        amp = fraction * case.gross_slip
        t_c, T_c = sphere.loop(amp, N, points=801)
        t_d, T_d, energy = array_loop(model, amp, n, points=801)
        T_amp = float(sphere.backbone(amp, N))
        loops.append({"fraction": fraction, "amplitude": amp, "t": t_c, "continuous": T_c, "discrete": T_d,
                      "energy_mindlin": float(sphere.dissipation(T_amp, N)),
                      "energy_discrete": energy})
        assert np.array_equal(t_c, t_d)
    amp = loops[0]["amplitude"]
    limit = sphere.mu * N
    marks_t = np.concatenate([amp - 2 * pts.t, -amp + 2 * pts.t])
    marks_T = np.concatenate([limit - 2 * pts.T, -limit + 2 * pts.T])
    return {"loops": loops, "marks_t": marks_t, "marks_T": marks_T, "normal_load": N}


def plot(data):
    import matplotlib.pyplot as plt

    lp = data["loops"][0]
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    um = 1e6
    ax.plot(lp["t"] * um, lp["continuous"], "k-", lw=2, label="continuous")
    ax.plot(lp["t"] * um, lp["discrete"], "--", color="tab:red", lw=1.8, label="discrete (J = 4)")
    ax.plot(data["marks_t"] * um, data["marks_T"], "s", ms=8, mfc="none", mec="tab:green", mew=2,
            label="tuning points (Masing)")
    ax.set_xlabel("tangential displacement t (µm)")
    ax.set_ylabel("tangential force T (N)")
    ax.set_title(f"Fig. 3a - complete loop at N = {data['normal_load']:g} N")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    return fig


def columns(data) -> dict:
    lp = data["loops"][0]
    return {"t [m]": lp["t"], "T continuous [N]": lp["continuous"], "T discrete [N]": lp["discrete"]}


def parameters(case) -> dict:
    return {"Fig. 3a loop amplitudes": ", ".join(f"{a:g}" for a in AMPLITUDES) + " x gross-slip displacement",
            "Fig. 3a samples per branch": "801"}


def error_rows(data) -> list:
    rows = []
    for lp in data["loops"]:
        e_d, e_c = lp["energy_discrete"], lp["energy_mindlin"]
        rows.append((f"Fig. 3a: energy per cycle at {data['normal_load']:g} N, amplitude {lp['fraction']:g} x gross "
                     f"slip ({ENERGY_UNIT}), vs Mindlin's formula", Energy(e_d), Energy(e_c), 100 * (e_d - e_c) / e_c,
                     "coarse 4-element array: order 10 %"))
    return rows
