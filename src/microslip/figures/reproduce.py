"""Run every section of :data:`microslip.figures.SECTIONS` and write the report."""

from __future__ import annotations

from pathlib import Path

from ..common._io import write_csv
from ..common._progress import Progress
from ..common.report import Report
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
        Default :data:`microslip.figures.SECTIONS`.

    Returns
    -------
    Path
        The HTML report.
    """
    import matplotlib.pyplot as plt

    from .sections import SECTIONS

    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    case = case or PaperCase()
    sections = SECTIONS if sections is None else sections
    bar = Progress(len(sections) + 1, enabled=progress)
    report = Report("microslip: reproduction of Gastaldi & Gola, 'An Improved Microslip Model "
                    "for Variable Normal Loads'")
    report.text(
        f"Sphere d = {2e3 * case.sphere.radius:g} mm on a plane, both steel (E = {case.sphere.E / 1e9:g} GPa - "
        f"the paper prints 200 MPa, a typo - nu = {case.sphere.nu:g}), mu = {case.sphere.mu:g}; the array "
        f"is tuned at N_tot = {case.normal_load:g} N with J = {case.elements} elements, points evenly spaced "
        f"in force. 'Continuous' is Hertz + Cattaneo-Mindlin (+ Mindlin-Deresiewicz), 'discrete' the tuned "
        f"array. All forces in N, displacements plotted in µm.")
    errors = []
    for section in sections:
        bar.step(section.CAPTION.split(":")[0])
        data = section.compute(case)
        fig = section.plot(data)
        report.heading(section.CAPTION.split(":")[0])
        report.figure(fig, section.NAME, section.CAPTION, out_dir)
        plt.close(fig)
        write_csv(out_dir / f"{section.NAME}.csv", section.columns(data))
        for caption, headers, rows in getattr(section, "tables", lambda _: [])(data):
            report.table(headers, rows, caption=caption)
        errors += section.error_rows(data)
    bar.step("report")
    report.heading("Differences between discrete and continuous")
    report.table(ERROR_HEADERS, [[q, _fmt(d), _fmt(c), _fmt(e), b] for q, d, c, e, b in errors])
    html_path, _ = report.write(out_dir)
    bar.done(f"wrote {out_dir}")
    return html_path


def _fmt(x) -> str:
    return "" if x is None else f"{x:.4g}"
