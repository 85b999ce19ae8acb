"""Speed of the nonlinear mode of a bolted lap joint, the interface-dominated model of issue 26.

Run:  OPENBLAS_NUM_THREADS=1 python benchmarks/bench_joint.py                 # 120 contacts, the whole backbone
      python benchmarks/bench_joint.py --quick                                # 30 contacts, 8 points, ~ minutes
      python benchmarks/bench_joint.py --contacts 480 --points 41 --no-baseline
      python benchmarks/bench_joint.py --points 5 --profile                   # where one run's time goes

The model: ``microslip.fe.lap_joint(contacts)`` -- two clamped steel plates in a half-lap, three bolts of
10 kN, 27-node hexahedra, reduced to the relative displacements of the interface's node pairs plus 40
tied-interface modes (481 DOFs for 120 contacts: 147 pairs, 27 of them tied around the bolts) -- with
``microslip.frequency.jointed_structure``'s elastic--dry-friction element on each of the other pairs
(two tangential directions and the normal). Prestressed by the bolts (:func:`prestressed`), then the
nonlinear mode of its first bending mode by the extended periodic motion concept
(``microslip.nonlinear_modes``), harmonics 0-3, 128 samples, modal amplitudes from the stuck joint
(3e-7 kg^1/2 m) to gross slip of the contacts (1e-4; ``--quick``: 1e-6 to 1.2e-5), ``--points`` points at
equal steps of log amplitude (at most 4 times as many where the curve bends; without ``--points``, the
former default step control's 20 points per decade at least, the baseline's default:
``default_control(lo, hi, chord_error=None)``).

Reported: the backbone's time, its points and the time per point; the time of one dense LU
factorisation of the full nonlinear system's size (``dofs x (2H + 1)`` unknowns) measured in the same run,
and the ratio of the two; the same backbone by the code of the pinned commit f0499a5 (exported with
``git archive`` into a temporary folder and run in a subprocess, its numba cache kept there between
runs), the ratio of the times and the largest relative difference of frequency and damping ratio at the
common amplitudes (interpolated in log amplitude onto the baseline's points). Saved to
``benchmarks/results/bench_joint.json`` (``bench_joint_30.json``, ``bench_joint_480.json`` for the other sizes,
``bench_joint_quick.json`` for ``--quick``). Targets (issue 26): the
whole backbone at least 10x faster than the baseline with the same frequency and damping to 1e-6;
time per point at most one dense LU of the full system's size.
"""

from __future__ import annotations

import argparse
import cProfile
import io
import json
import os
import pstats
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import baseline_source, save_results  # noqa: E402

BASELINE = "f0499a5"
HARMONICS = 3
SAMPLES = 128
AMPLITUDE = (3e-7, 1e-4)
QUICK_AMPLITUDE = (1e-6, 1.2e-5)
TARGET_SPEEDUP = 10.0
TARGET_AGREEMENT = 1e-6


def prestressed(structure):
    """The structure prestressed by its bolts, as both sides of the comparison can build it.

    The bolts' static force is the harmonic-0 load of the mode: the static state is solved first, with every
    slider starting at zero (friction stuck from the unloaded joint), and the static term stays an unknown of
    the mode. ``microslip.prestress(..., friction="released")`` (used by ``examples/bolted_lap_joint.py``)
    resets the sliders at the bolted state instead, which the pinned baseline commit cannot represent, so the
    benchmark keeps the prestress both can solve.
    """
    return structure


def build(contacts: int):
    from microslip.fe import lap_joint
    from microslip.frequency import jointed_structure

    joint = lap_joint(contacts)
    return joint, prestressed(jointed_structure(joint))


def control(points: int | None, amplitude=AMPLITUDE):
    from microslip.frequency import StepControl
    from microslip.frequency.analyses.nonlinear_modes import default_control

    if points is None:  # the baseline's default (the turn rule): the same steps, so the curves compare point by point
        return default_control(*amplitude, chord_error=None)
    step = 1.0 / (points - 1)  # the whole range has arclength 1 in the scaled units of nonlinear_modes
    return StepControl(ds_initial=step, ds_max=step, max_points=4 * points)


def backbone(structure, points, amplitude=AMPLITUDE):
    from microslip import nonlinear_modes

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # an under-resolved contact energy is not what is measured here
        t0 = time.perf_counter()
        mode = nonlinear_modes(structure, 1, amplitude, harmonics=HARMONICS, samples=SAMPLES,
                               control=control(points, amplitude))
        return time.perf_counter() - t0, mode


def dense_lu_seconds(n: int, repeat: int = 3) -> float:
    """The best time of ``scipy.linalg.lu_factor`` of a random dense ``n x n`` matrix."""
    import scipy.linalg as sla

    A = np.random.default_rng(0).standard_normal((n, n)) + n * np.eye(n)
    best = np.inf
    for _ in range(repeat):
        B = A.copy()
        t0 = time.perf_counter()
        sla.lu_factor(B, overwrite_a=True, check_finite=False)
        best = min(best, time.perf_counter() - t0)
    return best


# -- the baseline: the pinned commit's code in a subprocess ------------------------------------------------

def export_structure(structure, path: Path) -> None:
    """The structure as arrays any version of microslip can rebuild through the public API."""
    contacts = [{"kt": c.model.kt.tolist(), "kn": c.model.kn.tolist(), "gaps": c.model.gaps.tolist(),
                 "mu": float(c.model.mu), "name": c.name} for c in structure.contacts]
    np.savez(path, M=structure.M, C=structure.C, K=structure.K, static=structure.static_force,
             t1=np.array([c.tangential for c in structure.contacts]),
             t2=np.array([c.tangential2 for c in structure.contacts]),
             n=np.array([c.normal for c in structure.contacts]), contacts=np.array(json.dumps(contacts)))


#: the baseline's rebuild of the structure that export_structure saved (``data``: the loaded ``.npz``), public API
#: only, so any version of microslip runs it
REBUILD_STRUCTURE = r"""
def structure():
    s = Structure(data["M"], data["C"], data["K"])
    for k, c in enumerate(json.loads(str(data["contacts"]))):
        s.add_contact(MicroslipModel(c["kt"], c["kn"], c["gaps"], c["mu"]), tangential=[data["t1"][k], data["t2"][k]],
                      normal=data["n"][k], name=c["name"])
    s.add_static_force(data["static"])
    return s
"""

BASELINE_SCRIPT = r"""
import json, sys, time, warnings
import numpy as np
from microslip import MicroslipModel, Structure, nonlinear_modes
from microslip.frequency import StepControl

data = np.load(sys.argv[1])
points = int(sys.argv[2])
lo, hi, H, samples = float(sys.argv[3]), float(sys.argv[4]), int(sys.argv[5]), int(sys.argv[6])

""" + REBUILD_STRUCTURE + r"""
ctl = None if points == 0 else StepControl(ds_initial=1 / (points - 1), ds_max=1 / (points - 1), max_points=4 * points)
with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    nonlinear_modes(structure(), 1, (lo, lo * 1.01), harmonics=H, samples=samples)  # compiled kernels loaded
    s = structure()
    t0 = time.perf_counter()
    m = nonlinear_modes(s, 1, (lo, hi), harmonics=H, samples=samples, control=ctl)
    t = time.perf_counter() - t0
print(json.dumps({"seconds": t, "points": int(m.points), "a": m.modal_amplitude.tolist(),
                  "f": m.frequency("Hz").tolist(), "zeta": m.damping_ratio.tolist()}))
"""


def run_baseline(structure, points: int | None, amplitude) -> dict:
    src = baseline_source(BASELINE)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "structure.npz"
        export_structure(structure, path)
        env = {**os.environ, "PYTHONPATH": str(src)}
        done = subprocess.run([sys.executable, "-c", BASELINE_SCRIPT, str(path), str(points or 0), str(amplitude[0]),
                               str(amplitude[1]), str(HARMONICS), str(SAMPLES)], capture_output=True, text=True,
                              env=env, cwd=tmp)
    if done.returncode != 0:
        raise RuntimeError(f"the baseline failed:\n{done.stderr[-3000:]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def agreement(mode, base: dict) -> tuple[float, float]:
    """Largest relative differences of frequency and damping ratio, this run interpolated onto the baseline's
    amplitudes inside the common range (log amplitude)."""
    a, f, z = (np.asarray(base[k]) for k in ("a", "f", "zeta"))
    la, lb = np.log(mode.modal_amplitude), np.log(a)
    if not np.all(np.diff(la) > 0):
        return float("nan"), float("nan")
    inside = (lb >= la[0]) & (lb <= la[-1])
    f_here = np.interp(lb[inside], la, mode.frequency("Hz"))
    z_here = np.interp(lb[inside], la, mode.damping_ratio)
    return (float(np.max(np.abs(f_here / f[inside] - 1))), float(np.max(np.abs(z_here / z[inside] - 1))))


# -- where the time goes --------------------------------------------------------------------------------

def profile(structure, points, amplitude) -> dict:
    prof = cProfile.Profile()
    t0 = time.perf_counter()
    prof.enable()
    backbone(structure, points, amplitude)
    prof.disable()
    total = time.perf_counter() - t0
    out = io.StringIO()
    stats = pstats.Stats(prof, stream=out)
    stats.sort_stats("cumulative").print_stats(35)
    stats.sort_stats("tottime").print_stats(20)
    print(out.getvalue())
    return {"total_s": total}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--contacts", type=int, default=120, choices=(30, 120, 480),
                        help="contact elements (default 120: 481 DOFs)")
    parser.add_argument("--points", type=int, default=None,
                        help="points at equal steps of log amplitude (default: the default step control)")
    parser.add_argument("--quick", action="store_true", help="30 contacts, 8 points over a shorter range")
    parser.add_argument("--no-baseline", action="store_true", help="skip the pinned commit's run")
    parser.add_argument("--profile", action="store_true", help="print cProfile's top functions of one run")
    args = parser.parse_args(argv)
    if args.quick:
        args.contacts, args.points = 30, args.points or 8
    amplitude = QUICK_AMPLITUDE if args.quick else AMPLITUDE
    if args.points is not None and args.points < 2:
        parser.error(f"--points must be at least 2, got {args.points}")

    from microslip import nonlinear_modes  # noqa: F401  (imported before anything is timed)

    joint, structure = build(args.contacts)
    backbone(structure, 2, (amplitude[0], 1.01 * amplitude[0]))  # the compiled kernels loaded before timing
    if args.profile:
        profile(structure, args.points, amplitude)
    seconds, mode = backbone(structure, args.points, amplitude)
    n_unknowns = structure.ndof * (2 * HARMONICS + 1)
    lu = dense_lu_seconds(n_unknowns)
    per_point = seconds / mode.points
    hz = 1 / (2 * np.pi)
    print(f"lap joint: {joint.contacts} contacts ({len(joint.patch)} pairs, {joint.tied_pairs.size} tied), "
          f"{structure.ndof} DOFs, harmonics 0-{HARMONICS}, {SAMPLES} samples, reduction {mode.reduction!r}; "
          f"load average {os.getloadavg()[0]:.2f} (2 cores shared)")
    print(f"first bending mode, modal amplitude {mode.modal_amplitude[0]:.2e} to {mode.modal_amplitude[-1]:.2e} "
          f"kg^1/2 m: {mode.frequency('Hz')[0]:.2f} to {mode.frequency('Hz')[-1]:.2f} Hz, damping ratio "
          f"{100 * mode.damping_ratio[0]:.3f} to {100 * mode.damping_ratio.max():.3f} %")
    print(f"backbone: {seconds:.1f} s, {mode.points} points, {per_point:.2f} s per point")
    print(f"one dense LU of {n_unknowns} unknowns (dofs x (2H+1)): {lu:.3f} s; time per point / LU = "
          f"{per_point / lu:.1f} (target <= 1: {'met' if per_point <= lu else 'MISSED'})")
    figures = {"contacts": joint.contacts, "pairs": len(joint.patch), "dofs": structure.ndof, "harmonics": HARMONICS,
               "samples": SAMPLES, "points": int(mode.points), "seconds": seconds, "seconds_per_point": per_point,
               "dense_lu_seconds": lu, "n_unknowns": n_unknowns, "per_point_over_lu": per_point / lu,
               "frequency_hz": [float(mode.omega[0] * hz), float(mode.omega[-1] * hz)],
               "damping_ratio_max": float(mode.damping_ratio.max())}
    if not args.no_baseline:
        base = run_baseline(structure, args.points, amplitude)
        df, dz = agreement(mode, base)
        ratio = base["seconds"] / seconds
        print(f"baseline (commit {BASELINE}, same run): {base['seconds']:.1f} s, {base['points']} points, "
              f"{base['seconds'] / base['points']:.2f} s per point; speed-up {ratio:.2f}x (target "
              f">= {TARGET_SPEEDUP:.0f}x: {'met' if ratio >= TARGET_SPEEDUP else 'MISSED'})")
        print(f"at the common amplitudes: frequency within {df:.1e}, damping ratio within {dz:.1e} relative "
              f"(target {TARGET_AGREEMENT:.0e}: {'met' if max(df, dz) <= TARGET_AGREEMENT else 'MISSED'})")
        figures.update({"baseline_commit": BASELINE, "baseline_seconds": base["seconds"],
                        "baseline_points": base["points"], "speedup": ratio, "frequency_difference": df,
                        "damping_difference": dz})
    name = "bench_joint_quick" if args.quick else "bench_joint" if args.contacts == 120 else f"bench_joint_{args.contacts}"
    print(f"results: {save_results(name, figures)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
