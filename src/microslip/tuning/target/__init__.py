"""Tuning to an accuracy target: choose the paper's tuning points, and the number of elements, by measurement.

The paper spaces its tuning points evenly in force. Here the points are
chosen to make the tuned array accurate on the load paths it will meet: the
default family of variable-normal-load cycles (:func:`microslip.paths.default_family`)
restricted to a load range ``N_lo <= N <= N_hi`` and to tangential amplitudes
of at least ``min_amplitude`` times the gross-slip displacement at the
path's lowest load, measured against the exact continuous contact
(:func:`microslip.mdr`). The model is still tuned by the paper's equations at
``N_hi`` (:func:`microslip.tune` with ``displacements=``), so the result is a
paper-style array; only the points move.

The objective is the worst normalised error over the family,
``max(|energy error| / energy_target, force difference / force_target)``
(:mod:`microslip.accuracy`), a minimax objective, minimised over the points
(the logarithms of their spacings, so they stay increasing) by a
differential evolution seeded with the best of a few two-parameter spacing
laws, then Nelder--Mead on all the points (:func:`optimal_points`;
deterministic, fixed seed). Pass
``force_target=math.inf`` to minimise the worst energy error alone (targets are
fractions: 0.02 means 2 %; above 1 is refused).

Below ``min_amplitude`` a finite array dissipates too little by construction
(Mindlin's loss grows as the cube of the amplitude; the array's begins only
when its first element slips): see :meth:`TargetProblem.amplitude_report`.

The code is split by job: :mod:`.problem` (the problem), :mod:`.search`
(the point search, the smallest J), :mod:`.sweep` (sweeps over J) and
:mod:`.points` (the stored points); the public names are exported here.
"""

from .points import load_optimal_points, stored_fractions, stored_mismatch
from .problem import REFERENCE_ELEMENTS, SPACINGS, TargetProblem, TargetTuning, dense_options
from .search import METHODS, POPULATION, TargetNotMet, optimal_points, smallest_elements, tune_over_range, tune_to_target
from .sweep import ElementSweep, element_sweep, points_record

__all__ = ["REFERENCE_ELEMENTS", "SPACINGS", "METHODS", "POPULATION", "TargetProblem", "TargetTuning", "TargetNotMet",
           "dense_options", "optimal_points", "tune_to_target", "smallest_elements", "tune_over_range",
           "ElementSweep", "element_sweep", "load_optimal_points", "points_record", "stored_fractions",
           "stored_mismatch"]
