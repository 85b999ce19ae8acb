"""Speed of a nonlinear mode of a finite-element blade: the extended periodic motion concept on the contact DOFs.

Run:  OPENBLAS_NUM_THREADS=1 python benchmarks/bench_modes.py
      python benchmarks/bench_modes.py --dofs 1000 --contacts 40 --harmonics 3 --decades 3

The structure is bench_fe_scale.py's: ``microslip.fe.blade`` (about 10^3 DOFs: 1384), damping
``C = 2e-7 K``, one contact on each of the 40 platform nodes (the paper's sphere tuned with J = 8
elements at 37.5 N, normal load held), harmonics 0-3. Its first bending mode, from the linear mode with
the contacts stuck (1643 Hz) at modal amplitude 1e-7 kg^1/2 m through three decades, to gross slip
(1380 Hz), on the exact reduction onto the 40 contact DOFs (``reduction="auto"``). Reported: the mode's
wall time (target: below 10 s) and points, and, as the baseline measured in the same run, the forced
response of the same structure by harmonic balance over 1200-1800 Hz with the same harmonics and reduction
(bench_fe_scale.py's excitation, 40 N at the tip); their ratio, and how far the forced response's peak lies
from the mode's backbone at the peak's modal amplitude (phase resonance).

The side-by-side with tmdsimpy's EPMC (MIT, not on PyPI), on this blade reduced by Craig-Bampton with
Jenkins contacts, is bench_tmdsimpy.py (run with ``TMDSIMPY_PATH`` naming a local copy of tmdsimpy).
"""

from __future__ import annotations

import argparse
import os
import sys
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_fe_scale import RANGE, blade_case  # noqa: E402  (the same blade, contacts and excitation)

TARGET = 10.0  # s: the mode over three decades


def warm_up():
    """A small mode, so that Numba's compiled kernels are loaded before anything is timed."""
    from microslip import nonlinear_modes

    structure, _, _, _ = blade_case(300, 2)
    nonlinear_modes(structure, 1, (1e-7, 1e-6), harmonics=3)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dofs", type=int, default=1000, help="blade size asked for (default 1000: 1384 DOFs)")
    parser.add_argument("--contacts", type=int, default=40, help="contacts, an even number (default 40)")
    parser.add_argument("--harmonics", type=int, default=3, help="harmonics H (default 3)")
    parser.add_argument("--decades", type=float, default=3.0, help="decades of modal amplitude from 1e-7 (default 3)")
    args = parser.parse_args(argv)

    from microslip import frequency_response, nonlinear_modes

    warm_up()
    structure, force, tip, _ = blade_case(args.dofs, args.contacts)
    amplitude = (1e-7, 1e-7 * 10 ** args.decades)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # an under-resolved contact energy is not what is measured here
        t0 = time.perf_counter()
        mode = nonlinear_modes(structure, 1, amplitude, harmonics=args.harmonics)
        t_mode = time.perf_counter() - t0
        t0 = time.perf_counter()
        curve = frequency_response(structure, force, RANGE, harmonics=args.harmonics, reduction=mode.reduction,
                                   stability=False)
        t_curve = time.perf_counter() - t0
    w_peak, a_peak = curve.peak(structure.M @ mode.linear_mode, 1)
    backbone = np.interp(np.log(a_peak), np.log(mode.modal_amplitude), mode.omega)
    hz = 1 / (2 * np.pi)
    print(f"blade: {structure.ndof} DOFs, {args.contacts} contacts of J = 8, harmonics 0-{args.harmonics}, "
          f"reduction {mode.reduction!r} onto {mode.dofs.size} DOFs; load average {os.getloadavg()[0]:.2f} "
          f"(2 cores shared)")
    print(f"mode 1 over modal amplitude {amplitude[0]:.0e} to {amplitude[1]:.0e} kg^1/2 m: {t_mode:.2f} s, "
          f"{mode.points} points, {mode.omega[0] * hz:.1f} to {mode.omega[-1] * hz:.1f} Hz, damping ratio up to "
          f"{100 * mode.damping_ratio.max():.2f} % (target {TARGET:.0f} s: {'met' if t_mode < TARGET else 'MISSED'})")
    print(f"baseline, the forced response over {RANGE[0] * hz:.0f}-{RANGE[1] * hz:.0f} Hz: {t_curve:.2f} s, "
          f"{curve.points} points; mode / forced response = {t_mode / t_curve:.2f}")
    print(f"the forced peak (modal amplitude {a_peak:.3g} kg^1/2 m at {w_peak * hz:.2f} Hz) lies "
          f"{abs(backbone / w_peak - 1):.1e} from the backbone in frequency")
    print("tmdsimpy: its EPMC side by side with this one on a Craig-Bampton blade with Jenkins contacts: "
          "TMDSIMPY_PATH=/path/to/tmdsimpy python benchmarks/bench_tmdsimpy.py")
    return 0


if __name__ == "__main__":
    sys.exit(main())
