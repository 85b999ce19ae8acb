"""The report (HTML + Markdown) of a model tuned on measured loops: loops, fit, elements, validation."""

from __future__ import annotations

from pathlib import Path

from ..common.report import ENERGY_UNIT, Energy, Report, plural
from .loop_validation import Validation

_UM = 1e6


def run_parameters(result) -> dict:
    """The parameters of a :class:`~microslip.measured.loop_tuning.LoopTuning`, for the table under the title."""
    ref = result.reference
    return {"records": "; ".join(f"{L.record.source} at {L.normal_load:.4g} N" for L in result.loops),
            "tuning load N_tot": f"{ref.normal_load:.4g} N",
            "elements J": f"{result.model.elements}",
            "tuning points T": ", ".join(f"{T:.4g}" for T in result.points.T) + " N",
            "normal law": f"{getattr(ref.normal, 'law_name', type(ref.normal).__name__)}",
            "friction coefficient mu": f"{ref.mu:.4g} ({ref.notes.get('mu_source', 'given')})"}


def write_report(result, out_dir, *, stem: str = "report", title: str | None = None,
                 parameters=None) -> tuple[Path, Path]:
    """Write the report of a :class:`~microslip.measured.loop_tuning.LoopTuning` as HTML and Markdown.

    Parameters
    ----------
    result : LoopTuning
        The model tuned on measured loops.
    out_dir : str or Path
        Output folder; ``stem.html``, ``stem.md`` and the PNG figures
        (prefixed with ``stem``) are written there, each atomically.
    stem : str, default "report"
        File stem.
    title : str, optional
        Title of the report.
    parameters : mapping of str to object, optional
        Further parameters of the run (e.g. the command-line options), shown
        under the title after those of ``result`` (:func:`run_parameters`).

    Returns
    -------
    html, md : Path
        The two report files.
    """
    from matplotlib.figure import Figure


    ref, fit = result.reference, result.reference.fit
    rep = Report(title or "microslip: model tuned on measured loops",
                 parameters={**run_parameters(result), **dict(parameters or {})})
    rep.text(f"Records: {', '.join(L.record.source for L in result.loops)}. Tuned at N = {ref.normal_load:.4g} N "
             f"with J = {plural(result.model.elements, 'element')}, points evenly spaced in force unless given; "
             f"normal law: {getattr(ref.normal, 'law_name', type(ref.normal).__name__)}; "
             f"mu = {ref.mu:.4g} ({ref.notes.get('mu_source', 'given')}).")
    rep.heading("Measured loops")
    rep.table(["record", "N (N)", "cycles", "steady", f"energy ({ENERGY_UNIT})", "amplitude (µm)", "slip force (N)",
               "stick stiffness (N/µm)", "Masing error (%)", "Masing basis"],
              [[L.record.source, L.normal_load, L.cycles, f"{L.steady_from + 1}-{L.steady_to}",
                Energy(L.summary()["energy"]), L.summary()["amplitude"] * _UM, L.summary()["slip_force"],
                L.summary()["stick_stiffness"] / 1e6, 100 * L.masing_error, L.masing_basis] for L in result.loops])
    figures = [("loops", "the record at the tuning load, its steady cycle and branches",
                lambda ax: result.tuned_loops.plot(ax=ax)),
               ("branch", "fitted branch and tuning points", lambda ax: result.plot_branch(ax=ax)),
               ("elements", "per-element loops at the tuning load (paper Fig. 6a)",
                lambda ax: result.plot_elements(ax=ax)),
               ("elements-low", "per-element loops at the lowest load, predicted (paper Fig. 6b)",
                lambda ax: result.plot_elements(result.validation.loads[-1].normal_load, ax=ax)),
               ("normal", "normal force-approach curve and the elements' springs (paper Fig. 6c)",
                lambda ax: result.plot_normal(ax=ax)),
               ("validation", "measured and predicted loops at every load", lambda ax: result.validation.plot(ax=ax)),
               ("transition", "load raised at constant T (paper Fig. 4a, for this contact)",
                lambda ax: result.plot_transition(ax=ax))]
    rep.heading("Fit and tuning")
    rep.text(f"Concave fit of the branch: RMS residual {fit.residual:.3g} N ({100 * fit.relative_residual:.2g} % "
             f"of the slip force), initial stiffness {fit.initial_stiffness / 1e6:.4g} N/µm, gross slip at "
             f"{2 * fit.gross_slip_displacement * _UM:.4g} µm from the reversal, microslip ratio "
             f"{fit.microslip_ratio:.3g} (1 = a single macroslip element, 1.5 = Cattaneo-Mindlin); "
             f"Masing error {100 * ref.notes.get('masing_error', float('nan')):.2g} %.")
    rep.table(["element", "kt (N/µm)", "kn (N/µm)", "gap (µm)", "slips at t (µm)"],
              [[i + 1, result.model.kt[i] / 1e6, result.model.kn[i] / 1e6, result.model.gaps[i] * _UM,
                result.points.t[::-1][i] * _UM] for i in range(result.model.elements)])
    for name, caption, draw in figures:
        if name == "validation":
            rep.heading("Validation at the other loads")
            rep.table(*_energies_in_report_unit(list(Validation.HEADERS), result.validation.rows()),
                      caption="predicted by the model tuned at the highest load, against the measured records")
        fig = Figure(figsize=(6.4, 4.6))  # not pyplot: no window, the user's backend untouched
        draw(fig.subplots())
        fig.tight_layout()
        rep.figure(fig, f"{stem}-{name}", caption, out_dir)
    return rep.write(out_dir, stem)


def _energies_in_report_unit(headers, rows):
    """The columns headed ``(µJ)`` as :class:`~microslip.common.report.Energy` cells (J) headed with the
    report's energy unit: every energy of the report is then shown in one unit, chosen by magnitude."""
    columns = [j for j, h in enumerate(headers) if "(µJ)" in h]
    headers = [h.replace("(µJ)", f"({ENERGY_UNIT})") if j in columns else h for j, h in enumerate(headers)]
    rows = [[Energy(c * 1e-6) if j in columns else c for j, c in enumerate(r)] for r in rows]
    return headers, rows
