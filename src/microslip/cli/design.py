"""``microslip design``: the damper design curve (peak response against centrifugal load) from a TOML file."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ._args import add_output_folder


def add_parser(sub) -> None:
    p = sub.add_parser(
        "design", help="peak forced response against an under-platform damper's centrifugal load",
        description="Compute the curve engineers use to choose an under-platform damper: the peak forced "
                    "response of a structure against the damper's centrifugal load, at one excitation level "
                    "(low load: the damper slides and damps little; high load: it sticks and the system "
                    "stiffens; the optimum lies between). The TOML configuration is that of 'microslip frf' "
                    "with one [[damper]] table and a [design] table giving the loads and the DOF whose peak is "
                    "read (format: microslip config-reference). "
                    "Writes design.csv (with each load's status), design.png, report.html and report.md. A load whose "
                    "forced response fails, stops at [continuation] max_points, or is highest at an end of the [sweep] "
                    "range (the resonance lies outside it) has no peak: it is marked, left out of the optimum and "
                    "named. Exit status: 0 on success, 1 when a load has no peak (the others are written), 2 for an "
                    "invalid configuration, 130 when interrupted (Ctrl-C: the loads finished are written).")
    p.add_argument("config", help="TOML configuration file with a [[damper]] and a [design] table")
    add_output_folder(p, "microslip-design")
    p.set_defaults(func=run)


def run(args) -> int:
    import sys

    import matplotlib.pyplot as plt

    from ..common.report import Report, plural
    from ..frequency import ConvergenceError, NotPeriodicError, damper_design_curve
    from ..frequency.analyses.response import CurveInterrupted
    from ..config import ConfigError, load_config

    cfg = load_config(args.config)
    if cfg.design_loads is None:
        raise ConfigError(f"{args.config}: microslip design needs a [design] table (loads, dof)")
    if cfg.prestress is not None:
        raise ConfigError(f"{args.config}: [prestress] is read by microslip frf and modes; microslip design varies "
                          f"the damper's load, which changes the static state at every load: remove [prestress]")
    out = Path(args.out)
    force = {h: v[:cfg.bare.ndof] for h, v in cfg.force.items()}
    interrupted = None
    try:
        curve = damper_design_curve(cfg.bare, cfg.dampers[0], cfg.design_loads, force, cfg.omega, dof=cfg.design_dof,
                                    harmonics=cfg.harmonics, samples=cfg.samples, control=cfg.control,
                                    reduction=cfg.reduction, modes=cfg.modes, engine_order=cfg.engine_order,
                                    progress=not args.quiet)
    except (ConvergenceError, NotPeriodicError) as exc:  # before any load: the damper's own set-up
        print(f"microslip design: error: {exc}", file=sys.stderr)
        return 1
    except CurveInterrupted as exc:
        curve, interrupted = exc.partial, exc
    if curve is None or curve.loads.size == 0:
        print(f"microslip design: interrupted ({interrupted}); no load finished, nothing written", file=sys.stderr)
        return 130
    csv = curve.to_csv(out / "design.csv")
    name = cfg.dof_names[cfg.design_dof]
    report = Report(f"microslip design: {cfg.title}", parameters={
        "configuration": str(args.config), "output DOF": name, "harmonics H": cfg.harmonics,
        "frequency range (rad/s)": f"{cfg.omega[0]:.6g} to {cfg.omega[1]:.6g}",
        "centrifugal loads (N)": ", ".join(f"{v:.4g}" for v in cfg.design_loads),
        "damper mass (kg)": cfg.dampers[0].mass})
    report.table(["centrifugal load (N)", f"peak amplitude of {name} (µm)", "peak frequency (Hz)", "status"],
                 [[f"{L:.4g}", f"{a * 1e6:.4g}", f"{w / 6.283185307179586:.6g}", status]
                  for L, a, w, status in zip(curve.loads, curve.peak_amplitude, curve.peak_frequency, curve.status)],
                 caption="Peak response at each centrifugal load (status: 'peak', or why the value is no peak and "
                         "is left out of the optimum)")
    problems = [text.replace(" of the range past", " of [sweep] omega past")
                .replace("the continuation's max_points", "[continuation] max_points") for text in curve.problems()]
    if curve.trusted.any():
        load, peak = curve.optimum
        among = "among the loads computed" if not problems else "among the loads with a peak inside the range"
        summary = f"lowest peak {peak * 1e6:.4g} µm at {load:.4g} N ({among})"
    else:
        summary = "no optimum: no load has a peak inside the frequency range on a complete curve"
    report.text(summary[0].upper() + summary[1:] + ".")
    for text in problems:
        report.text(f"**Left out of the optimum**: {text}.")
    if interrupted is not None:
        left = cfg.design_loads.size - int(np.count_nonzero(curve.complete))
        report.text(f"**Interrupted** ({interrupted}): {plural(left, 'load')} of {cfg.design_loads.size} not "
                    f"finished; the results stop there.")
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    curve.plot(ax=ax)
    ax.set_title(cfg.title)
    report.figure(fig, "design", "Peak response against the damper's centrifugal load; the lowest peak marked, the "
                  "loads without a peak crossed.", out)
    report.write(out)
    print(f"{summary}; wrote {csv} and {out / 'report.html'}")
    if interrupted is not None:
        print(f"microslip design: interrupted: {interrupted}; wrote the loads up to there (marked incomplete)",
              file=sys.stderr)
        return 130
    if problems:
        print(f"microslip design: error: {plural(len(problems), 'load')} without a peak, left out of the optimum: "
              + "; ".join(problems), file=sys.stderr)
        return 1
    return 0
