"""A bolted lap joint: the first bending nonlinear mode, its frequency and damping against amplitude.
==================================================================================================

Two steel plates (240 x 30 x 12 mm, each half as thick over their 120 mm overlap, as in the Brake--Reuss
beam) are clamped at their far ends and bolted by three bolts of 10 kN. ``microslip.fe.lap_joint`` meshes
them with scikit-fem's 27-node hexahedra, finds the interface's node pairs (tributary areas, normals,
tangents) with ``contact_patch`` and reduces the plates to the pairs' relative displacements plus 40
tied-interface modes. ``microslip.frequency.jointed_structure`` puts an elastic--dry-friction element
(``PressureLaw``: normal and tangential stiffness per unit area, mu = 0.6) on every pair but the pairs
tied around the bolts, and the bolts' clamping as a static load.

The joint is prestressed by the bolts with the friction released (``microslip.prestress``: the static state
of a frictionless interface, every pair's sliders then reset there, the jointed-structure procedure), then its first
bending mode is followed from the stuck joint to the onset of gross slip by the extended periodic motion
concept (``microslip.nonlinear_modes``, harmonics 0-3, 128 samples): the natural frequency falls and the
damping ratio rises as the pairs far from the bolts (lightly pressed) slip one after the other.

Run ``python examples/bolted_lap_joint.py [--out DIR] [--quick]``: the default is the 120-contact model
(481 DOFs; several minutes), ``--quick`` the 30-contact one over a shorter range (under a minute). Writes
``bolted_lap_joint.png`` into ``DIR`` (default ``./microslip-examples``).
"""

from __future__ import annotations

import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from microslip import nonlinear_modes, prestress
from microslip.fe import lap_joint
from microslip.frequency import StepControl, jointed_structure

#: (contacts, tied-interface modes, modal amplitudes (kg^1/2 m), continuation step (the range is 1))
SETTINGS = {False: (120, 40, (3e-7, 1e-4), None), True: (30, 10, (1e-6, 1.2e-5), 1 / 12)}


def main(out=Path("microslip-examples") / "bolted_lap_joint.png", quick: bool = False):
    """The joint's first bending nonlinear mode (a NonlinearModes), its figure written to ``out``."""
    contacts, modes, amplitude, step = SETTINGS[bool(quick)]
    start = time.perf_counter()
    joint = lap_joint(contacts, modes=modes)
    structure = jointed_structure(joint)
    # the bolts tighten with the interface free to slide; the dynamics start stuck at that state
    bolted = prestress(structure, friction="released")
    built = time.perf_counter() - start
    control = None if step is None else StepControl(ds_initial=step, ds_max=step, max_points=60)
    start = time.perf_counter()
    mode = nonlinear_modes(structure, 1, amplitude, harmonics=3, samples=128, control=control, prestress=bolted)
    elapsed = time.perf_counter() - start

    closed = int(np.count_nonzero(bolted.closed_elements))
    f, zeta = mode.frequency("Hz"), mode.damping_ratio
    fig, (ax_f, ax_z) = plt.subplots(1, 2, figsize=(10, 4))
    mode.plot(axes=(ax_f, ax_z), label=f"{joint.contacts} contacts", color="C0", marker=".")
    ax_f.axhline(joint.tied_frequencies[0] / (2 * np.pi), color="0.5", ls="--", label="tied interface (monolithic)")
    ax_f.set_title(f"Bolted lap joint: first bending mode ({joint.contacts} contacts, 3 x "
                   f"{joint.geometry['bolt_load'] / 1e3:g} kN)", fontsize=10)
    ax_f.legend(fontsize=8)
    ax_z.set_title(f"damping ratio (viscous {100 * mode.viscous_damping_ratio[0]:.2f} % + contacts)", fontsize=10)
    fig.tight_layout()
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=120)
    plt.close(fig)
    print(f"lap joint: {joint.ndof} DOFs ({len(joint.patch)} pairs, {joint.contacts} contacts, "
          f"{joint.tied_pairs.size} tied), built and prestressed in {built:.1f} s: {closed} of {joint.contacts} "
          f"contacts pressed by the bolts")
    print(f"first bending mode: monolithic beam {joint.monolithic_frequency() / (2 * np.pi):.1f} Hz (Euler-Bernoulli), "
          f"tied interface {joint.tied_frequencies[0] / (2 * np.pi):.1f} Hz, stuck joint {f[0]:.2f} Hz")
    print(f"nonlinear mode: {mode.points} points in {elapsed:.1f} s; modal amplitude {mode.modal_amplitude[0]:.2e} to "
          f"{mode.modal_amplitude[-1]:.2e} kg^1/2 m: {f[0]:.2f} to {f[-1]:.2f} Hz, damping ratio "
          f"{100 * zeta[0]:.3f} to {100 * zeta[-1]:.3f} %; wrote {out}")
    return mode


if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(description="The first bending nonlinear mode of a bolted lap joint "
                                                 "(writes bolted_lap_joint.png).")
    parser.add_argument("--out", default="microslip-examples", help="folder to write into (default "
                                                                    "./microslip-examples)")
    parser.add_argument("--quick", action="store_true", help="the 30-contact model over a shorter range (< 1 min)")
    args = parser.parse_args()
    main(Path(args.out) / "bolted_lap_joint.png", quick=args.quick)
