"""Computations shared by the accuracy sections of ``microslip reproduce`` (cached per case)."""

from __future__ import annotations

from functools import lru_cache

from ..accuracy.compare import reference_run
from ..accuracy.paths import default_family
from ..reference.mdr import mdr
from ..tuning.target import TargetProblem, element_sweep, stored_fractions

#: lowest load of the target family, as a fraction of the tuning load (N >= 0.2 N_tot)
LOW_LOAD = 0.2
#: smallest tangential amplitude of the target family, a multiple of the gross-slip displacement at N_min
MIN_AMPLITUDE = 0.5
#: elements of the exact reference (MDR): its metrics are then within 1e-4 of the converged ones
MDR_ELEMENTS = 2000
#: J of the sweep (the stored optimised points cover these)
SWEEP = tuple(range(2, 17)) + (20, 24, 28, 32)


@lru_cache(maxsize=2)
def family_run(case):
    """The default family at the case's tuning load and the exact reference (MDR, 2000 elements) run on it."""
    family = default_family(case.sphere, case.normal_load)
    return reference_run(mdr(case.sphere, max_load=case.normal_load, elements=MDR_ELEMENTS), family)


@lru_cache(maxsize=2)
def problem(case) -> TargetProblem:
    """The target problem: loads 0.2..1 N_tot, amplitudes >= 0.5 t_gs(N_min), targets 2 % and 2 %."""
    return TargetProblem(case.sphere, (LOW_LOAD * case.normal_load, case.normal_load))


def stored_points(case):
    """The optimised points stored with the package, or None when they were found for another problem."""
    return stored_fractions(case.sphere, (LOW_LOAD * case.normal_load, case.normal_load))


@lru_cache(maxsize=2)
def sweep(case):
    """Worst errors against J: force and displacement spacings measured now, optimised points re-measured."""
    known = stored_points(case)
    spacings = ("force", "displacement", "optimal") if known else ("force", "displacement")
    Js = [J for J in SWEEP if known is None or J in known]
    return element_sweep(problem(case), Js, spacings=spacings, fractions=known)
