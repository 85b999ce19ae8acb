"""Tuning the paper's array on a reference contact.

* :mod:`.paper` -- the paper's eqs. 1--9: :func:`tuning_points`, :func:`model_from_points`, the
  :class:`ContactReference` protocol;
* :mod:`.target` -- choosing the tuning points (and the number of elements) to meet an accuracy
  target over a load range, measured against the exact contact;
* :func:`tune` -- the front door to both.
"""

from ._front import tune
from .paper import (ContactReference, TuningError, TuningPoints, model_from_points, normal_parameters,
                    tangential_stiffnesses, tuning_points)
from .target import (ElementSweep, TargetNotMet, TargetProblem, TargetTuning, element_sweep, smallest_elements,
                     tune_to_target)

__all__ = ["ContactReference", "ElementSweep", "TargetNotMet", "TargetProblem", "TargetTuning", "TuningError",
           "TuningPoints", "element_sweep", "model_from_points", "normal_parameters", "smallest_elements",
           "tangential_stiffnesses", "tune", "tune_to_target", "tuning_points"]
