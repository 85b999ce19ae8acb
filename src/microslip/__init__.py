"""microslip: friction contacts with variable normal load for structural dynamics.

The contact model of Gastaldi & Gola ("An Improved Microslip Model for
Variable Normal Loads"): a parallel array of macroslip elements, each with a
tangential stiffness, a normal stiffness and a normal gap, so the normal load
shifts between elements as the normal approach changes. SI units throughout.

The names most users need are exported here: the model (:class:`MicroslipModel`),
reference contacts and tuning (:class:`Sphere`, :func:`tune`), accuracy and
measured loops, the frequency domain (:class:`Structure`, :class:`CyclicStructure`,
:class:`UnderPlatformDamper`, :func:`frequency_response`, :func:`nonlinear_modes`,
:func:`damper_design_curve`, ...), design studies (:func:`sweep`) and every error
and warning (:class:`MicroslipError`, :class:`MicroslipWarning`). One package per
job holds the rest: :mod:`microslip.reference` (exact continuous contacts),
:mod:`microslip.tuning` (the paper's equations, tuning to a target),
:mod:`microslip.measured` (from measured loops to a validated model; its
:mod:`microslip.loops`), :mod:`microslip.accuracy` (load paths,
:mod:`microslip.paths`; accuracy against a reference), :mod:`microslip.frequency`
(harmonic balance, time integration), :mod:`microslip.fe` (finite-element
models), :mod:`microslip.config` (the configuration files), :mod:`microslip.study`
(design studies on Dask), :mod:`microslip.figures` (the paper's figures) and
:mod:`microslip.cli` (the command line). The documented packages and their
public names are listed by :mod:`microslip.common.surface`.
"""

import sys as _sys

from .common.errors import (BeyondTuningWarning, BranchPointWarning, ConfigError, ConvergenceError, CurveInterrupted,
                            DesignPointWarning, FileFormatError, FolderInUseError, IncompleteCurveWarning,
                            LoadLimitError, LoopError, MicroslipDeprecationWarning, MicroslipError, MicroslipWarning,
                            MissingVariable, NotPeriodicError, OneMatrixFile, OneSidedDamperWarning,
                            PeakOnEdgeWarning, SingularInteriorError, StudyFolderWarning, TargetNotMet, TuningError,
                            UnderResolvedWarning)
from .model import MicroslipModel, Response, State, Step
from .reference import Cylinder, MDRModel, Sphere, mdr
from .tuning import (ContactReference, TargetProblem, TargetTuning, TuningPoints, smallest_elements, tune,
                     tune_to_target, tuning_points)
from .accuracy import AccuracyReport, accuracy, paths
from .measured import (FittedBackbone, LoopTuning, MeasuredContact, Validation, fit_backbone, loops, tune_on_loops,
                       validate)
from .frequency import (CampbellDiagram, ContactCycle, CraigBampton, CyclicStructure, DesignCurve, FrequencyResponse,
                        NonlinearModes, Prestress, SpeedCurve, SpeedModel, SteadyState, StepControl, Structure,
                        SynthesizedResponse, UnderPlatformDamper, campbell, contact_cycle, craig_bampton,
                        damper_design_curve, damper_speed_curve, frequency_point, frequency_response, nonlinear_modes,
                        prestress, static_solution, steady_state)
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

__all__ = [
    # errors and warnings (microslip.common.errors)
    "BeyondTuningWarning", "BranchPointWarning", "ConfigError", "ConvergenceError", "CurveInterrupted",
    "DesignPointWarning", "FileFormatError", "FolderInUseError", "IncompleteCurveWarning", "LoadLimitError",
    "LoopError", "MicroslipDeprecationWarning", "MicroslipError", "MicroslipWarning", "MissingVariable",
    "NotPeriodicError", "OneMatrixFile", "OneSidedDamperWarning", "PeakOnEdgeWarning", "SingularInteriorError",
    "StudyFolderWarning", "TargetNotMet", "TuningError", "UnderResolvedWarning",
    # the contact model
    "MicroslipModel", "Response", "State", "Step",
    # reference contacts, tuning, accuracy, measured loops
    "Cylinder", "MDRModel", "Sphere", "mdr",
    "ContactReference", "TargetProblem", "TargetTuning", "TuningPoints", "smallest_elements", "tune", "tune_to_target",
    "tuning_points",
    "AccuracyReport", "accuracy", "paths",
    "FittedBackbone", "LoopTuning", "MeasuredContact", "Validation", "fit_backbone", "loops", "tune_on_loops",
    "validate",
    # structures and what is run on them
    "CraigBampton", "CyclicStructure", "SpeedModel", "StepControl", "Structure", "UnderPlatformDamper",
    "craig_bampton",
    "FrequencyResponse", "frequency_point", "frequency_response", "static_solution",
    "NonlinearModes", "SynthesizedResponse", "nonlinear_modes",
    "SteadyState", "steady_state",
    "Prestress", "prestress",
    "ContactCycle", "contact_cycle",
    "DesignCurve", "damper_design_curve",
    "CampbellDiagram", "SpeedCurve", "campbell", "damper_speed_curve",
    # design studies
    "SweepResult", "sweep",
]
