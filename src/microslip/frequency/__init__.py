"""Frequency domain: alternating frequency--time contact forces and harmonic balance.

* :func:`aft`, :func:`aft_batch` -- periodic forces of microslip contacts from
  the Fourier coefficients of their displacements, with exact Jacobians;
  :func:`aft_plane` the same for a contact moving on its plane (two
  tangential directions plus the normal);
* :class:`Structure` -- a linear structure (dense or sparse ``M, C, K``) with
  contacts attached to linear combinations of its degrees of freedom;
* :func:`frequency_response` -- harmonic balance with pseudo-arclength
  continuation, returning a :class:`FrequencyResponse`;
* :func:`frequency_point` -- the solution at one frequency;
* :func:`nonlinear_modes` -- a damped nonlinear mode's frequency and damping
  against its amplitude (extended periodic motion concept), returning a
  :class:`NonlinearModes` that synthesises forced responses near the mode;
* :func:`static_solution` -- the static equilibrium under preloads;
* ``reduction="exact" | "modal" | "none"`` of those three -- harmonic balance on
  the contact DOFs, the rest of the structure condensed exactly or modally
  (:mod:`.reduced`);
* :class:`CyclicStructure` -- one sector of a bladed disk, solved for an
  engine-order excitation (``engine_order=`` of the solvers);
* :class:`UnderPlatformDamper` -- a rigid damper body between two platforms,
  its interfaces given by geometry, attached to a structure or a sector;
* :class:`SpeedModel` -- stiffness at 2 or 3 rotation speeds fitted as
  ``K0 + Omega^2 K1 (+ Omega^4 K2)``, the damper's load ``m r Omega^2``;
  :func:`campbell` its Campbell diagram (stuck and free systems, engine-order
  crossings; a cyclic sector's per nodal diameter, :func:`excited_diameter`),
  :func:`damper_speed_curve` the peak response against speed;
* :func:`damper_design_curve` -- peak response against the damper's
  centrifugal load, the curve used to choose a damper;
* :func:`blade_scatter`, :func:`mistuned_disk`, :func:`blade_peaks`,
  :func:`amplification_factor` -- a mistuned disk (random blade stiffness
  scatter) assembled whole, each blade's peak against the tuned sector's;
* :func:`contact_cycle` -- a contact's forces over one steady period at a
  point of a response, with its slip state (stuck, microslip, gross slip,
  lift-off) at every sample;
* :func:`craig_bampton` -- a smaller :class:`Structure` on kept DOFs plus
  fixed-interface modes, with its recovery matrix;
* :func:`jointed_structure` -- the friction contacts and bolt load on a reduced
  lap joint (:func:`microslip.fe.lap_joint`);
* :func:`steady_state` -- direct time integration
  to the periodic steady state (an independent check);
* :func:`prestress` -- bolt and contact prestress: the static state with the
  friction released or stuck, then the dynamic analyses from it
  (``prestress=`` of the solvers), the prestressed structure's linear modes
  and a damping fitted on them (:class:`Prestress`).
"""

import importlib as _importlib
import sys as _sys

from .aft import (AFTResult, NotPeriodicError, PlaneAFTResult, UnderResolvedWarning, aft, aft_batch, aft_plane, cycle_work,
                  default_samples, synthesise, time_samples)
from .numerics.continuation import BranchPointWarning, ConvergenceError, StepControl
from .reduction.craig_bampton import CraigBampton, craig_bampton
from .structures.cyclic import CyclicStructure
from .structures.damper import DamperContact, UnderPlatformDamper
from .analyses.design import DesignCurve, damper_design_curve
from .structures.speed import SpeedModel
from .analyses.campbell import CampbellDiagram, SpeedCurve, campbell, damper_speed_curve, excited_diameter
from .reduction.condensation import SingularInteriorError
from .analyses.contact_cycle import ContactCycle, contact_cycle, plot_contact_cycles
from .equations.hbm import HarmonicBalance
from .structures.mistuning import blade_scatter, mistuned_disk
from .analyses.blade_peaks import amplification_factor, blade_peaks
from .analyses.nonlinear_modes import NonlinearModes, nonlinear_modes
from .analyses.response import (FrequencyResponse, IncompleteCurveWarning, frequency_point, frequency_response,
                                static_solution)
from .structures.joints import jointed_structure
from .structures.structure import Contact, Structure
from .analyses.synthesis import SynthesizedResponse
from .analyses.transient import SteadyState, steady_state
from .analyses.prestressed import Prestress, PrestressedModes
from .analyses.prestress import prestress

# The modules' paths before the package was laid out by role keep working (the same module objects).
_MOVED = {"continuation": "numerics.continuation", "structure": "structures.structure", "cyclic": "structures.cyclic",
          "damper": "structures.damper", "mistuning": "structures.mistuning",
          "condensation": "reduction.condensation", "modal": "reduction.modal",
          "cyclic_modal": "reduction.cyclic_modal",
          "craig_bampton": "reduction.craig_bampton", "hbm": "equations.hbm", "reduced": "equations.reduced",
          "cyclic_balance": "equations.cyclic_balance", "epmc": "equations.epmc", "response": "analyses.response",
          "stability": "analyses.stability", "nonlinear_modes": "analyses.nonlinear_modes",
          "synthesis": "analyses.synthesis", "transient": "analyses.transient",
          "contact_cycle": "analyses.contact_cycle", "design": "analyses.design"}
for _old, _new in _MOVED.items():
    _sys.modules.setdefault(f"{__name__}.{_old}", _importlib.import_module(f"{__name__}.{_new}"))
del _old, _new

__all__ = [
    "AFTResult",
    "CampbellDiagram",
    "SpeedCurve",
    "SpeedModel",
    "campbell",
    "damper_speed_curve",
    "excited_diameter",
    "BranchPointWarning",
    "Contact",
    "ContactCycle",
    "ConvergenceError",
    "CraigBampton",
    "CyclicStructure",
    "DamperContact",
    "DesignCurve",
    "FrequencyResponse",
    "HarmonicBalance",
    "IncompleteCurveWarning",
    "NonlinearModes",
    "NotPeriodicError",
    "PlaneAFTResult",
    "Prestress",
    "PrestressedModes",
    "SingularInteriorError",
    "StepControl",
    "SteadyState",
    "SynthesizedResponse",
    "UnderPlatformDamper",
    "UnderResolvedWarning",
    "Structure",
    "aft",
    "aft_batch",
    "aft_plane",
    "jointed_structure",
    "amplification_factor",
    "blade_peaks",
    "blade_scatter",
    "contact_cycle",
    "craig_bampton",
    "cycle_work",
    "damper_design_curve",
    "default_samples",
    "frequency_point",
    "frequency_response",
    "mistuned_disk",
    "nonlinear_modes",
    "plot_contact_cycles",
    "prestress",
    "static_solution",
    "steady_state",
    "time_samples",
]
