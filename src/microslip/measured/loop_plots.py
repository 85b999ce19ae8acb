"""Figures of a model tuned on measured loops (:class:`~microslip.measured.loop_tuning.LoopTuning` draws with these).

Each function takes the :class:`~microslip.measured.loop_tuning.LoopTuning` result
and an optional Axes, draws displacements in µm and forces in N, and
returns the Axes.
"""

from __future__ import annotations

import numpy as np

_UM = 1e6


def plot_branch(result, ax=None):
    """The measured steady branches (as ``2 x backbone``), the fitted curve and the tuning points."""
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(6, 4.4))
    x, y = result.tuned_loops.backbone_points()
    fit, ref = result.reference.fit, result.reference
    grid = np.linspace(0.0, x.max(), 300)
    ax.plot(2 * x * _UM, 2 * y, ",", color="0.55", alpha=0.5)
    ax.plot([], [], ".", color="0.55", label="measured steady branches (from each reversal)")
    ax.plot(2 * grid * _UM, 2 * ref.backbone(grid, ref.normal_load), "k-", lw=1.8,
            label=f"fitted concave branch (RMS residual {100 * fit.relative_residual:.2g} % of slip force)")
    ax.plot(2 * result.points.t * _UM, 2 * result.points.T, "s", mfc="none", mec="tab:green", mew=2, ms=8,
            label="tuning points")
    ax.plot(2 * grid * _UM, 2 * result.model.backbone(grid, result.points.approach), "--", color="tab:red",
            lw=1.4, label=f"tuned array, J = {result.model.elements}")
    ax.set_xlabel("displacement from reversal (µm)")
    ax.set_ylabel("force change from reversal (N)")
    ax.set_title(f"branch at N = {ref.normal_load:.4g} N (Masing: 2 x backbone)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="lower right")
    return ax


def plot_elements(result, normal_load=None, ax=None):
    """Paper Fig. 6a-b: the measured loop, the model's loop and each element's loop at a load (N)."""
    import matplotlib.pyplot as plt

    from ..common._style import element_colors

    if ax is None:
        _, ax = plt.subplots(figsize=(6, 4.4))
    v = result.validation_at(normal_load)
    L = v.measured
    a, b = L.cycle_bounds(L.steady_to - 1)
    t_c, T_c = L.centre
    t = L.record.t - t_c
    ax.plot(t[a:b + 1] * _UM, L.record.T[a:b + 1] - T_c, color="0.6", lw=2.5, label="measured (offsets removed)")
    r = result.model.simulate(t, float(result.reference.approach(v.normal_load)))
    ax.plot(t[a:b + 1] * _UM, r.T[a:b + 1], "k--", lw=1.3, label="model")
    for i, color in enumerate(element_colors(result.model.elements)):
        ax.plot(t[a:b + 1] * _UM, r.Ti[a:b + 1, i], color=color, lw=1, label=f"element {i + 1}")
    ax.set_xlabel("tangential displacement t (µm)")
    ax.set_ylabel("tangential force T (N)")
    ax.set_title(f"N = {v.normal_load:.4g} N" + (" (tuned)" if v is result.validation.loads[0] else " (predicted)"))
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    return ax


def plot_normal(result, ax=None, *, others=()):
    """Paper Fig. 6c: the normal law, the array's normal curve and each element's spring.

    Parameters
    ----------
    others : sequence of (label, normal law)
        Further laws to draw for comparison (e.g. Palmgren, Lundberg--Sjövall).
    """
    import matplotlib.pyplot as plt

    from ..common._style import element_colors

    if ax is None:
        _, ax = plt.subplots(figsize=(6, 4.4))
    n_tot = result.points.approach
    n = np.linspace(0.0, 1.05 * n_tot, 300)
    name = getattr(result.reference.normal, "law_name", "normal law")
    ax.plot(n * _UM, result.reference.normal_force(n), "k-", lw=2, label=f"{name} (tuned on)")
    for label, law in others:
        ax.plot(n * _UM, law.normal_force(n), ":", lw=1.5, label=label)
    ax.plot(n * _UM, result.model.normal_force(n), "--", color="tab:red", lw=1.5, label="tuned array")
    Ni = result.model.element_normal_forces(n)
    for i, color in enumerate(element_colors(result.model.elements)):
        ax.plot(n * _UM, Ni[:, i], color=color, lw=1, label=f"element {i + 1}")
    ax.set_xlabel("normal approach n (µm)")
    ax.set_ylabel("normal force N (N)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    return ax


def plot_transition(result, ax=None, **kwargs):
    """Plot :meth:`transition` (paper Fig. 4a, for this contact); returns the Axes."""
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(6, 4.4))
    d = result.transition(**kwargs)
    ax.plot(d["t_reference"] * _UM, d["T_reference"], "k-", lw=2, label="reference (Mindlin-Deresiewicz rule)")
    ax.plot(d["t_model"] * _UM, d["T_model"], "--", color="tab:red", lw=1.5, label="tuned array")
    ax.axhline(d["T_A"], color="0.6", lw=0.8, ls=":")
    ax.set_xlabel("tangential displacement t (µm)")
    ax.set_ylabel("tangential force T (N)")
    ax.set_title(f"load raised from {d['N']:.3g} N to {d['N'] + d['dN']:.3g} N at T = {d['T_A']:.3g} N")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    return ax
