"""``microslip frf``: forced response of a structure with microslip contacts, from a TOML file."""

from __future__ import annotations

from pathlib import Path

from ._args import add_output_folder


def add_parser(sub) -> None:
    p = sub.add_parser(
        "frf", help="forced response (harmonic balance + continuation) of a structure with contacts",
        description="Compute the forced response of a linear structure carrying microslip contacts over a "
                    "frequency range: harmonic balance with alternating frequency-time contact forces, "
                    "Newton's method with the exact Jacobian, pseudo-arclength continuation. The TOML "
                    "configuration gives the matrices (inline or .npz), the contacts (model JSON files from "
                    "'microslip tune'), the excitation and the sweep; its format is documented in "
                    "microslip.frequency.config (python -c 'import microslip.frequency.config as c; "
                    "print(c.__doc__)'). Writes frf.csv, frf.png, contacts.png, report.html and report.md, and prints "
                    "each contact's static state (normal and tangential force, elements closed). Exit status: "
                    "0 on success, 1 when the solution fails or the curve stops at [continuation] max_points "
                    "before the end of the range (the results up to there are written), 2 for an invalid "
                    "configuration.")
    p.add_argument("config", help="TOML configuration file")
    add_output_folder(p, "microslip-frf", "-o", "--output")
    p.set_defaults(func=run)


def _plots(result, cfg):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for d in cfg.plot_dofs:
        result.plot(d, cfg.harmonic, ax=ax, label=cfg.dof_names[d])
    what = "max |q - q0| over a period" if cfg.harmonic is None else f"harmonic {cfg.harmonic} amplitude"
    ax.set_ylabel(f"{what} (µm)")
    ax.set_title(cfg.title)
    figs = [("frf", fig, f"Forced response: {what} of each DOF against the excitation frequency.")]
    if result.structure.contacts:
        fig2, (a1, a2) = plt.subplots(2, 1, figsize=(6.5, 6), sharex=True)
        for c, contact in enumerate(result.structure.contacts):
            a1.plot(result.omega, result.contact_dissipation[:, c] * 1e3, label=contact.name)
            a2.plot(result.omega, result.contact_N[:, c, 0], label=contact.name)
        a1.set_ylabel("energy dissipated per cycle (mJ)")
        a2.set_ylabel("static normal load (N)")
        a2.set_xlabel("excitation frequency ω (rad/s)")
        for a in (a1, a2):
            a.grid(True, alpha=0.3)
            a.legend()
        figs.append(("contacts", fig2, "Energy dissipated per cycle and static normal load of each contact."))
    return figs


def run(args) -> int:
    import sys
    import warnings

    from ..frequency import ConvergenceError, IncompleteCurveWarning, NotPeriodicError, frequency_response
    from ..frequency.response import incomplete_message
    from ..frequency.config import load_config
    from ..common.report import Report

    cfg = load_config(args.config)
    out = Path(args.out)
    try:
        with warnings.catch_warnings():  # an incomplete curve is reported below, as an error
            warnings.simplefilter("ignore", IncompleteCurveWarning)
            result = frequency_response(cfg.structure, cfg.force, cfg.omega, harmonics=cfg.harmonics,
                                        samples=cfg.samples, control=cfg.control, progress=not args.quiet)
    except (ConvergenceError, NotPeriodicError) as exc:
        print(f"microslip frf: error: {exc}", file=sys.stderr)
        return 1
    csv = result.to_csv(out / "frf.csv", dofs=range(cfg.structure.ndof) if cfg.structure.ndof <= 20
                        else cfg.plot_dofs)
    report = Report(f"microslip frf: {cfg.title}")
    report.text(f"Configuration `{args.config}`: {cfg.structure.ndof} DOFs, {len(cfg.structure.contacts)} "
                f"contact(s), H = {result.harmonics} harmonics, {result.samples} AFT samples per period, "
                f"omega from {cfg.omega[0]:.6g} to {cfg.omega[1]:.6g} rad/s.")
    report.text(f"{result.points} points in {result.elapsed:.3g} s "
                f"({result.iterations.sum()} Newton iterations). Curve: `frf.csv` (SI units).")
    rows = []
    for d in cfg.plot_dofs:
        w, a = result.peak(d, cfg.harmonic)
        rows.append([cfg.dof_names[d], f"{w:.6g}", f"{w / (2 * 3.141592653589793):.6g}", f"{a * 1e6:.6g}"])
    report.table(["DOF", "peak ω (rad/s)", "peak f (Hz)", "peak amplitude (µm)"], rows,
                 caption="Highest point of each plotted DOF's curve")
    if not result.complete:
        report.text(f"**Incomplete curve**: {incomplete_message(result, cfg.omega[1], cfg.control)}.")
    for c, contact in enumerate(result.structure.contacts):
        report.text(_static_text(result, c) + f" Along the curve: mean normal load "
                    f"{result.contact_N[:, c, 0].min():.6g} to {result.contact_N[:, c, 0].max():.6g} N; "
                    f"largest energy dissipated per cycle {result.contact_dissipation[:, c].max():.6g} J.")
        print(_static_text(result, c))
    for name, fig, caption in _plots(result, cfg):
        report.figure(fig, name, caption, out)
    report.write(out)
    print(f"wrote {csv}, {out / 'frf.png'} and {out / 'report.html'} ({result.points} points, "
          f"{result.elapsed:.3g} s)")
    if not result.complete:
        print(f"microslip frf: error: incomplete curve: {incomplete_message(result, cfg.omega[1], cfg.control)} "
              f"(set max_points in [continuation]); the results written stop there", file=sys.stderr)
        return 1
    return 0


def _static_text(result, c: int) -> str:
    """One contact's static state: normal and tangential force, share of the slip force, closed elements."""
    contact = result.structure.contacts[c]
    N0, T0 = result.static_normal_force[c], result.static_tangential_force[c]
    limit = contact.model.mu * N0
    share = f"{abs(T0) / limit:.3g} of the slip force mu N0" if limit > 0 else "open"
    preload = f" (preload {contact.preload:.6g} N on the structure)" if contact.preload else ""
    return (f"Contact {contact.name}: {contact.model!r}; static state: normal force N0 = {N0:.6g} N{preload}, "
            f"tangential force T0 = {T0:.6g} N ({share}), {result.static_closed_elements[c]} of "
            f"{contact.model.elements} elements closed.")
