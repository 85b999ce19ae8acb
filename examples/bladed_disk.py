"""A bladed disk with an under-platform damper between every pair of blades, engine order 3.
=========================================================================================

24 blades clamped in a rigid disk, each the plane-stress finite-element blade of
``microslip.fe.blade`` (nickel alloy, E = 200 GPa, nu = 0.3, 8190 kg/m^3, 3 mm thick; a 16 mm shank
under a 40 mm x 6 mm platform, a 60 mm x 20 mm airfoil; about 4000 DOFs, first mode 1890 Hz),
stiffness-proportional damping (2e-7 s: 0.12 % at the first mode), reduced by Craig--Bampton onto
the DOFs the dampers and the excitation use (the platform's contact nodes and the tip) plus 20
fixed-interface modes. Between every pair of neighbouring platforms sits a curved-flat
under-platform damper (5 g, 2e-8 kg m^2, cobalt alloy E = 225 GPa, nu = 0.29): its flat face presses
on the underside of one blade's platform through two contacts 4 mm apart (a flat punch with rounded
edges, 1 mm flat and 5 mm edge radius, by the method of dimensionality reduction), its curved face on
the next blade's platform through one line contact (a 10 mm radius cylinder-like curved face, tuned
as the paper's sphere); both materials' moduli enter the contacts (E*, G* of the pair), mu = 0.5, each
law tuned with J = 8 elements at 1000 N. The faces' normals are inclined at 40 degrees from the
radial direction, pointing from the damper into each platform (the platform's underside is taken
inclined there; the finite-element platform is rectangular and only the contact directions carry
the angle), and pass through the damper's centre of mass. Every blade tip is excited
circumferentially by a travelling wave of engine order 3 (0.1 N), so one sector is solved with
cyclic symmetry (harmonic h in nodal diameter 3h mod 24), H = 5 harmonics.

The damper's centrifugal load runs from 3 N (the flat face rocks, its contacts lifting off in turn for
about half of the cycle, and the forced response bends back to lower frequencies as the damper slips more)
to 320 N (it sticks: the blades are coupled by the stuck contacts and the resonance moves up towards the
stuck limit); the lowest peak lies between. At 3 N the curve folds back and forth some 350 times (about
4800 points); below about 2.5 N the continuation does not reach the end of the range (at 2 N it wanders
between 11.4 and 12.3 krad/s through some 1000 folds in 20000 points, the flat face's contacts open for up
to 98 % of the cycle), so the curve starts at 3 N; its limit at zero load is the blade without damper,
drawn for reference. Figures: ``bladed_disk.png`` (the forced responses, and the peak against the
centrifugal load: the design curve) and ``bladed_disk_contacts.png`` (each contact's normal and
tangential force over one period at the lowest peak, with its slip state).

Run ``python examples/bladed_disk.py [--out DIR] [--quick]`` (about 2.5 minutes; ``--quick``: two loads,
about 20 s). It writes into ``DIR`` (default: the current folder) and
never over a file tracked by git. The figure in the README is ``examples/bladed_disk.png``.
"""

from __future__ import annotations

import subprocess
import time
import warnings
from pathlib import Path

import matplotlib
import matplotlib.ticker

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from microslip import Sphere, mdr, tune
from microslip.fe import blade, natural_frequencies
from microslip.frequency import (CyclicStructure, StepControl, Structure, UnderPlatformDamper, UnderResolvedWarning,
                                 contact_cycle, craig_bampton, damper_design_curve, frequency_response,
                                 plot_contact_cycles)
from microslip.reference.profiles import RoundedPunch

SECTORS, ENGINE_ORDER = 24, 3
TIP_FORCE = 0.1  # N, circumferential, on every blade tip
LOADS = [3.0, 4.0, 5.0, 10.0, 20.0, 40.0, 80.0, 160.0, 320.0]  # N: the damper's centrifugal loads
QUICK_LOADS = [40.0, 320.0]
RANGE = (9000.0, 18000.0)  # rad/s: the free blade's first mode (11.6 krad/s) to beyond the stuck one
PAIR = dict(E=200e9, nu=0.3, E2=225e9, nu2=0.29, mu=0.5)  # blade (nickel alloy) on damper (cobalt alloy)
TUNING_LOAD = 1000.0  # N
ANGLE = np.radians(40.0)  # the faces' normals from the radial direction
TIP = 6  # the tip's x DOF in the reduced sector (after the platform's six)


def contact_laws(elements: int = 8):
    """``(flat, curved)``: the flat face's contact law (a rounded punch, MDR) and the curved face's, J elements."""
    punch = mdr(Sphere(radius=5e-3, **PAIR), max_load=TUNING_LOAD, elements=2000, profile=RoundedPunch(1e-3, 5e-3))
    return (tune(punch.as_reference(), TUNING_LOAD, elements=elements),
            tune(Sphere(radius=10e-3, **PAIR), TUNING_LOAD, elements=elements))


def sector(dofs: int = 4000, modes: int = 20) -> tuple[CyclicStructure, float]:
    """One blade of the disk reduced by Craig--Bampton; returns it and the blade's first natural frequency (rad/s).

    Reduced DOFs: x, y of the right overhang's contact nodes 16 mm and 20 mm from the axis (0-3), x, y of the
    left overhang's node 18 mm from it (4, 5: where the previous blade's damper presses), the tip's x (6), then
    the modal coordinates.
    """
    b = blade(dofs, shank_width=0.016, platform_height=0.006)
    right, left = b.node_sets["platform_right"], b.node_sets["platform_left"]  # outer edge first
    keep = [b.dof_map.index(f"{n}:{c}") for n in (right[2], right[0], left[1]) for c in "xy"]
    keep.append(b.dof_map.index(f"{b.tip_node}:x"))
    disk = CyclicStructure(b.M, 2e-7 * b.K, b.K, sectors=SECTORS, left=[], right=[])  # a rigid disk
    cb = craig_bampton(disk, keep, modes=modes)
    return cb.structure, 2 * np.pi * float(natural_frequencies(b.M, b.K, 1)[0])


def damper(s: CyclicStructure, laws, load: float) -> UnderPlatformDamper:
    """The curved-flat damper between this blade's right overhang (flat face) and the next blade's left one."""
    flat, curved = laws
    d = UnderPlatformDamper(0.005, 2e-8, centrifugal_load=load, damping=100.0)
    mid = 4e-3 / np.tan(ANGLE)  # the faces' middles on their normals through the centre of mass
    lift = 2e-3 * np.tan(ANGLE)
    d.add_interface(flat, points=[(-6e-3, mid - lift), (-2e-3, mid + lift)], angle=np.pi / 2 + ANGLE,
                    platform=[{"x": 0, "y": 1}, {"x": 2, "y": 3}], name="flat")
    d.add_interface(curved, points=[(4e-3, mid)], angle=np.pi / 2 - ANGLE, platform={"x": s.next(4), "y": s.next(5)},
                    name="curved")
    return d


def references(s: CyclicStructure, laws, force, harmonics: int) -> dict:
    """The two limits of the design curve: the blade without damper, and with the damper stuck (linear)."""
    bare = Structure(s.M, s.C, s.K)
    free = frequency_response(bare, force, RANGE, harmonics=1)
    sticky = tuple(type(m)(m.kt, m.kn, m.gaps, 1e3) for m in laws)  # friction that never lets go
    stuck = frequency_response(damper(s, sticky, LOADS[-1]).attach(s), np.append(force, np.zeros(3)), RANGE,
                               harmonics=harmonics, engine_order=ENGINE_ORDER)
    return {"no damper": free, "damper stuck": stuck}


def _writable(path: Path) -> Path:
    """``path``, unless it is a file tracked by git (the example never overwrites one)."""
    if path.exists():
        try:
            tracked = subprocess.run(["git", "ls-files", "--error-unmatch", path.name], cwd=path.parent,
                                     capture_output=True).returncode == 0
        except OSError:  # no git: nothing is tracked
            tracked = False
        if tracked:
            raise SystemExit(f"{path} is tracked by git: choose another folder with --out")
    return path


def main(out=Path("."), quick: bool = False) -> dict:
    start = time.perf_counter()
    harmonics = 5
    loads = QUICK_LOADS if quick else LOADS
    s, w_free = sector()
    laws = contact_laws()
    force = np.zeros(s.ndof)
    force[TIP] = TIP_FORCE
    with warnings.catch_warnings():
        # where a contact lifts off, 128 samples per period leave the contacts' energy per cycle uncertain by up
        # to 5 % of the excitation's work; the amplitudes are resolved (the peaks move by less than 1e-3 with
        # 512 samples, at 5 N and at 40 N)
        warnings.simplefilter("ignore", UnderResolvedWarning)
        # at 3 N the curve folds back and forth some 350 times (the flat face rocking, its contacts lifting off in
        # turn): about 4800 points, close to the default limit of 5000
        curve = damper_design_curve(s, damper(s, laws, loads[0]), loads, force, RANGE, dof=TIP,
                                    harmonics=harmonics, engine_order=ENGINE_ORDER,
                                    control=StepControl(max_points=10000))
        limits = references(s, laws, force, harmonics)
    best = int(np.argmin(curve.peak_amplitude))
    at_best = curve.responses[best]
    k = int(np.argmax(at_best.amplitude(TIP)))
    cycles = [contact_cycle(at_best, c, k) for c in range(len(at_best.structure.contacts))]
    elapsed = time.perf_counter() - start

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    figure = _writable(out / "bladed_disk.png")
    contacts = _writable(out / "bladed_disk_contacts.png")
    fig, (ax, ax_d) = plt.subplots(1, 2, figsize=(12, 4.6), gridspec_kw={"width_ratios": [1.5, 1]})
    colours = plt.cm.viridis(np.linspace(0.0, 0.9, len(loads)))
    hz = 1 / (2 * np.pi)
    for load, r, colour in zip(loads, curve.responses, colours):
        ax.semilogy(r.omega * hz, r.amplitude(TIP) * 1e6, color=colour, label=f"{load:g} N")
    styles = {"no damper": "--", "damper stuck": ":"}
    for name, r in limits.items():
        ax.semilogy(r.omega * hz, r.amplitude(TIP) * 1e6, styles[name], color="0.35", label=name)
    ax.set_xlabel("excitation frequency f (Hz)")
    ax.set_ylabel("blade tip: max |x - x0| over a period (µm)")
    ax.set_title(f"Forced response: {SECTORS} blades, engine order {ENGINE_ORDER}, {TIP_FORCE:g} N at each tip",
                 fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, ncol=2, title="damper's centrifugal load", title_fontsize=8)
    ax_d.plot(curve.loads, curve.peak_amplitude * 1e6, "o-", color="k", label="peak response")
    ax_d.plot(curve.loads[best], curve.peak_amplitude[best] * 1e6, "*", ms=14, color="C1",
              label=f"lowest computed: {curve.loads[best]:g} N")
    for (name, r), limit in zip(limits.items(), ("load → 0", "load → ∞")):
        peak = r.peak(TIP)[1] * 1e6
        ax_d.axhline(peak, ls=styles[name], color="0.35", lw=1, label=f"{limit}: {name} ({peak:.3g} µm)")
    ax_d.set_xscale("log")
    ax_d.xaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
    ax_d.set_xlabel("damper's centrifugal load (N)")
    ax_d.set_ylabel("peak of the blade tip (µm)")
    ax_d.set_title("Design curve: the peak against the damper's load", fontsize=10)
    ax_d.grid(True, which="both", alpha=0.3)
    ax_d.set_ylim(0.0, None)
    ax_d.legend(fontsize=8, loc="upper left", bbox_to_anchor=(0.0, 0.93))  # below the no-damper line
    fig.tight_layout()
    fig.savefig(figure, dpi=130)
    plt.close(fig)

    fig = plot_contact_cycles(cycles, f"Contact forces over one period at the lowest peak ({loads[best]:g} N, "
                                      f"{curve.peak_frequency[best] * hz:.1f} Hz): the flat face's two contacts "
                                      f"and the curved face's")
    fig.savefig(contacts, dpi=130, bbox_inches="tight")
    plt.close(fig)

    print(f"sector: {s.ndof} Craig-Bampton DOFs (blade's first mode {w_free * hz:.0f} Hz) + a damper of "
          f"{len(cycles)} contacts; {len(loads)} loads in {elapsed:.1f} s; wrote {figure} and {contacts}")
    print("load (N)   peak (µm)   at (Hz)   static normal loads (N)   damper balance")
    d = damper(s, laws, loads[0])  # its balance takes the load each response was solved at
    for load, r, a, w in zip(loads, curve.responses, curve.peak_amplitude, curve.peak_frequency):
        print(f"{load:8.3g}   {a * 1e6:9.4g}   {w * hz:7.1f}   {np.round(r.static_normal_force, 2)}   "
              f"{d.static_balance(r):.1e}")
    for name, r in limits.items():
        w, a = r.peak(TIP)
        print(f"{name}: peak {a * 1e6:.4g} µm at {w * hz:.1f} Hz")
    for cy in cycles:
        print(f"{cy.name} at the lowest peak: N {cy.N.min():.3g} to {cy.N.max():.3g} N; {cy.summary()}")
    return {"curve": curve, "limits": limits, "cycles": cycles, "free": w_free, "sector": s, "laws": laws}


if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(description="A bladed disk with under-platform dampers: forced responses from "
                                                 "stuck to sliding, the design curve, the contact forces (writes "
                                                 "bladed_disk.png and bladed_disk_contacts.png).")
    parser.add_argument("--out", default=".", help="folder to write into (default: the current folder)")
    parser.add_argument("--quick", action="store_true", help="two loads only")
    args = parser.parse_args()
    main(Path(args.out), quick=args.quick)
