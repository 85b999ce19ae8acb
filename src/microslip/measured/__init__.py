"""From measured hysteresis loops to a tuned, validated model (the paper's Sect. 3, cylinder on a plane).

* :mod:`microslip.loops` (:mod:`.loops`) -- reading records and finding and measuring their cycles;
* :func:`fit_backbone` (:mod:`.backbone_fit`) -- a smooth, increasing, concave backbone fitted to a branch;
* :class:`MeasuredContact` (:mod:`.contact`) -- the reference built from loops and a normal law;
* :func:`tune_on_loops`, :func:`validate` (:mod:`.loop_tuning`, :mod:`.loop_validation`) -- tuning
  and validation at every measured load, with plots (:mod:`.loop_plots`) and a report
  (:mod:`.loop_report`).
"""

from . import loops
from .backbone_fit import FittedBackbone, fit_backbone
from .contact import MeasuredContact
from .loop_tuning import LoopTuning, tune_on_loops
from .loop_validation import LoadValidation, Validation, validate

__all__ = ["FittedBackbone", "LoadValidation", "LoopTuning", "MeasuredContact", "Validation", "fit_backbone", "loops",
           "tune_on_loops", "validate"]
