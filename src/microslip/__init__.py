"""microslip: friction contacts with variable normal load for structural dynamics.

The contact model of Gastaldi & Gola ("An Improved Microslip Model for
Variable Normal Loads"): a parallel array of macroslip elements, each with a
tangential stiffness, a normal stiffness and a normal gap, so the normal load
shifts between elements as the normal approach changes. SI units throughout.
"""

from .frequency import FrequencyResponse, Structure, frequency_response
from .model import MicroslipModel, Response, State, Step
from .reference import Sphere
from .tuning import ContactReference, TuningError, TuningPoints, tune, tuning_points

__version__ = "0.1.0"

__all__ = [
    "ContactReference",
    "FrequencyResponse",
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
