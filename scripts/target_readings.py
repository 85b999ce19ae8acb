"""Calibrate the target family of issue 3 (item 4): which reading gives "about 16" for even displacement points.

The issue's target family is "the default family restricted to N >= 0.2 N_tot
and tangential amplitudes of at least half the gross-slip displacement at the
path's lowest load"; its authors measured that points evenly spaced in
displacement need about 16 elements for 2 % / 2 %. This script measures the
smallest J meeting 2 % / 2 % with even displacement points (and the errors at
J = 16) under several readings of the loads and several samplings of the
amplitudes and load levels, and the stored optimised points on a dense
sampling. Run::

    python scripts/target_readings.py          # about 30 s on 2 shared cores

Readings of the loads (``N_tot`` = 37.5 N, the tuning load):

peak
    the project's default family: the peak load ``N_m + N_a`` runs from 0.1
    to 1 ``N_tot`` and the path's lowest load ``N_m - N_a >= 0.2 N_tot``;
mean, capped
    the mean load ``N_m`` runs from 0.1 to 1 ``N_tot``, paths whose peak
    exceeds ``N_tot`` dropped, lowest load ``>= 0.2 N_tot``;
mean, lowest >= 0.2
    mean loads 0.1 to 1 ``N_tot`` with ``N_a / N_m`` up to 0.9 (peaks up to
    1.9 ``N_tot``, beyond the tuning load), lowest load ``>= 0.2 N_tot``;
mean, mean >= 0.2
    the same with the restriction on the mean load;
peak, mean >= 0.2
    the default family restricted on the mean load ``N_m >= 0.2 N_tot``.
"""

from __future__ import annotations

import numpy as np

from microslip import Sphere, mdr, tune
from microslip.accuracy import accuracy, reference_run
from microslip.paths import AMPLITUDES, LEVELS, PHASES_DEG, RATIOS, variable_load_cycles
from microslip.tuning.target import load_optimal_points

SPHERE = Sphere.paper()
N_TOT = 37.5
T_GS = float(SPHERE.gross_slip_displacement(N_TOT))
ELEMENTS = range(8, 33)

READINGS = {
    "peak (default)": dict(levels_of="peak", restrict="lowest", cap=True),
    "mean, capped": dict(levels_of="mean", restrict="lowest", cap=True),
    "mean, lowest >= 0.2": dict(levels_of="mean", restrict="lowest", cap=False),
    "mean, mean >= 0.2": dict(levels_of="mean", restrict="mean", cap=False),
    "peak, mean >= 0.2": dict(levels_of="peak", restrict="mean", cap=True),
}
AMPLITUDE_GRIDS = {
    "default (0.1 ... 3, 9)": AMPLITUDES,
    "0.1, 0.3, 1, 3": (0.1, 0.3, 1.0, 3.0),
    "10 linear 0.1 ... 3": tuple(np.linspace(0.1, 3.0, 10)),
    "dense: 40 geometric 0.5 ... 3": tuple(np.geomspace(0.5, 3.0, 40)),
}
LEVEL_GRIDS = {
    "default (5)": LEVELS,
    "0.1, 0.25, 0.5, 0.75, 1": (0.1, 0.25, 0.5, 0.75, 1.0),
    "10 linear": tuple(np.linspace(0.1, 1.0, 10)),
}


def family(levels_of, restrict, cap, amplitudes=AMPLITUDES, levels=LEVELS, steps_per_cycle=180):
    """The restricted target family under one reading (N_lo = 0.2 N_tot, amplitudes >= 0.5)."""
    paths = []
    for r in RATIOS:
        for phi in PHASES_DEG[:1] if r == 0 else PHASES_DEG:
            for lev in levels:
                Nm = lev * N_TOT / (1 + r) if levels_of == "peak" else lev * N_TOT
                Na = r * Nm
                low = Nm - Na if restrict == "lowest" else Nm
                if low < 0.2 * N_TOT * (1 - 1e-12) or (cap and Nm + Na > N_TOT * (1 + 1e-12)):
                    continue
                tgs = float(SPHERE.gross_slip_displacement(Nm - Na))
                paths += [variable_load_cycles(SPHERE, Nm, Na, a * tgs, np.radians(phi), cycles=2,
                                               steps_per_cycle=steps_per_cycle)
                          for a in amplitudes if a >= 0.5 * (1 - 1e-12)]
    return paths


def worst(model, run):
    r = accuracy(model, run)
    return float(np.nanmax(np.abs(r.energy_error))), float(np.max(r.force_difference))


def smallest_even_displacement(paths):
    """(first J meeting 2 %/2 %, first J from which every larger J meets, errors at J = 16)."""
    peak = max(float(p.N.max()) for p in paths)
    run = reference_run(mdr(SPHERE, max_load=peak * (1 + 1e-9), elements=2000), paths)
    errors = {J: worst(tune(SPHERE, N_TOT, displacements=T_GS * np.arange(1, J + 1) / J), run) for J in ELEMENTS}
    ok = [J for J in ELEMENTS if max(errors[J]) <= 0.02]
    onwards = [J for J in ELEMENTS if all(max(errors[K]) <= 0.02 for K in ELEMENTS if K >= J)]
    return (ok[0] if ok else None), (onwards[0] if onwards else None), errors[16]


def main():
    print("smallest J with even displacement points meeting 2 % / 2 % (J = 8..32)")
    print(f"{'reading':22s} {'amplitudes':32s} {'levels':26s} {'paths':>5s} {'first':>5s} {'onwards':>7s}  J=16 e/f %")
    cases = [(rd, ag, lg) for rd in READINGS for ag in AMPLITUDE_GRIDS for lg in LEVEL_GRIDS
             if rd.startswith(("peak", "mean, capped")) or (ag.startswith("default") and lg.startswith("default"))]
    for rd, ag, lg in cases:
        paths = family(**READINGS[rd], amplitudes=AMPLITUDE_GRIDS[ag], levels=LEVEL_GRIDS[lg])
        first, onwards, (e, f) = smallest_even_displacement(paths)
        print(f"{rd:22s} {ag:32s} {lg:26s} {len(paths):5d} {first!s:>5s} {onwards!s:>7s}  {100 * e:.2f}/{100 * f:.2f}",
              flush=True)
    print("\nstored optimised points (src/microslip/data/optimal_points.json): worst energy / force (%)")
    fractions = load_optimal_points()["fractions"]
    for name, (ag, lg) in {"default sampling": ("default (0.1 ... 3, 9)", "default (5)"),
                           "dense amplitudes": ("dense: 40 geometric 0.5 ... 3", "default (5)"),
                           "dense amplitudes and levels": ("dense: 40 geometric 0.5 ... 3", "10 linear")}.items():
        paths = family(**READINGS["peak (default)"], amplitudes=AMPLITUDE_GRIDS[ag], levels=LEVEL_GRIDS[lg])
        run = reference_run(mdr(SPHERE, max_load=N_TOT, elements=2000), paths)
        cells = [f"J={J}: " + "/".join(f"{100 * x:.3g}" for x in worst(tune(SPHERE, N_TOT, displacements=T_GS * u),
                                                                          run))
                 for J, u in sorted(fractions.items()) if 8 <= J <= 20]
        print(f"{name:28s} ({len(paths)} paths) " + ", ".join(cells), flush=True)


if __name__ == "__main__":
    main()
