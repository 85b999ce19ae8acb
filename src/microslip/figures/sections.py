"""The sections of the report, in order (the contract each follows is in :mod:`microslip.figures`)."""

from . import accuracy, accuracy_amplitude, accuracy_sweep, fig2a, fig2b, fig3a, fig3b, fig4a, fig4b, fig6

SECTIONS = [fig2a, fig2b, fig3a, fig3b, fig4a, fig4b, fig6, accuracy, accuracy_sweep, accuracy_amplitude]
