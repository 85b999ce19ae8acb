"""Harmonic balance against time integration on the blade pair with its under-platform damper.

The blade pair and damper of ``tests/frequency/test_damper.py``. Two cases:

1. The flat face lifting off (50 N, 20 N at blade 0's tip, 2.5 % damping at the blades' mode,
   2000 1/s on the damper: ``lifting_pair``): every contact element slips or opens during each
   cycle, so the steady state forgets how it was reached. The difference between harmonic
   balance and time integration (largest difference of any DOF's Fourier coefficient, over the
   largest dynamic one) at five frequencies including the peak, against the harmonics ``H``, the
   AFT samples and the time step: it is the harmonics' truncation (lift-off puts kinks in the
   normal force, whose harmonics decay slowly), not the sampling nor the time step.
2. The lightly damped pair of the tests (50 N, 5 N at the tip, no lift-off) below its peak:
   elements of each contact stick through the whole cycle. Their force is the one they took
   when they last slipped, before the steady state -- in harmonic balance, the single static step
   from the unloaded contact to the mean of the motion; in time integration from rest, somewhere
   in the transient from the static equilibrium. Those two steady states differ by that history
   (the damper's mean rotation, i.e. how the load splits between the flat face's contacts),
   whatever H. Time integration started on the harmonic balance solution, its contacts in the
   state harmonic balance assumes (``steady_state(start=frequency_point(...))``), compares like
   with like: what is left is the truncation of the harmonics and the time step.

Run ``python scripts/damper_time_integration.py [lifting] [sticking]`` (both by default; about 2 minutes
on one core).
"""

from __future__ import annotations

import sys
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "frequency"))

from microslip.kernels.element import STICK  # noqa: E402
from microslip.frequency import (UnderResolvedWarning, frequency_point, frequency_response,  # noqa: E402
                                 steady_state)
from test_damper import blade_pair, damper, lifting_pair, steady_contacts, tip_force  # noqa: E402

TARGETS = (3800.0, 3880.0, 4000.0, 4200.0)  # rad/s, with the peak


def difference(result, k, ti) -> float:
    """Largest difference of any DOF's coefficient, over the largest dynamic coefficient of the time integration."""
    return float(np.abs(result.coefficients[k] - ti.coefficients).max() / np.abs(ti.coefficients[1:]).max())


def points(result) -> list[int]:
    """The curve's points nearest the target frequencies, and its highest point."""
    peak = int(np.argmax(result.amplitude(2)))
    return sorted({int(np.argmin(np.abs(result.omega - w))) for w in TARGETS} | {peak})


def lifting(harmonics=(5, 9, 15, 25), samples=(None, 1024), steps=(2048, 8192)) -> None:
    s = lifting_pair()
    force = tip_force(s, 20.0)
    print("1. flat face lifting off (50 N, 20 N at the tip): harmonic balance - time integration")
    print("   H  samples  steps   " + "  ".join(f"{'w (rad/s)':>9} {'diff':>8}" for _ in range(5)))
    for H in harmonics:
        for Ns in samples:
            r = frequency_response(s, force, (3700.0, 4300.0), harmonics=H, samples=Ns, stability=False)
            for n_steps in (steps if (H == 15 and Ns is None) else steps[:1]):
                if Ns is not None and H != 15:
                    continue
                row = []
                for k in points(r):
                    ti = steady_state(s, force, float(r.omega[k]), harmonics=H, steps_per_period=n_steps,
                                      tolerance=1e-9)
                    row.append(f"{r.omega[k]:9.1f} {difference(r, k, ti):8.1e}")
                print(f"  {H:3d}  {r.samples:7d}  {n_steps:5d}   " + "  ".join(row), flush=True)
    r = frequency_response(s, force, (3700.0, 4300.0), harmonics=15, stability=False)
    print("   at those points (H = 15): fraction of the period each contact is open, elements stuck throughout")
    for k in points(r):
        contacts = steady_contacts(r, k)
        open_ = [float(np.mean(N == 0.0)) for _, N in contacts]
        stuck = [int(np.all(c == STICK, axis=0).sum()) for c, _ in contacts]
        print(f"   {r.omega[k]:9.1f}  open {np.round(open_, 3)}  stuck throughout {stuck}")


def sticking(omegas=(3700.0, 3850.0), harmonics=(5, 15), steps=(2048, 8192)) -> None:
    s = damper(load=50.0).attach(blade_pair())
    force = tip_force(s, 5.0)
    R = s.ndof - 1
    print("2. lightly damped pair, 5 N at the tip, no lift-off: elements stuck through the cycle; time integration "
          "from rest, and started on the harmonic balance solution (start=)")
    for H in harmonics:
        for w in omegas:
            hb = frequency_point(s, force, w, harmonics=H, stability=False)
            stuck = [int(np.all(c == STICK, axis=0).sum()) for c, _ in steady_contacts(hb, 0)]
            rest = steady_state(s, force, w, harmonics=H, steps_per_period=steps[0], tolerance=1e-9)
            print(f"   H = {H:2d}, w = {w:7.1f}: elements stuck throughout {stuck}; damper's mean rotation (arc, m) "
                  f"HB {hb.coefficients[0, 0, R]:+.3e}", flush=True)
            for name, ti in [("from rest", rest)] + [
                    (f"on HB, {n} steps", steady_state(s, force, w, harmonics=H, steps_per_period=n, tolerance=1e-9,
                                                       start=hb)) for n in steps]:
                tip = np.hypot(*hb.coefficients[0, 1:3, 2]) / np.hypot(*ti.coefficients[1:3, 2]) - 1
                print(f"     {name:>19}: tip's first harmonic {tip:+.1e}, every coefficient {difference(hb, 0, ti):.1e}"
                      f"; mean rotation {ti.coefficients[0, R]:+.3e} ({ti.periods} periods)", flush=True)


def main(cases=("lifting", "sticking")) -> None:
    start = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnderResolvedWarning)
        for case in cases:
            {"lifting": lifting, "sticking": sticking}[case]()
    print(f"{time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(description="Harmonic balance against time integration on the damper pair.")
    parser.add_argument("cases", nargs="*", choices=["lifting", "sticking"], help="the cases to run (default: both)")
    main(parser.parse_args().cases or ("lifting", "sticking"))
