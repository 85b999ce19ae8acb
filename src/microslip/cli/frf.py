"""``microslip frf``: forced response of a structure with microslip contacts, from a TOML file."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..common.units import display_unit
from ._args import add_output_folder, percent
from ._contacts import static_tangential
from ._prestress import add_prestress_option, report_prestress


def add_parser(sub) -> None:
    p = sub.add_parser(
        "frf", help="forced response (harmonic balance + continuation) of a structure with contacts",
        description="Compute the forced response of a linear structure carrying microslip contacts over a "
                    "frequency range: harmonic balance with alternating frequency-time contact forces, "
                    "Newton's method with the exact Jacobian, pseudo-arclength continuation. The TOML "
                    "configuration gives the matrices (inline or .npz), the contacts (model JSON files from "
                    "'microslip tune'), the excitation and the sweep; its format is printed by "
                    "'microslip config-reference'. Writes frf.csv, frf.png, contacts.png, report.html and report.md, "
                    "and, with "
                    "contacts, contact_cycle.png and contact_cycle.csv (each contact's normal and tangential force "
                    "over one period at the peak, with its slip state: stuck, microslip, gross slip, lift-off); "
                    "prints each contact's static state (normal and tangential force, elements closed), each "
                    "damper's static balance, each contact's forces and slip states at the peak and the curve's "
                    "unstable stretches (Hill's method; dashed in the plot). Exit status: "
                    "0 on success, 1 when the solution fails or the curve stops at [continuation] max_points "
                    "before the end of the range (the results up to there are written), 2 for an invalid "
                    "configuration, 130 when interrupted (Ctrl-C: the curve up to there is written). A DOF whose "
                    "curve is highest at an end of the range (the resonance lies outside it) is named in a warning "
                    "and in the report. Plots and the report give frequencies in Hz unless [output] "
                    "frequency_unit = \"rad/s\"; frf.csv has both. A contact that opens and closes faster than "
                    "the AFT samples resolve is named in a warning and in the report, with the [sweep] samples "
                    "that resolve it. With a [prestress] table (or --prestress) the structure is first prestressed "
                    "under its static loads with the friction released or stuck, the dynamics start from that "
                    "state, and prestress.csv holds each contact's static state (the report adds the prestressed "
                    "structure's linear modes).")
    p.add_argument("config", help="TOML configuration file")
    add_prestress_option(p)
    add_output_folder(p, "microslip-frf")
    p.set_defaults(func=run)


def _frequency(cfg, omega):
    """Frequencies in the configured unit, and the axis label."""
    if cfg.frequency_unit == "Hz":
        return omega / (2 * np.pi), "excitation frequency f (Hz)"
    return omega, "excitation frequency ω (rad/s)"


def _plots(result, cfg):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for d in cfg.plot_dofs:
        result.plot(d, cfg.harmonic, ax=ax, label=cfg.dof_names[d], frequency_unit=cfg.frequency_unit)
    what = "max |q - q0| over a period" if cfg.harmonic is None else f"harmonic {cfg.harmonic} amplitude"
    ax.set_ylabel(f"{what} (µm)")
    ax.set_title(cfg.title)
    figs = [("frf", fig, f"Forced response: {what} of each DOF against the excitation frequency.")]
    if result.structure.contacts:
        fig2, (a1, a2) = plt.subplots(2, 1, figsize=(6.5, 6), sharex=True)
        x, label = _frequency(cfg, result.omega)
        unit, factor = display_unit(result.contact_dissipation, "energy")
        for c, contact in enumerate(result.structure.contacts):
            a1.plot(x, result.contact_dissipation[:, c] * factor, label=contact.name)
            a2.plot(x, result.contact_N[:, c, 0], label=contact.name)
        a1.set_ylabel(f"energy dissipated per cycle ({unit})")
        a2.set_ylabel("static normal load (N)")
        a2.set_xlabel(label)
        for a in (a1, a2):
            a.grid(True, alpha=0.3)
            a.legend()
        figs.append(("contacts", fig2, "Energy dissipated per cycle and static normal load of each contact."))
    return figs


def run(args) -> int:
    import sys
    import warnings

    from ..frequency import (ConvergenceError, IncompleteCurveWarning, NotPeriodicError, UnderResolvedWarning,
                             frequency_response)
    from ..frequency.analyses.response import CurveInterrupted, PeakOnEdgeWarning, edge_message, incomplete_message
    from ..config import apply_prestress, load_config
    from ..common.report import Report, plural
    from ._contacts import add_section

    cfg = load_config(args.config)
    out = Path(args.out)
    interrupted = None
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("ignore", IncompleteCurveWarning)  # reported below, as an error
            warnings.simplefilter("always", UnderResolvedWarning)  # printed and written in the report below
            state, table, force = apply_prestress(cfg, cfg.force, getattr(args, "prestress", None))
            result = frequency_response(cfg.structure, force, cfg.omega, harmonics=cfg.harmonics,
                                        samples=cfg.samples, control=cfg.control, progress=not args.quiet,
                                        reduction=cfg.reduction, modes=cfg.modes, engine_order=cfg.engine_order,
                                        prestress=state)
    except (ConvergenceError, NotPeriodicError) as exc:
        print(f"microslip frf: error: {exc}", file=sys.stderr)
        return 1
    except CurveInterrupted as exc:  # Ctrl-C: the curve up to there is written, marked
        result, interrupted = exc.partial, exc
    resolution = []
    for w in caught:
        if issubclass(w.category, UnderResolvedWarning):  # advice on [sweep] samples, without a traceback line
            resolution.append(str(w.message).replace("samples=", "[sweep] samples = "))
            print(f"microslip frf: warning: {resolution[-1]}", file=sys.stderr)
        else:
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    csv = result.to_csv(out / "frf.csv", dofs=range(cfg.structure.ndof) if cfg.structure.ndof <= 20
                        else cfg.plot_dofs, names=cfg.dof_names)
    report = Report(f"microslip frf: {cfg.title}", parameters={
        "configuration": str(args.config), "DOFs": cfg.structure.ndof, "contacts": len(cfg.structure.contacts),
        "harmonics H": cfg.harmonics, "AFT samples per period": result.samples,
        f"frequency range ({cfg.frequency_unit})": "{:.6g} to {:.6g}".format(*_frequency(cfg, np.array(cfg.omega))[0]),
        "reduction": result.reduction,
        "modes": result.modes if result.modes else "-", "output": str(out)})
    lo, hi = _frequency(cfg, np.array(cfg.omega))[0]
    reduced = (f"the linear structure condensed onto the {result.dofs.size} DOFs the contacts and the excitation "
               f"use ({result.reduction}" + (f", {result.modes} modes, estimated error "
                                             f"{result.reduction_error:.2g}" if result.modes else "") + ")"
               if result.reduction != "none" else "every DOF solved")
    report.text(f"Configuration `{args.config}`: {plural(cfg.structure.ndof, 'DOF')}, "
                f"{plural(len(cfg.structure.contacts), 'contact')}, H = {result.harmonics} harmonics, {result.samples} AFT samples per period, "
                f"excitation frequency from {lo:.6g} to {hi:.6g} {cfg.frequency_unit}; {reduced}.")
    report.table(["harmonic", "DOF", "amplitude (N)", "phase (°)"], _excitation_rows(cfg),
                 caption="Excitation: force amplitude on each DOF (static: a constant force)")
    if state is not None:
        for line in report_prestress(report, state, table, cfg, out):
            print(line)
    report.text(f"{result.points} points in {result.elapsed:.3g} s "
                f"({result.iterations.sum()} Newton iterations). Curve: `frf.csv` (SI units, ω in rad/s and f in "
                f"Hz).")
    rows, edges = [], []
    for d in cfg.plot_dofs:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", PeakOnEdgeWarning)  # said once below, with the DOF's name
            w, a = result.peak(d, cfg.harmonic)
        edge = result.peak_on_edge(d, cfg.harmonic)
        rows.append([cfg.dof_names[d], f"{w / (2 * np.pi):.6g}", f"{w:.6g}", f"{a * 1e6:.6g}",
                     "on the range's edge: no peak" if edge else "peak"])
        if edge:
            edges.append(f"{cfg.dof_names[d]}: " + edge_message(result.omega, result.amplitude(d, cfg.harmonic),
                                                                result.complete).replace("widen the range",
                                                                                         "widen [sweep] omega"))
            print(f"microslip frf: warning: {edges[-1]}", file=sys.stderr)
    report.table(["DOF", "peak f (Hz)", "peak ω (rad/s)", "peak amplitude (µm)", "highest point"], rows,
                 caption="Highest point of each plotted DOF's curve ('on the range's edge': the response still rises "
                         "at an end of the curve, so the resonance lies outside the range)")
    for text in edges:
        report.text(f"**Highest on the range's edge**: {text}.")
    if interrupted is not None:
        report.text(f"**Interrupted** ({interrupted}): the curve stops there.")
    elif not result.complete:
        report.text(f"**Incomplete curve**: {incomplete_message(result, cfg.omega[1], cfg.control)}.")
    for text in resolution:
        report.text(f"**Sampling**: {text}.")
    stability = ("Stability was not computed: the computation was interrupted." if result.stable is None
                 and interrupted is not None else _stability_text(result, cfg))
    report.text(stability)
    print(stability)
    if result.bifurcations:
        report.table(["kind", "ω (rad/s)", "f (Hz)"] + [f"{cfg.dof_names[d]} (µm)" for d in cfg.plot_dofs],
                     [[b.kind, f"{b.omega:.6g}", f"{b.omega / (2 * np.pi):.6g}"]
                      + [f"{b.interpolate(result.amplitude(d, cfg.harmonic)) * 1e6:.6g}" for d in cfg.plot_dofs]
                      for b in result.bifurcations],
                     caption="Bifurcations along the curve (between two points, linearly interpolated): "
                             "the response amplitude of each plotted DOF there")
    unit, factor = display_unit(result.contact_dissipation, "energy")
    for c, contact in enumerate(result.structure.contacts):
        report.text(_static_text(result, c) + f" Along the curve: mean normal load "
                    f"{result.contact_N[:, c, 0].min():.6g} to {result.contact_N[:, c, 0].max():.6g} N; "
                    f"largest energy dissipated per cycle {result.contact_dissipation[:, c].max() * factor:.4g} "
                    f"{unit}.")
        print(_static_text(result, c))
    for name, fig, caption in _plots(result, cfg):
        report.figure(fig, name, caption, out)
    if result.structure.contacts:
        for line in add_section(report, result, cfg, out):
            print(line)
    report.write(out)
    print(f"wrote {csv}, {out / 'frf.png'} and {out / 'report.html'} ({result.points} points, "
          f"{result.elapsed:.3g} s)")
    if interrupted is not None:
        print(f"microslip frf: interrupted: {interrupted}; the curve written stops there", file=sys.stderr)
        return 130
    if not result.complete:
        print(f"microslip frf: error: incomplete curve: {incomplete_message(result, cfg.omega[1], cfg.control)} "
              f"(set max_points in [continuation]); the results written stop there", file=sys.stderr)
        return 1
    return 0


def _stability_text(result, cfg) -> str:
    """Which stretches of the curve are unstable (Hill's method), in the configured frequency unit, and its folds."""
    if result.stable is None:
        from ..frequency.analyses.stability import HILL_LIMIT

        return (f"Stability was not computed: Hill's eigenproblem would have more than {HILL_LIMIT} unknowns "
                "(the whole structure's with reduction = \"exact\"; use reduction = \"modal\"), or the "
                "structure is a cyclic sector.")
    folds = sum(b.kind == "fold" for b in result.bifurcations)
    fold_text = f" The curve has {folds} fold{'s' if folds != 1 else ''}." if folds else ""
    if result.stable.all():
        return ("Stability (Hill's method): every point is stable (every Floquet exponent the harmonics resolve "
                "has a negative real part)." + fold_text)
    edges = np.flatnonzero(np.diff(np.concatenate([[0], (~result.stable).astype(int), [0]])))
    x, _ = _frequency(cfg, result.omega)
    stretches = [f"{x[lo:hi].min():.6g} to {x[lo:hi].max():.6g} {cfg.frequency_unit} (points {lo} to {hi - 1})"
                 for lo, hi in zip(edges[::2], edges[1::2])]
    return (f"Stability (Hill's method): {int((~result.stable).sum())} of {result.points} points are unstable "
            f"(dashed in the plot), from " + "; ".join(stretches) + "." + fold_text)


def _excitation_rows(cfg) -> list:
    """Rows ``(harmonic, DOF name, amplitude N, phase deg)`` of every non-zero force amplitude."""
    rows = []
    for h in sorted(cfg.force):
        for d, F in enumerate(np.asarray(cfg.force[h])):
            if F != 0:
                rows.append(["static" if h == 0 else str(h), cfg.dof_names[d], f"{abs(F):.6g}",
                             f"{np.degrees(np.angle(F)):.4g}"])
    return rows


def _static_text(result, c: int) -> str:
    """One contact's static state: normal and tangential force, share of the slip force, closed elements."""
    contact = result.structure.contacts[c]
    N0, T0 = result.static_normal_force[c], static_tangential(result, c)
    limit = contact.model.mu * N0
    share = f"{percent(abs(T0) / limit)} % of the slip force mu N0" if limit > 0 else "open"
    preload = f" (preload {contact.preload:.6g} N on the structure)" if contact.preload else ""
    return (f"Contact {contact.name}: {contact.model!r}; static state: normal force N0 = {N0:.6g} N{preload}, "
            f"tangential force T0 = {T0:.6g} N ({share}), {result.static_closed_elements[c]} of "
            f"{contact.model.elements} elements closed.")
