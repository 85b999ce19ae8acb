"""``microslip modes``: a damped nonlinear mode (frequency and damping against amplitude) from a TOML file."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ._args import add_output_folder, percent
from ._prestress import add_prestress_option, report_prestress
from ._words import in_config_words

#: rows of the report's table: one per this fraction of a decade of amplitude
_ROWS_PER_DECADE = 2


def add_parser(sub) -> None:
    p = sub.add_parser(
        "modes", help="damped nonlinear mode: natural frequency and damping ratio against vibration amplitude",
        description="Compute a damped nonlinear mode of a structure with microslip contacts by the extended "
                    "periodic motion concept: the unforced structure with a negative mass-proportional damping "
                    "that makes up for what the contacts and the viscous damping dissipate, solved by harmonic "
                    "balance (the contacts by alternating frequency-time) and followed from the linear mode with "
                    "the contacts stuck, over a range of modal amplitude, to gross slip. The TOML configuration is "
                    "that of 'microslip frf' with a [modes] table (mode, amplitude range, the DOF shown, compare; "
                    "for a [cyclic] sector the nodal diameter, by default its engine_order); "
                    "[excitation] and the [sweep] range are optional (format: microslip "
                    "config-reference). Writes modes.csv (the mode at every "
                    "amplitude: frequency, damping ratio and its viscous and contact shares, every DOF's harmonics "
                    "up to 20 DOFs), modes.png (frequency and damping ratio against the modal amplitude and "
                    "against the chosen DOF's), report.html and report.md. With an [excitation], the forced "
                    "response near the mode synthesised from the mode alone (single nonlinear mode: synthesis.csv, "
                    "synthesis.png), and with [modes] compare = true and a [sweep] range also the harmonic balance "
                    "forced response over that range, to compare their peaks. Prints the contacts' static state "
                    "and the mode's frequency and damping; shows progress on standard error. Exit status: 0 on "
                    "success, 1 when the solution fails or the mode stops before the end of its amplitude range "
                    "(the results up to there are written), 2 for an invalid configuration, 130 when interrupted "
                    "(Ctrl-C: the mode up to there is written). With a [prestress] table (or --prestress) the "
                    "mode vibrates about the prestressed state (the static loads with the friction released or "
                    "stuck) and starts from the prestressed structure's linear mode; prestress.csv holds each "
                    "contact's static state.")
    p.add_argument("config", help="TOML configuration file with a [modes] table")
    add_prestress_option(p)
    add_output_folder(p, "microslip-modes")
    p.set_defaults(func=run)


def _frequency(cfg, omega):
    """Frequencies in the configured unit, and that unit."""
    return (np.asarray(omega) / (2 * np.pi), "Hz") if cfg.frequency_unit == "Hz" else (np.asarray(omega), "rad/s")


def _rows(mode, cfg, dof: int) -> list:
    """The report's table: about two rows per decade of amplitude, and the maximum damping."""
    a = mode.modal_amplitude
    marks = np.geomspace(a[0], a[-1], max(2, int(_ROWS_PER_DECADE * np.log10(a[-1] / a[0])) + 1))
    picks = sorted(set(int(np.argmin(np.abs(np.log(a / m)))) for m in marks) | {int(np.argmax(mode.damping_ratio))})
    f, _ = _frequency(cfg, mode.omega)
    amp = mode.amplitude(dof, 1)
    contact = np.where(np.abs(mode.contact_damping_ratio) < 1e-12, 0.0, mode.contact_damping_ratio)  # rounding
    return [[f"{a[k]:.3g}", f"{amp[k] * 1e6:.4g}", f"{f[k]:.6g}", f"{percent(mode.damping_ratio[k])}",
             f"{percent(contact[k])}"] for k in picks]


def _plots(mode, cfg, dof: int):
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 2, figsize=(10, 6.5), sharex="col", sharey="row")
    mode.plot(axes=axes[:, 0], frequency_unit=cfg.frequency_unit)
    mode.plot(dof, 1, axes=axes[:, 1], frequency_unit=cfg.frequency_unit)
    axes[1, 1].set_xlabel(f"{cfg.dof_names[dof]}: harmonic 1 amplitude (µm)")
    axes[1, 1].set_ylabel("")
    axes[0, 1].set_ylabel("")
    fig.suptitle(f"{cfg.title}: mode {mode.mode}")
    return fig


def _synthesis(report, mode, cfg, dof: int, force, structure, out: Path, quiet: bool, lines: list,
               state=None) -> None:
    """The forced response synthesised from the mode, and compared with harmonic balance when asked for."""
    import matplotlib.pyplot as plt

    from ..common._io import write_csv
    from ..frequency import ConvergenceError, NotPeriodicError, frequency_response
    from ..frequency.analyses.synthesis import resonance_band

    synthesis = mode.forced_response(force)
    name = cfg.dof_names[dof]
    write_csv(out / "synthesis.csv", {"omega [rad/s]": synthesis.omega, "f [Hz]": synthesis.omega / (2 * np.pi),
                                      "modal amplitude [kg^0.5 m]": synthesis.modal_amplitude,
                                      f"{name} a1 amplitude [m]": synthesis.amplitude(dof, 1)})
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    synthesis.plot(dof, 1, ax=ax, frequency_unit=cfg.frequency_unit, label="synthesised from the mode")
    w_syn, a_syn = synthesis.peak(dof, 1)
    f_syn = _frequency(cfg, w_syn)[0]
    text = (f"Forced response under the first harmonic of [excitation], synthesised from the mode alone (single "
            f"nonlinear mode: the response keeps the mode's shape at its amplitude; valid near the resonance "
            f"where the mode is isolated, no other mode nor a harmonic of the excitation near it, light damping): "
            f"peak {a_syn * 1e6:.4g} µm of {name} at {f_syn:.6g} {_frequency(cfg, 1)[1]}.")
    # a sector's forced response compares when the excitation's engine order is the mode's nodal diameter
    compare = cfg.nonlinear_mode.compare and cfg.omega is not None and cfg.engine_order == mode.engine_order
    curve = None
    if compare:
        hb_force = {h: v for h, v in _force(cfg).items() if h}
        try:
            curve = frequency_response(structure, hb_force, cfg.omega, harmonics=cfg.harmonics, samples=cfg.samples,
                                       control=cfg.control, progress=not quiet, reduction=cfg.reduction,
                                       modes=cfg.modes, stability=False, engine_order=cfg.engine_order,
                                       prestress=state)
        except (ConvergenceError, NotPeriodicError) as exc:
            text += f" Harmonic balance over [sweep], to compare, failed: {exc}."
            compare = False
    if curve is not None:
        amplitude = curve.amplitude(dof, 1)
        x, _ = _frequency(cfg, curve.omega)
        ax.plot(x, amplitude * 1e6, "--", label="harmonic balance")
        # this mode's resonance: the curve's local maximum nearest the synthesised peak, not another mode's
        peaks = np.flatnonzero((amplitude[1:-1] >= amplitude[:-2]) & (amplitude[1:-1] >= amplitude[2:])) + 1
        lo, hi = resonance_band(synthesis, dof, 1)
        peaks = peaks[(curve.omega[peaks] >= lo) & (curve.omega[peaks] <= hi)]
        if peaks.size:
            k = peaks[int(np.argmin(np.abs(curve.omega[peaks] - w_syn)))]
            w_hb, a_hb = curve.omega[k], amplitude[k]
            text += (f" Harmonic balance over [sweep]: its peak near the mode {a_hb * 1e6:.4g} µm at "
                     f"{_frequency(cfg, w_hb)[0]:.6g} {_frequency(cfg, 1)[1]}; the synthesis differs by "
                     f"{percent(a_syn / a_hb - 1)} % in amplitude and {percent(w_syn / w_hb - 1)} % in frequency.")
        else:
            text += " The [sweep] range does not reach the mode's resonance: nothing to compare."
    ax.legend()
    ax.set_title(f"{cfg.title}: {name}")
    report.figure(fig, "synthesis", "Forced response near the mode, synthesised from the mode"
                  + (" and by harmonic balance" if compare else "") + "; the mode's backbone dotted.", out)
    report.text(text)
    lines.append(text)


def _force(cfg) -> dict:
    """The configuration's excitation, ``{harmonic: amplitudes}`` (N), on the structure's DOFs."""
    return {h: np.asarray(v) for h, v in cfg.force.items()}


def run(args) -> int:
    import sys

    from ..common.report import Report, plural
    from ..frequency import ConvergenceError, IncompleteCurveWarning, NotPeriodicError, nonlinear_modes
    from ..frequency.analyses.response import CurveInterrupted
    from ..config import apply_prestress, load_config
    from ..config.modes_control import mode_control
    from .frf import _static_text

    cfg = load_config(args.config, nonlinear=True)
    table = cfg.nonlinear_mode
    out = Path(args.out)
    structure = cfg.structure
    force = _force(cfg)
    prestressing = cfg.prestress is not None or getattr(args, "prestress", None) is not None
    state = prestress = None
    if 0 in force and not prestressing:  # a static force is part of the state the mode vibrates about
        structure.add_static_force(force[0].real)
    import warnings

    interrupted = None
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", IncompleteCurveWarning)
            if prestressing:  # the static force is the prestress's
                state, prestress, force = apply_prestress(cfg, force, getattr(args, "prestress", None))
            mode = nonlinear_modes(structure, table.mode, table.amplitude, harmonics=cfg.harmonics,
                                   samples=cfg.samples, reduction=cfg.reduction, modes=cfg.modes,
                                   control=mode_control(cfg, cfg.continuation_keys),
                                   progress=not args.quiet, nodal_diameter=table.nodal_diameter, prestress=state,
                                   folds=table.folds)
    except (ConvergenceError, NotPeriodicError) as exc:
        print(f"microslip modes: error: {exc}", file=sys.stderr)
        return 1
    except CurveInterrupted as exc:  # Ctrl-C: the mode up to there is written, marked
        mode, interrupted = exc.partial, exc
    incomplete = [in_config_words(str(w.message)) for w in caught if issubclass(w.category, IncompleteCurveWarning)]
    for w in caught:
        if not issubclass(w.category, IncompleteCurveWarning):
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    dof = table.dof
    ndof = structure.ndof
    csv = mode.to_csv(out / "modes.csv", dofs=range(ndof) if ndof <= 20 else sorted({dof, *cfg.plot_dofs}),
                      names=cfg.dof_names)
    f_lin, unit = _frequency(cfg, mode.linear_frequency)
    report = Report(f"microslip modes: {cfg.title}", parameters={
        "configuration": str(args.config), "DOFs": ndof, "contacts": len(structure.contacts), "mode": table.mode,
        **({"nodal diameter": mode.engine_order} if mode.engine_order is not None else {}),
        "modal amplitude (kg^1/2 m)": f"{table.amplitude[0]:.3g} to {table.amplitude[1]:.3g}",
        "harmonics H": cfg.harmonics, "AFT samples per period": mode.samples, "reduction": mode.reduction,
        "modes": mode.modes if mode.modes else "-", "output": str(out)})
    reduced = (f"the linear structure condensed onto the {mode.dofs.size} DOFs the contacts use ({mode.reduction}"
               + (f", {mode.modes} modes, estimated error {mode.reduction_error:.2g}" if mode.modes else "") + ")"
               if mode.reduction != "none" else "every DOF solved")
    f = _frequency(cfg, mode.omega)[0]
    k = int(np.argmax(mode.damping_ratio))
    summary = (f"Mode {table.mode}: {f_lin:.6g} {unit} with the contacts stuck; at the largest amplitude "
               f"{f[-1]:.6g} {unit} ({percent(mode.omega[-1] / mode.omega[0] - 1)} %). Damping ratio "
               f"{percent(mode.damping_ratio[0])} % at the smallest amplitude, at most "
               f"{percent(mode.damping_ratio[k])} % ({percent(mode.contact_damping_ratio[k])} % from the contacts) at "
               f"modal amplitude {mode.modal_amplitude[k]:.3g} kg^1/2 m ({mode.amplitude(dof, 1)[k] * 1e6:.4g} µm "
               f"of {cfg.dof_names[dof]}).")
    report.text(f"Configuration `{args.config}`: {plural(ndof, 'DOF')}, "
                f"{plural(len(structure.contacts), 'contact')}, H = {mode.harmonics} harmonics, {mode.samples} AFT "
                f"samples per period; {reduced}. The modal amplitude a is the first harmonic of the coordinate of "
                f"the linear mode (contacts stuck, mass-normalised): at small amplitude a DOF moves by a times the "
                f"mode's value there. {mode.points} points in {mode.elapsed:.3g} s ({mode.iterations.sum()} Newton "
                f"iterations). The mode: `modes.csv` (SI units).")
    report.text(summary)
    print(summary)
    if state is not None:
        for line in report_prestress(report, state, prestress, cfg, out):
            print(line)
    report.table(["modal amplitude (kg^1/2 m)", f"{cfg.dof_names[dof]} harmonic 1 (µm)", f"frequency ({unit})",
                  "damping ratio (%)", "contacts' share (%)"], _rows(mode, cfg, dof),
                 caption="The mode at about two amplitudes per decade and where it damps most")
    for text in incomplete:
        report.text(f"**Incomplete mode**: {text}.")
    if interrupted is not None:
        report.text(f"**Interrupted** ({interrupted}): the mode stops there.")
    for c in range(len(structure.contacts)):
        report.text(_static_text(mode, c))
        print(_static_text(mode, c))
    fig = _plots(mode, cfg, dof)
    report.figure(fig, "modes", "Natural frequency and damping ratio (total; dashed: the contacts' share) against "
                  "the modal amplitude and against the chosen DOF's first harmonic.", out)
    lines = []
    if 1 in force and np.any(force[1]) and interrupted is None:
        try:
            _synthesis(report, mode, cfg, dof, force[1], structure, out, args.quiet, lines, state)
        except ValueError as exc:  # no resonance within the mode's range: said, the mode is still written
            report.text(f"**Synthesis**: {exc}.")
            print(f"microslip modes: warning: synthesis: {exc}", file=sys.stderr)
        except KeyboardInterrupt:  # during the synthesis or its comparison: the mode is complete, written
            interrupted = "interrupted during the synthesis of the forced response; the mode is complete"
            report.text(f"**Interrupted**: {interrupted}.")
    for line in lines:
        print(line)
    report.write(out)
    print(f"wrote {csv}, {out / 'modes.png'} and {out / 'report.html'} ({mode.points} points, {mode.elapsed:.3g} s)")
    if interrupted is not None:
        print(f"microslip modes: interrupted: {interrupted}; wrote what was computed up to there", file=sys.stderr)
        return 130
    if incomplete:
        print(f"microslip modes: error: {incomplete[0]}; the results written stop there", file=sys.stderr)
        return 1
    return 0
