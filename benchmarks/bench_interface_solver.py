"""Speed of harmonic balance when the contacts use most of the DOFs: a nonlinear mode and a forced-response family.

Run:  python benchmarks/bench_interface_solver.py
      python benchmarks/bench_interface_solver.py --nx 21 --ny 7 --modes 40 --amplitude 1e-7 1e-5 --levels 0

The model is benchmarks/_interface_model.py's lap joint: two plates of springs and masses over their whole
face, reduced to the relative displacements of their ``nx ny`` node pairs (each a plane contact with a
preload, 4 elements) plus ``modes`` fixed-interface modes (default 21 x 7 pairs and 40 modes: 481 DOFs, 441
of them contact DOFs, 147 contacts, as a Brake-Reuss-beam-sized reduced model). Harmonics 0-3, 128 samples.

Measured in the same run:
* the nonlinear mode (EPMC) of the first mode over the modal amplitude range, solved as today's code did
  (``reduction="exact"``: the condensation onto the 441 contact DOFs, a dense LU of the whole Jacobian at
  every Newton iteration) and as ``reduction="auto"`` now does (every DOF, the Jacobian in parts, one
  factorisation reused over many steps by GMRES): wall times, points, their ratio, the frequency and
  damping of the two curves compared at the baseline's amplitudes (the new curve interpolated by a cubic
  in log amplitude), factorisations and GMRES iterations of the new path;
* one dense LU factorisation of the full nonlinear system's size (``7 x 481 + 2`` unknowns), for the
  target time per point;
* with ``--levels N``: a family of N forced responses (forcing levels 1 N, 2 N, 4 N ... on every
  fixed-interface mode) from above the linear resonance downwards, the first ``--points`` points of each
  (the curves have hundreds), both ways: time per point and the ratio.
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
from _interface_model import interface_model  # noqa: E402


def lu_seconds(n: int, repeat: int = 2) -> float:
    """Best wall time of a dense LU factorisation of ``n`` unknowns (float64, LAPACK getrf)."""
    import scipy.linalg as sla

    A = np.random.default_rng(0).standard_normal((n, n)) + n * np.eye(n)
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        sla.lu_factor(A, check_finite=False)
        best = min(best, time.perf_counter() - t0)
    return best


def compare(new, old, quantity: str) -> float:
    """Largest relative difference of ``quantity`` of ``new`` from ``old`` at ``old``'s amplitudes (cubic in log a)."""
    from scipy.interpolate import CubicSpline

    la, lb = np.log(new.modal_amplitude), np.log(old.modal_amplitude)
    keep = np.concatenate([[True], np.diff(la) > 0])
    inside = (lb >= la[keep][0]) & (lb <= la[keep][-1])
    spline = CubicSpline(la[keep], getattr(new, quantity)[keep])
    ref = getattr(old, quantity)[inside]
    return float(np.max(np.abs(spline(lb[inside]) / ref - 1)))


def timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nx", type=int, default=21, help="node pairs along the joint (default 21)")
    parser.add_argument("--ny", type=int, default=7, help="node pairs across (default 7)")
    parser.add_argument("--modes", type=int, default=40, help="fixed-interface modes (default 40)")
    parser.add_argument("--harmonics", type=int, default=3)
    parser.add_argument("--samples", type=int, default=128)
    parser.add_argument("--amplitude", type=float, nargs=2, default=(1e-7, 1e-5),
                        help="modal amplitude range, kg^1/2 m (default 1e-7 1e-5: stuck to macroslip)")
    parser.add_argument("--levels", type=int, default=0, help="forced responses in the family (default 0: none)")
    parser.add_argument("--points", type=int, default=40, help="points of each forced response (default 40)")
    parser.add_argument("--family-only", action="store_true", help="the mode's new path only, the family both ways")
    parser.add_argument("--no-baseline", action="store_true", help="the new path only")
    args = parser.parse_args(argv)

    from microslip.frequency import frequency_response, nonlinear_modes
    from microslip.frequency.numerics.reuse import COUNTS
    from microslip.frequency.analyses.nonlinear_modes import default_control

    structure, pairs = interface_model(args.nx, args.ny, args.modes)
    H, kw = args.harmonics, dict(harmonics=args.harmonics, samples=args.samples)
    n = (2 * H + 1) * structure.ndof + 2
    print(f"lap joint: {structure.ndof} DOFs, {3 * pairs} of them contact DOFs, {pairs} plane contacts of 4 elements, "
          f"harmonics 0-{H}, {args.samples} samples; load average {os.getloadavg()[0]:.2f} (2 cores shared)")
    nonlinear_modes(*interface_model(3, 2, 4)[:1], 1, (1e-7, 1e-6), harmonics=1, samples=16)  # compiled kernels
    figures = {"dofs": structure.ndof, "contacts": pairs, "harmonics": H, "samples": args.samples}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # an under-resolved contact energy is not what is measured here
        before = dict(COUNTS)
        # the turn rule: its steps are the same on both paths, so the curves compare point by point (the chord
        # rule's follow from tangents each path solves its own way)
        turn = dict(kw, control=default_control(*args.amplitude, chord_error=None))
        t_new, new = timed(lambda: nonlinear_modes(structure, 1, tuple(args.amplitude), **turn))
        counts = {k: COUNTS[k] - before[k] for k in COUNTS}
        t_lu = lu_seconds(n)
        print(f"one dense LU of {n} unknowns: {t_lu:.2f} s")
        print(f"new  ({new.reduction!r}): {t_new:7.2f} s, {new.points} points, {t_new / new.points:.3f} s per point "
              f"({t_new / new.points / t_lu:.2f} LU), {counts['factorisations']} factorisations, "
              f"{counts['krylov_iterations']} GMRES iterations")
        figures.update(new_seconds=t_new, new_points=new.points, lu_seconds=t_lu, **counts)
        if not (args.no_baseline or args.family_only):
            t_old, old = timed(lambda: nonlinear_modes(structure, 1, tuple(args.amplitude), reduction="exact", **turn))
            print(f"today ({old.reduction!r}): {t_old:7.2f} s, {old.points} points, {t_old / old.points:.3f} s per "
                  f"point ({t_old / old.points / t_lu:.2f} LU)")
            d_w, d_z = compare(new, old, "omega"), compare(new, old, "damping_ratio")
            print(f"backbone: today / new = {t_old / t_new:.1f}x (target 10x); per point "
                  f"{(t_old / old.points) / (t_new / new.points):.1f}x; frequency within {d_w:.1e}, damping ratio "
                  f"within {d_z:.1e} relative at today's amplitudes (new curve interpolated)")
            figures.update(old_seconds=t_old, old_points=old.points, ratio=t_old / t_new, frequency_difference=d_w,
                           damping_difference=d_z)
        if args.levels:
            from microslip.frequency import StepControl

            w0 = new.linear_frequency
            band = (0.8 * new.omega.min(), 1.02 * w0)
            tip = np.zeros(structure.ndof)
            tip[-args.modes:] = 1.0  # on the fixed-interface modes
            ctl = StepControl(max_points=args.points)  # the first points of each curve, both ways
            curves = {}
            for name, red in (("new", "auto"), ("today", "exact")):
                if name == "today" and args.no_baseline:
                    continue
                t0 = time.perf_counter()
                curves[name] = [frequency_response(structure, {1: 2.0 ** k * tip}, band[::-1], reduction=red,
                                                   stability=False, control=ctl, **kw) for k in range(args.levels)]
                t = time.perf_counter() - t0
                points = sum(c.points for c in curves[name])
                figures[f"family_{name}_seconds"], figures[f"family_{name}_points"] = t, points
                print(f"{args.levels} forced responses (first {args.points} points each, from above), {name}: {t:.2f} s, "
                      f"{points} points, {t / points:.3f} s per point")
            if not args.no_baseline:
                diff = max(float(np.max(np.abs(a.amplitude(0) / b.amplitude(0) - 1)))
                           for a, b in zip(curves["new"], curves["today"]) if a.points == b.points)
                ratio = figures["family_today_seconds"] / figures["family_new_seconds"]
                figures.update(family_ratio=ratio, family_difference=diff)
                print(f"family: today / new = {ratio:.1f}x; amplitudes within {diff:.1e} relative at the same points")
    save_results("interface_solver_family" if args.family_only else "interface_solver", figures)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
