"""``microslip target``: tune the paper's array to an accuracy target over a load range, or sweep J."""

from __future__ import annotations

import json
from pathlib import Path

from ._args import (add_sphere_options, checked, fraction, load_range, output_file, output_folder, percent, positive_int,
                    sphere_from)


def _elements_list(text):
    import argparse

    out = []
    for part in str(text).split(","):
        part = part.strip()
        try:
            if "-" in part:
                a, b = (int(x) for x in part.split("-"))
                out += list(range(a, b + 1))
            elif part:
                out.append(int(part))
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected element counts such as 2-16,20,24, got {text!r}") from None
    if not out or min(out) < 1:
        raise argparse.ArgumentTypeError(f"expected positive element counts such as 2-16,20,24, got {text!r}")
    return out


def add_parser(sub) -> None:
    p = sub.add_parser(
        "target", help="tune to an accuracy target: optimise the tuning points, find the smallest J, sweep J",
        description="Tune the paper's array (its eqs. 1-9, at the top of the load range) with tuning points "
                    "chosen to minimise the worst error against the exact continuous contact over the family "
                    "of variable-normal-load cycles within the load range (lowest load >= N_lo) and with "
                    "tangential amplitudes >= --min-amplitude times the gross-slip displacement at the path's "
                    "lowest load. The worst error is max(|energy error|/energy target, force difference/force "
                    "target). With --elements J: optimise the points of J elements. Without: find the smallest "
                    "J meeting both targets (exit status 1 and the best found if none up to --max-elements "
                    "does). With --sweep: the worst errors against J for points evenly spaced in force, evenly "
                    "spaced in displacement and optimised (slow: minutes for J up to 32).")
    p.add_argument("--reference", choices=["sphere"], default="sphere",
                   help="the reference contact (default: sphere)")
    add_sphere_options(p)
    p.add_argument("--load-range", type=load_range, default=(7.5, 37.5),
                   help="loads N_lo,N_hi the contact meets, e.g. 7.5N,37.5N (default); tuned at N_hi")
    p.add_argument("--energy-target", type=fraction, default=0.02,
                   help="worst allowed |energy-per-cycle error|: 2%% or 0.02 (a fraction; a bare number above 1 "
                        "is refused) (default 2%%)")
    p.add_argument("--force-target", type=fraction, default=0.02,
                   help="worst allowed force difference, of the reference's peak force: 2%% or 0.02 (default 2%%)")
    p.add_argument("--min-amplitude", type=float, default=0.5,
                   help="smallest tangential amplitude of the family, as a multiple of the gross-slip "
                        "displacement at a path's lowest load (default 0.5)")
    p.add_argument("--dense", action="store_true",
                   help="sample the family densely (40 amplitudes from --min-amplitude to 3, 10 load levels; "
                        "1560 paths instead of 96 at the defaults): the worst error over the continuous ranges "
                        "rather than over the default family's samples (about 15x slower per model)")
    what = p.add_mutually_exclusive_group()
    what.add_argument("--elements", type=positive_int, default=None, help="optimise the points of this many elements")
    what.add_argument("--sweep", type=_elements_list, default=None,
                      help="sweep these J, e.g. 2-16,20,24,28,32, and write sweep.csv and sweep.png to --out")
    p.add_argument("--method", choices=("global", "local"), default="global",
                   help="point search: 'global' (differential evolution seeded by spacing laws, then "
                        "Nelder-Mead; default) or 'local' (Nelder-Mead from the best spacing law only)")
    p.add_argument("--budget", type=positive_int, default=None,
                   help="models evaluated by the differential evolution per J (default 600 J; about 3 ms each "
                        "on the default family)")
    p.add_argument("--seed", type=int, default=0, help="seed of the differential evolution (default 0)")
    p.add_argument("--max-elements", type=positive_int, default=32,
                   help="largest J tried when searching for the smallest (default 32)")
    p.add_argument("--reuse-points", action="store_true",
                   help="with --sweep: re-measure the optimised points stored with the package instead of "
                        "searching again (fast; refused unless the problem is theirs: the paper's sphere, "
                        "7.5N,37.5N, --min-amplitude 0.5, equal targets)")
    p.add_argument("--start-from-stored", action="store_true",
                   help="with --sweep: start each J's search from the points stored with the package too (the "
                        "result is then never worse than them)")
    p.add_argument("--save-points", default=None, type=output_file("points.json"),
                   help="with --sweep: write the optimised points to this JSON file")
    p.add_argument("-o", "--output", default=None, type=output_file("model.json"),
                   help="without --sweep: the model file to write (default model.json)")
    p.add_argument("--out", default=None, type=output_folder, metavar="DIR",
                   help="with --sweep: the folder for sweep.csv, sweep.png and sweep.txt, created if needed "
                        "(default ./microslip-target)")
    p.add_argument("--quiet", action="store_true", help="do not show progress on standard error")
    p.set_defaults(func=run)


def run(args) -> int:
    from ..common._progress import Progress
    from ..tuning.target import TargetNotMet, TargetProblem, optimal_points, smallest_elements

    _check_options(args)
    reference = sphere_from(args)
    if args.reuse_points:  # before the exact reference is built
        from ..tuning.target import stored_mismatch

        why = stored_mismatch(reference, args.load_range, min_amplitude=args.min_amplitude,
                              energy_target=args.energy_target, force_target=args.force_target)
        if why:
            raise ValueError(f"--reuse-points: the stored points do not solve this problem ({why}); drop "
                             "--reuse-points to search (minutes), or --start-from-stored to start from them")
    bar = Progress(1, enabled=not args.quiet)
    bar.step("load paths and exact reference")
    problem = TargetProblem(reference, args.load_range, energy_target=args.energy_target,
                            force_target=args.force_target, min_amplitude=args.min_amplitude, dense=args.dense)
    if args.sweep is not None:
        return _sweep(args, problem)
    if args.elements is not None:
        res = optimal_points(problem, args.elements, progress=not args.quiet, **_search(args))
    else:
        try:
            res = smallest_elements(reference, args.load_range, problem=problem, max_elements=args.max_elements,
                                    progress=not args.quiet, **_search(args))
        except TargetNotMet as exc:
            exc.best.model.save(args.output)
            print(json.dumps(_summary(exc.best, args.output, meets=False)))
            print(f"microslip target: {exc}")
            return 1
    res.model.save(args.output)
    print(json.dumps(_summary(res, args.output, meets=res.meets)))
    return 0


def _check_options(args) -> None:
    """Refuse bad numbers and options that do not apply, naming the option (before any computation).

    ``-o`` names the model file a search writes, ``--out`` the folder a
    ``--sweep`` writes: each is refused where it would be ignored.
    """
    if args.sweep is not None and args.output is not None:
        raise ValueError(f"-o {args.output} names a model file, which --sweep does not write: --sweep writes "
                         "sweep.csv, sweep.png and sweep.txt into the folder --out DIR")
    if args.sweep is None:
        for option, value in (("--out", args.out), ("--save-points", args.save_points)):
            if value is not None:
                raise ValueError(f"{option} applies to --sweep only; without it the model goes to -o FILE")
    args.output = "model.json" if args.output is None else args.output
    args.out = "microslip-target" if args.out is None else args.out
    if args.sweep is None:  # the defaults are checked too
        checked("-o", output_file("model.json"), args.output)
    else:
        checked("--out", output_folder, args.out)
    if not (args.min_amplitude >= 0 and args.min_amplitude < float("inf")):
        raise ValueError(f"--min-amplitude must be a non-negative multiple of the gross-slip displacement, "
                         f"got {args.min_amplitude:g}")
    if args.seed < 0:
        raise ValueError(f"--seed must be a non-negative integer, got {args.seed}")
    if args.reuse_points and args.sweep is None:
        raise ValueError("--reuse-points applies to --sweep only")


def _search(args) -> dict:
    """Options of the point search from the command line."""
    return {"method": args.method, "budget": args.budget, "seed": args.seed}


def _summary(res, path, meets):
    return {"written": str(path), "elements": res.elements, "energy_error_percent": percent(res.energy_error),
            "force_difference_percent": percent(res.force_difference), "meets_target": bool(meets),
            "points_um": [round(x * 1e6, 6) for x in res.points.t]}


def _sweep(args, problem) -> int:
    import matplotlib.pyplot as plt

    from ..common._io import atomic_write, save_figure, write_csv
    from ..tuning.target import element_sweep, load_optimal_points, points_record

    stored = load_optimal_points()["fractions"] if args.reuse_points or args.start_from_stored else None
    sweep = element_sweep(problem, args.sweep, fractions=stored if args.reuse_points else None,
                          starts=stored if args.start_from_stored else None, progress=not args.quiet, **_search(args))
    out = Path(args.out)
    write_csv(out / "sweep.csv", sweep.columns())
    fig = sweep.plot()
    save_figure(fig, out / "sweep.png", dpi=130, bbox_inches="tight")
    plt.close(fig)
    if args.save_points:
        atomic_write(args.save_points, json.dumps(points_record(problem, sweep), indent=1) + "\n")
    lines = [f"worst errors over the family within {problem.load_range} N, amplitude >= "
             f"{problem.min_amplitude:g} t_gs(N_min), {len(problem.family)} paths"
             f"{' (dense sampling)' if problem.dense else ''}, against the exact contact (MDR); data: sweep.csv",
             "J    energy / force (%):  " + " | ".join(sweep.energy_error)]
    lines += [f"{row[0]:<4} " + " | ".join(row[1:]) for row in sweep.rows()]
    for s in sweep.energy_error:
        lines.append(f"smallest J meeting the target with {s} points: {sweep.smallest(s)}")
    atomic_write(out / "sweep.txt", "\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0
