"""``microslip tune``: tune the paper's array on a reference contact and save it as JSON."""

from __future__ import annotations

import json

from ._args import add_sphere_options, quantity, sphere_from


def _quantity_list(kind):
    one = quantity(kind)

    def convert(text):
        return [one(p) for p in str(text).split(",") if p.strip()]

    convert.__name__ = f"comma-separated {kind} quantities"
    return convert


def add_parser(sub) -> None:
    p = sub.add_parser(
        "tune", help="tune a microslip model and write it as JSON",
        description="Tune the paper's microslip array on a reference contact (eqs. 1-9) and write the "
                    "model as JSON, readable by MicroslipModel.load and by 'microslip simulate'.")
    p.add_argument("--reference", choices=["sphere"], default="sphere",
                   help="the reference contact (default: sphere, Hertz + Cattaneo-Mindlin)")
    add_sphere_options(p)
    p.add_argument("--load", type=quantity("force"), default=37.5,
                   help="normal load N_tot to tune at, e.g. 37.5N (default 37.5N)")
    pts = p.add_mutually_exclusive_group()
    pts.add_argument("--elements", type=int, default=None,
                     help="number of elements J; points evenly spaced in force (default 4)")
    pts.add_argument("--forces", type=_quantity_list("force"), default=None,
                     help="tuning forces, comma-separated, increasing, last = mu*N_tot (e.g. 3.75N,7.5N,11.25N,15N)")
    pts.add_argument("--displacements", type=_quantity_list("length"), default=None,
                     help="tuning displacements, comma-separated, increasing, last at gross slip")
    p.add_argument("-o", "--output", default="model.json", help="model file to write (default model.json)")
    p.set_defaults(func=run)


def run(args) -> int:
    from ..tuning import tune

    reference = sphere_from(args)
    points_given = args.forces is not None or args.displacements is not None
    model = tune(reference, args.load, forces=args.forces, displacements=args.displacements,
                 elements=None if points_given else (4 if args.elements is None else args.elements))
    model.save(args.output)
    print(json.dumps({"written": args.output, "elements": model.elements, "mu": model.mu}))
    return 0
