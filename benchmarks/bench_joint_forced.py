"""Speed of a family of forced responses of the bolted lap joint (issue 26, item 4) against the code before.

Run:  OPENBLAS_NUM_THREADS=1 python benchmarks/bench_joint_forced.py                 # 120 contacts, 2 levels
      python benchmarks/bench_joint_forced.py --contacts 30 --levels 2 --no-baseline   # a quick look

The model is bench_joint.py's: ``microslip.fe.lap_joint(contacts)`` reduced to its interface's relative
displacements plus tied-interface modes (481 DOFs for 120 contacts), elastic--dry-friction contacts with
two tangential directions, prestressed by the bolts. Its first bending mode ``phi`` (mass-normalised, the
joint stuck: ``nonlinear_modes(...).linear_mode``) is driven at harmonic 1 by the force ``level M phi``
(N), ``level`` from ``--level`` (default 0.4 N per kg^1/2) doubling ``--levels`` times, which takes the
resonance into microslip (at 0.8 the peak lies 0.2 % below the stuck frequency). Each response is
followed from 1.005 times the stuck frequency down to 0.985 times it, harmonics 0-3, 128 samples,
``stability=False`` (the cost of stability is bench_stability.py's subject), the default step control.

Reported: the family's wall time and points, and the same family by the code of the pinned commit f0499a5
(bench_joint.py's baseline: exported with ``git archive`` and run in a subprocess), the ratio of the times
(target: the backbone's speed-up, 10x), and how far the two families agree: the vibration amplitude (the
largest deviation from the static value over a period) at the DOF where the mode moves most, point by
point where both curves have a point at the same frequency (to 1e-9 relative; the step control is the
same, so most points are), and each resonance peak's amplitude and frequency (a parabola through the
highest point and its neighbours, for both). Saved to ``benchmarks/results/bench_joint_forced.json``
(``bench_joint_forced_30.json`` for 30 contacts).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import baseline_source, peak, save_results  # noqa: E402
from bench_joint import (BASELINE, HARMONICS, REBUILD_STRUCTURE, SAMPLES, TARGET_SPEEDUP, build,  # noqa: E402
                         export_structure)

BAND = (1.005, 0.985)  # times the stuck joint's first bending frequency: from above, downwards

BASELINE_SCRIPT = r"""
import json, sys, time, warnings
import numpy as np
from microslip import MicroslipModel, Structure, frequency_response

data = np.load(sys.argv[1])
H, samples = int(sys.argv[2]), int(sys.argv[3])

""" + REBUILD_STRUCTURE + r"""
s = structure()
band, forces, dof = tuple(data["band"]), data["forces"], int(data["dof"])
with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    frequency_response(s, {1: forces[0]}, (band[0], band[0] * 0.999), harmonics=H, samples=samples,
                       stability=False)  # compiled kernels loaded
    t0 = time.perf_counter()
    curves = [frequency_response(s, {1: f}, band, harmonics=H, samples=samples, stability=False) for f in forces]
    t = time.perf_counter() - t0
print(json.dumps({"seconds": t, "points": [int(c.points) for c in curves], "omega": [c.omega.tolist() for c in curves],
                  "amplitude": [c.amplitude(dof).tolist() for c in curves]}))
"""


def family(structure, forces, band, dof):
    """``(seconds, curves)`` of the forced responses to each force of ``forces`` over ``band`` (rad/s)."""
    from microslip import frequency_response

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # an under-resolved contact energy is not what is measured here
        t0 = time.perf_counter()
        curves = [frequency_response(structure, {1: f}, band, harmonics=HARMONICS, samples=SAMPLES, stability=False)
                  for f in forces]
        return time.perf_counter() - t0, curves


def run_baseline(structure, forces, band, dof) -> dict:
    src = baseline_source(BASELINE)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "structure.npz"
        export_structure(structure, path)
        with np.load(path) as data:
            arrays = dict(data)
        np.savez(path, **arrays, forces=np.asarray(forces), band=np.asarray(band), dof=dof)
        env = {**os.environ, "PYTHONPATH": str(src)}
        done = subprocess.run([sys.executable, "-c", BASELINE_SCRIPT, str(path), str(HARMONICS), str(SAMPLES)],
                              capture_output=True, text=True, env=env, cwd=tmp)
    if done.returncode != 0:
        raise RuntimeError(f"the baseline failed:\n{done.stderr[-3000:]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def agreement(curve, omega, amplitude, dof) -> tuple[int, float, float, float]:
    """This curve against the baseline's ``(omega, amplitude)`` at ``dof``: ``(points, amplitude, peak amplitude,
    peak frequency)``: the points at the same frequency (to 1e-9 relative) and the largest relative difference of
    their amplitudes, and the relative differences of the peaks (:func:`_common.peak`, both curves alike)."""
    omega, amplitude = np.asarray(omega), np.asarray(amplitude)
    mine, worst, same = curve.amplitude(dof), 0.0, 0
    for w, a in zip(curve.omega, mine):
        k = int(np.argmin(np.abs(omega - w)))
        if abs(omega[k] / w - 1) <= 1e-9:
            same += 1
            worst = max(worst, abs(a / amplitude[k] - 1))
    scale = float(np.ptp(omega))
    a_new, a_old = peak(curve.omega, mine, scale), peak(omega, amplitude, scale)
    w_new, w_old = curve.omega[int(np.argmax(mine))], omega[int(np.argmax(amplitude))]
    return same, float(worst), abs(a_new / a_old - 1), abs(w_new / w_old - 1)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--contacts", type=int, default=120, choices=(30, 120, 480),
                        help="contact elements (default 120: 481 DOFs)")
    parser.add_argument("--levels", type=int, default=2, help="forcing levels, each twice the last (default 2)")
    parser.add_argument("--level", type=float, default=0.4,
                        help="the first level: N per kg^1/2 of the modal force M phi (default 0.4)")
    parser.add_argument("--no-baseline", action="store_true", help="skip the pinned commit's run")
    args = parser.parse_args(argv)
    if args.levels < 1 or not args.level > 0:
        parser.error(f"--levels must be at least 1 and --level positive, got {args.levels} and {args.level}")

    from microslip import nonlinear_modes

    joint, structure = build(args.contacts)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        stuck = nonlinear_modes(structure, 1, (1e-8, 1.01e-8), harmonics=HARMONICS, samples=SAMPLES)
    phi, w0 = np.real(stuck.linear_mode), stuck.linear_frequency
    forces = [args.level * 2.0 ** k * (structure.M @ phi) for k in range(args.levels)]
    band = (BAND[0] * w0, BAND[1] * w0)
    dof = int(np.argmax(np.abs(phi)))  # where the mode moves most
    family(structure, forces[:1], (band[0], 0.999 * band[0]), dof)  # the compiled kernels loaded before timing
    seconds, curves = family(structure, forces, band, dof)
    points = [int(c.points) for c in curves]
    hz = 1 / (2 * np.pi)
    print(f"lap joint: {joint.contacts} contacts, {structure.ndof} DOFs, harmonics 0-{HARMONICS}, {SAMPLES} samples, "
          f"reduction {curves[0].reduction!r}; load average {os.getloadavg()[0]:.2f} (2 cores shared)")
    print(f"{args.levels} forced responses, {band[0] * hz:.1f} down to {band[1] * hz:.1f} Hz, modal force "
          f"{args.level:g} N/kg^1/2 doubling: {seconds:.1f} s, {sum(points)} points ({points}), "
          f"{seconds / sum(points):.2f} s per point")
    for level, c in zip(forces, curves):
        w_peak, a_peak = c.peak(dof)
        print(f"  peak {a_peak:.3e} m at {w_peak * hz:.2f} Hz{'' if c.complete else ' (INCOMPLETE)'}")
    figures = {"contacts": joint.contacts, "dofs": structure.ndof, "harmonics": HARMONICS, "samples": SAMPLES,
               "levels": args.levels, "first_level": args.level, "band_hz": [band[0] * hz, band[1] * hz],
               "points": points, "seconds": seconds, "seconds_per_point": seconds / sum(points)}
    if not args.no_baseline:
        base = run_baseline(structure, forces, band, dof)
        ratio = base["seconds"] / seconds
        rows = [agreement(c, w, a, dof) for c, w, a in zip(curves, base["omega"], base["amplitude"])]
        same, diff = sum(r[0] for r in rows), max(r[1] for r in rows)
        peak_a, peak_w = max(r[2] for r in rows), max(r[3] for r in rows)
        print(f"baseline (commit {BASELINE}, same run): {base['seconds']:.1f} s, {sum(base['points'])} points "
              f"({base['points']}); speed-up {ratio:.2f}x (target >= {TARGET_SPEEDUP:.0f}x: "
              f"{'met' if ratio >= TARGET_SPEEDUP else 'MISSED'})")
        print(f"at the {same} points of equal frequency: amplitude within {diff:.1e} relative; peaks: amplitude "
              f"within {peak_a:.1e}, frequency of the highest point within {peak_w:.1e}")
        figures.update({"baseline_commit": BASELINE, "baseline_seconds": base["seconds"],
                        "baseline_points": base["points"], "speedup": ratio, "points_compared": same,
                        "amplitude_difference": diff, "peak_amplitude_difference": peak_a,
                        "peak_frequency_difference": peak_w})
    name = "bench_joint_forced" if args.contacts == 120 else f"bench_joint_forced_{args.contacts}"
    print(f"results: {save_results(name, figures)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
