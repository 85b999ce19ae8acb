"""Run every section of ``microslip.figures.sections.SECTIONS`` and write the report."""

from __future__ import annotations

from pathlib import Path

from ..common._io import write_csv
from ..common._progress import Progress
from ..common.report import ENERGY_UNIT, Report, plural
from .case import PaperCase

ERROR_HEADERS = ["quantity", "discrete", "continuous", "error (%)", "expected"]


def reproduce(out_dir, *, case: PaperCase | None = None, progress: bool = True, sections=None) -> Path:
    """Compute, plot and tabulate every section; write PNG, CSV and ``report.html``/``report.md``.

    Parameters
    ----------
    out_dir : path
        Output folder (created if needed).
    case : PaperCase, optional
        The benchmark; default the paper's.
    progress : bool
        Show progress on standard error.
    sections : list of modules, optional
        Default ``microslip.figures.sections.SECTIONS``.

    Returns
    -------
    Path
        The HTML report.
    """
    from .sections import SECTIONS

    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    case = case or PaperCase()
    sections = SECTIONS if sections is None else sections
    bar = Progress(len(sections) + 1, enabled=progress)
    report = Report("microslip: reproduction of Gastaldi & Gola, 'An Improved Microslip Model "
                    "for Variable Normal Loads'", parameters=run_parameters(case, sections))
    report.text(
        f"Sphere d = {2e3 * case.sphere.radius:g} mm on a plane, both steel (E = {case.sphere.E / 1e9:g} GPa - "
        f"the paper prints 200 MPa, a typo - nu = {case.sphere.nu:g}), mu = {case.sphere.mu:g}; the array "
        f"is tuned at N_tot = {case.normal_load:g} N with J = {plural(case.elements, 'element')}, points evenly "
        f"spaced in force. 'Continuous' is Hertz + Cattaneo-Mindlin (+ Mindlin-Deresiewicz), 'discrete' the "
        f"tuned array. Forces in N, displacements in µm, energies in {ENERGY_UNIT} (the CSV files: SI units).")
    errors = []
    for section in sections:
        bar.step(section.CAPTION.split(":")[0])
        data = section.compute(case)
        fig = section.plot(data)
        report.heading(section.CAPTION.split(":")[0])
        report.figure(fig, section.NAME, f"{section.CAPTION} (data: {section.NAME}.csv)", out_dir)
        write_csv(out_dir / f"{section.NAME}.csv", section.columns(data))
        for caption, headers, rows in getattr(section, "tables", lambda _: [])(data):
            report.table(headers, rows, caption=caption)
        errors += section.error_rows(data)
    bar.step("report")
    report.heading("Differences between discrete and continuous")
    report.table(ERROR_HEADERS, [list(row) for row in errors])
    html_path, _ = report.write(out_dir)
    bar.done(f"wrote {out_dir}")
    return html_path


def run_parameters(case: PaperCase, sections) -> dict:
    """The parameters of the run, for the table under the report's title: the case's, then each section's."""
    sphere = case.sphere
    params = {"sphere diameter": f"{2e3 * sphere.radius:g} mm", "Young's modulus E": f"{sphere.E / 1e9:g} GPa",
              "Poisson's ratio nu": f"{sphere.nu:g}", "friction coefficient mu": f"{sphere.mu:g}",
              "tuning load N_tot": f"{case.normal_load:g} N", "elements J": f"{case.elements}",
              "tuning points": "evenly spaced in force (the paper's)"}
    for section in sections:
        params.update(getattr(section, "parameters", lambda _: {})(case))
    return params
