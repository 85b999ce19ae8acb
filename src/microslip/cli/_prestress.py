"""The prestress of ``microslip frf`` and ``microslip modes``: ``[prestress]`` or ``--prestress``, and its report."""

from __future__ import annotations

import numpy as np


def add_prestress_option(parser) -> None:
    """``--prestress {released,stuck}``: a static step first, as a ``[prestress]`` table with that friction."""
    parser.add_argument("--prestress", choices=("released", "stuck"), default=None,
                        help="prestress the structure first under its static loads (preloads, [excitation] static, "
                             "the dampers' centrifugal loads): 'released' solves the static state without friction "
                             "and resets the contacts there, 'stuck' loads them from the unloaded state; the "
                             "dynamics start from it (overrides [prestress] friction, or adds that table)")


def report_prestress(report, p, table, cfg, out) -> list[str]:
    """The prestress's section of a report (its CSV written to ``out``); returns the lines to print."""
    csv = p.to_csv(out / "prestress.csv")
    sector = getattr(cfg.structure, "independent", None)  # a cyclic sector: its modes in the engine order's diameter
    if sector is None:
        modes = p.modes(min(table.modes, cfg.structure.ndof))
    else:
        modes = p.modes(min(table.modes, sector.size), nodal_diameter=cfg.engine_order % cfg.structure.sectors)
    hz = cfg.frequency_unit == "Hz"
    damping = ("" if table.modal_damping is None and table.rayleigh_damping is None else
               " The viscous damping was fitted on these modes: "
               + (f"modal damping ratios {', '.join(f'{z:.4g}' for z in table.modal_damping)} on the lowest "
                  f"{table.modal_damping.size}" if table.modal_damping is not None else
                  f"Rayleigh damping with ratios {table.rayleigh_damping[0]:.4g} and {table.rayleigh_damping[1]:.4g} "
                  f"on modes {table.rayleigh_modes[0]} and {table.rayleigh_modes[1]}") + ".")
    text = (f"Prestress: a static step with the friction {p.friction} under the static loads, then the dynamics "
            f"from that state" + (" (the contacts' sliders reset there)" if p.friction == "released" else "")
            + f"; each contact's static state in `{csv.name}`." + damping)
    report.text(text)
    report.table(["contact", "N0 (N)", "|T0| (N)", "|T0| / mu N0", "closed elements"],
                 [[c.name, f"{p.normal_force[i]:.6g}",
                   f"{np.hypot(p.tangential_force[i], p.tangential_force2[i]):.6g}",
                   "open" if np.isnan(p.slip_share()[i]) else f"{p.slip_share()[i]:.3g}",
                   f"{p.closed_elements[i]} of {c.model.elements}"] for i, c in enumerate(cfg.structure.contacts)],
                 caption="Static state of each contact after the prestress")
    report.table(["mode", f"frequency ({'Hz' if hz else 'rad/s'})"],
                 [[str(k + 1), f"{(modes.frequency if hz else modes.omega)[k]:.6g}"] for k in range(len(modes))],
                 caption="Linear modes of the prestressed structure (contacts stuck at the prestress: the closed "
                         "elements' stiffness)" + ("" if sector is None else
                                                   f", nodal diameter {cfg.engine_order % cfg.structure.sectors}"))
    return [p.summary(), "prestressed modes (" + ("Hz" if hz else "rad/s") + "): "
            + ", ".join(f"{f:.6g}" for f in (modes.frequency if hz else modes.omega))]
