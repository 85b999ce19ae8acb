"""A finite-element blade with friction contacts under its platform, checked against time integration.
===================================================================================================

The blade is ``microslip.fe.blade``: meshed and assembled with scikit-fem (plane stress, 9-node
quadrilaterals, about ``--dofs`` DOFs, nickel alloy, clamped at the root of its shank), damped in
proportion to its stiffness (0.5 % at its first mode). Under each platform overhang two nodes
touch a fixed counterpart through the paper's steel sphere (4 elements tuned at 37.5 N): the
tangential direction along the chord (x), the normal one along the span (the platform pressed
down, -y), each node pressed by a static force of 25 N that the platform's own stiffness shares
with the contact. A 1 N force along x at the tip excites the first bending mode; the platform
rocks, so the normal loads of the two sides breathe in opposition (by 30 to 75 % at the peak),
and contact elements close, open, stick and slip within the cycle.

1. The forced response of the tip over 11-15.5 krad/s by harmonic balance (H = 5) on the contact
   and tip DOFs, the rest of the blade condensed by its 40 lowest modes plus the residual
   flexibility of the others (``reduction="modal"``, with its error estimate, and the difference
   to the exact condensation at the peak).
2. A Craig-Bampton model of the blade: the contact and tip DOFs plus 10 fixed-interface modes
   (19 DOFs), small enough to integrate in time.
3. At five frequencies including the peak: harmonic balance (H = 11) on that model against its
   time integration (``steady_state``, explicit central differences, 1024 steps per period, until
   the first harmonic changes by less than 1e-8 per period), started on the harmonic balance
   solution, and started from rest.

Started on the harmonic balance solution, time integration agrees with it to the truncation of
the harmonics and the time step (2.5e-4 at most, at the peak). Started from rest it reaches the
same steady state at the peak, where the response builds up without overshoot, and another one
off it (0.26 % to 1.2 % away): there the start-up transient beats, its first peaks up to 1.6
times the steady amplitude, and makes contact elements slip that then stick through the steady
cycle with the force the transient left them, where harmonic balance loads them once to the mean
of the motion. Both are steady states of the same equations; friction makes them depend on the
history.

Run ``python examples/fe_blade.py [--out DIR] [--dofs N]`` (about 15 s at 1000 DOFs); writes
``fe_blade_response.png`` and ``fe_blade_response.csv`` into ``DIR`` (default: the current folder).
"""

from __future__ import annotations

import csv
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from microslip import Sphere, Structure, frequency_response, tune
from microslip.fe import blade, natural_frequencies
from microslip.frequency import craig_bampton, frequency_point, steady_state

PRELOAD = 25.0  # N, the static force pressing each contact node
FORCE = 1.0  # N along x at the tip
RANGE = (11000.0, 15500.0)  # rad/s: the microslip resonance, up to the stuck blade's (14.4 krad/s)
OFF_PEAK = (11500.0, 12500.0, 13800.0, 14500.0)  # rad/s, with the peak: the five frequencies compared
STEPS = 1024  # time steps per period


def blade_with_contacts(dofs: int = 1000):
    """``(fe_blade, structure, tip row)``: the blade and its four contacts (SI units)."""
    b = blade(dofs, contact_nodes=2)
    omega_1 = 2 * np.pi * natural_frequencies(b.M, b.K, 1)[0]
    structure = Structure(b.M, (2 * 0.005 / omega_1) * b.K, b.K, dof_map=b.dof_map)
    sphere = tune(Sphere.paper(), 37.5, elements=4)
    for node in b.platform_nodes:
        structure.add_contact(sphere, tangential=f"{node}:x", normal={f"{node}:y": -1.0}, preload=PRELOAD,
                              name=f"node {node}")
    return b, structure, structure.dof_index(f"{b.tip_node}:x")


def compare(model, tip: int, frequencies):
    """Rows of harmonic balance (H = 11) against time integration of ``model``, the tip's first harmonic (m)."""
    force = np.zeros(model.ndof)
    force[tip] = FORCE
    rows = []
    for omega in frequencies:
        hb = frequency_point(model, force, omega, harmonics=11, reduction="exact")
        on = steady_state(model, force, omega, steps_per_period=STEPS, harmonics=1, tolerance=1e-8, start=hb)
        rest = steady_state(model, force, omega, steps_per_period=STEPS, harmonics=1, tolerance=1e-8)
        a, b, c = hb.amplitude(tip, 1)[0], on.amplitude(tip, 1), rest.amplitude(tip, 1)
        rows.append({"omega [rad/s]": omega, "harmonic balance [m]": a, "time integration from it [m]": b,
                     "time integration from rest [m]": c, "difference from it [-]": a / b - 1,
                     "difference from rest [-]": a / c - 1, "periods from it [-]": on.periods,
                     "periods from rest [-]": rest.periods})
    return rows


def draw_blade(ax, b) -> None:
    """The mesh (element edges), the contact nodes and the tip."""
    p, t = b.mesh.p, b.mesh.t
    for quad in t.T:
        ax.plot(*p[:, np.append(quad, quad[0])] * 1e3, color="0.75", lw=0.4)
    contacts = np.array([b.position(n) for n in b.platform_nodes]) * 1e3
    ax.plot(*contacts.T, "v", color="C3", label="contact nodes")
    ax.plot(*b.position(b.tip_node) * 1e3, "o", color="C0", label="excitation, output")
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title(f"scikit-fem blade, {b.ndof} DOFs", fontsize=10)
    ax.legend(fontsize=7, loc="upper left")


def main(out=Path("."), dofs: int = 1000) -> list[dict]:
    start = time.perf_counter()
    b, structure, tip = blade_with_contacts(dofs)
    force = np.zeros(structure.ndof)
    force[tip] = FORCE
    curve = frequency_response(structure, force, RANGE, harmonics=5, reduction="modal", modes=40, stability=False)
    peak, _ = curve.peak(tip, 1)
    exact = frequency_point(structure, force, peak, harmonics=5, reduction="exact")
    modal = frequency_point(structure, force, peak, harmonics=5, reduction="modal", modes=40)
    modal_difference = modal.amplitude(tip, 1)[0] / exact.amplitude(tip, 1)[0] - 1
    keep = [structure.dof_index(f"{node}:{c}") for node in b.platform_nodes for c in "xy"] + [tip]
    cb = craig_bampton(structure, keep, modes=10)
    frequencies = sorted([*OFF_PEAK, peak])
    rows = compare(cb.structure, len(keep) - 1, frequencies)
    elapsed = time.perf_counter() - start

    fig, (ax_mesh, ax, ax_diff) = plt.subplots(1, 3, figsize=(14, 4.6), gridspec_kw={"width_ratios": [0.8, 2, 1.3]})
    draw_blade(ax_mesh, b)
    ax.plot(curve.omega, curve.amplitude(tip, 1) * 1e6, color="0.3",
            label=f"harmonic balance, H = 5, 40 modes ({curve.points} points)")
    w = np.array([r["omega [rad/s]"] for r in rows])
    ax.plot(w, [r["time integration from it [m]"] * 1e6 for r in rows], "o", mfc="none", color="C0", ms=8,
            label="time integration from the harmonic balance solution")
    ax.plot(w, [r["time integration from rest [m]"] * 1e6 for r in rows], "x", color="C3",
            label="time integration from rest")
    ax.set_xlabel("excitation frequency ω (rad/s)")
    ax.set_ylabel("tip amplitude, first harmonic (µm)")
    ax.set_title(f"1 N at the tip, four contacts pressed with {PRELOAD:g} N each", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    ax_diff.semilogy(w, [abs(r["difference from it [-]"]) for r in rows], "o-", mfc="none", color="C0",
                     label="from the harmonic balance solution")
    ax_diff.semilogy(w, [abs(r["difference from rest [-]"]) for r in rows], "x-", color="C3", label="from rest")
    ax_diff.axvline(peak, color="0.6", lw=0.8, ls=":")
    ax_diff.set_xlabel("excitation frequency ω (rad/s)")
    ax_diff.set_ylabel("|harmonic balance / time integration - 1|")
    ax_diff.set_title("H = 11 on the Craig-Bampton model (19 DOFs)", fontsize=10)
    ax_diff.grid(True, which="both", alpha=0.3)
    ax_diff.legend(fontsize=7)
    fig.tight_layout()
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    figure, table = out / "fe_blade_response.png", out / "fe_blade_response.csv"
    fig.savefig(figure, dpi=110)
    plt.close(fig)
    with open(table, "w", newline="") as file:
        writer = csv.DictWriter(file, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)

    print(f"blade: {structure.ndof} DOFs, {len(structure.contacts)} contacts; static normal loads "
          f"{', '.join(f'{n:.2f}' for n in curve.static_normal_force)} N of {PRELOAD:g} N pressing")
    print(f"curve: {curve.points} points in {curve.elapsed:.2f} s (modal, 40 modes), peak at {peak:.1f} rad/s; "
          f"error estimate {curve.reduction_error:.1e}, difference to the exact condensation at the peak "
          f"{modal_difference:+.1e}")
    print(f"Craig-Bampton model: {cb.structure.ndof} DOFs (fixed-interface modes up to "
          f"{cb.frequencies[-1]:.3g} rad/s)")
    print("omega (rad/s)   HB (um)     TI from HB (um)  diff       TI from rest (um)  diff")
    for r in rows:
        print(f"{r['omega [rad/s]']:10.1f}   {r['harmonic balance [m]'] * 1e6:9.5f}   "
              f"{r['time integration from it [m]'] * 1e6:9.5f}       {r['difference from it [-]']:+.1e}   "
              f"{r['time integration from rest [m]'] * 1e6:9.5f}          {r['difference from rest [-]']:+.1e}")
    print(f"{elapsed:.1f} s; wrote {figure} and {table}")
    return rows


if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(description="Forced response of a scikit-fem blade with friction contacts "
                                                 "under its platform, against time integration (writes "
                                                 "fe_blade_response.png and fe_blade_response.csv).")
    parser.add_argument("--out", default=".", help="folder to write into (default: the current folder)")
    parser.add_argument("--dofs", type=int, default=1000, help="DOFs of the blade to come close to (default 1000)")
    args = parser.parse_args()
    main(Path(args.out), args.dofs)
