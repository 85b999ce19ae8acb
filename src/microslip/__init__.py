"""microslip: friction contacts with variable normal load for structural dynamics.

The contact model of Gastaldi & Gola ("An Improved Microslip Model for
Variable Normal Loads"): a parallel array of macroslip elements, each with a
tangential stiffness, a normal stiffness and a normal gap, so the normal load
shifts between elements as the normal approach changes. SI units throughout.
"""

from . import loops
from .frequency import FrequencyResponse, Structure, frequency_response
from .loop_tuning import LoopTuning, Validation, tune_on_loops, validate
from .measured import FittedBackbone, MeasuredContact, fit_backbone
from .model import MicroslipModel, Response, State, Step
from .reference import Cylinder, Sphere
from .tuning import ContactReference, TuningError, TuningPoints, tune, tuning_points
from . import paths
from .accuracy import AccuracyReport, accuracy
from .reference.mdr import LoadLimitError, MDRModel, mdr
from .tuning_target import TargetNotMet, TargetProblem, TargetTuning, smallest_elements, tune_to_target

__version__ = "0.1.0"

__all__ = [
    "AccuracyReport",
    "LoadLimitError",
    "MDRModel",
    "TargetNotMet",
    "TargetProblem",
    "TargetTuning",
    "accuracy",
    "mdr",
    "paths",
    "smallest_elements",
    "tune_to_target",
    "ContactReference",
    "Cylinder",
    "FittedBackbone",
    "FrequencyResponse",
    "LoopTuning",
    "MeasuredContact",
    "Validation",
    "fit_backbone",
    "loops",
    "tune_on_loops",
    "validate",
    "MicroslipModel",
    "Response",
    "Sphere",
    "State",
    "Step",
    "Structure",
    "TuningError",
    "TuningPoints",
    "frequency_response",
    "tune",
    "tuning_points",
]
