"""Measured hysteresis loops: reading records, finding cycles, measuring them.

>>> from microslip import loops
>>> record = loops.read("cylinder_36.6N.csv")          # doctest: +SKIP
>>> result = loops.analyse(record)                     # doctest: +SKIP
>>> result.summary()["energy"], result.plot()          # doctest: +SKIP

:func:`read` reads CSV/whitespace text whose header names the columns with
their units (``time [s], t [um], T [N], N [N]``) and the JSON layout of the
ARTS-Lab friction damper data set, converting everything to SI;
:func:`analyse` finds the reversals, cycles and steady state and measures
each cycle (energy, stick stiffness after reversals, slip forces,
amplitude) and checks Masing's rule. :mod:`microslip.loops.synthetic`
generates the synthetic cylinder-on-flat data set shipped with the package.
"""

from ._analysis import LoopError, Loops, analyse, find_reversals
from ._branch import analyse_branch  # noqa: F401  (for microslip.measured.contact)
from ._record import Record, read, read_with_options  # noqa: F401  (read_with_options: for the command line)
from . import synthetic  # noqa: F401  (the shipped data set; imported so `microslip.loops.synthetic` resolves)

__all__ = ["LoopError", "Loops", "Record", "analyse", "find_reversals", "read"]
