"""``microslip simulate``: march a saved model through a displacement history from a file."""

from __future__ import annotations

import numpy as np

from ._args import image_file, output_file, quantity


def add_parser(sub) -> None:
    p = sub.add_parser(
        "simulate", help="run a saved model through a history of t (and n) read from a table",
        description="Run a model (JSON from 'microslip tune') through the tangential displacement "
                    "history in a CSV/text table whose header names columns with units, e.g. "
                    "'t [um], n [um]'. Writes the forces as CSV (SI units). A model driven beyond the load it "
                    "was tuned for (its file records it) is run, with a warning naming both loads.")
    p.add_argument("model", help="model JSON file")
    p.add_argument("history", help="table with a column of tangential displacement and, optionally, "
                                   "of normal approach")
    p.add_argument("--t-column", default="t", metavar="NAME",
                   help="name of the tangential displacement column (default t)")
    p.add_argument("--n-column", default="n", metavar="NAME", help="name of the normal approach column (default n)")
    p.add_argument("--unit", default=None,
                   help="unit of the t and n columns whose header gives none, e.g. um (default m); a unit that "
                        "differs from the header's is an error, never an override")
    normal = p.add_mutually_exclusive_group()
    normal.add_argument("--n", dest="n_const", type=quantity("length"), default=None,
                        help="constant normal approach instead of a column, e.g. 2um (negative: separated)")
    normal.add_argument("--load", type=quantity("force", sign="non-negative"), default=None,
                        help="constant normal load instead of a column, e.g. 30N (converted with the model's "
                             "own normal curve)")
    p.add_argument("-o", "--output", default="forces.csv", type=output_file("forces.csv"),
                   help="CSV file to write (default forces.csv)")
    p.add_argument("--plot", default=None, type=image_file,
                   help="also save the T-t curve to this image file (PNG, PDF, SVG, ...)")
    p.set_defaults(func=run)


def run(args) -> int:
    import warnings

    from ..common._io import save_figure, write_csv
    from ..common._table import column_si, header_unit, read_table
    from ..model import BeyondTuningWarning, MicroslipModel

    model = MicroslipModel.load(args.model)
    columns, units = read_table(args.history)

    def length_column(name):
        unit = header_unit(units, name, args.unit, "length", path=args.history, option="--unit")
        return column_si(columns, units, name, "length", path=args.history, unit=unit)

    t = length_column(args.t_column)
    held = ""
    if args.n_const is not None:
        n = np.full_like(t, args.n_const)
    elif args.load is not None:
        n = np.full_like(t, float(model.approach(args.load)))
        held = f" at {args.load:.6g} N, approach {n[0]:.4g} m"
    else:
        n = length_column(args.n_column)
    tuned = model.provenance
    with warnings.catch_warnings():
        if args.load is not None and tuned is not None and args.load > tuned.normal_load:
            warnings.warn(f"--load {args.load:.6g} N is beyond the load {args.model} was tuned for "
                          f"({tuned.normal_load:.6g} N; tuned range 0-{tuned.normal_load:.6g} N, approach up to "
                          f"{tuned.approach:.4g} m): there every element is closed and the model only extrapolates "
                          f"linearly (approach {n[0]:.4g} m)", BeyondTuningWarning)
            warnings.simplefilter("ignore", BeyondTuningWarning)  # said above, in the command's own terms
        r = model.simulate(t, n, per_element=False)
    write_csv(args.output, {"t [m]": r.t, "n [m]": r.n, "T [N]": r.T, "N [N]": r.N})
    if args.plot:
        ax = r.plot()
        save_figure(ax.figure, args.plot, dpi=150, bbox_inches="tight")
    print(f"wrote {args.output} ({t.size} steps{held}, dissipation {r.dissipation:.4g} J)")
    return 0
