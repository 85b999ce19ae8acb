"""The paper's figures, one module each, and the sections of ``microslip reproduce``.

Every module in :data:`SECTIONS` follows one contract:

``NAME``
    file stem of its outputs (``fig2a`` -> ``fig2a.png``, ``fig2a.csv``);
``CAPTION``
    what it shows, naming the paper figure it reproduces;
``compute(case) -> data``
    the numbers, from a :class:`~microslip.figures.case.PaperCase`;
``plot(data) -> matplotlib.figure.Figure``
    the figure;
``columns(data) -> dict``
    the plotted data, written as CSV;
``error_rows(data) -> list``
    rows ``(quantity, discrete, continuous, error %, bound)`` of the
    report's error table (may be empty); energies as
    :class:`~microslip.common.report.Energy` (J), their unit written
    :data:`~microslip.common.report.ENERGY_UNIT` in the quantity.

Optional:

``parameters(case) -> dict``
    the section's own run parameters (name -> value with its unit), shown
    under the report's title with the case's;

``tables(data) -> list``
    further tables ``(caption, headers, rows)`` of the section, written in
    the report under its figure (for data that do not fit the error table).
"""

from . import accuracy, accuracy_amplitude, accuracy_sweep, fig2a, fig2b, fig3a, fig3b, fig4a, fig4b, fig6
from .case import PaperCase
from .reproduce import reproduce
from .sections import SECTIONS

__all__ = ["PaperCase", "reproduce"]
