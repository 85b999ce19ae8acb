"""microslip: friction contacts with variable normal load for structural dynamics.

The contact model of Gastaldi & Gola ("An Improved Microslip Model for
Variable Normal Loads"): a parallel array of macroslip elements, each with a
tangential stiffness, a normal stiffness and a normal gap, so the normal load
shifts between elements as the normal approach changes. SI units throughout.

One package per job: :mod:`microslip.reference` (exact continuous contacts),
:mod:`microslip.tuning` (the paper's equations, tuning to a target),
:mod:`microslip.measured` (from measured loops to a validated model),
:mod:`microslip.accuracy` (load paths, accuracy against a reference),
:mod:`microslip.frequency` (harmonic balance, time integration),
:mod:`microslip.figures` (the paper's figures), :mod:`microslip.study` (design
studies on Dask), :mod:`microslip.cli` (the command line); the model itself is :mod:`microslip.model`.
"""

import sys as _sys

from .common.errors import (BeyondTuningWarning, BranchPointWarning, ConfigError, ConvergenceError, CurveInterrupted,
                            DesignPointWarning, FileFormatError, FolderInUseError, IncompleteCurveWarning,
                            LoadLimitError, LoopError, MicroslipError, MicroslipWarning, MissingVariable,
                            NotPeriodicError, OneMatrixFile, OneSidedDamperWarning, PeakOnEdgeWarning,
                            SingularInteriorError, StudyFolderWarning, TargetNotMet, TuningError, UnderResolvedWarning)
from .common import errors as _errors
from .model import MicroslipModel, Response, State, Step
from .reference import Cylinder, MDRModel, Sphere, mdr
from .tuning import (ContactReference, TargetProblem, TargetTuning, TuningPoints, smallest_elements, tune,
                     tune_to_target, tuning_points)
from .accuracy import AccuracyReport, accuracy, paths
from .measured import (FittedBackbone, LoopTuning, MeasuredContact, Validation, fit_backbone, loops, tune_on_loops,
                       validate)
from .frequency import FrequencyResponse, NonlinearModes, Structure, frequency_response, nonlinear_modes
from .study import SweepResult, sweep
from . import config

from .common._version import __version__

# ``microslip.loops`` and ``microslip.paths`` keep the import paths users have always used.
for _alias, _module in (("loops", loops), ("paths", paths)):
    _sys.modules[f"{__name__}.{_alias}"] = _module
for _name, _module in list(_sys.modules.items()):
    if _name.startswith(f"{loops.__name__}."):
        _sys.modules[f"{__name__}.loops.{_name.rsplit('.', 1)[1]}"] = _module
_sys.modules.setdefault(f"{__name__}.frequency.config", config.frf)  # its former path
del _alias, _module, _name, _sys

__all__ = _errors.__all__ + [
    "AccuracyReport",
    "ContactReference",
    "Cylinder",
    "FittedBackbone",
    "FrequencyResponse",
    "LoopTuning",
    "MDRModel",
    "MeasuredContact",
    "MicroslipModel",
    "NonlinearModes",
    "Response",
    "Sphere",
    "State",
    "Step",
    "Structure",
    "SweepResult",
    "TargetProblem",
    "TargetTuning",
    "TuningPoints",
    "Validation",
    "accuracy",
    "fit_backbone",
    "frequency_response",
    "loops",
    "mdr",
    "nonlinear_modes",
    "paths",
    "smallest_elements",
    "sweep",
    "tune",
    "tune_on_loops",
    "tune_to_target",
    "tuning_points",
    "validate",
]
del _errors
