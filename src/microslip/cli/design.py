"""``microslip design``: the damper design curve (peak response against centrifugal load) from a TOML file."""

from __future__ import annotations

from pathlib import Path

from ._args import add_output_folder


def add_parser(sub) -> None:
    p = sub.add_parser(
        "design", help="peak forced response against an under-platform damper's centrifugal load",
        description="Compute the curve engineers use to choose an under-platform damper: the peak forced "
                    "response of a structure against the damper's centrifugal load, at one excitation level "
                    "(low load: the damper slides and damps little; high load: it sticks and the system "
                    "stiffens; the optimum lies between). The TOML configuration is that of 'microslip frf' "
                    "with one [[damper]] table and a [design] table giving the loads and the DOF whose peak is "
                    "read (format: python -c 'import microslip.config.frf as c; print(c.__doc__)'). "
                    "Writes design.csv, design.png, report.html and report.md. Exit status: 0 on success, 1 when "
                    "a forced response fails, 2 for an invalid configuration.")
    p.add_argument("config", help="TOML configuration file with a [[damper]] and a [design] table")
    add_output_folder(p, "microslip-design")
    p.set_defaults(func=run)


def run(args) -> int:
    import sys

    import matplotlib.pyplot as plt

    from ..common.report import Report
    from ..frequency import ConvergenceError, NotPeriodicError, damper_design_curve
    from ..config import ConfigError, load_config

    cfg = load_config(args.config)
    if cfg.design_loads is None:
        raise ConfigError(f"{args.config}: microslip design needs a [design] table (loads, dof)")
    out = Path(args.out)
    force = {h: v[:cfg.bare.ndof] for h, v in cfg.force.items()}
    try:
        curve = damper_design_curve(cfg.bare, cfg.dampers[0], cfg.design_loads, force, cfg.omega, dof=cfg.design_dof,
                                    harmonics=cfg.harmonics, samples=cfg.samples, control=cfg.control,
                                    reduction=cfg.reduction, modes=cfg.modes, engine_order=cfg.engine_order,
                                    progress=not args.quiet)
    except (ConvergenceError, NotPeriodicError) as exc:
        print(f"microslip design: error: {exc}", file=sys.stderr)
        return 1
    csv = curve.to_csv(out / "design.csv")
    load, peak = curve.optimum
    name = cfg.dof_names[cfg.design_dof]
    report = Report(f"microslip design: {cfg.title}", parameters={
        "configuration": str(args.config), "output DOF": name, "harmonics H": cfg.harmonics,
        "frequency range (rad/s)": f"{cfg.omega[0]:.6g} to {cfg.omega[1]:.6g}",
        "centrifugal loads (N)": ", ".join(f"{v:.4g}" for v in curve.loads), "damper mass (kg)": cfg.dampers[0].mass})
    report.table(["centrifugal load (N)", f"peak amplitude of {name} (µm)", "peak frequency (Hz)"],
                 [[f"{L:.4g}", f"{a * 1e6:.4g}", f"{w / 6.283185307179586:.6g}"]
                  for L, a, w in zip(curve.loads, curve.peak_amplitude, curve.peak_frequency)],
                 caption="Peak response at each centrifugal load")
    report.text(f"Lowest peak among the loads computed: {peak * 1e6:.4g} µm at {load:.4g} N.")
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    curve.plot(ax=ax)
    ax.set_title(cfg.title)
    report.figure(fig, "design", "Peak response against the damper's centrifugal load; the lowest peak marked.",
                  out)
    report.write(out)
    print(f"lowest peak {peak * 1e6:.4g} µm at {load:.4g} N; wrote {csv} and {out / 'report.html'}")
    return 0
