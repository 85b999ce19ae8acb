"""A nonlinear mode of a blade sector with a curved-flat under-platform damper: does it finish, and how fast.

Run:  OPENBLAS_NUM_THREADS=1 python benchmarks/bench_damper_modes.py
      OPENBLAS_NUM_THREADS=1 python benchmarks/bench_damper_modes.py --harmonics 1 --budget 600

The case of issue 26 item 5, built from the library's parts: ``microslip.fe.blade`` (plane stress, the
smallest mesh it makes: 408 DOFs, 16 mm shank, 6 mm platform, C = 2e-7 K), clamped in a rigid disk of
12 sectors (``CyclicStructure``, no boundary DOFs), a curved-flat ``UnderPlatformDamper`` (5 g, 2e-8 kg m^2,
damping 100 1/s) between this blade's right overhang (flat face: two contacts, a rounded punch by MDR) and
the next blade's left one (curved face: one contact), faces at 40 degrees from the radial direction,
mu = 0.5, laws tuned with 8 elements at 1000 N, centrifugal load 100 N (as ``examples/bladed_disk.py``).
Its first mode in nodal diameter 3 from modal amplitude 1e-9 to 1e-4 kg^1/2 m, harmonics 0-3 (the issue's
case; ``--harmonics 1`` the lighter one), ``nonlinear_modes`` defaults.

Where the continuation spent its points: with harmonics 0-3 the mode rises to about 2.1e-5 kg^1/2 m, where
the flat face's outer contact closes only for part of the period and the damper, held by the two others, is
nearly free to turn about a point: the mode turns back in amplitude (a fold) and beyond it the periodic
motions differ mainly by the damper's mean position; the curve wandered between 3e-6 and 2.1e-5 kg^1/2 m
for thousands of points (the user of issue 26 stopped it after 55 minutes). With harmonics 0-1 the same
happens at about 6.6e-5, and above it the motions form an exact straight line at one amplitude. Today a
nonlinear mode ends at its first fold in amplitude (``folds="stop"``, the default) with an
``IncompleteCurveWarning`` that says where and why (and crosses a line in doubling steps, stopping where it
starts when it does not end).

Printed: today's time, points, where the mode ended and why, points per decade of amplitude and steps
backwards in amplitude, against the target (a minute); the same for the baseline, the pinned commit
49f95a1 (``git archive`` into a temporary folder, run in a subprocess with this file), stopped at
``--budget`` points; the ratio of the times (a lower bound: the baseline does not end); and the largest
difference of frequency and damping ratio between the two where both rise in amplitude (joined by
straight lines in log amplitude). Saved through ``_common.save_results``.
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

BASELINE = "49f95a1"
TARGET = 60.0  # s: the mode completes within a minute (issue 26 item 5)
AMPLITUDE = (1e-9, 1e-4)  # kg^1/2 m
SECTORS, DIAMETER = 12, 3
LOAD = 100.0  # N
ANGLE = np.radians(40.0)  # the faces' normals from the radial direction


def sector(dofs: int = 300, load: float = LOAD):
    """The blade sector with its damper (a CyclicStructure, SI units), from public names only (any version)."""
    from microslip import Sphere, mdr, tune
    from microslip.fe import blade
    from microslip.frequency import CyclicStructure, UnderPlatformDamper
    from microslip.reference.profiles import RoundedPunch

    b = blade(dofs, shank_width=0.016, platform_height=0.006)
    right, left = b.node_sets["platform_right"], b.node_sets["platform_left"]  # outer edge first

    def dof(node, c):
        return b.dof_map.index(f"{node}:{c}")

    disk = CyclicStructure(b.M.toarray(), 2e-7 * b.K.toarray(), b.K.toarray(), sectors=SECTORS, left=[], right=[])
    pair = dict(E=200e9, nu=0.3, E2=225e9, nu2=0.29, mu=0.5)
    punch = mdr(Sphere(radius=5e-3, **pair), max_load=1000.0, elements=2000, profile=RoundedPunch(1e-3, 5e-3))
    flat = tune(punch.as_reference(), 1000.0, elements=8)
    curved = tune(Sphere(radius=10e-3, **pair), 1000.0, elements=8)
    d = UnderPlatformDamper(0.005, 2e-8, centrifugal_load=load, damping=100.0)
    mid, lift = 4e-3 / np.tan(ANGLE), 2e-3 * np.tan(ANGLE)
    d.add_interface(flat, points=[(-6e-3, mid - lift), (-2e-3, mid + lift)], angle=np.pi / 2 + ANGLE,
                    platform=[{"x": dof(right[2], "x"), "y": dof(right[2], "y")},
                              {"x": dof(right[0], "x"), "y": dof(right[0], "y")}], name="flat")
    d.add_interface(curved, points=[(4e-3, mid)], angle=np.pi / 2 - ANGLE,
                    platform={"x": disk.next(dof(left[1], "x")), "y": disk.next(dof(left[1], "y"))}, name="curved")
    return d.attach(disk)


def run(harmonics: int, budget: int) -> dict:
    """The mode with at most ``budget`` points: its figures (JSON-serialisable)."""
    from microslip import nonlinear_modes
    from microslip.frequency.analyses.nonlinear_modes import default_control

    structure = sector()
    control = default_control(*AMPLITUDE)
    control.max_points = budget
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        t0 = time.perf_counter()
        mode = nonlinear_modes(structure, 1, AMPLITUDE, harmonics=harmonics, nodal_diameter=DIAMETER,
                               control=control)
        seconds = time.perf_counter() - t0
    la = np.log10(mode.modal_amplitude)
    ended = [str(w.message) for w in caught if "Incomplete" in type(w.category).__name__ or
             "IncompleteCurve" in w.category.__name__]
    return {"seconds": seconds, "points": int(mode.points), "complete": bool(mode.complete),
            "last_amplitude": float(mode.modal_amplitude[-1]), "ndof": int(structure.ndof),
            "per_decade": [int(np.count_nonzero((la >= k) & (la < k + 1))) for k in range(-9, -4)],
            "backward": int(np.count_nonzero(np.diff(la) < 0)), "ended": ended[0] if ended else "",
            "omega": mode.omega.tolist(), "damping_ratio": mode.damping_ratio.tolist(),
            "amplitude": mode.modal_amplitude.tolist()}


def run_baseline(harmonics: int, budget: int) -> dict:
    from _common import baseline_source  # benchmarks/ on the path: see main

    env = dict(os.environ, PYTHONPATH=str(baseline_source(BASELINE)), OPENBLAS_NUM_THREADS="1")
    done = subprocess.run([sys.executable, __file__, "--child", "--harmonics", str(harmonics), "--budget", str(budget)],
                          capture_output=True, text=True, env=env, cwd=tempfile.gettempdir())
    if done.returncode != 0:
        raise SystemExit(f"the baseline ({BASELINE}) failed:\n{done.stderr[-3000:]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def rising(r: dict) -> int:
    """Points of a run before its first step backwards in amplitude."""
    back = np.flatnonzero(np.diff(np.log(r["amplitude"])) < 0)
    return int(back[0]) + 1 if back.size else len(r["amplitude"])


def agreement(a: dict, b: dict) -> tuple[float, float, float]:
    """``(frequency, damping, reach)``: the largest differences of two runs where both rise in amplitude, each
    joined by straight lines in log amplitude and compared at ``b``'s points (relative; of the largest damping
    ratio), and the amplitude up to which they are compared (kg^1/2 m)."""
    ka, kb = rising(a), rising(b)
    la, lb = np.log(a["amplitude"][:ka]), np.log(b["amplitude"][:kb])
    keep = lb <= la[-1]
    w = np.interp(lb[keep], la, a["omega"][:ka]) / np.array(b["omega"][:kb])[keep] - 1
    z = np.interp(lb[keep], la, a["damping_ratio"][:ka]) - np.array(b["damping_ratio"][:kb])[keep]
    return (float(np.max(np.abs(w))), float(np.max(np.abs(z)) / np.max(np.abs(b["damping_ratio"]))),
            float(np.exp(lb[keep][-1])))


def describe(name: str, r: dict) -> str:
    how = ("complete" if r["complete"] else f"ended at {r['last_amplitude']:.3g} kg^1/2 m: "
           + (r["ended"][:160] + "..." if r["ended"] else "?"))
    return (f"{name}: {r['seconds']:.1f} s, {r['points']} points ({1e3 * r['seconds'] / r['points']:.0f} ms each), "
            f"{how}\n    points per decade from 1e-9: {r['per_decade']}, steps backwards in amplitude: {r['backward']}")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--harmonics", type=int, default=3, help="harmonics H (default 3, the issue's case)")
    parser.add_argument("--budget", type=int, default=600, help="max_points of both runs (default 600)")
    parser.add_argument("--child", action="store_true", help=argparse.SUPPRESS)  # the baseline's side
    args = parser.parse_args(argv)
    if args.child:
        print(json.dumps(run(args.harmonics, args.budget)))
        return 0
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from _common import save_results

    run(args.harmonics, 3)  # Numba's kernels loaded, the laws' tuning cached by nothing: timed below as a whole
    today = run(args.harmonics, args.budget)
    base = run_baseline(args.harmonics, args.budget)
    print(f"blade sector: {today['ndof']} DOFs ({SECTORS} sectors, nodal diameter {DIAMETER}), curved-flat damper "
          f"at {LOAD:g} N, harmonics 0-{args.harmonics}, modal amplitude {AMPLITUDE[0]:g} to {AMPLITUDE[1]:g} "
          f"kg^1/2 m, max_points {args.budget}; load average {os.getloadavg()[0]:.2f} (2 cores shared)")
    print(describe("today", today))
    print(f"    target: the mode ends within {TARGET:g} s: {'met' if today['seconds'] <= TARGET else 'MISSED'}")
    print(describe(f"baseline {BASELINE}", base))
    dw, dz, reach = agreement(today, base)
    ratio = base["seconds"] / today["seconds"]
    print(f"baseline / today = {ratio:.2f} in time (the baseline stopped by its budget: a lower bound); "
          f"up to {reach:.3g} kg^1/2 m (where both still rise in amplitude), joined by straight lines in log amplitude: "
          f"frequency within {dw:.1e} (relative), damping ratio within {dz:.1e} of its largest value")
    figures = {"harmonics": args.harmonics, "budget": args.budget, "ratio": ratio, "target_seconds": TARGET, "frequency_difference": dw,
               "damping_difference": dz, "compared_up_to": reach}
    for name, r in (("today", today), ("baseline", base)):
        figures[name] = {k: v for k, v in r.items() if k not in ("omega", "damping_ratio", "amplitude")}
    print(f"results: {save_results('bench_damper_modes' + ('' if args.harmonics == 3 else f'_h{args.harmonics}'), figures)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
