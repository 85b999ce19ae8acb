"""``microslip campbell``: the Campbell diagram of a structure (or a cyclic sector) over rotation speed, from a TOML file."""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from ._args import add_output_folder, positive_int

SYSTEMS = ("both", "stuck", "free")


def engine_orders(text):
    """An argparse ``type`` for engine orders: whole numbers >= 1 separated by commas (``1,2,3`` or ``1-6``)."""
    out = []
    for part in str(text).split(","):
        part = part.strip()
        lo, dash, hi = part.partition("-")
        try:
            values = range(int(lo), int(hi) + 1) if dash else [int(part)]
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected engine orders such as 1,2,3 or 1-6, got {text!r}") from None
        if dash and int(hi) < int(lo):
            raise argparse.ArgumentTypeError(f"a range of engine orders must rise, such as 1-6, got {part!r}")
        out.extend(values)
    if not out or min(out) < 1:
        raise argparse.ArgumentTypeError(f"engine orders must be whole numbers >= 1, got {text!r}")
    if len(out) > 1000:
        raise argparse.ArgumentTypeError(f"at most 1000 engine orders, got {len(out)} from {text!r}")
    return sorted(set(out))


def add_parser(sub) -> None:
    p = sub.add_parser(
        "campbell", help="Campbell diagram: natural frequencies against rotation speed, engine-order crossings",
        description="Compute the Campbell diagram of a structure whose stiffness depends on the rotation speed "
                    "(centrifugal stiffening, spin softening): its natural frequencies with the contacts stuck at "
                    "their static state and without contacts, against the speed, the engine-order lines "
                    "f = EO x speed / 60 (rpm) and their crossings, each refined to 1e-13 of the speed. The TOML "
                    "configuration is the frf format (microslip.config.frf; python -c 'import microslip.config.frf "
                    "as c; print(c.__doc__)') with a [speed] table: at = [2 or 3 speeds], [structure] K at the first "
                    "and K = [the matrices at the others] (files or inline), K(speed) = K0 + speed^2 K1 "
                    "(+ speed^4 K2) through them; [campbell] (optional) sets the range of speeds, the points, the "
                    "engine orders, the modes, the systems and, for a [cyclic] sector, the nodal diameters. For a "
                    "sector every nodal diameter's modes are solved in that diameter, and engine order k crosses "
                    "only the diameter it excites (k = +-d mod N sectors). [excitation] and [sweep] are not needed. "
                    "Writes campbell.csv (every curve, rad/s, rpm and Hz, and the crossings) and campbell.png. "
                    "Exit status: 0 on success, 1 when a static state or an eigen-solve fails, 2 for an invalid "
                    "configuration, 130 when interrupted.")
    p.add_argument("config", help="TOML configuration file (the frf format with a [speed] table)")
    p.add_argument("--points", type=positive_int, default=None,
                   help="evenly spaced speeds over [campbell] speeds (default: [campbell] points, else 41)")
    p.add_argument("--modes", type=positive_int, default=None,
                   help="modes per system, per nodal diameter for a sector (default: [campbell] modes, else 6 or "
                        "the DOFs)")
    p.add_argument("--engine-orders", type=engine_orders, default=None, metavar="LIST",
                   help="engine orders of the lines, e.g. 1,2,3 or 1-6 (default: [campbell] engine_orders, "
                        "else 1-6)")
    p.add_argument("--contacts", choices=SYSTEMS, default=None,
                   help="the systems: 'stuck' (contacts stuck at their static state), 'free' (no contacts) or "
                        "'both' (default: [campbell] contacts, else both)")
    add_output_folder(p, "microslip-campbell")
    p.set_defaults(func=run)


def run(args) -> int:
    import sys

    import matplotlib.pyplot as plt

    from ..config import load_config
    from ..frequency import ConvergenceError, SpeedModel, campbell
    from ..frequency.analyses.campbell import RPM

    cfg = load_config(args.config, campbell=True)
    table = cfg.campbell
    speeds = table.speeds if args.points is None else np.linspace(table.speeds[0], table.speeds[-1], args.points)
    if speeds.size < 2:
        raise ValueError(f"--points must be at least 2 (speeds from {table.speeds[0]:.6g} to "
                         f"{table.speeds[-1]:.6g} rad/s), got {speeds.size}")
    structure = cfg.structure  # the template of the contacts (a sector's: its symmetry too)
    model = SpeedModel(structure.M, structure.C, cfg.speed.stiffness, cfg.speed.at, contacts=structure,
                       dof_map=structure.dof_map)
    out = Path(args.out)
    try:
        diagram = campbell(model, speeds, modes=args.modes or table.modes,
                           engine_orders=args.engine_orders or table.engine_orders,
                           contacts=args.contacts or table.contacts, nodal_diameters=table.nodal_diameters,
                           progress=not args.quiet)
    except ConvergenceError as exc:
        print(f"microslip campbell: error: {exc}", file=sys.stderr)
        return 1
    out.mkdir(parents=True, exist_ok=True)
    csv = diagram.to_csv(out / "campbell.csv")
    fig, ax = plt.subplots(figsize=(7.5, 5.2))
    diagram.plot(ax=ax)
    ax.set_title(cfg.title)
    png = out / "campbell.png"
    fig.savefig(png, dpi=150, bbox_inches="tight")
    plt.close(fig)
    what = (f"nodal diameters {', '.join(map(str, diagram.nodal_diameters))} of {diagram.sectors} sectors"
            if diagram.nodal_diameters is not None else f"{structure.ndof} DOFs")
    print(f"{cfg.title}: {what}, {speeds.size} speeds from {speeds[0] * RPM:.6g} to {speeds[-1] * RPM:.6g} rpm, "
          f"{len(diagram.crossings)} crossings with engine orders {', '.join(map(str, diagram.engine_orders))}")
    for c in diagram.crossings:
        nd = f" ND {c['nodal_diameter']}" if "nodal_diameter" in c else ""
        print(f"  {c['system']:5s}{nd} mode {c['mode']} x EO{c['engine_order']}: {c['speed'] * RPM:.6g} rpm "
              f"({c['speed']:.6g} rad/s), {c['frequency'] / (2 * np.pi):.6g} Hz")
    print(f"wrote {csv} and {png}")
    return 0
