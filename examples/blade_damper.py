"""A blade with an under-platform friction damper: forced response for rising excitation levels.
=============================================================================================

A two-degree-of-freedom blade -- platform (DOF 0, 50 g, 4 N/µm to the disk)
and airfoil tip (DOF 1, 100 g, 10 N/µm to the platform) -- is excited at the
tip. A friction damper, pressed against the platform by its centrifugal load
of 37.5 N, rubs on it along the platform's motion: the contact is the paper's
steel sphere (d = 10 mm, E = 200 GPa, mu = 0.4) tuned with 4 elements at
37.5 N. The damper body is light and free to follow the platform normally, so
its normal load stays at the centrifugal load: the contact's normal approach
is imposed at the one where the tuned contact carries 37.5 N
(``approach=damper.approach(37.5)``, ``normal=None``), all 4 elements closed,
and the static state has no tangential force (the damper starts stuck). A
``preload`` would instead be a force on the structure, shared between the
contact and the structure's springs (see ``Structure.add_contact``; the
inclined block of ``inclined_block.py`` is pressed that way, with a normal
load that varies with the motion).

The curves show the tip amplitude (largest deviation from the static position
over a period) per newton of excitation. At low levels the
damper sticks (the sharp resonance of the blade stiffened by the contact's
tangential stiffness, 8128 rad/s), at high levels it slides at mu N = 15 N (the
sharp resonance of the free blade, 4730 rad/s); in between, the elements slip
one after the other (microslip) and the response is smallest: the classic
family of damper curves with an optimum excitation level.

Run ``python examples/blade_damper.py [--out DIR]`` (about 1 s); writes
``blade_damper.png`` into ``DIR`` (default ``./microslip-examples``). The figure shown in the
README is ``examples/blade_damper.png``, made by this script.
"""

from __future__ import annotations

import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from microslip import Sphere, Structure, frequency_response, tune

LEVELS = [0.01, 0.2, 1.0, 3.0, 7.0, 12.0, 20.0, 100.0]  # excitation amplitude at the tip (N)
NORMAL_LOAD = 37.5  # centrifugal load of the damper (N)
RANGE = (4000.0, 12000.0)  # rad/s: both the free-blade and the stuck-damper resonances


def blade_with_damper(elements: int = 4) -> Structure:
    """The blade and its damper (SI units); the damper is the paper's sphere tuned with ``elements`` elements."""
    m_platform, m_tip = 0.05, 0.1  # kg
    k_root, k_blade = 4e6, 1e7  # N/m
    M = np.diag([m_platform, m_tip])
    K = np.array([[k_root + k_blade, -k_blade], [-k_blade, k_blade]])
    blade = Structure(M, 5e-7 * K, K)  # light stiffness-proportional damping
    damper = tune(Sphere.paper(), NORMAL_LOAD, elements=elements)
    blade.add_contact(damper, tangential=0, approach=float(damper.approach(NORMAL_LOAD)), name="damper")
    return blade


def main(out=Path("microslip-examples") / "blade_damper.png") -> list[tuple[float, float, float]]:
    blade = blade_with_damper()
    fig, (ax, ax_peak) = plt.subplots(1, 2, figsize=(11, 4.4), gridspec_kw={"width_ratios": [2, 1]})
    colours = plt.cm.viridis(np.linspace(0.0, 0.9, len(LEVELS)))
    peaks = []
    start = time.perf_counter()
    for F, colour in zip(LEVELS, colours):
        r = frequency_response(blade, [0.0, F], RANGE, harmonics=5)
        w, a = r.peak(1)
        peaks.append((F, w, a / F))
        ax.semilogy(r.omega, r.amplitude(1) / F * 1e6, color=colour, label=f"F = {F:g} N")
    elapsed = time.perf_counter() - start
    N0, T0, closed = r.static_normal_force[0], r.static_tangential_force[0], r.static_closed_elements[0]
    ax.set_xlabel("excitation frequency ω (rad/s)")
    ax.set_ylabel("tip amplitude / F (µm/N)")
    ax.set_title(f"Blade with a friction damper (sphere contact, 4 elements, N = {N0:g} N)", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, ncol=2)
    F, _, amp = np.array(peaks).T
    ax_peak.loglog(F, amp * 1e6, "o-", color="0.3")
    best = int(np.argmin(amp))
    ax_peak.annotate("optimum", (F[best], amp[best] * 1e6), textcoords="offset points", xytext=(8, 4),
                     ha="left", fontsize=8)
    ax_peak.set_xlabel("excitation amplitude F (N)")
    ax_peak.set_ylabel("peak tip amplitude / F (µm/N)")
    ax_peak.set_title("stuck → optimum → sliding", fontsize=10)
    ax_peak.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=120)
    print(f"{len(LEVELS)} curves in {elapsed:.2f} s; wrote {out}")
    print(f"static state of the damper: N0 = {N0:.4g} N, T0 = {T0:.3g} N, {closed} of 4 elements closed")
    print("F (N)   peak omega (rad/s)   peak tip amplitude / F (um/N)")
    for F, w, a in peaks:
        print(f"{F:6.2f}   {w:10.1f}           {a * 1e6:8.3f}")
    return peaks


if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(description="Forced response of a blade with a friction damper, stuck to "
                                                 "sliding (writes blade_damper.png).")
    parser.add_argument("--out", default="microslip-examples", help="folder to write into (default "
                                                                    "./microslip-examples)")
    main(Path(parser.parse_args().out) / "blade_damper.png")
