"""``microslip simulate``: march a saved model through a displacement history from a file, or along an orbit."""

from __future__ import annotations

import numpy as np

from ._args import degrees, image_file, output_file, positive_int, quantity

#: the orbits of --orbit and the paths builder of each
ORBITS = {"circle": "circle", "ellipse": "ellipse", "figure-eight": "figure_eight", "line": "line"}


def add_parser(sub) -> None:
    p = sub.add_parser(
        "simulate", help="run a saved model through a history of t (and n) read from a table, or along an orbit",
        description="Run a model (JSON from 'microslip tune') through the tangential displacement history in a "
                    "CSV/text table whose header names columns with units, e.g. 't [um], n [um]' (a second "
                    "tangential column, --ty-column, puts the history on the contact plane), or along an orbit on "
                    "the contact plane built from options (--orbit circle, ellipse, figure-eight or line, with a "
                    "normal load varying along it). Writes the forces as CSV (SI units; both tangential components "
                    "on the plane). A model driven beyond the load it was tuned for (its file records it) is run, "
                    "with a warning naming both loads.")
    p.add_argument("model", help="model JSON file")
    p.add_argument("history", nargs="?", default=None,
                   help="table with a column of tangential displacement (two on the contact plane) and, "
                        "optionally, of normal approach; leave out with --orbit")
    table = p.add_argument_group("history from a table")
    table.add_argument("--t-column", default="t", metavar="NAME",
                       help="name of the tangential displacement column (default t); on the plane its first "
                            "component")
    table.add_argument("--ty-column", default=None, metavar="NAME",
                       help="name of a column with the second tangential component: the history is then on the "
                            "contact plane, each element an isotropic Jenkins slider (default: none, one direction)")
    table.add_argument("--n-column", default="n", metavar="NAME",
                       help="name of the normal approach column (default n)")
    table.add_argument("--unit", default=None,
                       help="unit of the t and n columns whose header gives none, e.g. um (default m); a unit that "
                            "differs from the header's is an error, never an override")
    orbit = p.add_argument_group("orbit on the contact plane (instead of a table)")
    orbit.add_argument("--orbit", choices=sorted(ORBITS), default=None,
                       help="circle of radius SIZE; ellipse of semi-axes SIZE and MINOR, its major axis at ANGLE; "
                            "figure-eight (SIZE sin tau, MINOR sin 2 tau) turned by ANGLE; line of amplitude SIZE "
                            "at ANGLE. Circles and ellipses start with a turn spiralling out of the centre. The "
                            "normal load along it is N = LOAD + LOAD_AMPLITUDE sin(tau + LOAD_PHASE), turned into "
                            "the approach by the model's own normal curve")
    orbit.add_argument("--size", type=quantity("length", sign="positive"), default=None, metavar="LENGTH",
                       help="radius (circle), semi-major axis (ellipse), half-width (figure-eight) or amplitude "
                            "(line), e.g. 1.5um; required with --orbit")
    orbit.add_argument("--minor", type=quantity("length", sign="positive"), default=None, metavar="LENGTH",
                       help="semi-minor axis (ellipse, at most SIZE) or half-height (figure-eight), e.g. 0.5um "
                            "(default: half of SIZE)")
    orbit.add_argument("--angle", type=degrees, default=0.0, metavar="DEG",
                       help="direction of the ellipse's major axis, the figure-eight's long axis or the line, in "
                            "degrees from the first tangential axis (default 0; not for a circle)")
    orbit.add_argument("--load-amplitude", type=quantity("force", sign="non-negative"), default=0.0, metavar="FORCE",
                       help="amplitude of the normal load along the orbit, at most LOAD, e.g. 10N (default 0: "
                            "constant)")
    orbit.add_argument("--load-phase", type=degrees, default=0.0, metavar="DEG",
                       help="lead of the normal load on the orbit's phase tau, degrees (default 0)")
    orbit.add_argument("--cycles", type=positive_int, default=3, metavar="N",
                       help="number of orbits; the energy per cycle is the last one's (default 3)")
    orbit.add_argument("--steps-per-cycle", type=positive_int, default=360, metavar="N",
                       help="samples per orbit, at least 8 (default 360)")
    normal = p.add_mutually_exclusive_group()
    normal.add_argument("--n", dest="n_const", type=quantity("length"), default=None,
                        help="constant normal approach instead of a column, e.g. 2um (negative: separated); "
                             "not with --orbit")
    normal.add_argument("--load", type=quantity("force", sign="non-negative"), default=None,
                        help="constant normal load instead of a column, e.g. 30N (converted with the model's "
                             "own normal curve); with --orbit the mean load along it (required there)")
    p.add_argument("-o", "--output", default="forces.csv", type=output_file("forces.csv"),
                   help="CSV file to write (default forces.csv)")
    p.add_argument("--plot", default=None, type=image_file,
                   help="also save a figure to this image file (PNG, PDF, SVG, ...): the T-t curve along one "
                        "direction; on the plane the force orbit next to the displacement orbit")
    p.set_defaults(func=run)


def _check_options(args) -> None:
    """What depends on several options: a table or an orbit, and what each needs."""
    if (args.history is None) == (args.orbit is None):
        raise ValueError("give either a HISTORY table or --orbit (an orbit built from options), not "
                         + ("both" if args.history is not None else "neither"))
    if args.orbit is None:
        given = [name for name, value in (("--size", args.size), ("--minor", args.minor)) if value is not None]
        if given:
            raise ValueError(f"{', '.join(given)} shape(s) an orbit: give --orbit too, or leave them out")
        return
    if args.n_const is not None:
        raise ValueError("--orbit takes the normal load (--load, --load-amplitude, --load-phase), not --n")
    if args.load is None:
        raise ValueError("--orbit needs --load, the mean normal load along the orbit (e.g. 30N)")
    if args.size is None:
        raise ValueError(f"--orbit {args.orbit} needs --size (e.g. 1.5um)")
    if args.minor is not None and args.orbit in ("circle", "line"):
        raise ValueError(f"--minor shapes an ellipse or a figure-eight, not a {args.orbit}")
    if args.angle != 0.0 and args.orbit == "circle":
        raise ValueError("--angle turns an ellipse, a figure-eight or a line; a circle has no direction")
    if args.load_amplitude > args.load:
        raise ValueError(f"--load-amplitude {args.load_amplitude:.6g} N exceeds --load {args.load:.6g} N: the normal "
                         f"load along the orbit would become negative")
    if args.minor is not None and args.orbit == "ellipse" and args.minor > args.size:
        raise ValueError(f"--minor {args.minor:.6g} m exceeds --size {args.size:.6g} m: the semi-minor axis of an "
                         f"ellipse is at most its semi-major axis")
    if args.steps_per_cycle < 8:
        raise ValueError(f"--steps-per-cycle must be at least 8, got {args.steps_per_cycle}")


def _orbit_path(args, model):
    """The orbit of the options as a :class:`~microslip.paths.Path` (the model's normal curve turns N into n)."""
    from ..accuracy import paths

    build = getattr(paths, ORBITS[args.orbit])
    minor = args.minor if args.minor is not None else 0.5 * args.size
    size = {"circle": (args.size,), "line": (args.size,)}.get(args.orbit, (args.size, minor))
    kwargs = dict(cycles=args.cycles, steps_per_cycle=args.steps_per_cycle)
    if args.orbit != "circle":
        kwargs["angle_deg"] = args.angle
    return build(model, *size, args.load, args.load_amplitude, args.load_phase, **kwargs)


def run(args) -> int:
    import warnings

    from ..common._io import save_figure, write_csv
    from ..model import BeyondTuningWarning, MicroslipModel

    _check_options(args)
    model = MicroslipModel.load(args.model)
    held, path = "", None
    if args.orbit is not None:
        path = _orbit_path(args, model)
        t, n = path.t, path.n
        held = f", {path.label}"
    else:
        t, n, held = _history(args, model)
    tuned = model.provenance
    top = args.load if args.load is not None and path is None else (float(path.N.max()) if path is not None else None)
    with warnings.catch_warnings():
        if top is not None and tuned is not None and top > tuned.normal_load:
            what = f"--load {top:.6g} N is" if path is None else f"the normal load along the orbit reaches {top:.6g} N,"
            warnings.warn(f"{what} beyond the load {args.model} was tuned for "
                          f"({tuned.normal_load:.6g} N; tuned range 0-{tuned.normal_load:.6g} N, approach up to "
                          f"{tuned.approach:.4g} m): there every element is closed and the model only extrapolates "
                          f"linearly (approach {float(np.max(n)):.4g} m)", BeyondTuningWarning)
            warnings.simplefilter("ignore", BeyondTuningWarning)  # said above, in the command's own terms
        r = model.simulate(t, n, per_element=False)
    if r.plane:
        columns = {"tx [m]": r.t[:, 0], "ty [m]": r.t[:, 1], "n [m]": r.n, "Tx [N]": r.T[:, 0], "Ty [N]": r.T[:, 1],
                   "N [N]": r.N}
    else:
        columns = {"t [m]": r.t, "n [m]": r.n, "T [N]": r.T, "N [N]": r.N}
    write_csv(args.output, columns)
    if args.plot:
        drawn = r.plot()
        figure = drawn[0].figure if r.plane else drawn.figure
        if path is not None:
            figure.suptitle(path.label)
        save_figure(figure, args.plot, dpi=150, bbox_inches="tight")
    energy = ""
    if path is not None:
        steady = r.friction_work[path.steady.start + 1:path.steady.stop].sum()
        energy = f", energy per cycle {steady:.4g} J (the last)"
    print(f"wrote {args.output} ({t.shape[0]} steps{held}, dissipation {r.dissipation:.4g} J{energy})")
    return 0


def _history(args, model):
    """``(t, n, description)`` from the HISTORY table and the normal options (m, m)."""
    from ..common._table import column_si, header_unit, read_table

    columns, units = read_table(args.history)

    def length_column(name):
        unit = header_unit(units, name, args.unit, "length", path=args.history, option="--unit")
        return column_si(columns, units, name, "length", path=args.history, unit=unit)

    t = length_column(args.t_column)
    if args.ty_column is not None:
        t = np.column_stack([t, length_column(args.ty_column)])
    held = ""
    if args.n_const is not None:
        n = np.full(t.shape[0], args.n_const)
    elif args.load is not None:
        n = np.full(t.shape[0], float(model.approach(args.load)))
        held = f" at {args.load:.6g} N, approach {n[0]:.4g} m"
    else:
        n = length_column(args.n_column)
    return t, n, held
