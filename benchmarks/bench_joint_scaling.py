"""How the nonlinear mode's cost grows with the interface: the lap joint at 30, 120 and 480 contacts.

Run:  OPENBLAS_NUM_THREADS=1 python benchmarks/bench_joint_scaling.py            # 30, 120, 480 x H = 3, 7
      python benchmarks/bench_joint_scaling.py --quick                           # 30 and 120, H = 3, 3 points
      python benchmarks/bench_joint_scaling.py --contacts 30 120 --harmonics 3 --points 6

The model is bench_joint.py's (``microslip.fe.lap_joint`` with ``jointed_structure``, prestressed by its
bolts), at each size; its first bending nonlinear mode by ``microslip.nonlinear_modes`` with harmonics
0-H (128 samples for H = 3, 256 for H = 7), ``--points`` points at equal steps of log amplitude from the
stuck joint (1e-7 kg^1/2 m) into microslip (1e-5). Reported per size and H: the DOFs, the contact DOFs
(3 per contact), the time per point and per Newton iteration; and per H the exponent ``p`` of the least
squares fit ``time per point ~ (contact DOFs)^p`` (the dense LU of the whole system would give 3). The
baseline measured in the same run is the smallest size: the other sizes' times are printed as ratios to it.
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
from _common import save_results  # noqa: E402
from bench_joint import prestressed  # noqa: E402  (the one place the prestress step is chosen)

AMPLITUDE = (1e-7, 1e-5)
SAMPLES = {3: 128, 7: 256}


def run(contacts: int, harmonics: int, points: int) -> dict:
    from microslip import nonlinear_modes
    from microslip.fe import lap_joint
    from microslip.frequency import StepControl, jointed_structure

    t0 = time.perf_counter()
    structure = prestressed(jointed_structure(lap_joint(contacts)))
    built = time.perf_counter() - t0
    step = 1.0 / (points - 1)
    samples = SAMPLES.get(harmonics, 128)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # an incomplete or under-resolved curve still times its points
        t0 = time.perf_counter()
        mode = nonlinear_modes(structure, 1, AMPLITUDE, harmonics=harmonics, samples=samples,
                               control=StepControl(ds_initial=step, ds_max=step, max_points=points))
        seconds = time.perf_counter() - t0
    iterations = int(np.sum(mode.iterations))
    return {"contacts": contacts, "dofs": structure.ndof, "contact_dofs": 3 * contacts, "harmonics": harmonics,
            "samples": samples, "points": int(mode.points), "iterations": iterations, "seconds": seconds,
            "seconds_per_point": seconds / mode.points, "seconds_per_iteration": seconds / max(iterations, 1),
            "build_seconds": built, "reduction": mode.reduction}


def exponent(rows: list) -> float:
    """Least-squares slope of log(time per point) against log(contact DOFs)."""
    if len(rows) < 2:
        return float("nan")
    x = np.log([r["contact_dofs"] for r in rows])
    y = np.log([r["seconds_per_point"] for r in rows])
    return float(np.polyfit(x, y, 1)[0])


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--contacts", type=int, nargs="+", default=[30, 120, 480], choices=(30, 120, 480))
    parser.add_argument("--harmonics", type=int, nargs="+", default=[3, 7])
    parser.add_argument("--points", type=int, default=5, help="points per mode (default 5)")
    parser.add_argument("--quick", action="store_true", help="30 and 120 contacts, H = 3, 3 points")
    args = parser.parse_args(argv)
    if args.quick:
        args.contacts, args.harmonics, args.points = [30, 120], [3], 3
    if args.points < 2:
        parser.error(f"--points must be at least 2, got {args.points}")

    warm = run(30, 1, 2)  # the compiled kernels loaded before anything is timed
    del warm
    print(f"lap joint, first bending nonlinear mode, {args.points} points from {AMPLITUDE[0]:.0e} to "
          f"{AMPLITUDE[1]:.0e} kg^1/2 m; load average {os.getloadavg()[0]:.2f} (2 cores shared)")
    print(f"{'contacts':>8} {'DOFs':>5} {'H':>2} {'unknowns':>8} {'points':>6} {'s/point':>8} {'s/iteration':>11} "
          f"{'x smallest':>10}")
    figures = {"amplitude": list(AMPLITUDE), "rows": [], "exponent": {}}
    for H in args.harmonics:
        rows = []
        for c in sorted(args.contacts):
            r = run(c, H, args.points)
            rows.append(r)
            base = rows[0]["seconds_per_point"]
            print(f"{c:8d} {r['dofs']:5d} {H:2d} {r['dofs'] * (2 * H + 1):8d} {r['points']:6d} "
                  f"{r['seconds_per_point']:8.2f} {r['seconds_per_iteration']:11.3f} "
                  f"{r['seconds_per_point'] / base:10.1f}", flush=True)
        p = exponent(rows)
        print(f"H = {H}: time per point ~ (contact DOFs)^{p:.2f}")
        figures["rows"] += rows
        figures["exponent"][str(H)] = p
    print(f"results: {save_results('bench_joint_scaling' + ('_quick' if args.quick else ''), figures)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
