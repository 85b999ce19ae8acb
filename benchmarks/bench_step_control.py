"""Points against interpolation error of the continuation's step control: the turn rule and the chord rule.

Run:  OPENBLAS_NUM_THREADS=1 python benchmarks/bench_step_control.py            # the three cases, ~ minutes
      python benchmarks/bench_step_control.py --quick                           # smaller cases, under a minute
      python benchmarks/bench_step_control.py --chord 3e-4 --ds-max 0.25        # another chord rule for modes
      python benchmarks/bench_step_control.py --cases b --joint-contacts 120    # the issue's 120-contact joint

Each case's curve is followed three times in the same run: with the turn rule (``chord_error=None``: steps set
by ``max_angle``, the corrector's iterations and ``ds_max``; for nonlinear modes ``ds_max`` is 1/20 decade of
amplitude, ``default_control(lo, hi, chord_error=None)``, their default until the chord rule replaced it), with
the chord rule (``StepControl.chord_error`` sets the steps: for modes their default, ``default_control(lo, hi)``,
which measures the frequency's and damping's difference from the straight lines; for the forced response
``FORCED_CHORD``, opt-in there), and a reference with the turn rule at 4x shorter steps (``ds_max``,
``ds_initial`` and ``max_angle`` divided by 4). For the modes the turn rule is also run at 10, 28 and 40 points
per decade (``TURN_DENSITIES``): the fewest points with which it is as close as the chord rule in both quantities
("turn rule points for the chord rule's error") is what "fewer points for the same error" rests on. Each run's
quantities are joined by straight lines and evaluated at the reference's points; the interpolation error is
the largest difference from the reference there, relative to the quantity's range over the reference
(what a plot of the curve shows between its points).

Cases:
(a) the nonlinear mode of the first bending mode of bench_fe_scale.py's blade (``blade_case``; 1000 DOFs
    asked for, 40 contacts, harmonics 0-3), modal amplitude 1e-7 to 1e-4 kg^1/2 m: frequency and damping
    ratio against log modal amplitude;
(b) the backbone of bench_joint.py's lap joint with 30 contacts (harmonics 0-3, 128 samples, prestressed
    by its bolts), modal amplitude 3e-7 to 1e-4: the same quantities;
(c) the forced response of the blade of (a) over bench_fe_scale.py's band (1200-1800 Hz), its excitation,
    harmonics 0-3, ``stability=False``: the first harmonic's amplitude at the tip against frequency.
``--quick``: (a) 20 contacts over two decades, (b) 1e-6 to 1.2e-5, (c) the blade of (a).

Reported per case: the points and wall times of the runs, the ratio of points old / new, the errors of old
and new, and for the modes the turn rule's points for the chord rule's error. Saved to ``benchmarks/results/bench_step_control.json``
(``bench_step_control_quick.json`` for ``--quick``, ``..._joint120.json`` with ``--joint-contacts 120``).
The machine is shared: the times are indicative, the
points and errors are what the comparison rests on.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import save_results  # noqa: E402
from bench_fe_scale import RANGE, blade_case  # noqa: E402  (the blade, its contacts and excitation)

REFINE = 4  # the reference's steps are this many times shorter

#: points per decade of amplitude of the turn rule's further runs on the modes (20 is the old run)
TURN_DENSITIES = (10, 28, 40)

#: the chord rule measured on the forced response (opt-in there: StepControl's default is the turn rule)
FORCED_CHORD = {"chord_error": 1e-3, "ds_max": 0.2, "max_angle": 0.6}


def reference_of(control):
    """The old control with ``REFINE`` times shorter steps and turns."""
    return replace(control, ds_initial=control.ds_initial / REFINE, ds_max=control.ds_max / REFINE,
                   max_angle=control.max_angle / REFINE, chord_error=None, max_points=REFINE * control.max_points)


def interpolation_error(x, ys, x_ref, ys_ref) -> list:
    """Largest difference of each ``ys`` joined by straight lines in ``x`` from ``ys_ref`` at ``x_ref``,
    relative to the range of ``ys_ref``; ``x`` must increase (or decrease) along the curve."""
    order, order_ref = np.argsort(x), np.argsort(x_ref)
    if not (np.all(np.diff(x[order]) >= 0) and (np.all(np.diff(x) >= 0) or np.all(np.diff(x) <= 0))):
        raise ValueError("the curve folds in its parameter: a straight-line interpolation in it is not defined")
    out = []
    for y, y_ref in zip(ys, ys_ref):
        inside = (x_ref >= x.min()) & (x_ref <= x.max())
        between = np.interp(x_ref[inside], x[order], y[order])
        span = np.ptp(y_ref[order_ref])
        out.append(float(np.max(np.abs(between - y_ref[inside])) / span))
    return out


def run_mode(structure, amplitude, control, **kwargs):
    from microslip import nonlinear_modes

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # an under-resolved contact energy is not what is measured here
        t0 = time.perf_counter()
        m = nonlinear_modes(structure, 1, amplitude, harmonics=3, control=control, **kwargs)
        seconds = time.perf_counter() - t0
    return {"points": int(m.points), "seconds": seconds, "x": np.log(m.modal_amplitude),
            "ys": [m.omega, m.damping_ratio], "complete": bool(m.complete)}


def run_forced(structure, force, tip, band, control):
    from microslip import frequency_response

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t0 = time.perf_counter()
        r = frequency_response(structure, force, band, harmonics=3, stability=False, control=control)
        seconds = time.perf_counter() - t0
    return {"points": int(r.points), "seconds": seconds, "x": r.omega, "ys": [r.amplitude(tip, 1)],
            "complete": bool(r.complete)}


def compare(name, quantities, run, old, new, denser=()):
    """Run old, new, the reference and the old rule at each ``denser`` control; print and return the figures."""
    ref = run(reference_of(old))
    rows = {"old": run(old), "new": run(new)}
    figures = {"quantities": quantities, "reference": {"points": ref["points"], "seconds": ref["seconds"]}}
    print(f"{name}: reference ({REFINE}x shorter steps) {ref['points']} points, {ref['seconds']:.1f} s")
    for key, r in rows.items():
        err = interpolation_error(r["x"], r["ys"], ref["x"], ref["ys"])
        figures[key] = {"points": r["points"], "seconds": r["seconds"], "complete": r["complete"],
                        "errors": dict(zip(quantities, err))}
        print(f"  {key:>3}: {r['points']:4d} points, {r['seconds']:6.1f} s, error "
              + ", ".join(f"{q} {e:.2e}" for q, e in zip(quantities, err)) + ("" if r["complete"] else " INCOMPLETE"))
    ratio = rows["old"]["points"] / rows["new"]["points"]
    worse = max(figures["new"]["errors"][q] / max(figures["old"]["errors"][q], 1e-300) for q in quantities)
    figures["points_old_over_new"] = ratio
    figures["error_new_over_old"] = worse
    print(f"  points old / new = {ratio:.2f}; error new / old at most {worse:.2f}")
    if denser:
        turn = [{"points": figures["old"]["points"], "seconds": figures["old"]["seconds"],
                 "errors": figures["old"]["errors"], "label": "old"}]
        for label, control in denser:
            r = run(control)
            err = dict(zip(quantities, interpolation_error(r["x"], r["ys"], ref["x"], ref["ys"])))
            turn.append({"points": r["points"], "seconds": r["seconds"], "errors": err, "label": label})
            print(f"  turn rule at {label}: {r['points']:4d} points, {r['seconds']:6.1f} s, error "
                  + ", ".join(f"{q} {e:.2e}" for q, e in err.items()))
        figures["turn_rule"] = turn
        # the fewest points with which the turn rule is at least as close as the chord rule in every quantity
        close = [t["points"] for t in turn if all(t["errors"][q] <= figures["new"]["errors"][q] for q in quantities)]
        figures["turn_points_for_new_error"] = min(close) if close else None
        most = max(t["points"] for t in turn)
        print("  turn rule points for the chord rule's error: "
              + (f"{min(close)}" if close else f"more than {most} (none of its runs is as close)")
              + f"; the chord rule: {figures['new']['points']}")
    return figures


def mode_controls(lo, hi, args):
    from microslip.frequency.analyses.nonlinear_modes import CHORD_ERROR, default_control

    old = default_control(lo, hi, chord_error=None)
    new = default_control(lo, hi)
    assert new.chord_error == CHORD_ERROR  # the default
    if args.chord is not None or args.ds_max is not None:
        new = replace(new, chord_error=args.chord if args.chord is not None else new.chord_error,
                      ds_max=args.ds_max if args.ds_max is not None else new.ds_max)
        new = replace(new, ds_initial=min(new.ds_initial, new.ds_max))
    return old, new


def _turn_points(case: dict) -> str:
    """The turn rule's points for the chord rule's error, as the table shows them."""
    if "turn_rule" not in case:
        return "-"
    found = case["turn_points_for_new_error"]
    return str(found) if found is not None else f"> {max(t['points'] for t in case['turn_rule'])}"


def denser_turns(old):
    """The turn rule ``old`` (1/20 decade) at :data:`TURN_DENSITIES` points per decade: ``(label, control)``."""
    return [(f"{n} per decade", replace(old, ds_initial=old.ds_max * 20 / n, ds_max=old.ds_max * 20 / n))
            for n in TURN_DENSITIES]


def forced_controls(args):
    from microslip.frequency import StepControl

    old = StepControl()
    new = replace(old, **FORCED_CHORD)
    if args.forced_chord is not None or args.forced_ds_max is not None:
        new = replace(new, chord_error=args.forced_chord if args.forced_chord is not None else new.chord_error,
                      ds_max=args.forced_ds_max if args.forced_ds_max is not None else new.ds_max)
    return old, new


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller cases, under a minute")
    parser.add_argument("--chord", type=float, default=None, help="the modes' chord_error (default: default_control's)")
    parser.add_argument("--ds-max", type=float, default=None, help="the modes' ds_max with the chord rule")
    parser.add_argument("--forced-chord", type=float, default=None,
                        help="the forced response's chord_error (default: StepControl's)")
    parser.add_argument("--forced-ds-max", type=float, default=None,
                        help="the forced response's ds_max with the chord rule (default: StepControl's)")
    parser.add_argument("--joint-contacts", type=int, default=30, choices=(30, 120, 480),
                        help="the lap joint's contact elements in (b) (default 30)")
    parser.add_argument("--cases", default="abc", help="which cases to run (default abc)")
    args = parser.parse_args(argv)

    from microslip import nonlinear_modes

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    load = os.getloadavg()[0]
    dofs, contacts, blade_amp = (300, 20, (1e-7, 1e-5)) if args.quick else (1000, 40, (1e-7, 1e-4))
    joint_amp = (1e-6, 1.2e-5) if args.quick else (3e-7, 1e-4)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        nonlinear_modes(blade_case(300, 2)[0], 1, (1e-7, 1e-6), harmonics=3)  # compiled kernels loaded first
    figures = {"quick": args.quick, "load_average": load, "refine": REFINE}
    structure, force, tip, _ = blade_case(dofs, contacts)
    if "a" in args.cases:
        old, new = mode_controls(*blade_amp, args)
        figures["blade_mode"] = compare(
            f"(a) blade mode, {structure.ndof} DOFs, {contacts} contacts, {blade_amp[0]:.0e}-{blade_amp[1]:.0e}",
            ["frequency", "damping_ratio"], lambda c: run_mode(structure, blade_amp, c), old, new, denser_turns(old))
        figures["blade_mode"]["new_control"] = {"chord_error": new.chord_error, "ds_max": new.ds_max,
                                             "max_angle": new.max_angle}
    if "b" in args.cases:
        from bench_joint import SAMPLES, build

        _, joint = build(args.joint_contacts)
        old, new = mode_controls(*joint_amp, args)
        figures["joint_backbone"] = compare(
            f"(b) lap joint backbone, {args.joint_contacts} contacts, {joint.ndof} DOFs, "
            f"{joint_amp[0]:.0e}-{joint_amp[1]:.0e}",
            ["frequency", "damping_ratio"], lambda c: run_mode(joint, joint_amp, c, samples=SAMPLES), old, new,
            denser_turns(old))
        figures["joint_backbone"]["new_control"] = {"chord_error": new.chord_error, "ds_max": new.ds_max,
                                             "max_angle": new.max_angle}
    if "c" in args.cases:
        old, new = forced_controls(args)
        hz = 1 / (2 * np.pi)
        figures["blade_forced"] = compare(
            f"(c) blade forced response, {RANGE[0] * hz:.0f}-{RANGE[1] * hz:.0f} Hz",
            ["amplitude"], lambda c: run_forced(structure, force, tip, RANGE, c), old, new)
        figures["blade_forced"]["new_control"] = {"chord_error": new.chord_error, "ds_max": new.ds_max,
                                             "max_angle": new.max_angle}
    print(f"load average {load:.2f} at the start (2 cores shared: times are indicative)")
    figures["joint_contacts"] = args.joint_contacts
    figures["description"] = ("Points and interpolation error of the continuation's old step control (the turn rule) "
                              "and the new (the chord rule: the default of nonlinear modes, opt-in for forced "
                              "responses), against a curve with 4x shorter steps: the largest difference of each "
                              "quantity between the points, relative to its range; for the modes, the fewest "
                              "points with which the turn rule (at 10, 20, 28 and 40 points per decade) is as "
                              "close as the chord rule.")
    figures["command"] = " ".join(["OPENBLAS_NUM_THREADS=1 python benchmarks/bench_step_control.py",
                                   *(argv if argv is not None else sys.argv[1:])])
    figures["tables"] = [{"caption": "points and interpolation errors (old, new)",
                          "columns": ["case", "reference points", "old points", "new points", "old / new points",
                                      "turn rule points for the new error", "old errors", "new errors"],
                          "rows": [[case, figures[case]["reference"]["points"], figures[case]["old"]["points"],
                                    figures[case]["new"]["points"], figures[case]["points_old_over_new"],
                                    _turn_points(figures[case]),
                                    ", ".join(f"{q} {e:.2e}" for q, e in figures[case]["old"]["errors"].items()),
                                    ", ".join(f"{q} {e:.2e}" for q, e in figures[case]["new"]["errors"].items())]
                                   for case in ("blade_mode", "joint_backbone", "blade_forced") if case in figures]}]
    name = "bench_step_control" + ("_quick" if args.quick else "") + ("" if args.joint_contacts == 30 else
                                                                       f"_joint{args.joint_contacts}")
    save_results(name, figures)
    return 0


if __name__ == "__main__":
    sys.exit(main())
